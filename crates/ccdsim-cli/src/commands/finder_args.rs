//! The finders' options on the command line: one `--NAME VALUE` flag per option that a finder
//! of the library declares (`ccdsim::finder::finder_options`), so that this tool lists none of
//! them itself and a finder's new option appears here by itself.

use anyhow::Result;
use ccdsim::finder::{finder_options, FinderOption};
use ccdsim::FinderOptions;
use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};

/// The finder options given on the command line, by option name.
#[derive(Clone, Debug, Default)]
pub struct FinderArgs {
    given: Vec<(&'static FinderOption, f64)>,
}

/// The flag of an option: its name with dashes (`bvh_grow` → `bvh-grow`).
fn flag(option: &FinderOption) -> String {
    option.name.replace('_', "-")
}

impl FinderArgs {
    /// Whether any finder option was given.
    pub fn any_given(&self) -> bool {
        !self.given.is_empty()
    }

    /// The library's options: the defaults with the given ones set, checked; a bad one is
    /// named by its flag (`--bvh-grow`).
    pub fn options(&self) -> Result<FinderOptions> {
        let mut options = FinderOptions::default();
        for (option, value) in &self.given {
            (option.set)(&mut options, *value);
        }
        match options.check() {
            Err(ccdsim::FinderError::Option { option, why }) => {
                anyhow::bail!("--{}: {why}", option.replace('_', "-"))
            }
            Err(e) => Err(e.into()),
            Ok(()) => Ok(options),
        }
    }
}

impl FromArgMatches for FinderArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let given = finder_options()
            .filter_map(|o| matches.get_one::<f64>(o.name).map(|v| (o, *v)))
            .collect();
        Ok(FinderArgs { given })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl Args for FinderArgs {
    fn augment_args(cmd: Command) -> Command {
        finder_options().fold(cmd, |cmd, o| {
            cmd.arg(
                Arg::new(o.name)
                    .long(flag(o))
                    .value_name("VALUE")
                    .value_parser(clap::value_parser!(f64))
                    .allow_negative_numbers(true)
                    .help(format!("{}: {} [default: {}]", o.finder, o.help, o.default))
                    .help_heading("Finder options"),
            )
        })
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

//! Finder options: one record of every finder's settings, and the options each finder
//! declares for itself.
//!
//! Each finder owns its options: it lists them (name, meaning, default, how to set one) as
//! [`FinderOption`]s in its own module and checks them when it is made. Tools discover them
//! through [`finder_options`] and set them by name with [`FinderOptions::set`], so a command
//! line or a binding offers every finder's options without naming any of them.

use super::FinderError;

/// One option a finder reads, described for tools: its name, meaning and default, and how
/// to set it on a [`FinderOptions`].
#[derive(Clone, Copy, Debug)]
pub struct FinderOption {
    /// The finder that reads it, as [`make_finder`](super::make_finder) names it.
    pub finder: &'static str,
    /// The option's name, as [`FinderError::Option`] names it (`bvh_grow`); a command line
    /// spells it with dashes (`--bvh-grow`).
    pub name: &'static str,
    /// What it means, with its unit and range, in one sentence.
    pub help: &'static str,
    /// Its default, as text for help screens (`2`, or `automatic`).
    pub default: &'static str,
    /// Stores `value` (not yet checked: see [`FinderOptions::check`]).
    pub set: fn(&mut FinderOptions, f64),
}

/// Every option of every finder of this crate, finder by finder.
pub fn finder_options() -> impl Iterator<Item = &'static FinderOption> {
    super::bvh::OPTIONS.iter().chain(super::cells::OPTIONS)
}

/// Options of all finders; each finder reads its own.
#[derive(Clone, Debug, PartialEq)]
pub struct FinderOptions {
    /// `bvh`: factor by which the time step Δ grows while no event is found (> 1; thesis: 2).
    pub bvh_grow: f64,
    /// `bvh`: factor by which Δ shrinks after an event is found (in (0, 1]; thesis: 1/2).
    pub bvh_shrink: f64,
    /// `bvh`: the first Δ, seconds (> 0).
    pub bvh_initial_dt: f64,
    /// `cells`: the skin of the neighbour lists, relative to the largest contact distance
    /// (0: no lists, cell crossings; else in `[0.001, 1]`); `None`: automatic
    /// ([`auto_cells_skin_at`], by dimension and packing). Lists are used in periodic worlds only; other worlds always use
    /// cell crossings.
    pub cells_skin: Option<f64>,
}

impl Default for FinderOptions {
    fn default() -> Self {
        FinderOptions {
            bvh_grow: 2.0,
            bvh_shrink: 0.5,
            bvh_initial_dt: 1e-3,
            cells_skin: None,
        }
    }
}

/// The skin the `cells` finder uses in `D` dimensions when [`FinderOptions::cells_skin`] is
/// `None`: lists pay in 3D (about 23 candidates per cell scan against 9 in a list at packing
/// 0.45), not in 2D (5.7 candidates per scan, few to save, and list rebuilds cost more than
/// cell crossings): see the measurements in docs/benchmarks.md.
#[must_use]
pub fn auto_cells_skin(dim: usize) -> f64 {
    if dim >= 3 {
        0.4
    } else {
        0.0
    }
}

/// The volume fraction from which the automatic skin of a 3D periodic world is
/// [`auto_cells_skin`]'s: below it a body flies far between collisions and leaves its shell
/// many times per collision (at 0.01, about 110 rebuilds per collision, 19 times slower than
/// cell crossings), so the `cells` finder crosses cells instead. Measured crossover on a 3D
/// gas of 10⁴ spheres, 10⁶ collisions: lists 1.56× slower at 0.3, even at 0.35, 1.25× faster
/// at 0.4 and 1.5× at 0.45.
pub const LIST_PACKING: f64 = 0.36;

/// The skin the `cells` finder uses in a `dim`-dimensional periodic world at volume (area)
/// fraction `packing` when [`FinderOptions::cells_skin`] is `None`: [`auto_cells_skin`]
/// from [`LIST_PACKING`] up, 0 (cell crossings) below it.
#[must_use]
pub fn auto_cells_skin_at(dim: usize, packing: f64) -> f64 {
    if packing >= LIST_PACKING {
        auto_cells_skin(dim)
    } else {
        0.0
    }
}

impl FinderOptions {
    /// Sets the option called `name` (see [`finder_options`]) to `value` and checks every
    /// option's range; an unknown name or a value out of range is refused, naming the option,
    /// and leaves the options as they were.
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), FinderError> {
        let Some(option) = finder_options().find(|o| o.name == name) else {
            return Err(FinderError::Option {
                option: "finder option",
                why: format!(
                    "no finder has an option `{name}` (known: {})",
                    finder_options()
                        .map(|o| o.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            });
        };
        // Checked on a copy: a refused value must not stay behind.
        let mut next = self.clone();
        (option.set)(&mut next, value);
        next.check()?;
        *self = next;
        Ok(())
    }

    /// Checks every finder's options, as each finder does when it is made.
    pub fn check(&self) -> Result<(), FinderError> {
        super::bvh::check_options(self)?;
        super::check_cells_options(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_declared_option_is_settable_by_name_and_checked() {
        let names: Vec<&str> = finder_options().map(|o| o.name).collect();
        assert_eq!(
            names,
            ["bvh_grow", "bvh_shrink", "bvh_initial_dt", "cells_skin"]
        );
        let mut o = FinderOptions::default();
        o.set("bvh_grow", 3.0).unwrap();
        o.set("bvh_initial_dt", 0.25).unwrap();
        o.set("cells_skin", 0.2).unwrap();
        assert_eq!(
            (o.bvh_grow, o.bvh_initial_dt, o.cells_skin),
            (3.0, 0.25, Some(0.2))
        );
        for o in finder_options() {
            assert!(
                super::super::FINDER_NAMES.contains(&o.finder),
                "{}",
                o.finder
            );
        }
    }

    #[test]
    fn unknown_names_and_bad_values_are_refused_by_name() {
        let mut o = FinderOptions::default();
        let e = o.set("bvh_speed", 2.0).unwrap_err().to_string();
        assert!(e.contains("bvh_speed") && e.contains("bvh_grow"), "{e}");
        let e = o.set("bvh_shrink", 2.0).unwrap_err();
        assert!(
            matches!(
                e,
                FinderError::Option {
                    option: "bvh_shrink",
                    ..
                }
            ),
            "{e:?}"
        );
        let e = o.set("cells_skin", 5.0).unwrap_err();
        assert!(
            matches!(
                e,
                FinderError::Option {
                    option: "cells_skin",
                    ..
                }
            ),
            "{e:?}"
        );
    }
}

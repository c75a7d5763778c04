//! `ccdsim bench pool-break`: a racked pool table broken again and again; the median time per
//! break and breaks per second, beside pooltool's when the layout file carries its timing
//! (`scripts/pool-break-compare`).

use anyhow::{anyhow, bail, Context, Result};
use ccdsim::billiards::{Game, PoolFinder};
use ccdsim::motion::CueStrike;
use ccdsim::Vector;
use ccdsim_bench::{pool_break, BreakLayout};
use serde_json::Value;
use std::path::PathBuf;
use std::process::ExitCode;

/// The games `--game` takes.
#[derive(Clone, Copy, clap::ValueEnum)]
enum GameArg {
    NineBall,
    EightBall,
}

/// Arguments of `ccdsim bench pool-break`.
#[derive(clap::Args)]
pub struct Args {
    /// The rack (ignored with --layout).
    #[arg(long, value_enum, default_value = "nine-ball")]
    game: GameArg,
    /// Seed of the rack's small random offsets (ignored with --layout).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Cue speed, m/s, straight at the apex ball (ignored with --layout).
    #[arg(long, default_value_t = 8.0)]
    speed: f64,
    /// Breaks to time; the median is reported.
    #[arg(long, default_value_t = 1000)]
    runs: usize,
    /// A layout written by bench/pooltool/break_speed.py: the balls, the strike and
    /// pooltool's own timing of the same break.
    #[arg(long)]
    layout: Option<PathBuf>,
    /// How each event is found: all-pairs, sedgewick, cells or bvh (the same events, bit for
    /// bit).
    #[arg(long, default_value = "cells")]
    finder: String,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

fn number(v: &Value, what: &str) -> Result<f64> {
    v.as_f64()
        .ok_or_else(|| anyhow!("layout: `{what}` is not a number"))
}

/// The layout, and pooltool's timing and events if the file has them.
fn read_layout(path: &PathBuf) -> Result<(BreakLayout, Option<Pooltool>)> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let v: Value =
        serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))?;
    let balls = v["balls"]
        .as_object()
        .ok_or_else(|| anyhow!("layout: no `balls` object"))?;
    let mut list = Vec::new();
    for (name, xy) in balls {
        let p = xy
            .as_array()
            .filter(|a| a.len() == 2)
            .ok_or_else(|| anyhow!("layout: ball {name} is not [x, y]"))?;
        list.push((
            name.clone(),
            Vector([number(&p[0], name)?, number(&p[1], name)?]),
        ));
    }
    if !list.iter().any(|(n, _)| n == "cue") {
        bail!("layout: no ball named `cue`");
    }
    let s = &v["strike"];
    let strike = CueStrike {
        speed: number(&s["V0"], "strike.V0")?,
        phi: number(&s["phi"], "strike.phi")?,
        theta: number(&s["theta"], "strike.theta")?,
        a: number(&s["a"], "strike.a")?,
        b: number(&s["b"], "strike.b")?,
    };
    let theirs = v["pooltool"]["median_seconds"].as_f64().map(|median| {
        let events = v["pooltool"]["events"]
            .as_array()
            .map(|list| list.iter().map(event_of).collect())
            .unwrap_or_default();
        Pooltool { median, events }
    });
    Ok((
        BreakLayout {
            balls: list,
            strike,
        },
        theirs,
    ))
}

/// One of pooltool's events: type, agents, time (seconds).
fn event_of(e: &Value) -> (String, Vec<String>, f64) {
    let agents = e["agents"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|x| x.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default();
    let kind = e["type"].as_str().unwrap_or_default().to_owned();
    (kind, agents, e["time"].as_f64().unwrap_or(f64::NAN))
}

/// pooltool's timing and events of the same break.
struct Pooltool {
    median: f64,
    events: Vec<(String, Vec<String>, f64)>,
}

/// How ccdsim's events compare with pooltool's: the same types and agents in the same order
/// (events at exactly the same time in ccdsim, such as two balls that start rolling together,
/// in either order), and the largest difference in time; or where they first part.
fn agreement(ours: &[(String, Vec<String>, f64)], theirs: &[(String, Vec<String>, f64)]) -> String {
    // Two balls meeting are named in either order.
    let key = |e: &(String, Vec<String>, f64)| {
        let mut a = e.1.clone();
        if e.0 == "ball_ball" {
            a.sort();
        }
        (e.0.clone(), a)
    };
    let mut worst = 0.0f64;
    let mut i = 0;
    while i < ours.len().min(theirs.len()) {
        let mut j = i + 1;
        while j < ours.len() && ours[j].2 == ours[i].2 {
            j += 1;
        }
        let j = j.min(theirs.len());
        let mut mine: Vec<_> = ours[i..j].iter().map(key).collect();
        let mut their: Vec<_> = theirs[i..j].iter().map(key).collect();
        mine.sort();
        their.sort();
        if mine != their {
            let (a, b) = (&ours[i], &theirs[i]);
            return format!(
                "events part at {i}: ccdsim {} {:?} at {:.9} s, pooltool {} {:?} at {:.9} s",
                a.0, a.1, a.2, b.0, b.1, b.2
            );
        }
        for k in i..j {
            worst = worst.max((ours[k].2 - theirs[k].2).abs());
        }
        i = j;
    }
    if ours.len() != theirs.len() {
        return format!(
            "{} events in ccdsim, {} in pooltool",
            ours.len(),
            theirs.len()
        );
    }
    format!(
        "the same {} events as pooltool, in the same order; times within {worst:.1e} s",
        ours.len()
    )
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    if args.runs == 0 {
        bail!("--runs must be at least 1");
    }
    let (layout, pooltool) = match &args.layout {
        Some(path) => read_layout(path)?,
        None => {
            let game = match args.game {
                GameArg::NineBall => Game::NineBall,
                GameArg::EightBall => Game::EightBall,
            };
            (BreakLayout::racked(game, args.seed, args.speed), None)
        }
    };
    let names: Vec<String> = layout.balls.iter().map(|(n, _)| n.clone()).collect();
    let finder: PoolFinder = args.finder.parse().map_err(anyhow::Error::msg)?;
    let report = pool_break(&layout, args.runs, finder).map_err(|e| anyhow!(e.describe(&names)))?;
    if args.json {
        let mut v = serde_json::to_value(&report)?;
        v["breaks_per_second"] = (1.0 / report.median_seconds).into();
        if let Some(p) = &pooltool {
            v["pooltool_median_seconds"] = p.median.into();
            v["speedup"] = (p.median / report.median_seconds).into();
            v["agreement"] = agreement(&report.event_list, &p.events).into();
        }
        outln!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    outln!(
        "{} balls, {} events ({} ball-ball{}, {} cushion), every ball still after {:.3} s; pocketed: {}",
        layout.balls.len(),
        report.events,
        report.ball_ball,
        if report.pressings > 0 {
            format!(", {} of them pressed balls parted", report.pressings)
        } else {
            String::new()
        },
        report.cushion,
        report.duration,
        if report.pocketed.is_empty() {
            "none".to_owned()
        } else {
            report.pocketed.join(", ")
        }
    )?;
    outln!(
        "{} breaks, finder {}: median {:.1} µs per break ({:.0} breaks/s), fastest {:.1} µs, slowest {:.1} µs",
        report.runs,
        report.finder,
        report.median_seconds * 1e6,
        1.0 / report.median_seconds,
        report.min_seconds * 1e6,
        report.max_seconds * 1e6
    )?;
    if let Some(p) = &pooltool {
        outln!(
            "pooltool: median {:.1} ms per break; ccdsim is {:.0}× faster",
            p.median * 1e3,
            p.median / report.median_seconds
        )?;
        outln!("{}", agreement(&report.event_list, &p.events))?;
    }
    Ok(ExitCode::SUCCESS)
}

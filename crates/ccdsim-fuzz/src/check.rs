//! Runs a case through the all-pairs oracle and every other finder (and every mode of
//! `cells`), and compares what they wrote: the run files byte for byte, the sensor logs and
//! how each run ended. The oracle's run file is then read back and replayed by `verify`.

use crate::case::{Case, Schedule};
pub use crate::verdict::{Checked, Failure};
use ccdsim::finder::{make_finder, FinderOptions, FINDER_NAMES};
use ccdsim::record::{RunReader, RunWriter};
use ccdsim::verify::Verifier;
use ccdsim::{AnyScene, Scene, Simulation};

/// What one run of a case produced, everything a finder could change.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The run file.
    pub bytes: Vec<u8>,
    /// Events resolved.
    pub events: u64,
    /// Every sensor event, as text (time bits, body, sensor, change).
    pub sensors: Vec<String>,
    /// How the run ended (`Halt`, if any), as text.
    pub halt: String,
}

/// Every finder but the oracle with every mode its options select: `cells` with automatic
/// options, without neighbour lists (crossings), with a small skin (many rebuilds) and with
/// the largest (long lists). Lists apply to periodic worlds only.
#[must_use]
pub fn variants() -> Vec<(&'static str, FinderOptions)> {
    let mut out = Vec::new();
    for &name in FINDER_NAMES.iter().filter(|&&n| n != "all-pairs") {
        out.push((name, FinderOptions::default()));
        if name == "cells" {
            for skin in [0.0, 0.02, 1.0] {
                out.push((
                    name,
                    FinderOptions {
                        cells_skin: Some(skin),
                        ..FinderOptions::default()
                    },
                ));
            }
        }
    }
    out
}

/// Runs `case`'s scene with finder `name` and `options`, recording it.
pub fn run<const D: usize>(
    case: &Case,
    scene: &Scene<D>,
    name: &str,
    options: &FinderOptions,
) -> Outcome {
    let finder = make_finder::<D>(name, options).expect("a known finder");
    let mut sim = Simulation::with_finder(scene, finder).expect("a valid scene");
    // A scene's arrivals are recorded as the additions they are.
    let steered = !case.edits.is_empty() || !scene.arrivals.is_empty();
    let mut rec = if steered {
        sim.record_edits(true);
        RunWriter::new_steered(Vec::new(), name.into(), scene).expect("header")
    } else {
        RunWriter::new(Vec::new(), name.into(), scene).expect("header")
    };
    let end = scene.start_time + case.duration;
    let mut edits = case.edits.iter();
    let mut events = 0u64;
    let mut sensors = Vec::new();
    let mut log_sensors = |sim: &mut Simulation<D>| {
        for s in sim.take_sensor_events() {
            sensors.push(format!(
                "{:016x} {} {} {:?}",
                s.time.to_bits(),
                s.body,
                s.sensor,
                s.change
            ));
        }
    };
    let edit = |sim: &mut Simulation<D>, rec: &mut RunWriter<Vec<u8>, D>, op: &crate::EditOp| {
        op.apply(sim);
        for e in sim.take_edits() {
            rec.write_event(&e).expect("write");
        }
    };
    match case.schedule {
        Schedule::Events { every } => {
            let every = u64::from(every.max(1));
            while events < case.max_events {
                let next = sim.peek_event();
                write_arrivals(&mut sim, &mut rec);
                match next {
                    Some(e) if e.time <= end => {}
                    _ => break,
                }
                let Some(c) = sim.step_event() else { break };
                rec.write_event(&c).expect("write");
                log_sensors(&mut sim);
                events += 1;
                if events % every == 0 {
                    if let Some(op) = edits.next() {
                        edit(&mut sim, &mut rec, op);
                    }
                }
            }
        }
        Schedule::Frames { dt } => {
            let mut frame_end = scene.start_time + dt;
            // A game loop steps with `step_event_until`, which looks no further than the
            // next event past the frame's end: `peek_event` would go on through up to
            // 1024 + 64 n box exits when bodies never meet (the events schedule covers that).
            while events < case.max_events && frame_end <= end {
                let next = sim.step_event_until(frame_end);
                // Arrivals that came before the event, then the event.
                write_arrivals(&mut sim, &mut rec);
                match next {
                    Some(c) => {
                        rec.write_event(&c).expect("write");
                        log_sensors(&mut sim);
                        events += 1;
                    }
                    None => {
                        if sim.halt().is_some() {
                            break;
                        }
                        sim.run_until(frame_end);
                        write_arrivals(&mut sim, &mut rec);
                        log_sensors(&mut sim);
                        frame_end += dt;
                        if let Some(op) = edits.next() {
                            edit(&mut sim, &mut rec, op);
                        }
                    }
                }
            }
        }
    }
    log_sensors(&mut sim);
    Outcome {
        bytes: rec.finish(sim.time()).expect("finish"),
        events,
        sensors,
        halt: format!("{:?}", sim.halt()),
    }
}

/// Reads back a run file of `scene` and replays it through `verify`.
pub fn verify_run<const D: usize>(scene: &Scene<D>, bytes: &[u8]) -> Result<(), String> {
    let mut reader =
        RunReader::<_, D>::new(bytes, "fuzz".into()).map_err(|e| format!("read header: {e}"))?;
    let (events, end) = reader
        .read_events()
        .map_err(|e| format!("read records: {e}"))?;
    let mut v = Verifier::new(scene);
    for c in &events {
        v.check(c).map_err(|e| e.to_string())?;
    }
    v.finish(end.ok_or("no end record")?)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// Compares every finder with the oracle on `scene` and, with `verify`, replays the oracle's
/// run through `verify`.
pub fn check_scene<const D: usize>(
    case: &Case,
    scene: &Scene<D>,
    verify: bool,
) -> Result<Checked, Failure> {
    let oracle = run(case, scene, "all-pairs", &FinderOptions::default());
    let variants = variants();
    for (name, options) in &variants {
        let got = run(case, scene, name, options);
        if got != oracle {
            let skin = options
                .cells_skin
                .map_or(String::new(), |s| format!(" (cells_skin {s})"));
            let what = if got.events != oracle.events {
                format!("{} events, the oracle {}", got.events, oracle.events)
            } else if got.bytes != oracle.bytes {
                let at = got
                    .bytes
                    .iter()
                    .zip(&oracle.bytes)
                    .position(|(a, b)| a != b)
                    .unwrap_or(got.bytes.len().min(oracle.bytes.len()));
                format!("run files differ from byte {at}")
            } else if got.sensors != oracle.sensors {
                "sensor logs differ".into()
            } else {
                format!("halts differ: {} vs the oracle's {}", got.halt, oracle.halt)
            };
            return Err(Failure::Mismatch(format!("{name}{skin}, {D}D: {what}")));
        }
    }
    if verify {
        verify_run(scene, &oracle.bytes).map_err(Failure::Verify)?;
    }
    Ok(Checked {
        events: oracle.events,
        runs: variants.len(),
    })
}

/// Checks a case: `Ok(None)` when its scene is refused by the validator (nothing to compare),
/// `Ok(Some(_))` when every finder agreed with the oracle and the oracle's run verified. A
/// case holding a pool scene is a shot, checked by [`crate::pool::check_pool`]. A panic
/// anywhere is a failure too, with its message.
pub fn check_case(case: &Case) -> Result<Option<Checked>, Failure> {
    check_case_with(case, true)
}

/// [`check_case`], replaying the oracle's run through `verify` only when `verify` is set (a
/// campaign after finder mismatches alone goes faster without).
pub fn check_case_with(case: &Case, verify: bool) -> Result<Option<Checked>, Failure> {
    let checked = std::panic::catch_unwind(|| {
        if case.is_pool() {
            return crate::pool::check_pool(case, verify);
        }
        match case.any_scene() {
            Err(_) => Ok(None),
            Ok(AnyScene::D2(s)) => check_scene(case, &s, verify).map(Some),
            Ok(AnyScene::D3(s)) => check_scene(case, &s, verify).map(Some),
        }
    });
    checked.unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".into());
        Err(Failure::Panic(message))
    })
}

/// Writes the arrivals `sim` brought in since the last call (its journaled additions).
fn write_arrivals<const D: usize>(sim: &mut Simulation<D>, rec: &mut RunWriter<Vec<u8>, D>) {
    for e in sim.take_edits() {
        rec.write_event(&e).expect("write");
    }
}

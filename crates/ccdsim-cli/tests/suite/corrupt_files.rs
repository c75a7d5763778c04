//! A corrupted-file fuzzer for the run-file reader, `verify`, `export` and `render`.
//!
//! Valid run files of several kinds are recorded here (2D and 3D, gravity, resting and
//! turning bodies, moving walls, periodic boxes, growing radii, a thermostat, a steered run
//! that adds and removes bodies), then corrupted: cut at every kind of offset, bits flipped
//! at random, and fields edited (times, positions, velocities, ids, tags, version, dimension,
//! header length, the header's JSON) with the record checksum recomputed, so that the
//! corruption reaches the parser. Each file goes through the library's reader, verifier and
//! JSON Lines export, and every few files the viewer's PNG renderer. None may panic or take
//! longer than [`FILE_SECONDS`]; each must end in an error or a verdict, and corruptions that
//! certainly break a file (a non-finite number, a record far out of place, a raised version)
//! must never pass as a valid run.
//!
//! `cargo test` tries [`DEFAULT_FILES`] files (a few seconds); set `CCDSIM_FUZZ_FILES=10000`
//! (and optionally `CCDSIM_FUZZ_SEED`) for a long run, which prints its figures.

use crate::common;

use ccdsim::record::{export_jsonl, open_run, record_len, AnyRunReader, RunReader, RunRecord};
use ccdsim::record::{RunWriter, PREAMBLE_LEN};
use ccdsim::verify::Verifier;
use ccdsim::{BodySpec, CollisionFilter, Scene, Simulation, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::Read;
use std::path::Path;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Corrupted files `cargo test` tries.
const DEFAULT_FILES: usize = 2500;
/// Seed of the corruptions.
const FUZZ_SEED: u64 = 0x00c0_ffee_0bad_f11e;
/// Longest any one file may take through every entry point, seconds.
const FILE_SECONDS: u64 = 20;

/// A valid run file, and what kind of run it holds.
struct Source {
    name: &'static str,
    bytes: Vec<u8>,
}

fn record<const D: usize>(scene: &Scene<D>, events: u64) -> Vec<u8> {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    let mut w = RunWriter::new(Vec::new(), "memory".into(), scene).unwrap();
    sim.run_events_with(events, |c| w.write_event(c).unwrap());
    w.finish(sim.time()).unwrap()
}

fn example(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

/// A steered run: bodies added, removed, moved and refiltered between frames.
fn steered() -> Vec<u8> {
    let scene: Scene<2> = Scene::from_json(&example("two_balls.json")).unwrap();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "steered".into(), &scene).unwrap();
    sim.record_edits(true);
    for frame in 0..40u32 {
        let w = sim.world();
        let live: Vec<usize> = (0..w.len()).filter(|&i| !w.is_vacant(i)).collect();
        match frame % 4 {
            0 => {
                let x = 0.5 + f64::from(frame * 37 % 30) / 10.0;
                let _ = sim.add_body(BodySpec::new(Vector([x, 0.4]), Vector([0.3, 0.7]), 0.1));
            }
            1 if live.len() > 3 => {
                let _ = sim.remove_body(live[live.len() - 1]);
            }
            2 => {
                let i = live[frame as usize % live.len()];
                let _ = sim.set_collision_filter(i, CollisionFilter { group: 1, mask: 1 });
            }
            _ => {
                let _ = sim.set_velocity(live[0], Vector([0.5, -0.25]));
            }
        }
        for record in sim.take_edits().iter().chain(&sim.advance(0.1)) {
            run.write_event(record).unwrap();
        }
    }
    run.finish(sim.time()).unwrap()
}

fn sources() -> Vec<Source> {
    let two = |name: &'static str, file: &str, events: u64| Source {
        name,
        bytes: record::<2>(&Scene::from_json(&example(file)).unwrap(), events),
    };
    let growth2 = r#"{"dim": 2, "settings": {"growth": {"rate": 0.02}},
        "bodies": [{"pos": [1, 1], "vel": [1, 0.3], "radius": 0.2},
                   {"pos": [3, 1.2], "vel": [-0.5, 0.1], "radius": 0.3},
                   {"pos": [2, 3], "vel": [0.2, -0.8], "radius": 0.25}],
        "walls": [{"a": [0, 0], "b": [4, 0]}, {"a": [4, 0], "b": [4, 4]},
                  {"a": [4, 4], "b": [0, 4]}, {"a": [0, 4], "b": [0, 0]}]}"#;
    let periodic3 = r#"{"dim": 3, "periodic": [4, 4, 4],
        "bodies": [{"pos": [1, 1, 1], "vel": [1, 0.3, 0.2], "radius": 0.3},
                   {"pos": [3, 1.2, 2], "vel": [-0.5, 0.1, 0.7], "radius": 0.3},
                   {"pos": [2, 3, 3], "vel": [0.2, -0.8, -0.1], "radius": 0.3}]}"#;
    let thermostat2 = r#"{"dim": 2,
        "settings": {"thermostat": {"temperature": 1.0, "rate": 2.0, "seed": 5}},
        "bodies": [{"pos": [1, 1], "vel": [1, 0.3], "radius": 0.2},
                   {"pos": [3, 1.2], "vel": [-0.5, 0.1], "radius": 0.3}],
        "walls": [{"a": [0, 0], "b": [4, 0]}, {"a": [4, 0], "b": [4, 4]},
                  {"a": [4, 4], "b": [0, 4]}, {"a": [0, 4], "b": [0, 0]}]}"#;
    let slow2 = r#"{"dim": 2,
        "bodies": [{"pos": [1, 1], "vel": [1e-170, 0], "radius": 0.25},
                   {"pos": [3, 1], "vel": [-1e-170, 0], "radius": 0.25}],
        "walls": [{"a": [0, 0], "b": [4, 0]}, {"a": [4, 0], "b": [4, 2]},
                  {"a": [4, 2], "b": [0, 2]}, {"a": [0, 2], "b": [0, 0]}]}"#;
    let mut out = vec![
        two("two balls", "two_balls.json", 30),
        two("break", "break.json", 60),
        two("pegs (gravity)", "pegs.json", 60),
        two("piston (moving walls)", "piston.json", 40),
        two("resting", "resting.json", 40),
        two("rolling (turns)", "rolling.json", 40),
        two("shelves", "shelves.json", 40),
        Source {
            name: "box3d",
            bytes: record::<3>(&Scene::from_json(&example("box3d.json")).unwrap(), 40),
        },
        Source {
            name: "growth",
            bytes: record::<2>(&Scene::from_json(growth2).unwrap(), 40),
        },
        Source {
            name: "periodic 3D",
            bytes: record::<3>(&Scene::from_json(periodic3).unwrap(), 40),
        },
        Source {
            name: "slow (1e-170 m/s)",
            bytes: record::<2>(&Scene::from_json(slow2).unwrap(), 6),
        },
        Source {
            name: "steered",
            bytes: steered(),
        },
    ];
    if let Ok(scene) = Scene::<2>::from_json(thermostat2) {
        out.push(Source {
            name: "thermostat",
            bytes: record::<2>(&scene, 40),
        });
    }
    out
}

/// FNV-1a, 32 bits: the run file's record checksum.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

/// Where a file's parts are.
struct Layout {
    dim: usize,
    data: usize,
    records: usize,
}

fn layout(bytes: &[u8]) -> Layout {
    let dim = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let len = u64::from_le_bytes(bytes[16..24].try_into().unwrap()) as usize;
    let data = PREAMBLE_LEN + len;
    Layout {
        dim,
        data,
        records: (bytes.len() - data) / record_len(dim),
    }
}

/// Recomputes the checksum of record `k`.
fn reseal(bytes: &mut [u8], l: &Layout, k: usize) {
    let n = record_len(l.dim);
    let at = l.data + k * n;
    let sum = fnv1a(&bytes[at..at + n - 4]);
    bytes[at + n - 4..at + n].copy_from_slice(&sum.to_le_bytes());
}

/// A float to plant: special values, huge and tiny ones, or random bits.
fn nasty_float(rng: &mut ChaCha8Rng, old: f64) -> f64 {
    match rng.random_range(0..12) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => 1e308,
        4 => -1e308,
        5 => 1e-320,
        6 => -0.0,
        7 => old + 1e6,
        8 => old * (1.0 + 1e-6),
        9 => f64::from_bits(old.to_bits() ^ (1 << rng.random_range(0..64))),
        10 => f64::from_bits(rng.random()),
        _ => -old,
    }
}

/// How a file was corrupted, and whether the corruption certainly breaks it.
struct Corruption {
    what: String,
    /// A valid verdict ("OK") on this file would be a lie.
    must_fail: bool,
}

/// `restless`: the source's bodies move in a closed box without gravity, so that they would
/// cross a wall (or each other) if the run went on for 10³⁰⁰ s without an event.
fn corrupt(src: &[u8], restless: bool, rng: &mut ChaCha8Rng) -> (Vec<u8>, Corruption) {
    let mut b = src.to_vec();
    let l = layout(src);
    let n = record_len(l.dim);
    let c = |what: String, must_fail: bool| Corruption { what, must_fail };
    let record_at = |rng: &mut ChaCha8Rng| rng.random_range(0..l.records);
    match rng.random_range(0..9) {
        0 => {
            // A cut: anywhere, or at and around the part boundaries.
            let k = record_at(rng);
            let cuts = [
                rng.random_range(0..b.len()),
                rng.random_range(0..PREAMBLE_LEN),
                PREAMBLE_LEN,
                l.data - 1,
                l.data,
                l.data + k * n,
                l.data + k * n + 1,
                l.data + k * n + n - 1,
                b.len() - 1,
            ];
            let cut = cuts[rng.random_range(0..cuts.len())];
            b.truncate(cut);
            (b, c(format!("cut at byte {cut}"), false))
        }
        1 => {
            // Random bits flipped, the checksum left as it is.
            let flips = rng.random_range(1..8);
            for _ in 0..flips {
                let at = rng.random_range(0..b.len());
                b[at] ^= 1 << rng.random_range(0..8);
            }
            (b, c(format!("{flips} bits flipped"), false))
        }
        2 => {
            // Bits flipped in one record, its checksum recomputed.
            let k = record_at(rng);
            for _ in 0..rng.random_range(1..4) {
                let at = l.data + k * n + rng.random_range(0..n - 4);
                b[at] ^= 1 << rng.random_range(0..8);
            }
            reseal(&mut b, &l, k);
            (b, c(format!("bits flipped in record {k}, resealed"), false))
        }
        3 => {
            // A record's time.
            let k = record_at(rng);
            let at = l.data + k * n + 9;
            let old = f64::from_le_bytes(b[at..at + 8].try_into().unwrap());
            let new = nasty_float(rng, old);
            b[at..at + 8].copy_from_slice(&new.to_le_bytes());
            reseal(&mut b, &l, k);
            let last = k + 1 == l.records;
            // Not finite, or far later than a record that follows (which then goes back), or
            // an end 10³⁰⁰ s on for bodies in a box that never come to rest.
            let must = !new.is_finite() || (new >= 1e300 && (!last || restless));
            (b, c(format!("record {k} time {old} -> {new}"), must))
        }
        4 => {
            // A number of a record's body slots.
            let k = record_at(rng);
            let slot = rng.random_range(0..4 * l.dim);
            let at = l.data + k * n + 17 + 8 * slot;
            let old = f64::from_le_bytes(b[at..at + 8].try_into().unwrap());
            let new = nasty_float(rng, old);
            b[at..at + 8].copy_from_slice(&new.to_le_bytes());
            reseal(&mut b, &l, k);
            let tag = src[l.data + k * n] & 0x0f;
            // The first slot's position and velocity of a body, wall or reset record are
            // plain numbers: a non-finite one is never valid.
            let must = slot < 2 * l.dim && (1..=4).contains(&tag) && tag != 3 && !new.is_finite();
            (
                b,
                c(format!("record {k} number {slot} {old} -> {new}"), must),
            )
        }
        5 => {
            // A record's body or wall indices, or its tag.
            let k = record_at(rng);
            let base = l.data + k * n;
            let field = rng.random_range(0..3);
            let value: u32 = match rng.random_range(0..5) {
                0 => u32::MAX,
                1 => 1 << 31,
                2 => rng.random_range(0..64),
                3 => rng.random(),
                _ => u32::from_le_bytes(b[base + 1..base + 5].try_into().unwrap()) + 1,
            };
            let what = match field {
                0 => {
                    b[base] = value as u8;
                    format!("record {k} tag {:#x}", value as u8)
                }
                1 => {
                    b[base + 1..base + 5].copy_from_slice(&value.to_le_bytes());
                    format!("record {k} a = {value}")
                }
                _ => {
                    b[base + 5..base + 9].copy_from_slice(&value.to_le_bytes());
                    format!("record {k} b = {value}")
                }
            };
            reseal(&mut b, &l, k);
            // Indices far beyond any body or wall (the end record has none).
            let must = field > 0 && value >= 1 << 20 && src[base] & 0x0f != 3;
            (b, c(what, must))
        }
        6 => {
            // The version or the dimension.
            let (at, value) = if rng.random_bool(0.5) {
                (8, rng.random_range(0..16u32))
            } else {
                (12, rng.random_range(0..5u32))
            };
            let value = if rng.random_bool(0.1) {
                u32::MAX
            } else {
                value
            };
            b[at..at + 4].copy_from_slice(&value.to_le_bytes());
            let raised = at == 8 && value > ccdsim::record::VERSION_NEWEST;
            (b, c(format!("preamble byte {at} = {value}"), raised))
        }
        7 => {
            // The header length.
            let len = (l.data - PREAMBLE_LEN) as u64;
            let value = match rng.random_range(0..5) {
                0 => 0,
                1 => len - 1,
                2 => len + 1,
                3 => 1 << 60,
                _ => u64::MAX,
            };
            b[16..24].copy_from_slice(&value.to_le_bytes());
            (b, c(format!("header length {len} -> {value}"), false))
        }
        _ => {
            // A number in the header's JSON, the header length kept right.
            let json = String::from_utf8(src[PREAMBLE_LEN..l.data].to_vec()).unwrap();
            let spots: Vec<usize> = json
                .char_indices()
                .filter(|&(i, ch)| {
                    ch.is_ascii_digit()
                        && !json[..i].ends_with(|p: char| p.is_ascii_digit() || p == '.')
                })
                .map(|(i, _)| i)
                .collect();
            let at = spots[rng.random_range(0..spots.len())];
            let end = at
                + json[at..]
                    .find(|ch: char| !(ch.is_ascii_digit() || "eE.+-".contains(ch)))
                    .unwrap_or(json.len() - at);
            let planted = [
                "1e308",
                "0",
                "1e-320",
                "4294967296",
                "1152921504606846976",
                "1e400",
            ][rng.random_range(0..6)];
            let new_json = format!("{}{planted}{}", &json[..at], &json[end..]);
            let mut out = src[..PREAMBLE_LEN].to_vec();
            out[16..24].copy_from_slice(&(new_json.len() as u64).to_le_bytes());
            out.extend_from_slice(new_json.as_bytes());
            out.extend_from_slice(&src[l.data..]);
            let what = format!("header number {} -> {planted}", &json[at..end]);
            (out, c(what, false))
        }
    }
}

/// What the entry points said about one file.
#[derive(Debug)]
struct Outcome {
    /// The reader read every record without an error.
    read_ok: bool,
    /// `verify` found the run valid.
    verified: bool,
}

fn verify_run<R: Read, const D: usize>(mut r: RunReader<R, D>) -> Result<(), String> {
    let mut verifier = Verifier::new(r.scene());
    let mut end = r.scene().start_time;
    while let Some(rec) = r.next_record().map_err(|e| e.to_string())? {
        match rec {
            RunRecord::Event(c) => {
                end = c.event.time;
                verifier.check(&c).map_err(|v| v.to_string())?;
            }
            RunRecord::End(t) => end = t,
        }
    }
    verifier.finish(end).map(|_| ()).map_err(|v| v.to_string())
}

fn read_all<R: Read, const D: usize>(mut r: RunReader<R, D>) -> Result<u64, String> {
    let mut n = 0;
    while r.next_record().map_err(|e| e.to_string())?.is_some() {
        n += 1;
    }
    Ok(n)
}

/// Every entry point on the file at `path`.
fn try_file(path: &Path, png: &Path, render: bool) -> Outcome {
    let read_ok = match open_run(path) {
        Ok(AnyRunReader::D2(r)) => read_all(r).is_ok(),
        Ok(AnyRunReader::D3(r)) => read_all(r).is_ok(),
        Err(_) => false,
    };
    let verified = match open_run(path) {
        Ok(AnyRunReader::D2(r)) => verify_run(r).is_ok(),
        Ok(AnyRunReader::D3(r)) => verify_run(r).is_ok(),
        Err(_) => false,
    };
    let mut sink = std::io::sink();
    let _ = match open_run(path) {
        Ok(AnyRunReader::D2(mut r)) => export_jsonl(&mut r, &mut sink).map(|_| ()),
        Ok(AnyRunReader::D3(mut r)) => export_jsonl(&mut r, &mut sink).map(|_| ()),
        Err(e) => Err(e.into()),
    };
    if render {
        let options = ccdsim_viewer::RenderOptions {
            width: 48,
            height: Some(48),
            ..ccdsim_viewer::RenderOptions::default()
        };
        for at in [0.0, 1.0] {
            let _ = ccdsim_viewer::render_png(path, at, png, &options);
        }
    }
    Outcome { read_ok, verified }
}

/// Runs `try_file` on its own thread: a panic is caught there, and a file that takes longer
/// than [`FILE_SECONDS`] fails the test.
fn guarded(path: &Path, png: &Path, render: bool) -> Result<Outcome, String> {
    let (tx, rx) = mpsc::channel();
    let (path, png) = (path.to_path_buf(), png.to_path_buf());
    std::thread::spawn(move || {
        let out = std::panic::catch_unwind(|| try_file(&path, &png, render));
        let _ = tx.send(out.map_err(|e| {
            e.downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| (*s).to_string()))
                .unwrap_or_default()
        }));
    });
    match rx.recv_timeout(Duration::from_secs(FILE_SECONDS)) {
        Ok(Ok(out)) => Ok(out),
        Ok(Err(panic)) => Err(format!("panicked: {panic}")),
        Err(_) => Err(format!("took longer than {FILE_SECONDS} s")),
    }
}

#[test]
fn corrupted_run_files_get_an_error_or_a_verdict_never_a_panic_or_a_lie() {
    let files: usize = std::env::var("CCDSIM_FUZZ_FILES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_FILES);
    let seed: u64 = std::env::var("CCDSIM_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(FUZZ_SEED);
    let dir = common::scratch_dir("corrupt-files", "fuzz");
    let (path, png) = (dir.join("run.ccd"), dir.join("frame.png"));
    let sources = sources();
    // Each source reads, verifies and exports as it was written.
    for s in &sources {
        std::fs::write(&path, &s.bytes).unwrap();
        let out = guarded(&path, &png, true).unwrap_or_else(|e| panic!("{}: {e}", s.name));
        assert!(out.read_ok && out.verified, "{}: {out:?}", s.name);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let started = Instant::now();
    let (mut refused, mut verdicts, mut failures) = (0usize, 0usize, Vec::new());
    for k in 0..files {
        let s = &sources[k % sources.len()];
        let restless =
            ["two balls", "break", "box3d", "growth", "slow (1e-170 m/s)"].contains(&s.name);
        let (bytes, corruption) = corrupt(&s.bytes, restless, &mut rng);
        std::fs::write(&path, &bytes).unwrap();
        let what = format!("file {k} ({}: {})", s.name, corruption.what);
        match guarded(&path, &png, k % 16 == 0) {
            Err(e) => {
                // Kept for a regression test, outside the scratch directory.
                let keep = std::env::temp_dir().join(format!("ccdsim-fuzz-{seed}-{k}.ccd"));
                std::fs::write(&keep, &bytes).unwrap();
                failures.push(format!("{what}: {e} (kept as {})", keep.display()));
            }
            Ok(out) => {
                if corruption.must_fail && out.verified {
                    let keep = std::env::temp_dir().join(format!("ccdsim-fuzz-{seed}-{k}.ccd"));
                    std::fs::write(&keep, &bytes).unwrap();
                    failures.push(format!(
                        "{what}: verified OK, a lie (kept as {})",
                        keep.display()
                    ));
                }
                if out.read_ok {
                    verdicts += 1;
                } else {
                    refused += 1;
                }
            }
        }
    }
    let took = started.elapsed();
    eprintln!(
        "corrupt_files: {files} corrupted files from {} sources (seed {seed}) in {:.1} s: {refused} \
         refused by the reader, {verdicts} read to a verdict, {} failures",
        sources.len(),
        took.as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The reader's verdict on `bytes`, then `verify`'s: `Err` with the reader's error, or `Ok`
/// with `verify`'s (`Ok(())` or the violation).
fn judge(bytes: &[u8], dir: &Path) -> Result<Result<(), String>, String> {
    let path = dir.join("judged.ccd");
    std::fs::write(&path, bytes).unwrap();
    let read = match open_run(&path).map_err(|e| e.to_string())? {
        AnyRunReader::D2(r) => read_all(r),
        AnyRunReader::D3(r) => read_all(r),
    };
    read?;
    Ok(match open_run(&path).unwrap() {
        AnyRunReader::D2(r) => verify_run(r),
        AnyRunReader::D3(r) => verify_run(r),
    })
}

/// Sets the `f64` at byte `off` of record `k` and reseals it.
fn plant(bytes: &[u8], k: usize, off: usize, x: f64) -> Vec<u8> {
    let mut b = bytes.to_vec();
    let l = layout(bytes);
    let at = l.data + k * record_len(l.dim) + off;
    b[at..at + 8].copy_from_slice(&x.to_le_bytes());
    reseal(&mut b, &l, k);
    b
}

/// The header's scene with only its first body, the records as they were.
fn fewer_bodies(bytes: &[u8]) -> Vec<u8> {
    let l = layout(bytes);
    let json = std::str::from_utf8(&bytes[PREAMBLE_LEN..l.data]).unwrap();
    let mut scene: serde_json::Value = serde_json::from_str(json).unwrap();
    scene["bodies"].as_array_mut().unwrap().truncate(1);
    let json = scene.to_string();
    let mut out = bytes[..16].to_vec();
    out.extend_from_slice(&(json.len() as u64).to_le_bytes());
    out.extend_from_slice(json.as_bytes());
    out.extend_from_slice(&bytes[l.data..]);
    out
}

#[test]
fn the_reported_files_get_their_verdicts() {
    let dir = common::scratch_dir("corrupt-files", "reported");
    let slow = |v: f64| {
        let json = format!(
            r#"{{"dim": 2,
            "bodies": [{{"pos": [1, 1], "vel": [{v}, 0], "radius": 0.25}},
                       {{"pos": [3, 1], "vel": [{}, 0], "radius": 0.25}}],
            "walls": [{{"a": [0, 0], "b": [4, 0]}}, {{"a": [4, 0], "b": [4, 2]}},
                      {{"a": [4, 2], "b": [0, 2]}}, {{"a": [0, 2], "b": [0, 0]}}]}}"#,
            -v
        );
        record::<2>(&Scene::from_json(&json).unwrap(), 6)
    };
    // 1. Two balls at ±1e-170 and ±1e-280 m/s: valid, verified within memory.
    for v in [1e-170, 1e-280] {
        assert_eq!(judge(&slow(v), &dir), Ok(Ok(())), "{v:e} m/s");
    }
    let two = record::<2>(&Scene::from_json(&example("two_balls.json")).unwrap(), 20);
    let end = layout(&two).records - 1;
    // 2. A NaN position: refused, the field named.
    let e = judge(&plant(&two, 3, 17, f64::NAN), &dir).unwrap_err();
    assert!(e.contains("record 3") && e.contains("position"), "{e}");
    // 3. A time of 1e308: in the middle, the next record goes back; at the end, the balls
    // cross the walls long before.
    let e = judge(&plant(&two, 5, 9, 1e308), &dir).unwrap_err();
    assert!(
        e.contains("record 6") && e.contains("goes backwards"),
        "{e}"
    );
    let v = judge(&plant(&two, end, 9, 1e308), &dir)
        .unwrap()
        .unwrap_err();
    assert!(v.contains("crosses wall"), "{v}");
    // 4. A header listing fewer bodies than the records name (formats 13 and 10).
    for file in ["rolling.json", "piston.json"] {
        let run = record::<2>(&Scene::from_json(&example(file)).unwrap(), 40);
        let e = judge(&fewer_bodies(&run), &dir).unwrap_err();
        assert!(e.contains("index out of range"), "{file}: {e}");
    }
    // 5. A version raised above the one its scene's runs are written in.
    let mut raised = two.clone();
    raised[8..12].copy_from_slice(&13u32.to_le_bytes());
    let e = judge(&raised, &dir).unwrap_err();
    assert!(e.contains("format version 13 is later"), "{e}");
}

//! Golden run files: every example scene, the built-in break, generated scenes of each kind
//! and two packings, run through the CLI, must give byte for byte the files recorded in
//! `tests/golden/runs.txt` (their SHA-256 and length). It guards behaviour across changes
//! that must not alter it (a reorganisation of the library, a faster kernel): a difference
//! names the case and the command that reproduces it.
//!
//! Each case runs with `cells`, `bvh` and `sedgewick` (and the all-pairs oracle when it is
//! small), and every finder must give the recorded file. After a change that is *meant* to
//! alter runs, record the corpus again with `CCDSIM_GOLDEN_WRITE=1 cargo test -p ccdsim-cli
//! --test suite -- golden_runs::` and say why in the commit.

use crate::common;

use common::{ccdsim, run_ok, scratch_dir};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where a case's scene comes from.
enum Source {
    /// The built-in billiard break (`ccdsim run` with no scene).
    BuiltIn,
    /// A file of `examples/`.
    Example(&'static str),
    /// Written by `ccdsim gen` with these arguments.
    Generated(&'static [&'static str]),
}

/// One corpus entry.
struct Case {
    name: &'static str,
    source: Source,
    /// Further arguments of `ccdsim run` (how long).
    run: Vec<String>,
    /// Also run the all-pairs oracle (O(n) a step: small scenes only).
    oracle: bool,
    /// Also compare the sensor log.
    sensors: bool,
}

const FAST_FINDERS: [&str; 3] = ["cells", "bvh", "sedgewick"];

fn corpus() -> Vec<Case> {
    let until = |t: &str| vec!["--until".to_string(), t.to_string()];
    let example = |name: &'static str, file: &'static str| Case {
        name,
        source: Source::Example(file),
        run: until("10"),
        oracle: true,
        sensors: false,
    };
    // Scenes of 1000 bodies and more skip the oracle, whose search is O(n) a body.
    let generated = |name: &'static str, gen: &'static [&'static str], events: u64| Case {
        name,
        source: Source::Generated(gen),
        run: vec!["--events".to_string(), events.to_string()],
        oracle: events <= 2000,
        sensors: false,
    };
    vec![
        Case {
            name: "built-in-break",
            source: Source::BuiltIn,
            run: until("10"),
            oracle: true,
            sensors: false,
        },
        example("example-box3d", "box3d.json"),
        example("example-break", "break.json"),
        example("example-pegs", "pegs.json"),
        example("example-piston", "piston.json"),
        example("example-resting", "resting.json"),
        example("example-rolling", "rolling.json"),
        example("example-shelves", "shelves.json"),
        example("example-two-balls", "two_balls.json"),
        generated(
            "gas-2d-walls",
            &["gas", "--n", "1000", "--seed", "3", "--radius-min", "0.3"],
            20_000,
        ),
        generated(
            "gas-3d-periodic",
            &[
                "gas",
                "--dim",
                "3",
                "--n",
                "1000",
                "--periodic",
                "--packing",
                "0.3",
            ],
            20_000,
        ),
        generated(
            "gas-2d-lattice-gravity",
            &["gas", "--n", "100", "--lattice", "--gravity", "0,-9.81"],
            2000,
        ),
        generated(
            "gas-3d-walls-gravity",
            &["gas", "--dim", "3", "--n", "100", "--gravity", "0,0,-9.81"],
            2000,
        ),
        generated(
            "gas-2d-periodic-thermostat",
            &["gas", "--n", "100", "--periodic", "--temperature", "2"],
            2000,
        ),
        generated(
            "thesis-2d-wall-pieces",
            &["thesis", "--n", "1024", "--wall-pieces", "4"],
            20_000,
        ),
        generated(
            "thesis-3d",
            &["thesis", "--n", "1024", "--dim", "3"],
            20_000,
        ),
        generated("rack", &["rack", "--offset", "0"], 2000),
        Case {
            name: "pegs-bins-inelastic",
            source: Source::Generated(&[
                "pegs",
                "--balls",
                "40",
                "--bins",
                "8",
                "--restitution",
                "0.8",
            ]),
            // Inelastic balls piling up in the bins collide ever more often (the TC model
            // keeps it finite): a count of events, not a time.
            run: vec!["--events".to_string(), "5000".to_string()],
            oracle: true,
            sensors: true,
        },
        Case {
            // Arrivals (recorded as bodies added), kinematic pegs, the TC model.
            name: "galton",
            source: Source::Generated(&["galton", "--balls", "30", "--rows", "6"]),
            run: until("5"),
            oracle: true,
            sensors: false,
        },
    ]
}

/// `ccdsim pack` cases: its packing (scene and extended XYZ) is the output.
const PACKINGS: [(&str, &[&str]); 2] = [
    (
        "pack-2d-bidisperse",
        &[
            "--dim",
            "2",
            "--n",
            "64",
            "--bidisperse",
            "1.4",
            "--rate",
            "0.1",
        ],
    ),
    (
        "pack-3d-periodic",
        &["--dim", "3", "--n", "64", "--periodic", "--rate", "0.1"],
    ),
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn golden_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/runs.txt")
}

/// `name → (sha256, length)` as recorded.
fn recorded() -> BTreeMap<String, (String, u64)> {
    let text = std::fs::read_to_string(golden_path()).unwrap_or_default();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(f.len(), 3, "a golden line is `name sha256 length`: {l}");
            (f[0].to_string(), (f[1].to_string(), f[2].parse().unwrap()))
        })
        .collect()
}

fn digest(bytes: &[u8]) -> (String, u64) {
    let hash = Sha256::digest(bytes);
    let hex = hash.iter().map(|b| format!("{b:02x}")).collect();
    (hex, bytes.len() as u64)
}

/// One output of the corpus: `(entry name, finder or "", command, bytes)`.
type Output = (String, String, String, Vec<u8>);

/// One `ccdsim run` of the corpus: the entry names its outputs go under and the command.
struct Job {
    name: String,
    finder: String,
    record: PathBuf,
    /// The sensor log, when the case compares it.
    log: Option<PathBuf>,
    cmd: std::process::Command,
}

/// The outputs of every case and finder: `(entry name, finder or "", command, bytes)`, in
/// corpus order. The runs are independent processes: they run on as many threads as the
/// machine has cores.
fn outputs(dir: &Path) -> Vec<Output> {
    let mut jobs = Vec::new();
    for case in corpus() {
        let scene: Option<PathBuf> = match case.source {
            Source::BuiltIn => None,
            Source::Example(file) => Some(root().join("examples").join(file)),
            Source::Generated(args) => {
                let path = dir.join(format!("{}.json", case.name));
                run_ok(ccdsim().arg("gen").args(args).arg("--out").arg(&path));
                Some(path)
            }
        };
        let mut finders: Vec<&str> = FAST_FINDERS.to_vec();
        if case.oracle {
            finders.push("all-pairs");
        }
        for finder in finders {
            let record = dir.join(format!("{}-{finder}.ccd", case.name));
            let log = dir.join(format!("{}-{finder}.sensors", case.name));
            let mut cmd = ccdsim();
            cmd.arg("run");
            if let Some(scene) = &scene {
                cmd.arg(scene);
            }
            cmd.args(&case.run)
                .args(["--finder", finder, "-q", "--record"])
                .arg(&record);
            if case.sensors {
                cmd.arg("--sensor-log").arg(&log);
            }
            jobs.push(Job {
                name: case.name.to_string(),
                finder: finder.to_string(),
                record,
                log: case.sensors.then_some(log),
                cmd,
            });
        }
    }
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots: Vec<std::sync::Mutex<Option<Job>>> = jobs
        .into_iter()
        .map(|j| std::sync::Mutex::new(Some(j)))
        .collect();
    let done: std::sync::Mutex<Vec<(usize, Vec<Output>)>> = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(slot) = slots.get(k) else { break };
                let mut job = slot.lock().unwrap().take().expect("each job once");
                let shown = format!("{:?}", job.cmd);
                run_ok(&mut job.cmd);
                let mut outs = vec![(
                    job.name.clone(),
                    job.finder.clone(),
                    shown.clone(),
                    std::fs::read(&job.record).unwrap(),
                )];
                if let Some(log) = &job.log {
                    outs.push((
                        format!("{}-sensor-log", job.name),
                        job.finder.clone(),
                        shown,
                        std::fs::read(log).unwrap(),
                    ));
                }
                done.lock().unwrap().push((k, outs));
            });
        }
    });
    let mut done = done.into_inner().unwrap();
    done.sort_by_key(|(k, _)| *k);
    let mut out: Vec<_> = done.into_iter().flat_map(|(_, outs)| outs).collect();
    for (name, args) in PACKINGS {
        let prefix = dir.join(name);
        let mut cmd = ccdsim();
        cmd.arg("pack")
            .args(args)
            .arg("-q")
            .arg("--out")
            .arg(&prefix);
        let shown = format!("{cmd:?}");
        run_ok(&mut cmd);
        for ext in ["json", "xyz"] {
            let bytes = std::fs::read(prefix.with_extension(ext)).unwrap();
            out.push((format!("{name}-{ext}"), String::new(), shown.clone(), bytes));
        }
    }
    out
}

#[test]
fn runs_match_the_recorded_corpus() {
    let dir = scratch_dir("golden", "runs");
    let outputs = outputs(&dir);
    if std::env::var_os("CCDSIM_GOLDEN_WRITE").is_some() {
        let mut text = String::from(
            "# Golden outputs of tests/suite/golden_runs.rs: name, SHA-256, length in bytes.\n\
             # Written by `CCDSIM_GOLDEN_WRITE=1 cargo test -p ccdsim-cli --test suite -- \
             golden_runs::`.\n",
        );
        let mut seen = BTreeMap::new();
        for (name, finder, shown, bytes) in &outputs {
            let d = digest(bytes);
            match seen.get(name) {
                None => {
                    text.push_str(&format!("{name} {} {}\n", d.0, d.1));
                    seen.insert(name.clone(), d);
                }
                Some(first) => assert_eq!(
                    first, &d,
                    "{name}: {finder} differs from the first finder's output ({shown})"
                ),
            }
        }
        std::fs::create_dir_all(golden_path().parent().unwrap()).unwrap();
        std::fs::write(golden_path(), text).unwrap();
        return;
    }
    let golden = recorded();
    let mut failures = Vec::new();
    let mut names = std::collections::BTreeSet::new();
    for (name, finder, shown, bytes) in &outputs {
        names.insert(name.clone());
        let got = digest(bytes);
        match golden.get(name) {
            None => failures.push(format!("{name}: not recorded (write the corpus again)")),
            Some(want) if *want != got => failures.push(format!(
                "{name} with {}: {} bytes, SHA-256 {}; recorded {} bytes, {}\n    {shown}",
                if finder.is_empty() { "pack" } else { finder },
                got.1,
                got.0,
                want.1,
                want.0
            )),
            Some(_) => {}
        }
    }
    for name in golden.keys() {
        if !names.contains(name) {
            failures.push(format!("{name}: recorded but no longer produced"));
        }
    }
    assert!(
        failures.is_empty(),
        "outputs differ from the golden corpus:\n{}",
        failures.join("\n")
    );
}

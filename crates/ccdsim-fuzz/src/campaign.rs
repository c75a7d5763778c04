//! A fuzzing campaign: cases drawn for a given time (or count), in batches of proptest runs
//! with seeds derived from one campaign seed, on one or more threads. A failing case is shrunk
//! by proptest to a minimal one and handed back, to be written out as a regression case. A
//! watchdog stops the process on a case that runs far too long (a finder that loops), after
//! writing that case out.

use crate::case::Case;
use crate::check::check_case_with;
use crate::features::{features, FEATURES};
use crate::genome;
use crate::pool;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The case each thread is checking, and since when: what the watchdog looks at.
type Running = Mutex<Vec<Option<(Instant, Case)>>>;

/// Cases per proptest run: each run has its own seed, and a failure ends only its run.
const BATCH: u32 = 64;

/// What a campaign does.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Campaign seed: the same seed and limits draw the same cases.
    pub seed: u64,
    /// Stop drawing new cases after this long.
    pub duration: Duration,
    /// Stop after this many cases (all threads together, split evenly), if given.
    pub max_cases: Option<u64>,
    /// Bodies per scene, at most.
    pub max_bodies: usize,
    /// One batch of cases in this many is of pool shots ([`crate::pool`]), the others of
    /// scenes: 0 for none, 1 for pool shots only.
    pub pool_every: u64,
    /// Replay each oracle run through `verify` too (else finders alone are compared).
    pub verify: bool,
    /// Threads, each with its own seeds.
    pub threads: usize,
    /// A case running longer than this is written out as a hang and the process exits (3).
    pub hang_limit: Duration,
    /// A process holding more than this many bytes while a case runs writes that case out as a
    /// memory blow-up and exits (4).
    pub memory_limit: u64,
    /// Where hangs are written.
    pub out_dir: PathBuf,
}

/// A failure found and shrunk.
#[derive(Clone, Debug)]
pub struct Found {
    /// The shrunk case, with a note saying what failed.
    pub case: Case,
    /// The failure on the shrunk case.
    pub reason: String,
    /// Cases this thread had tried when it drew the first failing one (that one included).
    pub after: u64,
    /// The thread and batch that found it, to find it again.
    pub origin: String,
}

/// What a campaign did.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Cases drawn and checked (refused scenes included).
    pub tried: u64,
    /// Cases whose scene the validator accepted, run through every finder.
    pub valid: u64,
    /// Events of the oracle's runs, added up.
    pub events: u64,
    /// Finder runs compared with the oracle.
    pub runs: u64,
    /// Valid cases per feature.
    pub coverage: BTreeMap<&'static str, u64>,
    /// Failures, shrunk.
    pub found: Vec<Found>,
    /// Wall time.
    pub elapsed: Duration,
}

impl Report {
    fn merge(&mut self, other: Report) {
        self.tried += other.tried;
        self.valid += other.valid;
        self.events += other.events;
        self.runs += other.runs;
        for (k, v) in other.coverage {
            *self.coverage.entry(k).or_default() += v;
        }
        self.found.extend(other.found);
    }

    /// Cases per minute of wall time.
    #[must_use]
    pub fn per_minute(&self) -> f64 {
        self.tried as f64 / self.elapsed.as_secs_f64().max(1e-9) * 60.0
    }

    /// The coverage table as text: each feature and the valid cases that had it.
    #[must_use]
    pub fn coverage_table(&self) -> String {
        let mut out = String::new();
        for name in FEATURES {
            let n = self.coverage.get(name).copied().unwrap_or(0);
            out.push_str(&format!("  {name:<24} {n}\n"));
        }
        out
    }
}

/// Progress shared with the caller (a progress bar) and the watchdog.
#[derive(Debug, Default)]
pub struct Progress {
    /// Cases tried so far.
    pub tried: AtomicU64,
    /// Failures found so far.
    pub failures: AtomicU64,
    stop: AtomicBool,
}

/// Runs a campaign.
pub fn run(settings: &Settings, progress: &Arc<Progress>) -> Report {
    let start = Instant::now();
    let running: Arc<Running> = Arc::new(Mutex::new(vec![None; settings.threads.max(1)]));
    let watchdog = {
        let (running, progress, settings) = (running.clone(), progress.clone(), settings.clone());
        std::thread::spawn(move || watch(&running, &progress, &settings))
    };
    let mut report = Report::default();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..settings.threads.max(1))
            .map(|thread| {
                let running = running.clone();
                let progress = progress.clone();
                scope.spawn(move || run_thread(settings, thread, start, &progress, &running))
            })
            .collect();
        for h in handles {
            report.merge(h.join().expect("a fuzz thread"));
        }
    });
    progress.stop.store(true, Ordering::Relaxed);
    let _ = watchdog.join();
    report.elapsed = start.elapsed();
    report
}

fn watch(running: &Running, progress: &Progress, s: &Settings) {
    while !progress.stop.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(50));
        let slots = running.lock().unwrap_or_else(|e| e.into_inner()).clone();
        let memory = resident_bytes();
        let runaway = slots.iter().flatten().find_map(|(started, _)| {
            if started.elapsed() > s.hang_limit {
                Some((format!("ran more than {} s", s.hang_limit.as_secs()), 3))
            } else if memory > s.memory_limit {
                Some((format!("held the process at {memory} bytes"), 4))
            } else {
                None
            }
        });
        let Some((what, code)) = runaway else {
            continue;
        };
        // Which thread's case it is cannot be told apart from here: every running case is
        // written out, and replaying them one by one tells.
        let _ = std::fs::create_dir_all(&s.out_dir);
        for (thread, slot) in slots.into_iter().enumerate() {
            let Some((_, mut case)) = slot else {
                continue;
            };
            case.note = Some(format!(
                "runaway suspect: a case {what} (seed {}, thread {thread})",
                s.seed
            ));
            let path = s.out_dir.join(format!("runaway-{}-{thread}.json", s.seed));
            let _ = std::fs::write(&path, case.to_json_pretty());
            eprintln!("a case {what}: running case written to {}", path.display());
        }
        std::process::exit(code);
    }
}

/// The process's resident memory, bytes (0 where `/proc` is missing).
fn resident_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1)?.parse::<u64>().ok())
        .map_or(0, |pages| pages * 4096)
}

/// Marks a thread's case as running for the watchdog; unmarks it when dropped, also when the
/// case panics (proptest catches the panic as a failure and goes on shrinking).
struct Watched<'a> {
    running: &'a Running,
    thread: usize,
}

impl<'a> Watched<'a> {
    fn new(running: &'a Running, thread: usize, case: &Case) -> Self {
        running.lock().unwrap_or_else(|e| e.into_inner())[thread] =
            Some((Instant::now(), case.clone()));
        Watched { running, thread }
    }
}

impl Drop for Watched<'_> {
    fn drop(&mut self) {
        self.running.lock().unwrap_or_else(|e| e.into_inner())[self.thread] = None;
    }
}

fn run_thread(
    s: &Settings,
    thread: usize,
    start: Instant,
    progress: &Progress,
    running: &Running,
) -> Report {
    let report = RefCell::new(Report::default());
    let threads = s.threads.max(1) as u64;
    // A count is split between the threads, each drawing its own cases: the same seed and
    // count check the same cases however the threads are scheduled.
    let share = s.max_cases.map(|m| m.div_ceil(threads));
    let over =
        || start.elapsed() >= s.duration || share.is_some_and(|m| report.borrow().tried >= m);
    let mut batch = 0u64;
    while !over() {
        let mut seed = [0u8; 32];
        seed[..8].copy_from_slice(&s.seed.to_le_bytes());
        seed[8..16].copy_from_slice(&(thread as u64).to_le_bytes());
        seed[16..24].copy_from_slice(&batch.to_le_bytes());
        let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed);
        let config = Config {
            cases: BATCH,
            failure_persistence: None,
            max_shrink_iters: 4096,
            ..Config::default()
        };
        let mut runner = TestRunner::new_with_rng(config, rng);
        let shrinking = Cell::new(false);
        let first_failure = Cell::new(0u64);
        let test = |case: Case| {
            if !shrinking.get() && over() {
                return Ok(());
            }
            let result = {
                let _watched = Watched::new(running, thread, &case);
                check_case_with(&case, s.verify)
            };
            if !shrinking.get() {
                let mut r = report.borrow_mut();
                r.tried += 1;
                progress.tried.fetch_add(1, Ordering::Relaxed);
                if let Ok(Some(checked)) = &result {
                    r.valid += 1;
                    r.events += checked.events;
                    r.runs += checked.runs as u64;
                    for f in features(&case) {
                        *r.coverage.entry(f).or_default() += 1;
                    }
                }
            }
            match result {
                Ok(_) => Ok(()),
                Err(f) => {
                    if !shrinking.replace(true) {
                        first_failure.set(report.borrow().tried);
                    }
                    Err(TestCaseError::fail(f.to_string()))
                }
            }
        };
        // The scene batches keep the seeds they had before pool batches joined them.
        let outcome = if s.pool_every > 0 && batch % s.pool_every == s.pool_every - 1 {
            runner.run(&pool::case(), test)
        } else {
            runner.run(&genome::case(s.max_bodies), test)
        };
        if let Err(TestError::Fail(reason, mut case)) = outcome {
            progress.failures.fetch_add(1, Ordering::Relaxed);
            let origin = format!(
                "seed {}, thread {thread} of {threads}, batch {batch}",
                s.seed
            );
            case.note = Some(format!("{reason} (found by the fuzzer: {origin})"));
            report.borrow_mut().found.push(Found {
                case,
                reason: reason.to_string(),
                after: first_failure.get(),
                origin,
            });
        }
        batch += 1;
    }
    report.into_inner()
}

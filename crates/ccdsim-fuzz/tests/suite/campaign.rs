//! A bounded fuzzing campaign, as `scripts/test` runs it: `CCDSIM_FUZZ_CASES` adversarial
//! cases (default 10,000: 43 s measured on two cores in the test build of commit ee68c27)
//! from seed `CCDSIM_FUZZ_SEED` (default 1), on two threads, the same cases on every machine;
//! one batch in eight of pool shots; every finder must agree with the oracle on every case,
//! and the oracle's runs must verify.
//! For longer campaigns, run `scripts/fuzz --minutes M`.

use ccdsim_fuzz::campaign::{run, Progress, Settings};
use std::sync::Arc;
use std::time::Duration;

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn a_bounded_campaign_finds_no_failure() {
    let out = tempfile::tempdir().expect("a scratch directory");
    let settings = Settings {
        seed: env_or("CCDSIM_FUZZ_SEED", 1),
        duration: Duration::from_secs(3600),
        max_cases: Some(env_or("CCDSIM_FUZZ_CASES", 10_000)),
        max_bodies: 24,
        pool_every: 8,
        verify: true,
        threads: 2,
        hang_limit: Duration::from_secs(300),
        memory_limit: 6 << 30,
        out_dir: out.path().to_path_buf(),
    };
    let report = run(&settings, &Arc::new(Progress::default()));
    println!(
        "{} cases ({} valid) in {:.1} s, {:.0} per minute\n{}",
        report.tried,
        report.valid,
        report.elapsed.as_secs_f64(),
        report.per_minute(),
        report.coverage_table()
    );
    assert!(report.valid > 0, "no valid case drawn");
    let failures: Vec<String> = report
        .found
        .iter()
        .map(|f| format!("{} ({}):\n{}", f.reason, f.origin, f.case.to_json_pretty()))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

//! Every case in `regressions/` (failures the fuzzer found, shrunk, and the reports that led
//! to it) passes: every finder writes the oracle's run file, and the oracle's run verifies.

use ccdsim_fuzz::{check_case, Case};

#[test]
fn every_regression_case_passes() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/regressions");
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .expect("the regression directory")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no regression case in {dir}");
    let mut failures = Vec::new();
    for path in &paths {
        let text = std::fs::read_to_string(path).expect("readable");
        let case = Case::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        match check_case(&case) {
            Ok(Some(_)) => {}
            Ok(None) => failures.push(format!("{}: the scene is refused", path.display())),
            Err(f) => failures.push(format!("{}: {f}", path.display())),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

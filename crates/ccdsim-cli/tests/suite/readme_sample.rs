//! The README's sample output of its first command (`ccdsim run`, the built-in break) is what
//! the command prints, wall-clock figures aside: numbers as people write them (8.5, 2.0125,
//! 3.2e-14), one formatting for every summary.

use crate::common;

use common::{ccdsim, run_ok};
use std::path::Path;

/// `line` with the wall-clock figures (`in X s of wall time`, `N events/s`) blanked.
fn without_timing(line: &str) -> String {
    let Some((head, rest)) = line.split_once(" in ") else {
        return line.to_string();
    };
    let Some((_, rest)) = rest.split_once(" s of wall time:") else {
        return line.to_string();
    };
    let Some((events, _)) = rest.rsplit_once(", ") else {
        return line.to_string();
    };
    format!("{head} in _ s of wall time:{events}, _ events/s")
}

#[test]
fn the_readme_shows_what_the_first_command_prints() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let (_, after) = readme
        .split_once("The first command simulates")
        .expect("the README introduces its first command's output");
    let block = after.split("```").nth(1).expect("a code block follows");
    let shown: Vec<String> = block.trim().lines().map(without_timing).collect();
    let out = run_ok(ccdsim().args(["run", "--quiet"]));
    let printed: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .trim()
        .lines()
        .map(without_timing)
        .collect();
    assert_eq!(shown, printed);
    assert!(printed
        .iter()
        .any(|l| l.contains("kinetic energy 8.5 -> 8.5 J")));
}

//! The layout section of ARCHITECTURE.md matches the tree: every path it names exists, and
//! every top-level module of the library and every crate of the workspace is named.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .and_then(Path::parent)
        .unwrap()
}

/// The paths the layout block names, made relative to the root (an indented `src/x` belongs
/// to the crate named on the last unindented line).
fn layout_paths() -> Vec<String> {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let section = text.split("## Layout").nth(1).expect("a Layout section");
    let block = section.split("```").nth(1).expect("a code block");
    let mut parent = String::new();
    let mut paths = Vec::new();
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let first = line.split_whitespace().next().unwrap();
        // Continuation lines of a description start with a lower-case word or a parenthesis.
        if first.starts_with('(') || !(first.contains('/') || first.contains('.')) {
            continue;
        }
        if line.starts_with(' ') {
            paths.push(format!("{parent}{first}"));
        } else {
            parent = first.to_string();
            paths.push(first.to_string());
        }
    }
    paths
}

#[test]
fn every_path_in_the_layout_exists() {
    let paths = layout_paths();
    assert!(paths.len() > 10, "{paths:?}");
    for p in &paths {
        assert!(
            root().join(p).exists(),
            "ARCHITECTURE.md's layout names {p}, which is not in the tree"
        );
    }
}

#[test]
fn every_library_module_and_crate_is_in_the_layout() {
    let paths = layout_paths();
    let named = |p: &str| paths.iter().any(|q| q.trim_end_matches('/') == p);
    for entry in std::fs::read_dir(root().join("crates/ccdsim/src")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name == "lib.rs" {
            continue;
        }
        let p = format!("crates/ccdsim/src/{name}");
        assert!(named(&p), "{p} is missing from ARCHITECTURE.md's layout");
    }
    for entry in std::fs::read_dir(root().join("crates")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let p = format!("crates/{name}");
        assert!(named(&p), "{p} is missing from ARCHITECTURE.md's layout");
    }
}

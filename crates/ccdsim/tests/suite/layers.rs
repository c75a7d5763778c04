//! The library's imports follow its layers (ARCHITECTURE.md, "Layers"): every module imports
//! only from its own layer or the layers below it, and no modules import each other in a loop
//! (through `crate::`, `super::` and `self::` paths, in `use` declarations or inline, and
//! through the crate root's re-exports). Files that import each other in a loop cannot be
//! understood, tested or moved on their own.
//!
//! A module's paths to its own children (`grid::Grid` in `cells/mod.rs`) are not counted: a
//! folder is one room seen from outside; the children's paths to it (`super::`) are.
//!
//! Test code (`tests.rs` files and `#[cfg(test)] mod tests { … }` at a file's end) is left out:
//! a test may import what it checks from anywhere.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every source file of the library, as its module path (`["finder", "cells", "grid"]`)
/// and its text without test code.
fn modules() -> BTreeMap<Vec<String>, String> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    walk(&src(), &mut files);
    let mut out = BTreeMap::new();
    for file in files {
        let rel = file.strip_prefix(src()).unwrap().with_extension("");
        let mut path: Vec<String> = rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        match path.last().map(String::as_str) {
            Some("tests") => continue,
            Some("mod") | Some("lib") => {
                path.pop();
            }
            _ => {}
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let code = match text.find("#[cfg(test)]\nmod tests {") {
            Some(at) => text[..at].to_string(),
            None => text,
        };
        out.insert(path, without_comments(&code));
    }
    out
}

/// `code` without `//` comments (doc comments name paths that are no imports).
fn without_comments(code: &str) -> String {
    code.lines()
        .map(|l| match l.find("//") {
            Some(at) if !l[..at].contains('"') => &l[..at],
            _ => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The paths a `use` tree names, with its braces expanded: `a::{b, c::{d, e}}` gives
/// `a::b`, `a::c::d`, `a::c::e`.
fn expand(tree: &str) -> Vec<String> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        return vec![tree.split(" as ").next().unwrap().trim().to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap()];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, ch) in inner.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.trim().is_empty())
        .flat_map(expand)
        .map(|p| format!("{prefix}{p}"))
        .collect()
}

/// The paths a module's code names: its `use` declarations, expanded, and the `crate::…`
/// and `super::…` paths written inline.
fn named_paths(code: &str) -> Vec<String> {
    let mut paths = Vec::new();
    let mut rest = code;
    while let Some(at) = find_use(rest) {
        let body = &rest[at..];
        let end = body.find(';').unwrap_or(body.len());
        let decl = body[..end].trim_start_matches("use ");
        paths.extend(expand(&decl.replace('\n', " ")));
        rest = &body[end..];
    }
    let is_path_char = |c: char| c.is_alphanumeric() || c == '_' || c == ':';
    for root in ["crate::", "super::"] {
        let mut from = 0;
        while let Some(at) = code[from..].find(root) {
            let start = from + at;
            let before = code[..start].chars().next_back();
            if !before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                let len = code[start..]
                    .find(|c: char| !is_path_char(c))
                    .unwrap_or(code.len() - start);
                paths.push(code[start..start + len].to_string());
            }
            from = start + root.len();
        }
    }
    paths
}

/// The offset of the next `use` declaration (at a line's start, perhaps `pub`).
fn find_use(code: &str) -> Option<usize> {
    let mut offset = 0;
    for line in code.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let skip = line.len() - trimmed.len();
        for lead in ["use ", "pub use ", "pub(crate) use ", "pub(super) use "] {
            if trimmed.starts_with(lead) {
                return Some(offset + skip + lead.len() - 4);
            }
        }
        offset += line.len();
    }
    None
}

/// The module a path names from module `here`, the longest prefix that is a file.
fn target(
    here: &[String],
    path: &str,
    modules: &BTreeMap<Vec<String>, String>,
) -> Option<Vec<String>> {
    let mut segments: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
    let mut base: Vec<String> = match segments.first().copied() {
        Some("crate") => Vec::new(),
        Some("super") | Some("self") => here.to_vec(),
        _ => return None,
    };
    if segments[0] == "crate" {
        segments.remove(0);
    }
    while let Some(&s) = segments.first() {
        match s {
            "super" => {
                base.pop()?;
            }
            "self" => {}
            _ => break,
        }
        segments.remove(0);
    }
    let mut best = None;
    let mut path = base;
    if modules.contains_key(&path) {
        best = Some(path.clone());
    }
    for s in segments {
        path.push(s.to_string());
        if modules.contains_key(&path) {
            best = Some(path.clone());
        }
    }
    best
}

/// Strongly connected components of more than one module (Tarjan's algorithm).
fn circles(graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<BTreeSet<String>> {
    struct State<'a> {
        graph: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'a Vec<String>, usize>,
        low: BTreeMap<&'a Vec<String>, usize>,
        stack: Vec<&'a Vec<String>>,
        on_stack: BTreeSet<&'a Vec<String>>,
        out: Vec<BTreeSet<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a Vec<String>) {
        let i = s.index.len();
        s.index.insert(v, i);
        s.low.insert(v, i);
        s.stack.push(v);
        s.on_stack.insert(v);
        for w in &s.graph[v] {
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = BTreeSet::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on_stack.remove(w);
                component.insert(w.join("::"));
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                s.out.push(component);
            }
        }
    }
    let mut s = State {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.out
}

#[test]
fn expand_reads_nested_use_trees() {
    assert_eq!(
        expand("crate::a::{b, c::{d, e as f}, self}"),
        [
            "crate::a::b",
            "crate::a::c::d",
            "crate::a::c::e",
            "crate::a::self"
        ]
    );
}

/// What each `pub use` of the crate root names, by the name it is re-exported as: a path
/// into the root (`crate::World`) is a path into that module.
fn root_reexports(modules: &BTreeMap<Vec<String>, String>) -> BTreeMap<String, Vec<String>> {
    let mut out = BTreeMap::new();
    let root = &modules[&Vec::new()];
    let mut rest = root.as_str();
    while let Some(at) = rest.find("pub use ") {
        let body = &rest[at + "pub use ".len()..];
        let end = body.find(';').unwrap_or(body.len());
        for path in expand(&body[..end].replace('\n', " ")) {
            let name = path.rsplit("::").next().unwrap().to_string();
            if let Some(t) = target(&[], &format!("crate::{path}"), modules) {
                out.insert(name, t);
            }
        }
        rest = &body[end..];
    }
    out
}

/// Every module's imports: the modules its code names (not itself, not the root, not its
/// own children).
fn import_graph(
    modules: &BTreeMap<Vec<String>, String>,
) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let reexports = root_reexports(modules);
    let mut graph: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    for (module, code) in modules {
        let edges = graph.entry(module.clone()).or_default();
        if module.is_empty() {
            continue;
        }
        for path in named_paths(code) {
            let Some(mut t) = target(module, &path, modules) else {
                continue;
            };
            if t.is_empty() {
                // `crate::Name`: the module the root re-exports `Name` from.
                let name = path
                    .trim_start_matches("crate::")
                    .split("::")
                    .next()
                    .unwrap();
                match reexports.get(name) {
                    Some(m) => t = m.clone(),
                    None => continue,
                }
            }
            if !t.starts_with(module) {
                edges.insert(t);
            }
        }
    }
    graph
}

/// The layers of ARCHITECTURE.md's "Layers" block, top first: each line `name: module …`,
/// a module named by its path (`observables::thermodynamic`).
fn layers() -> Vec<(String, Vec<Vec<String>>)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../ARCHITECTURE.md");
    let text = std::fs::read_to_string(path).unwrap();
    let section = text.split("## Layers").nth(1).expect("a Layers section");
    let block = section.split("```").nth(1).expect("a code block");
    block
        .lines()
        .filter_map(|l| l.split_once(':'))
        .map(|(name, mods)| {
            let mods = mods
                .split_whitespace()
                .map(|m| m.split("::").map(str::to_string).collect())
                .collect();
            (name.trim().to_string(), mods)
        })
        .collect()
}

/// The layer of `module` (0 the top): the layer naming the longest prefix of its path.
fn layer_of(module: &[String], layers: &[(String, Vec<Vec<String>>)]) -> Option<usize> {
    layers
        .iter()
        .enumerate()
        .flat_map(|(k, (_, mods))| mods.iter().map(move |m| (k, m)))
        .filter(|(_, m)| module.starts_with(m))
        .max_by_key(|(_, m)| m.len())
        .map(|(k, _)| k)
}

#[test]
fn no_import_circle() {
    let found = circles(&import_graph(&modules()));
    let show = |c: &BTreeSet<String>| c.iter().cloned().collect::<Vec<_>>().join(" ");
    assert!(
        found.is_empty(),
        "modules that import each other in a loop:\n{}",
        found.iter().map(show).collect::<Vec<_>>().join("\n")
    );
}

#[test]
fn imports_follow_the_layers() {
    let modules = modules();
    let layers = layers();
    assert!(layers.len() >= 5, "{layers:?}");
    let name = |m: &[String]| m.join("::");
    let mut problems = Vec::new();
    for (module, imports) in import_graph(&modules) {
        if module.is_empty() {
            continue;
        }
        let Some(here) = layer_of(&module, &layers) else {
            problems.push(format!("{} is in no layer", name(&module)));
            continue;
        };
        for t in imports {
            match layer_of(&t, &layers) {
                Some(there) if there < here => problems.push(format!(
                    "{} (layer {}) imports {} from the layer above it, {}",
                    name(&module),
                    layers[here].0,
                    name(&t),
                    layers[there].0
                )),
                _ => {}
            }
        }
    }
    for (layer, mods) in &layers {
        for m in mods {
            if !modules.contains_key(m) {
                problems.push(format!(
                    "layer {layer} names {}, which is no module",
                    name(m)
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_loop_and_an_upward_import_are_found() {
    let m = |s: &str| s.split("::").map(str::to_string).collect::<Vec<_>>();
    let mut graph = BTreeMap::new();
    graph.insert(m("a"), BTreeSet::from([m("b")]));
    graph.insert(m("b"), BTreeSet::from([m("a")]));
    graph.insert(m("c"), BTreeSet::from([m("a")]));
    let found = circles(&graph);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0], BTreeSet::from(["a".to_string(), "b".to_string()]));
    let layers = vec![
        ("top".to_string(), vec![m("c"), m("a::x")]),
        ("bottom".to_string(), vec![m("a"), m("b")]),
    ];
    assert_eq!(layer_of(&m("a::x::y"), &layers), Some(0));
    assert_eq!(layer_of(&m("a::z"), &layers), Some(1));
    assert_eq!(layer_of(&m("d"), &layers), None);
}

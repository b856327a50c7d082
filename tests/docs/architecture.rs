//! The library's layers point one way (ARCHITECTURE.md): every `crate::` path in a module of
//! `src/` names a module of its own layer or a lower one, but for the known debts listed here,
//! which may only shrink.

use std::collections::BTreeSet;
use std::path::Path;

/// Each top-level module's layer, as ARCHITECTURE.md's table gives it.
const LAYERS: &[(&str, u32)] = &[
    ("limits", 0),
    ("level", 1),
    ("builtin", 1),
    ("motion", 2),
    ("ladder", 2),
    ("shape", 2),
    ("oneway", 2),
    ("backend", 3),
    ("config", 3),
    ("controller", 3),
    ("sweep", 4),
    ("rapier", 4),
    ("box2d", 4),
    ("scenario", 5),
    ("trace", 5),
    ("parallel", 5),
    ("metrics", 6),
    ("registry", 7),
    ("stress", 8),
    ("tradeoff", 8),
    ("report", 9),
    ("suite", 9),
    ("cli", 10),
    ("prelude", 11),
];

/// The imports that point up (`from -> to`) and are known: none. The list may only shrink; an
/// upward import is a design change to argue in ARCHITECTURE.md, not a line to add here.
const KNOWN: &[&str] = &[];

fn layer(module: &str) -> Option<u32> {
    LAYERS.iter().find(|(m, _)| *m == module).map(|(_, l)| *l)
}

/// The identifier `s` starts with (after spaces).
fn leading_name(s: &str) -> String {
    s.trim()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// The top-level modules `text` names through `crate::` (comments left out).
fn crate_refs(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                // `use crate::{a, b::c}` on one line.
                let inner = group.split('}').next().unwrap_or("");
                out.extend(inner.split(',').map(leading_name).filter(|n| !n.is_empty()));
            } else {
                let name = leading_name(rest);
                if !name.is_empty() {
                    out.insert(name);
                }
            }
        }
    }
    out
}

/// A multi-line `use crate::{` group: its top-level names.
fn grouped_refs(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = text;
    while let Some(i) = rest.find("use crate::{") {
        rest = &rest[i + "use crate::{".len()..];
        let inner = rest.split('}').next().unwrap_or("");
        for part in inner.split(',') {
            let part = part
                .lines()
                .map(|l| l.split("//").next().unwrap_or(""))
                .collect::<String>();
            let name = leading_name(&part);
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Every import between two top-level modules of `src/`: `(from, to)`.
fn module_imports() -> BTreeSet<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut edges = BTreeSet::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let own = first.trim_end_matches(".rs").to_string();
        if own == "lib" {
            continue;
        }
        assert!(
            layer(&own).is_some(),
            "src/{own}: add it to ARCHITECTURE.md and LAYERS"
        );
        let text = std::fs::read_to_string(f).unwrap();
        for m in crate_refs(&text).union(&grouped_refs(&text)) {
            if *m != own && layer(m).is_some() {
                edges.insert((own.clone(), m.clone()));
            }
        }
    }
    edges
}

#[test]
fn imports_point_down_the_layers_but_for_the_known_debts() {
    let up: BTreeSet<String> = module_imports()
        .into_iter()
        .filter(|(from, to)| layer(to) > layer(from))
        .map(|(from, to)| format!("{from} -> {to}"))
        .collect();
    let known: BTreeSet<String> = KNOWN.iter().map(|s| s.to_string()).collect();
    let new: Vec<&String> = up.difference(&known).collect();
    assert!(
        new.is_empty(),
        "imports that point up the layers (ARCHITECTURE.md): {new:?}"
    );
    let gone: Vec<&String> = known.difference(&up).collect();
    assert!(
        gone.is_empty(),
        "known upward imports no longer there: remove them from KNOWN: {gone:?}"
    );
}

/// The modules `from` reaches through imports of its own layer.
fn reach_within_layer(edges: &BTreeSet<(String, String)>, from: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut todo = vec![from.to_string()];
    while let Some(m) = todo.pop() {
        for (a, b) in edges {
            if *a == m && layer(a) == layer(b) && seen.insert(b.clone()) {
                todo.push(b.clone());
            }
        }
    }
    seen
}

#[test]
fn modules_of_one_layer_import_each_other_one_way() {
    // Upward imports are the test above's; a cycle can also close inside a layer (backend and
    // controller both at layer 3), which the layer numbers alone do not catch.
    let edges = module_imports();
    let cyclic: Vec<&str> = LAYERS
        .iter()
        .map(|(m, _)| *m)
        .filter(|m| reach_within_layer(&edges, m).contains(*m))
        .collect();
    assert!(
        cyclic.is_empty(),
        "modules of one layer that import each other in a cycle: {cyclic:?}"
    );
}

#[test]
fn the_check_sees_an_upward_import() {
    // The reader finds each form of path the check relies on.
    let text = "use crate::metrics::MetricRow;\nuse crate::{scenario::RunConfig, level::Level};\nfn f() { crate::tradeoff::x(); } // crate::report\n";
    let refs = crate_refs(text);
    for m in ["metrics", "scenario", "level", "tradeoff"] {
        assert!(refs.contains(m), "{m}: {refs:?}");
    }
    assert!(!refs.contains("report"), "a comment is not an import");
    let grouped =
        grouped_refs("use crate::{\n    backend::X,\n    // crate::cli\n    motion::Y,\n};\n");
    assert_eq!(
        grouped,
        ["backend", "motion"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    );
}

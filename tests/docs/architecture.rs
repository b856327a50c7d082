//! The library's layers point one way (ARCHITECTURE.md): every `crate::`, `$crate::` and
//! `super::` path in a module of `src/` names a module of its own layer or a lower one; modules of
//! one layer never import each other in a cycle; and the table lists every module of `src/`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Each top-level module's layer, read from ARCHITECTURE.md's table (`| N | `name` | ... |`).
fn layers() -> BTreeMap<String, u32> {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let mut out = BTreeMap::new();
    for line in text.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 {
            continue;
        }
        if let (Ok(layer), Some(name)) = (
            cells[1].parse::<u32>(),
            cells[2].strip_prefix('`').and_then(|c| c.strip_suffix('`')),
        ) {
            assert!(
                out.insert(name.to_string(), layer).is_none(),
                "ARCHITECTURE.md lists {name} twice"
            );
        }
    }
    assert!(!out.is_empty(), "ARCHITECTURE.md has no layer table");
    out
}

/// `text` with comments, string literals and char literals blanked out, so that only code is
/// read (a `//` inside a string does not hide the rest of its line).
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            i += 2;
            while i + 1 < b.len() && !(b[i] == '*' && b[i + 1] == '/') {
                i += 1;
            }
            i += 2;
        } else if c == 'r' && (next == Some('"') || next == Some('#')) && !ident_before(&b, i) {
            // A raw string: r"..." or r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            while j < b.len()
                && !(b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')))
            {
                j += 1;
            }
            i = j + 1 + hashes;
            out.push(' ');
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                i += if b[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push(' ');
        } else if c == '\'' && (b.get(i + 2) == Some(&'\'') || next == Some('\\')) {
            // A char literal ('x' or '\n'), not a lifetime.
            i += 1;
            while i < b.len() && b[i] != '\'' {
                i += if b[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push(' ');
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_before(b: &[char], i: usize) -> bool {
    i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')
}

/// Identifiers and the punctuation a path is made of (`::`, `{`, `}`, `,`), in order.
fn tokens(code: &str) -> Vec<String> {
    let b: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_alphanumeric() || c == '_' || c == '$' {
            let s = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_' || b[i] == '$') {
                i += 1;
            }
            out.push(b[s..i].iter().collect());
        } else if c == ':' && b.get(i + 1) == Some(&':') {
            out.push("::".into());
            i += 2;
        } else {
            if matches!(c, '{' | '}' | ',' | ';') {
                out.push(c.to_string());
            } else if !c.is_whitespace() {
                out.push("#".into());
            }
            i += 1;
        }
    }
    out
}

/// The first segments of the paths that start at token `i` (just after a `::`): one name, or
/// each item's first name of a `{...}` group, nested groups included.
fn first_segments(t: &[String], i: usize) -> Vec<String> {
    match t.get(i).map(String::as_str) {
        Some("{") => {
            let mut out = Vec::new();
            let mut depth = 0;
            let mut expect = true;
            for tok in &t[i..] {
                match tok.as_str() {
                    "{" => {
                        depth += 1;
                        expect = depth == 1;
                    }
                    "}" => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    "," => expect = depth == 1,
                    name if expect => {
                        out.push(name.to_string());
                        expect = false;
                    }
                    _ => {}
                }
            }
            out
        }
        Some(name) => vec![name.to_string()],
        None => Vec::new(),
    }
}

/// The top-level modules a file of module path `module` (e.g. `["sweep", "resolve"]`) names
/// through `crate::`, `$crate::` and `super::` paths.
fn refs(text: &str, module: &[String]) -> BTreeSet<String> {
    let t = tokens(&code_only(text));
    let mut out = BTreeSet::new();
    let mut i = 0;
    while i + 1 < t.len() {
        let starts = i == 0 || t[i - 1] != "::";
        if starts && (t[i] == "crate" || t[i] == "$crate") && t[i + 1] == "::" {
            out.extend(first_segments(&t, i + 2));
        } else if starts && t[i] == "super" && t[i + 1] == "::" {
            let mut ups = 1;
            let mut j = i + 2;
            while t.get(j).map(String::as_str) == Some("super")
                && t.get(j + 1).map(String::as_str) == Some("::")
            {
                ups += 1;
                j += 2;
            }
            // `super` from a file's module goes up `ups` levels; reaching the crate root, the
            // next segment is a top-level module.
            if ups >= module.len() {
                out.extend(first_segments(&t, j));
            }
        }
        i += 1;
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// A file's module path under `src/`: `sweep/resolve.rs` is `["sweep", "resolve"]`,
/// `sweep/mod.rs` is `["sweep"]`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// Every import between two top-level modules: `(from, to)`. Files `lib.rs` pulls in with
/// `#[path]` from outside `src/` count as the module they are declared as.
fn module_imports(layers: &BTreeMap<String, u32>) -> BTreeSet<(String, String)> {
    let src = root().join("src");
    let mut files: Vec<(PathBuf, Vec<String>)> = Vec::new();
    let mut found = Vec::new();
    rust_files(&src, &mut found);
    for f in found {
        let module = module_path(f.strip_prefix(&src).unwrap());
        if module != ["lib"] {
            files.push((f, module));
        }
    }
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    let lines: Vec<&str> = lib.lines().collect();
    for (k, line) in lines.iter().enumerate() {
        if let Some(path) = line.trim().strip_prefix("#[path = \"") {
            let path = path.trim_end_matches("\"]");
            let decl = lines[k + 1];
            let name = decl.rsplit("mod ").next().unwrap().trim_end_matches(';');
            files.push((src.join(path), vec![name.to_string()]));
        }
    }
    let mut edges = BTreeSet::new();
    for (f, module) in &files {
        let own = &module[0];
        assert!(
            layers.contains_key(own),
            "src/{own}: add it to ARCHITECTURE.md's table"
        );
        let text = std::fs::read_to_string(f).unwrap();
        for m in refs(&text, module) {
            if m != *own && layers.contains_key(&m) {
                edges.insert((own.clone(), m));
            }
        }
    }
    edges
}

#[test]
fn imports_point_down_the_layers() {
    let layers = layers();
    let up: Vec<String> = module_imports(&layers)
        .into_iter()
        .filter(|(from, to)| layers[to] > layers[from])
        .map(|(from, to)| format!("{from} -> {to}"))
        .collect();
    assert!(
        up.is_empty(),
        "imports that point up the layers (ARCHITECTURE.md): {up:?}"
    );
}

#[test]
fn modules_of_one_layer_import_each_other_one_way() {
    // A cycle can also close inside a layer (backend and controller both at layer 3), which the
    // layer numbers alone do not catch.
    let layers = layers();
    let edges: Vec<(String, String)> = module_imports(&layers)
        .into_iter()
        .filter(|(a, b)| layers[a] == layers[b])
        .collect();
    let reach = |from: &str| {
        let mut seen = BTreeSet::new();
        let mut todo = vec![from.to_string()];
        while let Some(m) = todo.pop() {
            for (a, b) in &edges {
                if *a == m && seen.insert(b.clone()) {
                    todo.push(b.clone());
                }
            }
        }
        seen
    };
    let cyclic: Vec<&String> = layers.keys().filter(|m| reach(m).contains(*m)).collect();
    assert!(
        cyclic.is_empty(),
        "modules of one layer that import each other in a cycle: {cyclic:?}"
    );
}

#[test]
fn the_table_lists_the_modules_lib_rs_declares() {
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let declared: BTreeSet<String> = lib
        .lines()
        .filter_map(|l| l.trim().rsplit_once("mod "))
        .map(|(_, name)| name.trim_end_matches(';').to_string())
        .collect();
    let listed: BTreeSet<String> = layers().into_keys().collect();
    assert_eq!(declared, listed, "src/lib.rs against ARCHITECTURE.md");
}

#[test]
fn the_reader_sees_every_form_of_path() {
    let m = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let set = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<BTreeSet<_>>();
    let top = m(&["sweep", "resolve"]);
    for (text, want) in [
        ("use crate::metrics::MetricRow;", set(&["metrics"])),
        (
            "use crate::{scenario::Runner, level::Level};",
            set(&["level", "scenario"]),
        ),
        // The cases a line-by-line reader missed: a nested group, a group over lines, a
        // `super::` chain to the crate root, a `//` in a string, spaces around `::`.
        (
            "use crate::{level::{Level, Tile}, report::Table};",
            set(&["level", "report"]),
        ),
        (
            "use crate::{\n    level::{Level, Tile},\n    report::Table,\n};",
            set(&["level", "report"]),
        ),
        ("use super::super::report::Table;", set(&["report"])),
        (
            "let u = \"http://x\"; crate::report::f();",
            set(&["report"]),
        ),
        ("use crate :: report :: Table;", set(&["report"])),
        (
            "macro_rules! m { () => { $crate::trace::x() } }",
            set(&["trace"]),
        ),
        // Not imports: comments, strings, a `super` inside the module, a path's inner segment.
        (
            "// crate::report\n/* crate::cli */ let s = \"crate::cli\";",
            set(&[]),
        ),
        (
            "use super::space::Space; let c = 'c'; fn f<'a>(x: &'a u8) {}",
            set(&[]),
        ),
        ("use glam::crate_like::x; use other::super_thing;", set(&[])),
    ] {
        assert_eq!(refs(text, &top), want, "{text}");
    }
    // From a module's own `mod.rs`, one `super` reaches the root.
    assert_eq!(
        refs("use super::report::X;", &m(&["sweep"])),
        set(&["report"])
    );
}

//! The table that closes a `cargo bench --bench step` run: each sweep configuration's median
//! time per character step on each built-in scenario, as a ratio to the bound's (the direct
//! tile-grid sweep of [`super`]), read back from the estimates criterion has just written.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where criterion writes its estimates, found as criterion finds it: `$CRITERION_HOME`, else
/// `$CARGO_TARGET_DIR/criterion`, else the `criterion` folder of the target directory this
/// bench binary was built in (`target/release/deps/step-*` → `target/criterion`).
fn criterion_dir() -> Option<PathBuf> {
    if let Some(home) = std::env::var_os("CRITERION_HOME") {
        return Some(home.into());
    }
    if let Some(target) = std::env::var_os("CARGO_TARGET_DIR") {
        return Some(Path::new(&target).join("criterion"));
    }
    let exe = std::env::current_exe().ok()?;
    Some(exe.parent()?.parent()?.parent()?.join("criterion"))
}

/// Every `(group, function) → median ns per iteration` criterion holds from its latest run of
/// each benchmark (the `new` folders).
fn medians(dir: &Path) -> BTreeMap<(String, String), f64> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.file_name().is_some_and(|n| n == "benchmark.json")
                && p.parent()
                    .and_then(|q| q.file_name())
                    .is_some_and(|n| n == "new")
            {
                if let Some(row) = read_pair(&p) {
                    out.insert((row.0, row.1), row.2);
                }
            }
        }
    }
    out
}

/// `(group, function, median ns)` from one benchmark's `benchmark.json` and `estimates.json`.
fn read_pair(benchmark: &Path) -> Option<(String, String, f64)> {
    let read = |p: &Path| -> Option<serde_json::Value> {
        serde_json::from_str(&std::fs::read_to_string(p).ok()?).ok()
    };
    let id = read(benchmark)?;
    let est = read(&benchmark.with_file_name("estimates.json"))?;
    Some((
        id["group_id"].as_str()?.to_string(),
        id["function_id"].as_str()?.to_string(),
        est["median"]["point_estimate"].as_f64()?,
    ))
}

/// Prints the ratio table (nothing if the bound or no sweep step was measured, as when a
/// filter left them out).
pub fn print() {
    let Some(dir) = criterion_dir() else {
        return;
    };
    let m = medians(&dir);
    let bound: Vec<(&str, f64)> = m
        .iter()
        .filter(|((g, _), _)| g == "bound")
        .map(|((_, f), ns)| (f.as_str(), *ns))
        .collect();
    // The ratio's denominator is the cheapest bound measured: the stricter comparison.
    let Some(&(bound_name, bound_ns)) = bound.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
        return;
    };
    let mut configs: Vec<&str> = Vec::new();
    let mut rows: BTreeMap<&str, BTreeMap<&str, f64>> = BTreeMap::new();
    for ((g, f), ns) in &m {
        let (Some(scenario), true) = (g.strip_prefix("step/"), f.starts_with("sweep/")) else {
            continue;
        };
        if !configs.contains(&f.as_str()) {
            configs.push(f);
        }
        rows.entry(scenario).or_default().insert(f, *ns);
    }
    if rows.is_empty() {
        return;
    }
    let others: Vec<String> = bound
        .iter()
        .map(|(n, ns)| format!("{n} {ns:.1} ns"))
        .collect();
    println!();
    println!(
        "The sweep's median time per character step as a ratio to the bound ({bound_name}, \
         {bound_ns:.1} ns; measured: {}), from the latest run of each bench in {}:",
        others.join(", "),
        dir.display()
    );
    // Each column as wide as its configuration's name, and never narrower than a cell.
    let width = |c: &str| c.len().max(18) + 2;
    print!("{:<40}", "scenario");
    for c in &configs {
        print!("{c:>w$}", w = width(c));
    }
    println!();
    let mut worst: BTreeMap<&str, (f64, &str)> = BTreeMap::new();
    for (scenario, cells) in &rows {
        print!("{scenario:<40}");
        for c in &configs {
            match cells.get(c) {
                Some(ns) => {
                    let r = ns / bound_ns;
                    print!("{:>w$}", format!("{r:.2}x ({ns:.0} ns)"), w = width(c));
                    let w = worst.entry(c).or_insert((0.0, scenario));
                    if r > w.0 {
                        *w = (r, scenario);
                    }
                }
                None => print!("{:>w$}", "-", w = width(c)),
            }
        }
        println!();
    }
    for (c, (r, s)) in &worst {
        println!("worst for {c}: {r:.2}x on {s}");
    }
}

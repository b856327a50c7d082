//! Shared helpers for the integration tests: the built-in levels and runs over them.
#![allow(dead_code)]

#[path = "../../compare/builtin.rs"]
mod builtin;

use platbench::level::{parse_level, Level};
use platbench::metrics::{evaluate, Evaluation, MetricRow};
use platbench::scenario::RunConfig;

/// Every built-in level, parsed.
pub fn builtin_levels() -> Vec<Level> {
    builtin::LEVELS
        .iter()
        .map(|(f, t)| parse_level(t, f).expect("built-in level parses"))
        .collect()
}

/// One built-in level by name.
pub fn level(name: &str) -> Level {
    builtin_levels()
        .into_iter()
        .find(|l| l.name == name)
        .unwrap_or_else(|| panic!("no built-in level {name}"))
}

/// Runs every scenario of `levels` on `run`.
pub fn evaluate_all(levels: &[Level], run: &RunConfig) -> Vec<(String, Evaluation)> {
    let mut out = Vec::new();
    for l in levels {
        for s in &l.scenarios {
            let e = evaluate(l, s, run).expect("scenario runs");
            out.push((format!("{}.{}", l.name, s.name), e));
        }
    }
    out
}

/// All rows of metric `m`, which must exist: a loop over them asserts nothing if there are none,
/// so a metric that stopped being measured fails here instead of passing silently.
pub fn some_rows<'a>(evals: &'a [(String, Evaluation)], m: &str) -> Vec<&'a MetricRow> {
    let r = rows(evals, m);
    assert!(!r.is_empty(), "no {m} rows measured");
    r
}

/// All rows of metric `m`.
pub fn rows<'a>(evals: &'a [(String, Evaluation)], m: &str) -> Vec<&'a MetricRow> {
    evals
        .iter()
        .flat_map(|(_, e)| e.metrics.iter())
        .filter(|r| r.metric == m)
        .collect()
}

/// The `platbench` binary, to run as a user does.
pub fn platbench() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_platbench"))
}

/// Fails the test with the command's stderr unless it exited successfully.
pub fn assert_success(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The value of metric `metric` on the scenario named `scenario`.
pub fn value(evals: &[(String, Evaluation)], scenario: &str, metric: &str) -> f64 {
    rows(evals, metric)
        .into_iter()
        .find(|r| r.scenario == scenario)
        .unwrap_or_else(|| panic!("{metric} on {scenario}"))
        .value
}

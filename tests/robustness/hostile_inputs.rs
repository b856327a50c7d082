//! Hostile input, part two: diff fails on NaN, missing and truncated traces; input that
//! panicked inside a dependency is an error; silently accepted input is an error or a warning;
//! the small things (damaged files, counts, ignored flags).

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{assert_success, platbench};

use super::hostile::{assert_error, quick_level, run_quick, stderr};

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// `platbench diff BASE NEW EXTRA...`
pub(super) fn diff(base: &Path, new: &Path, extra: &[&str]) -> Output {
    platbench()
        .arg("diff")
        .arg(base)
        .arg(new)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn diff_fails_on_nan_missing_and_truncated_traces_and_refuses_bad_tolerances() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let base = dir.path().join("base");
    assert_success(&run_quick(&level, &base, &[]));
    let trace = "traces/quick.stand.sweep.csv";
    let fresh = |name: &str| {
        let new = dir.path().join(name);
        copy_dir(&base, &new);
        new
    };
    // A copy is the same run: exit 0.
    let same = fresh("same");
    assert_eq!(diff(&base, &same, &[]).status.code(), Some(0));

    // Every position NaN: once "0 diverge" and exit 0.
    let nan = fresh("nan");
    let text = std::fs::read_to_string(nan.join(trace)).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for l in lines.iter_mut().skip(1) {
        let mut f: Vec<&str> = l.split(',').collect();
        f[3] = "NaN";
        f[4] = "NaN";
        *l = f.join(",");
    }
    std::fs::write(nan.join(trace), lines.join("\n") + "\n").unwrap();
    let out = diff(&base, &nan, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("1 trace(s) diverge"),
        "{}",
        stderr(&out)
    );
    assert_eq!(
        diff(&base, &nan, &["--allow-divergence"]).status.code(),
        Some(0)
    );

    // Truncated: the last frames cut off.
    let cut = fresh("cut");
    std::fs::write(
        cut.join(trace),
        text.lines().take(10).collect::<Vec<_>>().join("\n") + "\n",
    )
    .unwrap();
    let out = diff(&base, &cut, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("end before"), "{}", stderr(&out));

    // Missing: a trace and a metric row of the baseline gone.
    let gone = fresh("gone");
    std::fs::remove_file(gone.join(trace)).unwrap();
    let metrics = std::fs::read_to_string(gone.join("metrics.csv")).unwrap();
    let kept: Vec<&str> = metrics
        .lines()
        .filter(|l| !l.contains(",rest_gap,"))
        .collect();
    assert!(kept.len() < metrics.lines().count());
    std::fs::write(gone.join("metrics.csv"), kept.join("\n") + "\n").unwrap();
    let out = diff(&base, &gone, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("trace(s) of the baseline are missing"),
        "{err}"
    );
    assert!(
        err.contains("metric(s) of the baseline are missing"),
        "{err}"
    );
    assert_eq!(
        diff(&base, &gone, &["--allow-missing"]).status.code(),
        Some(0)
    );

    // Tolerances that would pass anything, and a metric that does not exist.
    for (args, needle) in [
        (vec!["--position-tolerance", "NaN"], "--position-tolerance"),
        (vec!["--position-tolerance", "inf"], "--position-tolerance"),
        (vec!["--position-tolerance", "-1"], "--position-tolerance"),
        (vec!["--tol", "rest_gap=nan"], "--tol"),
        (vec!["--tol", "rest_gap=1,inf"], "--tol"),
        (vec!["--tol", "rest_gap=-1"], "--tol"),
        (vec!["--tol", "no_such_metric=1"], "no metric is named"),
    ] {
        assert_error(&diff(&base, &nan, &args), needle);
    }
}

// ---- 4. no panic text from any input ----------------------------------------------------

#[test]
fn a_tiled_layer_shorter_than_its_map_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("short.tmx");
    // A 4 x 2 map whose only layer holds 5 of its 8 cells.
    std::fs::write(
        &map,
        "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"4\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n <tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\"/>\n <layer id=\"1\" name=\"ground\" width=\"4\" height=\"2\">\n  <data encoding=\"csv\">\n0,0,0,0,\n1\n</data>\n </layer>\n</map>\n",
    )
    .unwrap();
    let out = platbench()
        .arg("run")
        .arg(&map)
        .arg("--out")
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    assert_error(
        &out,
        "holds 5 comma-separated cells; expected exactly 8 cells",
    );
    assert!(
        !stderr(&out).contains("index out of bounds"),
        "{}",
        stderr(&out)
    );
}

// ---- 5. what was accepted silently ------------------------------------------------------

#[test]
fn silently_accepted_levels_are_errors_or_warnings_that_say_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        // rest_gap = inf, silently.
        (
            "name = \"a\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [100.5, 1.0]\nduration = 1.0\n",
            "is outside the map",
        ),
        (
            "name = \"b\"\nmap = \"\"\"\n#...\n####\n\"\"\"\n[legend]\n\"#\" = \"empty\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\n",
            "cannot be redefined as empty",
        ),
        // Every position collapsed, and the summary blamed Rapier.
        (
            "name = \"c\"\norigin = [1e30, 1e30]\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\n",
            "origin x is 1",
        ),
        // Zero steps.
        (
            "name = \"d\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\ndt = 1e30\n",
            "expected a time step",
        ),
    ];
    for (text, needle) in cases {
        let path = dir.path().join("l.toml");
        std::fs::write(&path, text).unwrap();
        let out = platbench()
            .arg("run")
            .arg(&path)
            .arg("--out")
            .arg(dir.path().join("o"))
            .output()
            .unwrap();
        assert_error(&out, needle);
        assert!(stderr(&out).contains("l.toml:"), "{}", stderr(&out));
    }
    // A level with no scenarios is skipped with a warning (a 0-cost, 0-error setting once
    // reached the trade-off's front); the other level runs.
    let empty = dir.path().join("empty.toml");
    std::fs::write(
        &empty,
        "name = \"empty\"\nmap = \"\"\"\n....\n####\n\"\"\"\n",
    )
    .unwrap();
    let level = quick_level(dir.path());
    let out = platbench()
        .arg("run")
        .arg(&empty)
        .arg(&level)
        .args(["--backend", "sweep", "--out"])
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    assert_success(&out);
    assert!(
        stderr(&out).contains("empty.toml: the level has no scenario"),
        "{}",
        stderr(&out)
    );
    // Alone, it is an error: nothing would run.
    let out = platbench()
        .args(["sweep", "--out"])
        .arg(dir.path().join("s"))
        .arg(&empty)
        .output()
        .unwrap();
    assert_error(&out, "none of the level files has a scenario to run");
}

#[test]
fn report_refuses_a_damaged_tradeoff_file_naming_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let trade = dir.path().join("tradeoff.csv");
    // `report LEVEL --tradeoff FILE` with FILE holding `text`.
    let report_with = |text: &str| {
        std::fs::write(&trade, text).unwrap();
        platbench()
            .arg("report")
            .arg(&level)
            .arg("--tradeoff")
            .arg(&trade)
            .args(["--backend", "sweep", "--out"])
            .arg(dir.path().join("r"))
            .output()
            .unwrap()
    };
    let head = "backend,setting,cost_us,error,pareto,scenarios\n";
    let out = report_with(&format!(
        "{head}sweep,dt=1/60,2.5,0.01,true,1\nsweep,dt=1/30,NaN,0.01,false,1\n"
    ));
    assert_error(&out, "tradeoff.csv:3: cost_us is NaN");
    let out = report_with(&format!("{head}sweep,dt=1/60,-1e308,0.01,true,1\n"));
    assert_error(&out, "tradeoff.csv:2: cost_us is -1");
    // One row past src/limits.rs MAX_TRADEOFF_ROWS (100,000) is refused at its line before the
    // run; the chart drew an element per row (2.6 million rows took 3.8 GB).
    let rows: String = (0..=100_000)
        .map(|k| format!("sweep,dt=1/{k},2.5,0.01,false,1\n"))
        .collect();
    let out = report_with(&format!("{head}{rows}"));
    assert_error(&out, "tradeoff.csv:100002: more than 100000 rows");
}

// ---- 6. the small things ----------------------------------------------------------------

#[test]
fn the_header_counts_the_traces_written_and_stderr_stays_clean_off_a_terminal() {
    // The built-in set on the sweep's three configurations. Integer positions once skipped the
    // levels with slopes or moving platforms, which the header once counted anyway; since they
    // model both, every configuration runs all 64 scenarios, so the header counts 192 runs, all
    // written, and announces no skip.
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("o");
    let out = platbench()
        .args(["run", "--backend", "sweep", "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert_success(&out);
    let err = stderr(&out);
    let runs: usize = err
        .split_once(" runs")
        .and_then(|(head, _)| head.rsplit('(').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no run count in: {err}"));
    let written = std::fs::read_dir(out_dir.join("traces")).unwrap().count();
    assert_eq!(runs, written, "{err}");
    assert!(err.contains(&format!("wrote {written} traces")), "{err}");
    assert_eq!(runs, 64 * 3, "{err}");
    assert!(!err.contains("skipped"), "{err}");
    // No progress line rewritten in place: stderr is a pipe here, as in CI.
    assert!(!err.contains('\r') && !err.contains('\x1b'), "{err:?}");
}

#[test]
fn shape_without_a_rapier_backend_is_an_error_and_the_rules_map_runs_alone() {
    let out = platbench()
        .args(["run", "--backend", "sweep", "--shape", "ball"])
        .output()
        .unwrap();
    assert_error(&out, "add --backend rapier");
    let dir = tempfile::tempdir().unwrap();
    let out = platbench()
        .arg("run")
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/maps/rules.tmx"))
        .args(["--backend", "sweep", "--out"])
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    assert_success(&out);
}

#[test]
fn a_toml_level_past_32_mib_is_refused_before_it_is_read() {
    // MAX_TOML_BYTES (src/limits.rs): 32 MiB; one byte more is refused by its size, unread.
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("big.toml");
    let mut big = std::fs::read_to_string(quick_level(dir.path())).unwrap();
    big.push_str(&"#".repeat(32 * 1024 * 1024 + 1 - big.len()));
    std::fs::write(&level, &big).unwrap();
    let out = platbench().arg("run").arg(&level).output().unwrap();
    assert_error(&out, "big.toml: it holds more than 32 MiB");
}

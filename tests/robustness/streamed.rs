//! Hostile input, part four (issue 40): `diff` streams its inputs, so what it finds and
//! refuses far down a file is seen through what it reports: a malformed row named by its line
//! and field, a repeat named by both lines, a trace that differs only at its last frame found,
//! and a bad row past a divergence still refused. Each file is a few rows written for the case.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::{Path, PathBuf};

use super::hostile::{assert_error, stderr};
use super::hostile_inputs::diff;

const METRICS: &str =
    "level,scenario,backend,config,metric,value,unit,reference,error,frame,q1,q3\n";
const TRACE: &str =
    "frame,t,character,x,y,vx,vy,grounded,ground_nx,ground_ny,platform,ladder,crushed\n";

/// A run directory `name` holding `rows` (after the header) as its metrics.csv and `trace`
/// rows, if any, as the trace `l.s.sweep.csv`.
fn run_dir(root: &Path, name: &str, rows: &str, trace: Option<&str>) -> PathBuf {
    let d = root.join(name);
    std::fs::create_dir_all(d.join("traces")).unwrap();
    std::fs::write(d.join("metrics.csv"), format!("{METRICS}{rows}")).unwrap();
    if let Some(t) = trace {
        std::fs::write(d.join("traces/l.s.sweep.csv"), format!("{TRACE}{t}")).unwrap();
    }
    d
}

/// A metrics row of metric `m` with value `v` (reference 0).
fn row(m: &str, v: &str) -> String {
    format!("l,s,sweep,default,{m},{v},tiles,0.0,{v},,,\n")
}

/// Trace rows for frames `0..n`, x = frame, the last frame's x replaced by `last_x`.
fn frames(n: u32, last_x: &str) -> String {
    (0..n)
        .map(|f| {
            let x = if f + 1 == n {
                last_x.to_string()
            } else {
                f.to_string()
            };
            format!("{f},0.0,0,{x},1.0,0.0,0.0,1,0.0,1.0,,0,0\n")
        })
        .collect()
}

#[test]
fn a_malformed_metric_far_down_is_named_by_file_line_field_and_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let good: String = ["rest_gap", "max_penetration", "tunneling", "air_time"]
        .iter()
        .map(|m| row(m, "0.0"))
        .collect();
    let base = run_dir(dir.path(), "base", &good, None);
    // The fifth row (line 6) holds a word where its value belongs.
    let bad = format!("{good}{}", row("jump_height", "tall"));
    let new = run_dir(dir.path(), "new", &bad, None);
    assert_error(
        &diff(&base, &new, &[]),
        &format!(
            "{}:6: field 6 (value): found \"tall\"; expected a number",
            new.join("metrics.csv").display()
        ),
    );
    // A frame that is no frame number, in the baseline this time: the baseline's file named.
    let bad_frame = format!("{good}l,s,sweep,default,jump_height,0.0,tiles,0.0,0.0,-3,,\n");
    let odd = run_dir(dir.path(), "odd", &bad_frame, None);
    assert_error(
        &diff(&odd, &base, &[]),
        &format!(
            "{}:6: field 10 (frame): found \"-3\"; expected a whole number",
            odd.join("metrics.csv").display()
        ),
    );
}

#[test]
fn a_repeat_far_from_its_first_row_names_both_lines_in_either_file() {
    let dir = tempfile::tempdir().unwrap();
    let rows: String = ["rest_gap", "max_penetration", "tunneling"]
        .iter()
        .map(|m| row(m, "0.0"))
        .collect();
    let base = run_dir(dir.path(), "base", &rows, None);
    // rest_gap (line 2) again at line 5: in the new run's file, then in the baseline's.
    let repeated = format!("{rows}{}", row("rest_gap", "0.5"));
    let new = run_dir(dir.path(), "new", &repeated, None);
    assert_error(&diff(&base, &new, &[]), ":5: the row repeats line 2");
    assert_error(&diff(&new, &base, &[]), ":5: the row repeats line 2");
    // A repeat of a row the baseline lacks (an added row) too.
    let added = format!("{rows}{}{}", row("air_time", "1"), row("air_time", "2"));
    let new = run_dir(dir.path(), "added", &added, None);
    assert_error(&diff(&base, &new, &[]), ":6: the row repeats line 5");
}

#[test]
fn verdicts_come_in_the_baseline_s_order_then_the_added_rows_in_the_new_run_s() {
    let dir = tempfile::tempdir().unwrap();
    let base = run_dir(
        dir.path(),
        "base",
        &[
            row("tunneling", "0"),
            row("rest_gap", "0.0"),
            row("max_penetration", "0.0"),
        ]
        .concat(),
        None,
    );
    // The new run lists them in another order: max_penetration worse, tunneling missing, two
    // rows added.
    let new = run_dir(
        dir.path(),
        "new",
        &[
            row("air_time", "1"),
            row("max_penetration", "0.5"),
            row("rest_gap", "0.0"),
            row("jump_height", "2"),
        ]
        .concat(),
        None,
    );
    let out = diff(&base, &new, &["--format", "csv"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let order: Vec<(&str, &str)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[2], f[5])
        })
        .collect();
    assert_eq!(
        order,
        [
            ("tunneling", "missing"),
            ("max_penetration", "worse"),
            ("air_time", "added"),
            ("jump_height", "added"),
        ],
        "{text}"
    );
}

#[test]
fn a_trace_differing_only_at_its_last_frame_is_found_and_a_bad_row_past_a_divergence_refused() {
    let dir = tempfile::tempdir().unwrap();
    let m = row("rest_gap", "0.0");
    let base = run_dir(dir.path(), "base", &m, Some(&frames(200, "199")));
    let same = run_dir(dir.path(), "same", &m, Some(&frames(200, "199")));
    assert_eq!(diff(&base, &same, &[]).status.code(), Some(0));
    // Frame 199 of 200 moved half a tile: found there, exit 1.
    let last = run_dir(dir.path(), "last", &m, Some(&frames(200, "199.5")));
    let out = diff(&base, &last, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(text.contains("| 199 "), "{text}");
    assert!(text.contains("(199.5, 1)"), "{text}");
    // Diverged at frame 0, and its last row (line 201) holds a word: still an error, naming
    // the line (the files are read to their end past a divergence).
    let mut rows = frames(200, "oops");
    rows.replace_range(
        ..rows.find('\n').unwrap(),
        "0,0.0,0,5,1.0,0.0,0.0,1,0.0,1.0,,0,0",
    );
    let bad = run_dir(dir.path(), "bad", &m, Some(&rows));
    let trace = bad.join("traces/l.s.sweep.csv");
    assert_error(
        &diff(&base, &bad, &[]),
        &format!("{}:201: field 4 (x): found \"oops\"", trace.display()),
    );
    // One row short at the end: truncated at the 199 rows both have.
    let cut = run_dir(dir.path(), "cut", &m, Some(&frames(199, "198")));
    let out = diff(&base, &cut, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("end before"), "{}", stderr(&out));
}

#[test]
fn an_empty_metrics_file_or_trace_is_refused_not_read_as_a_run_of_no_rows() {
    // A 0-byte baseline passed `diff` (every new row "added", exit 0) and a 0-byte new run
    // failed it only as "missing" rows: either is a damaged file, exit 2.
    let root = tempfile::tempdir().unwrap();
    let full = run_dir(root.path(), "full", &row("rest_gap", "0.0"), None);
    let empty = root.path().join("empty");
    std::fs::create_dir_all(empty.join("traces")).unwrap();
    std::fs::write(empty.join("metrics.csv"), "").unwrap();
    for (base, new) in [(&empty, &full), (&full, &empty)] {
        let out = diff(base, new, &[]);
        assert_error(&out, "metrics.csv: the file is empty");
    }
    // An empty trace beside a whole one.
    let a = run_dir(
        root.path(),
        "a",
        &row("rest_gap", "0.0"),
        Some(&frames(3, "2")),
    );
    let b = run_dir(root.path(), "b", &row("rest_gap", "0.0"), Some(""));
    std::fs::write(b.join("traces/l.s.sweep.csv"), "").unwrap();
    let out = diff(&a, &b, &[]);
    assert_error(&out, "l.s.sweep.csv: the file is empty");
}

#[test]
fn a_row_longer_than_the_record_limit_is_refused_at_its_line_before_it_is_buffered() {
    // A metrics row holding a 1 GB field was read into one buffer and aborted at 3 GB; a
    // trace frame likewise. The limit is src/limits.rs's MAX_CSV_RECORD_BYTES (1 MiB): one
    // byte past it, at line 3 of each file (the header is line 1), is refused there. A quoted
    // field's newlines stay inside its record, so they do not reset the count.
    let root = tempfile::tempdir().unwrap();
    let long = "x".repeat(1024 * 1024);
    let base = run_dir(
        root.path(),
        "base",
        &row("rest_gap", "0.0"),
        Some(&frames(3, "2")),
    );
    let quoted = format!("\"{}\"", long.replacen('x', "\n", 1000));
    for (name, metrics, trace) in [
        (
            "metrics",
            row("rest_gap", "0.0") + &row(&long, "0.0"),
            frames(3, "2"),
        ),
        (
            "quoted",
            row("rest_gap", "0.0") + &row(&quoted, "0.0"),
            frames(3, "2"),
        ),
        (
            "trace",
            row("rest_gap", "0.0"),
            frames(1, "0") + &frames(1, &long),
        ),
    ] {
        let new = run_dir(root.path(), name, &metrics, Some(&trace));
        let out = diff(&base, &new, &[]);
        assert_error(&out, "line 3: the row passes 1048576 bytes");
    }
}

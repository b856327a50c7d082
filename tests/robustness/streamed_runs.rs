//! Hostile input, part five (issue 40): `check` and `review` read a run's metrics and traces a
//! row at a time, keeping what they list or show (a run's name, the rows of a run shown, a
//! trace's drawn frames), never a file whole. What they read far down a file is seen through
//! what they report: each run counted once however many rows it has, a damaged row at the end
//! named by its line, a long trace drawn at its drawn frames and a damaged one left out.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::{assert_success, platbench};

use super::hostile::{assert_error, quick_level, stderr};

/// A baseline of the quick level on the sweep's three configurations (three runs, twelve
/// metric rows each, traces of 31 frames), in `dir/baseline`.
fn baseline(dir: &Path) -> PathBuf {
    let bl = dir.join("baseline");
    let out = platbench()
        .arg("baseline")
        .arg(quick_level(dir))
        .args(["--backend", "sweep", "--baseline"])
        .arg(&bl)
        .output()
        .unwrap();
    assert_success(&out);
    bl
}

/// `platbench check --baseline BL --out DIR/NAME`.
fn check(bl: &Path, dir: &Path, name: &str) -> (Output, PathBuf) {
    let ck = dir.join(name);
    let out = platbench()
        .arg("check")
        .arg("--baseline")
        .arg(bl)
        .arg("--out")
        .arg(&ck)
        .output()
        .unwrap();
    (out, ck)
}

/// Appends `text` to the file at `path`.
fn append(path: &Path, text: &str) {
    let mut bytes = std::fs::read(path).unwrap();
    bytes.extend_from_slice(text.as_bytes());
    std::fs::write(path, bytes).unwrap();
}

/// Appends `gone` (rows of runs the check does not run) to the baseline `bl`'s metrics, checks
/// against it, and returns what it printed and its --out: a run missing fails the check (exit 1).
fn check_with_gone(bl: &Path, dir: &Path, gone: &str) -> (String, PathBuf) {
    append(&bl.join("metrics.csv"), gone);
    let (out, ck) = check(bl, dir, "check");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    (String::from_utf8_lossy(&out.stdout).into_owned(), ck)
}

/// A trace row of frame `f` at x = `x` (standing on the floor).
fn frame(f: u32, x: &str) -> String {
    format!("{f},{},0,{x},1.0,0.0,0.0,1,0.0,1.0,,0,0\n", f as f32 / 60.0)
}

#[test]
fn check_lists_each_run_once_however_many_rows_it_has() {
    let dir = tempfile::tempdir().unwrap();
    let bl = baseline(dir.path());
    // 200 scenarios of a level the check does not run, on two configurations, five metric rows
    // each: 2,000 rows after the baseline's own.
    let metrics = [
        "rest_gap",
        "max_penetration",
        "tunneling",
        "air_time",
        "apex_error",
    ];
    let gone: String = (0..200)
        .flat_map(|k| {
            metrics.iter().flat_map(move |m| {
                ["default", "other"]
                    .map(|c| format!("gone,s{k},sweep,{c},{m},0.0,tiles,0.0,0.0,,,\n"))
            })
        })
        .collect();
    let (text, ck) = check_with_gone(&bl, dir.path(), &gone);
    // Three runs pass; the 2,000 rows make 400 runs (200 scenarios, two configurations each),
    // each listed once, missing.
    assert!(
        text.contains("3 passed, 400 failed (0 worse, 0 diverged, 400 missing; 0 better, 0 new)"),
        "{text}"
    );
    assert_eq!(
        text.lines().filter(|l| l.starts_with("missing ")).count(),
        400
    );
    let listed = std::fs::read_to_string(ck.join("check.csv")).unwrap();
    assert_eq!(listed.lines().count(), 1 + 403);
    // A damaged row at the end of the baseline's file: named by its line.
    append(
        &bl.join("metrics.csv"),
        "gone,s0,sweep,x,rest_gap,tall,tiles,0.0,0.0,,,\n",
    );
    let (out, _) = check(&bl, dir.path(), "check");
    // 36 rows of the baseline's own, 2,000 appended, the header: the damaged row is line 2038.
    assert_error(&out, "metrics.csv:2038: field 6 (value): found \"tall\"");
}

#[test]
fn review_reads_the_runs_it_shows_to_the_end_of_each_file() {
    let dir = tempfile::tempdir().unwrap();
    let bl = baseline(dir.path());
    // The default configuration's baseline trace: 2,000 frames where the run makes 31, so the
    // check finds it diverged and the page draws the longer one.
    let trace = bl.join("traces/quick.stand.sweep.csv");
    let header = std::fs::read_to_string(&trace).unwrap();
    let header = header.lines().next().unwrap().to_string();
    let long: String = (0..2000).map(|f| frame(f, "1.5")).collect();
    std::fs::write(&trace, format!("{header}\n{long}")).unwrap();
    let (out, ck) = check(&bl, dir.path(), "check");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let review = |extra: &str| {
        platbench()
            .arg("review")
            .arg(&ck)
            .arg("--baseline")
            .arg(&bl)
            .arg(extra)
            .output()
            .unwrap()
    };
    assert_success(&review("--reject-all"));
    let page = ck.join("review/quick.stand.sweep.html");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("default (baseline)") && html.contains("default (new)"));
    // 2,000 frames drawn every 5th (src/report/replay.rs MAX_DRAWN_FRAMES, 400) and the
    // last: 401 drawn frames, the scrubber from 0 to 400.
    assert!(html.contains("max=\"400\""), "no scrubber to 400");
    // The baseline's trace damaged at its last row: left out of the page, the new one drawn.
    append(&trace, "2000,33.3,0,oops,1.0,0.0,0.0,1,0.0,1.0,,0,0\n");
    assert_success(&review("--reject-all"));
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(!html.contains("default (baseline)") && html.contains("default (new)"));
    // The check's metrics.csv damaged at its end: the review names the line and accepts
    // nothing.
    let before = std::fs::read(bl.join("metrics.csv")).unwrap();
    append(
        &ck.join("metrics.csv"),
        "quick,stand,sweep,default,rest_gap,tall,tiles,0,0,,,\n",
    );
    let out = review("--accept-all");
    // The header and the run's 36 rows: the damaged row is line 38.
    assert_error(&out, "metrics.csv:38: field 6 (value): found \"tall\"");
    assert_eq!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
}

#[test]
fn accepting_copies_the_baseline_row_by_row_and_refuses_rows_it_cannot_tell_apart() {
    let dir = tempfile::tempdir().unwrap();
    let bl = baseline(dir.path());
    let metrics = bl.join("metrics.csv");
    let text = std::fs::read_to_string(&metrics).unwrap();
    // The default configuration's rest_gap made worse in the baseline's copy of the check:
    // the check finds one run changed.
    let worse = text.replacen(
        "quick,stand,sweep,default,rest_gap,0.0,tiles,0.0,0.0,",
        "quick,stand,sweep,default,rest_gap,-1.0,tiles,0.0,-1.0,",
        1,
    );
    assert_ne!(worse, text);
    // A last row without its line end, of a run the check lacks.
    let kept = "gone,s,sweep,default,rest_gap,0.0,tiles,0.0,0.0,,,";
    std::fs::write(&metrics, format!("{worse}{kept}")).unwrap();
    let (out, ck) = check(&bl, dir.path(), "check");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    // A blank line after that last row: csv skips it, a splice would lose it. Found at the
    // end of the file, before anything is swapped in.
    std::fs::write(&metrics, format!("{worse}{kept}\n\n")).unwrap();
    // The default configuration's run accepted, the gone run (missing) rejected.
    let review = || {
        platbench()
            .arg("review")
            .arg(&ck)
            .arg("--baseline")
            .arg(&bl)
            .args(["--accept", "quick.stand/sweep default"])
            .output()
            .unwrap()
    };
    let out = review();
    assert_error(
        &out,
        "cannot tell its rows apart byte for byte; refusing to edit it",
    );
    assert_eq!(
        std::fs::read_to_string(&metrics).unwrap(),
        format!("{worse}{kept}\n\n")
    );
    // Without it, the accepted run's rows are the check's (as the baseline first wrote them),
    // every other byte the baseline's, the last row still without its line end.
    std::fs::write(&metrics, format!("{worse}{kept}")).unwrap();
    assert_success(&review());
    assert_eq!(
        std::fs::read_to_string(&metrics).unwrap(),
        format!("{text}{kept}")
    );
}

#[test]
fn check_lists_the_first_runs_the_new_run_lacks_and_counts_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let bl = baseline(dir.path());
    // 1,200 runs the check does not run, one metric row each: 200 past MAX_LISTED_CHANGES
    // (1,000, src/limits.rs), the most runs the new run lacks that `check` lists.
    let gone: String = (0..1200)
        .map(|k| format!("gone,s{k},sweep,default,rest_gap,0.0,tiles,0.0,0.0,,,\n"))
        .collect();
    let (text, ck) = check_with_gone(&bl, dir.path(), &gone);
    assert!(
        text.contains("3 passed, 1200 failed (0 worse, 0 diverged, 1200 missing; 0 better, 0 new)"),
        "{text}"
    );
    // The first 1,000 in the baseline's order, then the count of the rest.
    let missing: Vec<&str> = text.lines().filter(|l| l.starts_with("missing ")).collect();
    assert_eq!(missing.len(), 1000);
    assert!(missing[999].contains("gone.s999 "), "{}", missing[999]);
    assert!(
        text.contains("and 200 more runs of the baseline not in the new run"),
        "{text}"
    );
    // check.csv lists every run: the header, 3 runs passing, 1,200 missing.
    let listed = std::fs::read_to_string(ck.join("check.csv")).unwrap();
    assert_eq!(listed.lines().count(), 1 + 1203);
    // The summary lists as many, and its diff table the first 1,000 missing metrics of 1,200.
    let md = std::fs::read_to_string(ck.join("summary.md")).unwrap();
    let runs = md
        .lines()
        .filter(|l| l.starts_with("| missing |") && l.ends_with("| not in the new run |"));
    assert_eq!(runs.count(), 1000);
    assert!(
        md.contains("and 200 more runs of the baseline not in the new run"),
        "{md}"
    );
    assert!(md.contains("1200 missing, 0 added"), "{md}");
    assert!(
        md.contains("and 200 more changed metrics not listed"),
        "{md}"
    );
    // `diff --format csv` lists every one: the header and 1,200 rows.
    let csv = platbench()
        .arg("diff")
        .arg(&bl)
        .arg(&ck)
        .args(["--format", "csv", "--allow-divergence"])
        .output()
        .unwrap();
    assert_eq!(csv.status.code(), Some(1), "{}", stderr(&csv));
    let rows = String::from_utf8_lossy(&csv.stdout).into_owned();
    assert_eq!(
        rows.lines().filter(|l| l.contains(",missing,")).count(),
        1200
    );
}

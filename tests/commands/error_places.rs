//! Issue 40: a command's error says where the fault is. A CSV row is placed at its true line
//! whatever its files' line ends (`\n`, `\r\n` or `\r`: the csv crate's own line count put a
//! `\r\n` file's rows a line early and every row of a `\r` file on line 1), and a baseline
//! directory is named by where it came from (`PLATBENCH_BASELINE`, not `--baseline`, when the
//! environment gave it).

use std::path::Path;

use crate::common::platbench;

const METRICS_HEADER: &str =
    "level,scenario,backend,config,metric,value,unit,reference,error,frame,q1,q3";
const METRICS_ROW: &str = "flat,stand,sweep,default,rest_gap,0.0,tiles,0.0,0.0,120,,";
const METRICS_BAD: &str = "flat,stand,sweep,default,rest_gap_declared,abc,tiles,0.0,0.0,120,,";
const TRADEOFF_HEADER: &str = "backend,setting,cost_us,error,pareto,scenarios,scope";
const TRADEOFF_ROW: &str = "sweep,dt=1/30,1.85,0.0,true,1,all";
const TRADEOFF_BAD: &str = "sweep,dt=1/30,1.85,zz,true,1,landing";

/// The text of `lines` each ended by `end`.
fn joined(lines: &[&str], end: &str) -> String {
    lines.iter().map(|l| format!("{l}{end}")).collect()
}

fn stderr_of(out: &std::process::Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

#[test]
fn a_bad_csv_row_is_placed_at_its_line_whatever_the_line_ends() {
    let dir = tempfile::tempdir().unwrap();
    for (name, end) in [("lf", "\n"), ("crlf", "\r\n"), ("cr", "\r")] {
        // The bad row is line 3: after the header and one good row.
        let run = dir.path().join(name);
        std::fs::create_dir_all(run.join("traces")).unwrap();
        let metrics = run.join("metrics.csv");
        let text = joined(&[METRICS_HEADER, METRICS_ROW, METRICS_BAD], end);
        std::fs::write(&metrics, text).unwrap();
        let out = platbench()
            .arg("diff")
            .arg(&run)
            .arg(&run)
            .output()
            .unwrap();
        let err = stderr_of(&out);
        let want = format!(
            "{}: line 3, field 6 (value): found \"abc\"; expected a number",
            metrics.display()
        );
        assert!(err.contains(&want), "{name}: {want:?} in: {err}");
        // A trade-off file (read by another reader): line 3 too, after a blank line at 2
        // it is line 4.
        let tradeoff = dir.path().join(format!("tradeoff_{name}.csv"));
        for (lines, line) in [
            (&[TRADEOFF_HEADER, TRADEOFF_ROW, TRADEOFF_BAD][..], 3),
            (&[TRADEOFF_HEADER, "", TRADEOFF_ROW, TRADEOFF_BAD][..], 4),
        ] {
            std::fs::write(&tradeoff, joined(lines, end)).unwrap();
            let out = platbench()
                .arg("report")
                .arg("--tradeoff")
                .arg(&tradeoff)
                .arg("--out")
                .arg(dir.path().join("report"))
                .output()
                .unwrap();
            let err = stderr_of(&out);
            let want = format!(
                "{}:{line}: field 4 (error): found \"zz\"; expected a number",
                tradeoff.display()
            );
            assert!(err.contains(&want), "{name}: {want:?} in: {err}");
        }
    }
}

#[test]
fn a_baseline_name_too_long_is_blamed_on_where_it_came_from() {
    let dir = tempfile::tempdir().unwrap();
    // 300 bytes: past the 218 a baseline's folder name may have (src/cli/output.rs: 255 less
    // the `.platbench-old-<pid>-<n>-` prefix of the copy moved aside).
    let long = dir.path().join("x".repeat(300));
    let from_env = |args: &[&str]| {
        let out = platbench()
            .args(args)
            .env("PLATBENCH_BASELINE", &long)
            .output()
            .unwrap();
        stderr_of(&out)
    };
    let want = format!(
        "PLATBENCH_BASELINE {}: the folder's name is 300 bytes; expected at most 218",
        long.display()
    );
    for args in [&["baseline"][..], &["run", "--bless"][..]] {
        let err = from_env(args);
        assert!(err.contains(&want), "{args:?}: {want:?} in: {err}");
        assert!(
            !err.contains("--baseline /") && !err.contains("--out"),
            "{err}"
        );
    }
    // Given on the command line, the option is named.
    let out = platbench()
        .args(["baseline", "--baseline"])
        .arg(&long)
        .env("PLATBENCH_BASELINE", dir.path())
        .output()
        .unwrap();
    let err = stderr_of(&out);
    assert!(
        err.contains(&format!("--baseline {}: the folder's name", long.display())),
        "{err}"
    );
    assert!(!Path::new(&long).exists());
}

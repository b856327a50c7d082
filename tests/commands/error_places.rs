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
            "{}:3: field 6 (value): found \"abc\"; expected a number",
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

/// Runs `cmd`, which must exit 2 with `want` in its error.
fn fails_with(cmd: &mut std::process::Command, want: &str) {
    let err = stderr_of(&cmd.output().unwrap());
    assert!(err.contains(want), "{want:?} in: {err}");
}

#[test]
fn a_column_the_header_lacks_is_said_at_the_header() {
    // Issue 40: a metrics file without its `level` column was "CSV deserialize error: record 1
    // (line: 2, byte: 63): missing field `level`"; a trade-off file given to --stability the
    // same at line 2.
    let dir = tempfile::tempdir().unwrap();
    let run = dir.path().join("run");
    std::fs::create_dir_all(run.join("traces")).unwrap();
    let metrics = run.join("metrics.csv");
    let header = METRICS_HEADER.replacen("level,", "lvl,", 1);
    std::fs::write(&metrics, joined(&[&header, METRICS_ROW], "\n")).unwrap();
    let want = format!("{}:1: the header has no column `level`", metrics.display());
    fails_with(platbench().arg("diff").arg(&run).arg(&run), &want);
    let tradeoff = dir.path().join("tradeoff.csv");
    std::fs::write(&tradeoff, joined(&[TRADEOFF_HEADER, TRADEOFF_ROW], "\n")).unwrap();
    let want = format!("{}:1: the header has no column `", tradeoff.display());
    let report = dir.path().join("report");
    fails_with(
        platbench()
            .arg("report")
            .arg("--stability")
            .arg(&tradeoff)
            .arg("--out")
            .arg(report),
        &want,
    );
}

#[test]
fn an_option_value_that_does_not_parse_says_what_was_expected() {
    // Issue 40: `--seed -1` said "invalid digit found in string", `--dt 1/60` "invalid float
    // literal"; a time step may now be written as a fraction.
    for (args, want) in [
        (
            &["hunt", "--seed", "-1"][..],
            "found \"-1\"; expected a whole number from 0 to 18446744073709551615",
        ),
        (
            &["run", "--dt", "1/6o"][..],
            "found \"1/6o\"; expected seconds, a number such as 0.0166 or a fraction such as 1/60",
        ),
        (
            &["run", "--epsilon", "tiny"][..],
            "found \"tiny\"; expected a number of tiles",
        ),
    ] {
        fails_with(platbench().args(args), want);
    }
    // `--dt 1/60` runs as `--dt 0.016666668` (1/60 in f32) does: the same metrics.
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("tiny.toml");
    let text = "map = \"\"\"\n......\n######\n\"\"\"\n\n[[scenario]]\nname = \"fall\"\nspawn = [1.5, 1.0]\nduration = 1.0\n";
    std::fs::write(&level, text).unwrap();
    let metrics = |dt: &str| {
        let out_dir = dir.path().join(dt.replace('/', "_"));
        let out = platbench()
            .args(["run", "--backend", "sweep", "--dt", dt, "--out"])
            .arg(&out_dir)
            .arg(&level)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read(out_dir.join("metrics.csv")).unwrap()
    };
    assert_eq!(metrics("1/60"), metrics("0.016666668"));
}

#[test]
fn a_file_given_for_a_directory_is_named_as_such() {
    // Issue 40: `diff FILE FILE` said "FILE/metrics.csv: cannot read it: Not a directory" and
    // `check --baseline FILE` named FILE/manifest.toml.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("afile");
    std::fs::write(&file, "x").unwrap();
    let want = format!(
        "BASE {} is a file, not a directory; expected the --out directory",
        file.display()
    );
    fails_with(platbench().arg("diff").arg(&file).arg(&file), &want);
    let want = format!("the baseline {} is a file, not a directory", file.display());
    let ck = dir.path().join("ck");
    fails_with(
        platbench()
            .arg("check")
            .arg("--baseline")
            .arg(&file)
            .arg("--out")
            .arg(ck),
        &want,
    );
}

#[test]
#[cfg(feature = "tiled")]
fn an_option_that_changes_nothing_on_the_files_given_says_so() {
    // Issue 40: `--intgrid` on a Tiled map ran without a word; `--level` on one warned.
    let map = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps/showcase.tmx");
    let dir = tempfile::tempdir().unwrap();
    let out = platbench()
        .args(["run", "--backend", "sweep", "--intgrid", "1=solid", "--out"])
        .arg(dir.path().join("run"))
        .arg(&map)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("warning: --intgrid names LDtk IntGrid values, and no .ldtk file is given, so it changes nothing"),
        "{err}"
    );
}

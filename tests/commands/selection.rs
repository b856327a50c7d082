//! The selection options every command that runs controllers takes alike (`run`, `report`,
//! `stress`, `sweep`): the same flags pick the backends and the scenarios, and a selection that
//! matches nothing is a clear error.
// The built-in comparison's backends are named below: with the default features only.
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{assert_success, platbench};

/// The distinct values of CSV column `col` in `text` (header skipped).
fn column(text: &str, col: usize) -> Vec<String> {
    let mut v: Vec<String> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(col).unwrap().to_string())
        .collect();
    v.sort();
    v.dedup();
    v
}

#[test]
fn run_report_and_sweep_take_the_same_backend_and_scenario_selection() {
    let dir = tempfile::tempdir().unwrap();
    let sel = [
        "--backend",
        "sweep",
        "--scenario",
        "jumps.jump_1,drops",
        "--jobs",
        "2",
    ];
    let out = platbench()
        .arg("run")
        .args(sel)
        .arg("--out")
        .arg(dir.path().join("run"))
        .output()
        .unwrap();
    assert_success(&out);
    let metrics = std::fs::read_to_string(dir.path().join("run/metrics.csv")).unwrap();
    // metrics.csv columns: level, scenario, backend.
    assert_eq!(column(&metrics, 0), ["drops", "jumps"]);
    assert_eq!(column(&metrics, 2), ["sweep"]);
    let scenarios = column(&metrics, 1);
    assert!(scenarios.contains(&"jump_1".to_string()));
    assert!(!scenarios.contains(&"jump_2".to_string()), "{scenarios:?}");

    let out = platbench()
        .arg("sweep")
        .args(sel)
        .arg("--out")
        .arg(dir.path().join("sweep"))
        .output()
        .unwrap();
    assert_success(&out);
    let tradeoff = std::fs::read_to_string(dir.path().join("sweep/tradeoff.csv")).unwrap();
    let header = tradeoff.lines().next().unwrap();
    let backend = header.split(',').position(|c| c == "backend").unwrap();
    assert_eq!(column(&tradeoff, backend), ["sweep"]);

    let out = platbench()
        .arg("report")
        .args(sel)
        .arg("--out")
        .arg(dir.path().join("report"))
        .output()
        .unwrap();
    assert_success(&out);
    let md = std::fs::read_to_string(dir.path().join("report/report.md")).unwrap();
    assert!(md.contains("jump_1") && !md.contains("jump_2"), "{md}");
    assert!(!md.contains("rapier"), "{md}");
}

#[test]
fn a_selection_that_matches_nothing_is_an_error_naming_what_there_is() {
    for cmd in ["run", "report", "sweep"] {
        let out = platbench()
            .args([cmd, "--scenario", "jumps.nosuch"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--scenario jumps.nosuch"), "{err}");
        assert!(err.contains("jumps.jump_1"), "{err}");
    }
    // stress runs its own probes: a scenario filter is refused, and a backend the registry
    // lacks is refused as on every command.
    let out = platbench()
        .args(["stress", "--scenario", "jumps"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    for cmd in ["run", "report", "stress", "sweep"] {
        let out = platbench()
            .args([cmd, "--backend", "nosuch"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("possible values: sweep, rapier, box2d")
        );
    }
}

#[test]
fn the_header_counts_only_what_runs_and_nothing_runs_twice() {
    let dir = tempfile::tempdir().unwrap();
    // A floor 2^14 + 1 tiles wide: Box2D refuses it as a bound (box2d::MAX_LEVEL_EXTENT) before
    // building, so its four configurations' runs are not counted; the sweep's three run.
    let width = (1 << 14) + 1;
    let level = dir.path().join("wide.toml");
    std::fs::write(
        &level,
        format!(
            "name = \"wide\"\nmap = \"\"\"\n{}\n{}\n\"\"\"\n[[scenario]]\nname = \"stand\"\nspawn = [2.5, 1.0]\nduration = 0.5\n",
            ".".repeat(width),
            "#".repeat(width)
        ),
    )
    .unwrap();
    let out = platbench()
        .args(["run", "--backend", "sweep,box2d"])
        .arg(&level)
        .output()
        .unwrap();
    assert_success(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("1 scenarios on 7 configurations (3 runs, 4 skipped"),
        "{err}"
    );
    // A character Box2D refuses (a capsule radius under 0.01 tiles, box2d::check_radius) is
    // not counted either: one scenario, the sweep's three runs.
    let thin = dir.path().join("thin.toml");
    std::fs::write(
        &thin,
        "name = \"thin\"\nmap = \"\"\"\n#....#\n######\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [2.5, 1.0]\nsize = [0.015, 0.9]\nduration = 0.5\n",
    )
    .unwrap();
    let out = platbench()
        .args(["run", "--backend", "sweep,box2d"])
        .arg(&thin)
        .output()
        .unwrap();
    assert_success(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("1 scenarios on 7 configurations (3 runs, 4 skipped"),
        "{err}"
    );
    assert!(err.contains("[3/3]"), "{err}");
    // A precision listed twice runs each configuration once.
    let out = platbench()
        .args(["run", "--backend", "sweep", "--scenario", "jumps.jump_1"])
        .args(["--precision", "f64,f64"])
        .output()
        .unwrap();
    assert_success(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    // The sweep's two float configurations have an f64 build; integer positions do not.
    assert!(
        err.contains("1 scenarios on 2 configurations (2 runs)"),
        "{err}"
    );
    // A report or sweep that measures nothing (Box2D refuses the wide level) fails and
    // writes nothing, as run does.
    for cmd in ["report", "sweep"] {
        let target = dir.path().join(cmd);
        let out = platbench()
            .args([cmd, "--backend", "box2d", "--out"])
            .arg(&target)
            .arg(&level)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("nothing was measured"),
            "{cmd}"
        );
        assert!(!target.exists(), "{cmd}");
    }
}

//! `platbench baseline` then `platbench check`: what a check finds, and what it refuses.

use std::process::{ExitCode, Stdio};

use platbench::cli::Harness;
use platbench::registry::Registry;
use platbench::sweep::SweepConfig;

use super::common::platbench;
use super::toy::{cli, harness, path, setup, statuses, Toy};

#[test]
fn check_names_the_scenario_a_changed_controller_broke() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let (before, after) = (harness(false, &bl), harness(true, &bl));
    assert_eq!(
        cli(
            &before,
            &["baseline", path(&level), "--baseline", path(&bl)]
        ),
        ExitCode::SUCCESS
    );
    assert!(bl.join("manifest.toml").is_file());
    // The same controller checks clean, and keeps no trace: nothing changed.
    let same = dir.path().join("same");
    assert_eq!(
        cli(
            &before,
            &["check", "--baseline", path(&bl), "--out", path(&same)]
        ),
        ExitCode::SUCCESS
    );
    let rows = statuses(&same);
    assert_eq!(rows.len(), 4, "{rows:?}");
    assert!(rows.iter().all(|(_, _, s)| s == "pass"), "{rows:?}");
    assert_eq!(std::fs::read_dir(same.join("traces")).unwrap().count(), 0);
    // The changed controller fails on `drop` only, on both configurations.
    let changed = dir.path().join("changed");
    assert_eq!(
        cli(
            &after,
            &["check", "--baseline", path(&bl), "--out", path(&changed)]
        ),
        ExitCode::from(1)
    );
    for (scenario, config, status) in statuses(&changed) {
        if scenario == "plain.drop" {
            assert!(
                status == "worse" || status == "diverged",
                "{config}: {status}"
            );
        } else {
            assert_eq!(status, "pass", "{scenario} {config}");
        }
    }
    // Its output keeps the changed traces only, and a summary naming the scenario.
    let mut traces: Vec<String> = std::fs::read_dir(changed.join("traces"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    traces.sort();
    assert_eq!(
        traces,
        ["plain.drop.toy.flush.csv", "plain.drop.toy.hover.csv"]
    );
    let md = std::fs::read_to_string(changed.join("summary.md")).unwrap();
    assert!(md.contains("2 passed, 2 failed"), "{md}");
    assert!(md.contains("| plain.drop | toy flush |"), "{md}");
    assert!(!md.contains("plain.walk"), "{md}");
}

#[test]
fn a_baseline_of_one_backend_checks_with_nothing_missing() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let h = Harness {
        registry: Registry::new().with::<SweepConfig>().with::<Toy<false>>(),
        baseline: bl.clone(),
    };
    assert_eq!(
        cli(
            &h,
            &[
                "baseline",
                path(&level),
                "--backend",
                "toy",
                "--traces",
                "failing"
            ]
        ),
        ExitCode::SUCCESS
    );
    let manifest = std::fs::read_to_string(bl.join("manifest.toml")).unwrap();
    assert!(manifest.contains("backends = [\"toy\"]"), "{manifest}");
    assert!(!manifest.contains("backend = \"sweep\""), "{manifest}");
    let out = dir.path().join("check");
    assert_eq!(cli(&h, &["check", "--out", path(&out)]), ExitCode::SUCCESS);
    let rows = statuses(&out);
    assert_eq!(rows.len(), 4, "{rows:?}");
    assert!(
        rows.iter()
            .all(|(_, c, s)| s == "pass" && c.starts_with("toy ")),
        "{rows:?}"
    );
}

#[test]
fn an_existing_baseline_is_replaced_only_with_replace() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let h = harness(false, &bl);
    let args = ["baseline", path(&level), "--scenario", "plain.walk"];
    assert_eq!(cli(&h, &args), ExitCode::SUCCESS);
    let before = std::fs::read(bl.join("metrics.csv")).unwrap();
    assert_eq!(cli(&h, &["baseline", path(&level)]), ExitCode::from(2));
    assert_eq!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
    assert_eq!(
        cli(&h, &["baseline", path(&level), "--replace"]),
        ExitCode::SUCCESS
    );
    assert_ne!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
    // `run --out` into it is refused as into any baseline.
    assert_eq!(
        cli(&h, &["run", path(&level), "--out", path(&bl)]),
        ExitCode::from(2)
    );
}

#[test]
fn a_bad_or_missing_manifest_is_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let bl = dir.path().join("baseline");
    std::fs::create_dir(&bl).unwrap();
    std::fs::write(bl.join(".platbench-output"), "platbench baseline\n").unwrap();
    let check = |what: &str| {
        let out = platbench()
            .args(["check", "--baseline"])
            .arg(&bl)
            .arg("--out")
            .arg(dir.path().join("out"))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{what}");
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let file = bl.join("manifest.toml");
        assert!(err.contains(&file.display().to_string()), "{what}: {err}");
        assert!(!err.contains("panicked"), "{what}: {err}");
        err
    };
    check("missing");
    std::fs::write(bl.join("manifest.toml"), "format = 1\nplatbench = [1, 2]\n").unwrap();
    let err = check("malformed");
    assert!(err.contains("is not a baseline manifest"), "{err}");
    std::fs::write(
        bl.join("manifest.toml"),
        "format = 9\nplatbench = \"0.1.0\"\n[selection]\ntraces = \"all\"\n",
    )
    .unwrap();
    let err = check("another format");
    assert!(err.contains("format 9"), "{err}");
    // Review, without a terminal and without a decision flag, refuses to ask.
    let out = platbench()
        .args(["review", "somewhere"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("stdin is not one") && err.contains("--accept-all"),
        "{err}"
    );
}

#[test]
fn help_names_the_default_baseline_and_fits_the_terminal() {
    let out = platbench().arg("--help").output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout).into_owned();
    for (cmd, starts) in [
        ("baseline", "Write a baseline of the selection you choose"),
        ("check", "For CI: run a baseline's selection again"),
        ("review", "Review the changes a check found"),
    ] {
        let line = help
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{cmd} ")))
            .unwrap_or_else(|| panic!("no line for {cmd}:\n{help}"));
        assert!(line.contains(starts), "{cmd}: {line}");
        let out = platbench()
            .env("PLATBENCH_BASELINE", "some/where")
            .args([cmd, "--help"])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        let wide: Vec<&str> = text.lines().filter(|l| l.chars().count() > 120).collect();
        assert!(wide.is_empty(), "`platbench {cmd} --help`: {wide:?}");
        // The default baseline, and the directory it resolves to from here.
        let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
        let here = std::env::current_dir().unwrap().join("some/where");
        assert!(
            flat.contains("Default: the harness's baseline, some/where (here:")
                && flat.contains(&here.display().to_string()),
            "{cmd}: {flat}"
        );
    }
}

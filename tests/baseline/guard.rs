//! What `check` and `review` refuse: a review against a baseline the check did not run
//! against, a check output over a baseline, an empty accept pattern; and the manifest a review
//! keeps current.

use std::process::ExitCode;

use super::common::platbench;
use super::toy::{cli, harness, path, setup};

#[test]
fn review_refuses_a_baseline_the_check_did_not_run_against() {
    let (dir, level) = setup();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let before_a = harness(false, &a);
    assert_eq!(
        cli(&before_a, &["baseline", path(&level)]),
        ExitCode::SUCCESS
    );
    assert_eq!(
        cli(
            &before_a,
            &["baseline", path(&level), "--baseline", path(&b)]
        ),
        ExitCode::SUCCESS
    );
    let after = harness(true, &a);
    let ck = dir.path().join("check");
    assert_eq!(
        cli(&after, &["check", "--out", path(&ck)]),
        ExitCode::from(1)
    );
    let b_metrics = std::fs::read(b.join("metrics.csv")).unwrap();
    assert_eq!(
        cli(
            &after,
            &["review", path(&ck), "--baseline", path(&b), "--accept-all"]
        ),
        ExitCode::from(2)
    );
    assert_eq!(std::fs::read(b.join("metrics.csv")).unwrap(), b_metrics);
    // A baseline replaced at the same path since the check is not the one it ran against.
    assert_eq!(
        cli(
            &before_a,
            &[
                "baseline",
                path(&level),
                "--replace",
                "--scenario",
                "plain.drop"
            ]
        ),
        ExitCode::SUCCESS
    );
    assert_eq!(
        cli(&after, &["review", path(&ck), "--accept-all"]),
        ExitCode::from(2)
    );
}

#[test]
fn check_hint_names_the_baseline_and_review_names_both_paths() {
    let (dir, level) = setup();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    for bl in [&a, &b] {
        let out = platbench()
            .args([
                "baseline",
                path(&level),
                "--backend",
                "sweep",
                "--scenario",
                "plain.drop",
            ])
            .args(["--baseline", path(bl)])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let ck = dir.path().join("check");
    let out = platbench()
        .args(["check", "--baseline", path(&a), "--out", path(&ck)])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!(
            "--baseline {}",
            a.canonicalize().unwrap().display()
        )) || err.contains(&format!("--baseline {}", a.display())),
        "{err}"
    );
    let out = platbench()
        .args(["review", path(&ck), "--baseline", path(&b), "--accept-all"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let name = |p: &std::path::Path| p.canonicalize().unwrap().display().to_string();
    assert!(err.contains(&name(&a)) && err.contains(&name(&b)), "{err}");
    // A directory that is not there is named as such.
    let out = platbench()
        .args(["review", path(&dir.path().join("nowhere")), "--accept-all"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("does not exist"), "{err}");
    // `baseline --baseline FILE` names --baseline, not --out.
    let file = dir.path().join("afile");
    std::fs::write(&file, "x").unwrap();
    let out = platbench()
        .args(["baseline", path(&level), "--baseline", path(&file)])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--baseline") && !err.contains("--out"),
        "{err}"
    );
}

#[test]
fn check_never_writes_over_a_baseline_even_with_force() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let h = harness(false, &bl);
    assert_eq!(cli(&h, &["baseline", path(&level)]), ExitCode::SUCCESS);
    // Without its marker, a baseline is still recognised by its manifest and its path.
    std::fs::remove_file(bl.join(".platbench-output")).unwrap();
    let inner = bl.join("traces");
    for out in [&bl, &inner, &dir.path().to_path_buf()] {
        assert_eq!(
            cli(&h, &["check", "--out", path(out), "--force"]),
            ExitCode::from(2),
            "{}",
            out.display()
        );
        assert!(bl.join("manifest.toml").is_file(), "{}", out.display());
    }
    // A copy of a baseline elsewhere, holding a manifest.toml, is not replaced either.
    let copy = dir.path().join("copy");
    std::fs::create_dir(&copy).unwrap();
    std::fs::copy(bl.join("manifest.toml"), copy.join("manifest.toml")).unwrap();
    assert_eq!(
        cli(&h, &["check", "--out", path(&copy), "--force"]),
        ExitCode::from(2)
    );
    assert!(copy.join("manifest.toml").is_file());
}

#[test]
fn check_accepts_diffs_allow_flags() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    assert_eq!(
        cli(&harness(false, &bl), &["baseline", path(&level)]),
        ExitCode::SUCCESS
    );
    let ck = dir.path().join("check");
    // The changed toy only diverges and moves metrics; --allow-divergence is accepted.
    let code = cli(
        &harness(true, &bl),
        &[
            "check",
            "--out",
            path(&ck),
            "--allow-divergence",
            "--allow-missing",
        ],
    );
    assert_ne!(code, ExitCode::from(2));
}

#[test]
fn review_refuses_an_empty_pattern() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    assert_eq!(
        cli(&harness(false, &bl), &["baseline", path(&level)]),
        ExitCode::SUCCESS
    );
    let after = harness(true, &bl);
    let ck = dir.path().join("check");
    assert_eq!(
        cli(&after, &["check", "--out", path(&ck)]),
        ExitCode::from(1)
    );
    let before = std::fs::read(bl.join("metrics.csv")).unwrap();
    assert_eq!(
        cli(&after, &["review", path(&ck), "--accept", ""]),
        ExitCode::from(2)
    );
    assert_eq!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
    // A pattern matching nothing is a warning, not an error.
    let out = platbench()
        .args([
            "review",
            path(&ck),
            "--accept",
            "no-such-run",
            "--baseline",
            path(&bl),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    // (The binary has no toy controller: no replay pages, but the matching is the same.)
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("warning") && err.contains("no-such-run"),
        "{err}"
    );
}

#[test]
fn accepting_a_run_of_a_changed_level_updates_the_manifest() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let h = harness(false, &bl);
    assert_eq!(cli(&h, &["baseline", path(&level)]), ExitCode::SUCCESS);
    // The level changes: the drop scenario starts higher.
    let text = std::fs::read_to_string(&level).unwrap();
    std::fs::write(
        &level,
        text.replace("spawn = [2.5, 2.5]", "spawn = [2.5, 2.6]"),
    )
    .unwrap();
    let ck = dir.path().join("check");
    assert_eq!(cli(&h, &["check", "--out", path(&ck)]), ExitCode::from(1));
    let old = std::fs::read_to_string(bl.join("manifest.toml")).unwrap();
    assert_eq!(
        cli(&h, &["review", path(&ck), "--accept-all"]),
        ExitCode::SUCCESS
    );
    let new = std::fs::read_to_string(bl.join("manifest.toml")).unwrap();
    assert_ne!(old, new);
    // A check now passes, with no note about the level.
    let again = dir.path().join("again");
    assert_eq!(
        cli(&h, &["check", "--out", path(&again)]),
        ExitCode::SUCCESS
    );
    let md = std::fs::read_to_string(again.join("summary.md")).unwrap();
    assert!(!md.contains("changed since the baseline"), "{md}");
}

#[test]
fn a_review_holds_the_baseline_locked() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    assert_eq!(
        cli(&harness(false, &bl), &["baseline", path(&level)]),
        ExitCode::SUCCESS
    );
    let after = harness(true, &bl);
    let ck = dir.path().join("check");
    assert_eq!(
        cli(&after, &["check", "--out", path(&ck)]),
        ExitCode::from(1)
    );
    let before = std::fs::read(bl.join("metrics.csv")).unwrap();
    // Another review holds the lock: this one is refused, the baseline unchanged.
    let lock = bl.join(".platbench-lock");
    std::fs::write(&lock, "platbench review, process 1, 0\n").unwrap();
    assert_eq!(
        cli(&after, &["review", path(&ck), "--accept-all"]),
        ExitCode::from(2)
    );
    assert_eq!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
    assert!(lock.is_file());
    // A lock older than an hour is taken over; the review leaves no lock behind.
    let two_hours = std::time::Duration::from_secs(7200);
    std::fs::File::options()
        .write(true)
        .open(&lock)
        .unwrap()
        .set_modified(std::time::SystemTime::now() - two_hours)
        .unwrap();
    assert_eq!(
        cli(&after, &["review", path(&ck), "--accept-all"]),
        ExitCode::SUCCESS
    );
    assert_ne!(std::fs::read(bl.join("metrics.csv")).unwrap(), before);
    assert!(!lock.exists());
}

#[test]
fn a_review_touches_no_file_a_check_row_names_outside_its_folders() {
    // Issue 40: a `check.csv` row whose trace names `../../victim.csv` (or an absolute path)
    // had `review --accept-all` delete that file and write an HTML page beside it.
    let (dir, level) = setup();
    let b = dir.path().join("b");
    assert_eq!(
        cli(&harness(false, &b), &["baseline", path(&level)]),
        ExitCode::SUCCESS
    );
    let after = harness(true, &b);
    let ck = dir.path().join("check");
    assert_eq!(
        cli(&after, &["check", "--out", path(&ck)]),
        ExitCode::from(1)
    );
    let victim = dir.path().join("victim.csv");
    std::fs::write(&victim, "a user's file\n").unwrap();
    let units = ck.join("check.csv");
    let text = std::fs::read_to_string(&units).unwrap();
    let b_metrics = std::fs::read(b.join("metrics.csv")).unwrap();
    for named in ["../../victim.csv", victim.to_str().unwrap()] {
        // Every row's trace: the sixth column (level, scenario, backend, config, status,
        // trace, detail).
        let edited: String = text
            .lines()
            .enumerate()
            .map(|(i, l)| {
                let mut f: Vec<&str> = l.split(',').collect();
                if i > 0 {
                    f[5] = named;
                }
                f.join(",") + "\n"
            })
            .collect();
        std::fs::write(&units, edited).unwrap();
        assert_eq!(
            cli(&after, &["review", path(&ck), "--accept-all"]),
            ExitCode::from(2)
        );
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "a user's file\n");
        assert!(!dir.path().join("victim.html").exists());
        assert_eq!(std::fs::read(b.join("metrics.csv")).unwrap(), b_metrics);
    }
}

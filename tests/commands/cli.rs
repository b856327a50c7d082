//! The `platbench` command as a user runs it.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{assert_success, platbench};

#[test]
fn no_arguments_prints_the_verdict_first_within_120_columns() {
    let out = platbench().output().unwrap();
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    // The verdict first, one block per built-in profile (compare/profiles), then the scorecard,
    // then the declared capabilities.
    assert!(
        stdout.starts_with("Which controller for which game"),
        "{stdout}"
    );
    let at = |s: &str| {
        stdout
            .find(s)
            .unwrap_or_else(|| panic!("no {s:?} in:\n{stdout}"))
    };
    let profiles = [
        "\npixel-precise: ",
        "\nslopes: ",
        "\nmoving-platforms: ",
        "\nhuge-worlds: ",
        "\ncrowds: ",
    ];
    let mut last = 0;
    for p in profiles {
        assert!(at(p) > last, "{p} out of order");
        last = at(p);
    }
    assert!(at("\nScorecard:") > last);
    assert!(at("\nDeclared by ") > at("\nScorecard:"));
    assert!(stdout.matches("\n  pick       ").count() == profiles.len());
    // The terminal: 120 columns, in a terminal and a CI log alike.
    for line in stdout.lines() {
        assert!(
            line.chars().count() <= 120,
            "{} columns: {line}",
            line.chars().count()
        );
    }
    // One scorecard row per configuration, named as in every table.
    for config in [
        "\nsweep ",
        "\nrapier per-tile capsule ",
        "\nrapier merged cuboid ",
        "\nbox2d per-tile capsule ",
    ] {
        assert!(
            stdout.contains(config),
            "scorecard lacks {config}:\n{stdout}"
        );
    }
    // The metric tables are behind --detail.
    assert!(!stdout.contains("| configuration"), "{stdout}");
}

#[test]
fn detail_adds_the_metric_tables_after_the_verdict() {
    let out = platbench()
        .args([
            "run",
            "compare/levels/jumps.toml",
            "--detail",
            "--backend",
            "sweep",
        ])
        .output()
        .unwrap();
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let verdict = stdout.find("Which controller").unwrap();
    let tables = stdout.find("Worst value of each metric").unwrap();
    assert!(verdict < tables);
    // Metric names are stacked in the tables' headers, one word a line.
    for m in ["land", "apex", "error"] {
        assert!(stdout[tables..].contains(m), "tables lack {m}:\n{stdout}");
    }
}

#[test]
fn run_writes_traces_and_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["run", "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert_success(&out);
    let metrics = std::fs::read_to_string(out_dir.join("metrics.csv")).unwrap();
    assert!(metrics.starts_with(
        "level,scenario,backend,config,metric,value,unit,reference,error,frame,q1,q3\n"
    ));
    // The frame column (before the quartiles, empty but for timing rows): a maximum over
    // frames always has one.
    let deepest: Vec<&str> = metrics
        .lines()
        .filter(|l| l.contains(",max_penetration,"))
        .collect();
    assert!(!deepest.is_empty());
    for l in deepest {
        let f: Vec<&str> = l.split(',').collect();
        assert!(f[9].parse::<u32>().is_ok(), "{l}");
        assert_eq!((f[10], f[11]), ("", ""), "{l}");
    }
    let trace = out_dir.join("traces/flat_seams.walk_right_10s.sweep.csv");
    let text = std::fs::read_to_string(&trace).unwrap();
    // 10 s at 1/60 s: the spawn row, 600 step rows, and the header.
    assert_eq!(text.lines().count(), 602);
    // Running again into the same directory replaces it whole: no stale files survive.
    std::fs::write(out_dir.join("traces/stale.csv"), "x").unwrap();
    let again = platbench()
        .args(["run", "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert!(again.status.success());
    assert!(!out_dir.join("traces/stale.csv").exists());
}

#[test]
fn bad_level_file_is_an_error_with_position_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, "name = \"bad\"\nmap = \"\"\"\n..\n#x\n\"\"\"\n").unwrap();
    let out = platbench().arg("run").arg(&path).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:4:2: unknown map character 'x'"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn missing_file_and_bad_flags_are_errors() {
    let out = platbench()
        .args(["run", "/nonexistent/level.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read level file"));
    let out = platbench().args(["run", "--dt", "-1"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--dt"));
}

#[test]
fn levels_lists_the_builtins() {
    let out = platbench().arg("levels").output().unwrap();
    assert_success(&out);
    let s = String::from_utf8_lossy(&out.stdout);
    for l in [
        "flat_seams",
        "drops",
        "jumps",
        "corridor",
        "thin_wall",
        "moving_wall",
    ] {
        assert!(s.contains(l), "{s}");
    }
}

#[test]
fn an_unchanged_run_diffs_clean_and_a_changed_constant_is_named() {
    let baseline = concat!(env!("CARGO_MANIFEST_DIR"), "/compare/baseline");
    let dir = tempfile::tempdir().unwrap();
    let same = dir.path().join("same");
    let run = platbench()
        .args(["run", "--out"])
        .arg(&same)
        .output()
        .unwrap();
    assert_success(&run);
    let d = platbench()
        .arg("diff")
        .arg(baseline)
        .arg(&same)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&d.stdout);
    // The committed baseline is this build's behaviour: a run diffs clean, bit for bit.
    assert_eq!(d.status.code(), Some(0), "{text}");
    assert!(
        text.contains("0 worse, 0 better, 0 missing, 0 added"),
        "{text}"
    );
    assert!(text.contains("0 diverge"), "{text}");

    // One constant of the sweep controller changed through its config: the epsilon.
    let changed = dir.path().join("changed");
    let run = platbench()
        .args(["run", "--epsilon", "0.05", "--out"])
        .arg(&changed)
        .output()
        .unwrap();
    assert!(run.status.success());
    let d = platbench()
        .arg("diff")
        .arg(baseline)
        .arg(&changed)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&d.stdout);
    assert_eq!(d.status.code(), Some(1), "{text}");
    // The metric that got worse is named, with the configuration and both values...
    assert!(text.contains("| worse  | drops.drop_0_1"), "{text}");
    assert!(text.contains("land_frame_error"), "{text}");
    // ...and the first divergent frame of a trace, with both positions.
    assert!(
        text.contains("| corridor.jump_into_ceiling.sweep.csv") && text.contains("| 18 "),
        "{text}"
    );
}

#[test]
fn the_baseline_is_written_only_with_bless() {
    // A stand-in baseline, so that a broken guard cannot touch the committed one. It is a
    // baseline by its marker, wherever it lies: the path is not what protects it.
    let dir = tempfile::tempdir().unwrap();
    let baseline = dir.path().join("baseline");
    std::fs::create_dir(&baseline).unwrap();
    std::fs::write(baseline.join(".platbench-output"), "platbench baseline\n").unwrap();
    std::fs::write(baseline.join("keep"), "keep").unwrap();
    for extra in [&[][..], &["--force"][..]] {
        let out = platbench()
            .args(["run", "--out"])
            .arg(&baseline)
            .args(extra)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("--bless"));
        assert!(baseline.join("keep").exists(), "the baseline was replaced");
    }
    // --bless is the way: it replaces the baseline with a full run, and marks it a baseline.
    let out = platbench()
        .env("PLATBENCH_BASELINE", &baseline)
        .args(["run", "--bless"])
        .output()
        .unwrap();
    assert_success(&out);
    assert!(!baseline.join("keep").exists());
    assert!(baseline.join("metrics.csv").exists());
    assert_eq!(
        std::fs::read_to_string(baseline.join(".platbench-output")).unwrap(),
        "platbench baseline\n"
    );
    // The committed baseline carries the same marker, so a copy of it anywhere is protected.
    let committed = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/compare/baseline/.platbench-output"
    );
    assert_eq!(
        std::fs::read_to_string(committed).unwrap(),
        "platbench baseline\n"
    );
}

#[test]
fn precision_runs_each_configuration_in_every_listed_precision_it_has_a_build_in() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("t.toml");
    std::fs::write(
        &level,
        "name = \"t\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"stand\"\nspawn = [1.5, 1.0]\nduration = 0.5\n",
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["run", "--timing", "--precision", "f32,f64", "--out"])
        .arg(&out_dir)
        .arg(&level)
        .output()
        .unwrap();
    assert_success(&out);
    let metrics = std::fs::read_to_string(out_dir.join("metrics.csv")).unwrap();
    let timed: Vec<(String, String)> = metrics
        .lines()
        .filter(|l| l.contains(",ns_per_character_step,"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[2].to_string(), f[3].to_string())
        })
        .collect();
    // The 23 built-in configurations in f32, and again in f64 the 16 Rapier ones (every Rapier
    // configuration has a build on rapier2d-f64) and the 2 float sweeps (the f64 mode); the
    // integer sweep and Box2D have none.
    assert_eq!(timed.len(), 23 + 18, "{metrics}");
    let f64s: Vec<&(String, String)> = timed.iter().filter(|(_, c)| c.ends_with(" f64")).collect();
    assert_eq!(f64s.len(), 18);
    assert_eq!(f64s.iter().filter(|(b, _)| b == "rapier").count(), 16);
    for (backend, config) in f64s {
        let f32_label = config.trim_end_matches(" f64");
        assert!(
            timed.iter().any(|(b, c)| b == backend && c == f32_label),
            "{config}"
        );
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("left out"), "{stderr}");
    // Only f64: the configurations without an f64 build are left out, and said so.
    let out = platbench()
        .args(["run", "--precision", "f64", "--backend", "sweep,box2d"])
        .arg(&level)
        .output()
        .unwrap();
    assert_success(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("left out sweep positions=integer/32: no build in f64"),
        "{stderr}"
    );
    assert!(
        stderr.contains("left out box2d per-tile capsule: no build in f64"),
        "{stderr}"
    );
    let out = platbench()
        .args(["run", "--precision", "f64", "--backend", "box2d"])
        .arg(&level)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("no configuration that runs has a build in it"),
        "{stderr}"
    );
}

#[test]
fn a_level_file_placed_1e12_tiles_out_runs_on_the_f64_configurations_and_skips_the_f32_ones() {
    // A level file's origin is f64 (to 1e15 tiles), so 1e12 is placed exactly (as an f32 it would
    // be 999,999,995,904). The f32 configurations refuse it (beyond 1e7 an f32 position moves in
    // whole tiles; limits::MAX_F32_ORIGIN) and say so; the f64 builds run it.
    let dir = tempfile::tempdir().unwrap();
    let text = |origin: &str| {
        format!(
            "name = \"far\"\n{origin}map = \"\"\"\n............\n............\n............\n############\n\"\"\"\n\
             [[platform]]\nrect = [2.0, 2.0, 3.0, 0.5]\nsine = {{ amplitude = [3.0, 0.0], period = 4.0 }}\n\
             [[scenario]]\nname = \"ride\"\nspawn = [3.5, 2.5]\nduration = 4.0\nride = 0\n\
             [[scenario]]\nname = \"stand\"\nspawn = [9.5, 1.0]\nduration = 1.0\n"
        )
    };
    let run = |name: &str, origin: &str| {
        let level = dir.path().join(format!("{name}.toml"));
        std::fs::write(&level, text(origin)).unwrap();
        let out_dir = dir.path().join(name);
        let out = platbench()
            .args(["run", "--precision", "f32,f64", "--backend", "sweep,rapier"])
            .args(["--traces", "none", "--out"])
            .arg(&out_dir)
            .arg(&level)
            .output()
            .unwrap();
        assert_success(&out);
        let metrics = std::fs::read_to_string(out_dir.join("metrics.csv")).unwrap();
        (String::from_utf8_lossy(&out.stderr).to_string(), metrics)
    };
    let (stderr, far) = run("far", "origin = [1e12, 1e12]\n");
    let refused = "a level origin of (1000000000000, 1000000000000) tiles in f32";
    assert!(
        stderr.contains(&format!(
            "skipped sweep default: the sweep backend refuses {refused}"
        )),
        "{stderr}"
    );
    // A bound kept on purpose, not a feature missing "yet".
    assert!(
        stderr.contains("a bound it keeps by design (level far)") && !stderr.contains(" yet "),
        "{stderr}"
    );
    assert!(
        stderr.contains("skipped rapier per-tile capsule:"),
        "{stderr}"
    );
    // Only f64 configurations have rows: the two float sweeps' f64 mode and the 16 Rapier ones.
    let config = |l: &str| l.split(',').nth(3).unwrap().to_string();
    let mut configs: Vec<String> = far.lines().skip(1).map(config).collect();
    configs.sort();
    configs.dedup();
    assert!(configs.iter().all(|c| c.ends_with(" f64")), "{configs:?}");
    assert_eq!(configs.len(), 2 + 16, "{configs:?}");
    // The f64 sweep there carries its rider as at the origin: within sqrt(2) f64 spacings at
    // 1e12 (2^-13 tile) plus the trace's f32 rounding (the bound of tests/behaviour/platforms.rs).
    let (_, near) = run("near", "");
    let value = |csv: &str, scenario: &str, config: &str, metric: &str| -> f64 {
        csv.lines()
            .map(|l| l.split(',').collect::<Vec<_>>())
            .find(|f| f[1] == scenario && f[3] == config && f[4] == metric)
            .unwrap_or_else(|| panic!("{scenario} {config} {metric}"))[5]
            .parse()
            .unwrap()
    };
    let bound = 2f64.sqrt() * 2f64.powi(-13) + 2f64.powi(-18);
    let drift = value(&far, "ride", "default f64", "carry_drift");
    assert!(drift <= bound, "carry_drift {drift} at 1e12");
    // At the origin: 4.8e-7 measured, one f32 spacing at the ride's height (the trace's level
    // coordinates); 1e-6 is two (the bound of tests/commands/stress.rs's f64 carry).
    assert!(value(&near, "ride", "default f64", "carry_drift") <= 1e-6);
    // At the origin the f32 configurations run as always: the sweep rests flush on the floor,
    // within its overlap tolerance (the default epsilon, 1e-3 tile).
    assert!(value(&near, "stand", "default", "rest_gap").abs() <= 1e-3);
}

#[test]
fn bad_command_line_values_are_named() {
    for (args, needle) in [
        (vec!["run", "--dt", "nan"], "--dt"),
        (vec!["run", "--dt", "0"], "--dt"),
        (vec!["run", "--epsilon", "-1"], "--epsilon"),
        (vec!["diff", "a", "b", "--tol", "rest_gap=x"], "--tol"),
        (
            vec!["diff", "/nonexistent/a", "/nonexistent/b"],
            "cannot read",
        ),
    ] {
        let out = platbench().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn killing_a_run_midway_leaves_the_previous_output_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    // A first, complete run (one level, quick).
    let level = dir.path().join("k.toml");
    std::fs::write(
        &level,
        "name = \"k\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 0.5\n",
    )
    .unwrap();
    let first = platbench()
        .args(["run", "--out"])
        .arg(&out_dir)
        .arg(&level)
        .output()
        .unwrap();
    assert!(first.status.success());
    let before = std::fs::read(out_dir.join("metrics.csv")).unwrap();
    let traces_before = std::fs::read_dir(out_dir.join("traces")).unwrap().count();
    // A second, long run into the same directory (the built-in set), killed while it runs.
    let mut child = platbench()
        .args(["run", "--timing", "--out"])
        .arg(&out_dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(400));
    let still_running = child.try_wait().unwrap().is_none();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        still_running,
        "the second run ended before it could be killed"
    );
    assert_eq!(std::fs::read(out_dir.join("metrics.csv")).unwrap(), before);
    let traces_after = std::fs::read_dir(out_dir.join("traces")).unwrap().count();
    assert_eq!(traces_after, traces_before);
}

#[test]
fn help_describes_every_subcommand_under_its_own_name() {
    let out = platbench().arg("--help").output().unwrap();
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    // Each subcommand's line starts with its own description (a doc comment attached to the
    // wrong variant once put the stress text under `sweep` and left `stress` blank).
    for (cmd, starts) in [
        ("run", "Run levels and print the comparison"),
        ("levels", "List the built-in levels"),
        ("sweep", "Speed against accuracy"),
        ("stress", "Stability at the extremes"),
        ("report", "Run levels and write the report"),
        ("diff", "Compare a run directory"),
    ] {
        let line = help
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{cmd} ")))
            .unwrap_or_else(|| panic!("no line for {cmd}:\n{help}"));
        assert!(
            line[line.find(cmd).unwrap() + cmd.len()..]
                .trim_start()
                .starts_with(starts),
            "{cmd}: {line}"
        );
    }
    // Help wraps to fit a 120-column terminal (clap's wrap_help at 100 columns).
    for cmd in [
        "", "run", "sweep", "stress", "report", "diff", "inspect", "levels",
    ] {
        let mut c = platbench();
        if !cmd.is_empty() {
            c.arg(cmd);
        }
        let out = c.arg("--help").output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        let wide: Vec<&str> = text.lines().filter(|l| l.chars().count() > 120).collect();
        assert!(wide.is_empty(), "`platbench {cmd} --help`: {wide:?}");
    }
}

/// A run in which every configuration refuses every scenario fails and says so, and writes no
/// output directory (it used to succeed with an empty summary and an empty metrics.csv).
#[test]
fn a_run_that_measures_nothing_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // Box2D's mover refuses a capsule radius under 0.01 tiles (twice its linear slop).
    let level = "name = \"thin\"\nmap = \"\"\"\n#....#\n######\n\"\"\"\n\n[[scenario]]\nname = \"s\"\nspawn = [2.5, 1.0]\nsize = [0.015, 0.9]\nduration = 0.5\n";
    let file = dir.path().join("thin.toml");
    std::fs::write(&file, level).unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["run", "--backend", "box2d", "--out"])
        .arg(&out_dir)
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("nothing was measured"), "{stderr}");
    assert!(
        stderr.contains("a bound it keeps by design (level thin)"),
        "{stderr}"
    );
    assert!(!out_dir.exists());
}

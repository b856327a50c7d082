//! Nothing lost, nothing hangs: one regression case for each class of hostile input found,
//! run through the `platbench` binary as a user runs it (part two: `hostile_inputs.rs`).
//!
//! 1. outputs: `--out` never replaces what is not a platbench output of the same command;
//! 2. limits: inputs that hung or ran out of memory are refused before any work;
//! 3. diff: NaN, bad tolerances and missing or truncated traces fail the diff;
//! 4. panics: input that panicked inside a dependency is an error;
//! 5. silently accepted input is an error or a warning;
//! 6. the small things (permissions, counts, ignored flags).
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{assert_success, platbench};

/// A quick level: a floor and one 0.5 s scenario.
const QUICK: &str = "name = \"quick\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"stand\"\nspawn = [1.5, 1.0]\nduration = 0.5\n";

pub(super) fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Fails unless the command exited 2 (an error) with `needle` in its message and no panic.
pub(super) fn assert_error(out: &Output, needle: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(needle), "expected {needle:?} in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

pub(super) fn quick_level(dir: &Path) -> PathBuf {
    let path = dir.join("quick.toml");
    std::fs::write(&path, QUICK).unwrap();
    path
}

/// `platbench run LEVEL --backend sweep --out OUT EXTRA...`
pub(super) fn run_quick(level: &Path, out: &Path, extra: &[&str]) -> Output {
    platbench()
        .arg("run")
        .arg(level)
        .args(["--backend", "sweep", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap()
}

// ---- 1. outputs -------------------------------------------------------------------------

#[test]
fn out_refuses_a_directory_of_user_files_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let mine = dir.path().join("mine");
    std::fs::create_dir_all(mine.join("sub")).unwrap();
    std::fs::write(mine.join("main.rs"), "fn main() {}").unwrap();
    let out = run_quick(&level, &mine, &[]);
    assert_error(&out, "--force");
    assert!(stderr(&out).contains(&mine.display().to_string()));
    assert_eq!(
        std::fs::read_to_string(mine.join("main.rs")).unwrap(),
        "fn main() {}"
    );
    assert!(mine.join("sub").is_dir());
    // With --force the user asked for it: the directory becomes the run.
    let out = run_quick(&level, &mine, &["--force"]);
    assert_success(&out);
    assert!(!mine.join("main.rs").exists());
    assert!(mine.join("metrics.csv").exists());
    // Now it is a run's output, replaced by the next run without --force.
    assert_success(&run_quick(&level, &mine, &[]));
}

#[test]
fn out_writes_an_empty_directory_and_refuses_another_commands_output() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_success(&run_quick(&level, &empty, &[]));
    assert_eq!(
        std::fs::read_to_string(empty.join(".platbench-output")).unwrap(),
        "platbench run\n"
    );
    // A run's output is not a report's to replace.
    let out = platbench()
        .arg("report")
        .arg(&level)
        .args(["--backend", "sweep", "--out"])
        .arg(&empty)
        .output()
        .unwrap();
    assert_error(&out, "holds the output of `platbench run`");
    assert!(empty.join("metrics.csv").exists());
}

#[test]
fn out_never_replaces_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let file = dir.path().join("notes.txt");
    std::fs::write(&file, "my notes").unwrap();
    for extra in [&[][..], &["--force"][..]] {
        let out = run_quick(&level, &file, extra);
        assert_error(&out, "is not a directory");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "my notes");
    }
    // Nothing was moved aside or staged.
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(
        names.iter().all(|n| !n.starts_with(".platbench")),
        "{names:?}"
    );
}

#[test]
fn report_stress_and_sweep_refuse_a_directory_of_user_files_before_working() {
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("keep.txt"), "keep").unwrap();
    for cmd in ["report", "stress", "sweep"] {
        let out = platbench()
            .args([cmd, "--out"])
            .arg(&mine)
            .output()
            .unwrap();
        assert_error(&out, "--force");
        assert!(mine.join("keep.txt").exists(), "{cmd}");
    }
}

/// The id of a process that has ended: a child we waited for.
fn dead_pid() -> u32 {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_platbench"))
        .arg("--version")
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let dead = child.id();
    child.wait().unwrap();
    dead
}

#[test]
fn a_staging_directory_left_by_a_dead_run_is_removed_and_others_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let dead = dead_pid();
    // What a run killed while writing leaves: its staging directory, marked.
    let stale = dir.path().join(format!(".platbench-staging-{dead}-0"));
    std::fs::create_dir_all(stale.join("traces")).unwrap();
    std::fs::write(stale.join(".platbench-output"), "platbench run\n").unwrap();
    // A staging directory of a live process (this test), and one platbench did not name.
    let live = dir
        .path()
        .join(format!(".platbench-staging-{}-0", std::process::id()));
    std::fs::create_dir(&live).unwrap();
    let foreign = dir.path().join(".platbench-staging-mine");
    std::fs::create_dir(&foreign).unwrap();
    let out = run_quick(&level, &dir.path().join("out"), &[]);
    assert_success(&out);
    if Path::new("/proc/self").exists() {
        assert!(!stale.exists(), "{}", stderr(&out));
        assert!(stderr(&out).contains("left by an interrupted platbench"));
    }
    assert!(live.exists() && foreign.exists());
    // The run itself left no staging directory behind.
    let left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with(".platbench-staging-") && n.contains('-'))
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

#[test]
fn an_output_moved_aside_by_a_dead_run_is_put_back_under_its_own_name_whatever_its_bytes() {
    use std::ffi::OsString;
    use std::os::unix::ffi::OsStringExt;
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let dead = dead_pid();
    // A run killed between its two renames left the previous output of `runs-\xff` aside; an
    // unrelated `out` of the user's stands beside it.
    let name = OsString::from_vec(b"runs-\xff".to_vec());
    let mut aside = OsString::from(format!(".platbench-old-{dead}-0-"));
    aside.push(&name);
    let aside = dir.path().join(aside);
    std::fs::create_dir(&aside).unwrap();
    std::fs::write(aside.join(".platbench-output"), "platbench run\n").unwrap();
    std::fs::write(aside.join("metrics.csv"), "previous").unwrap();
    let mine = dir.path().join("out");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("keep.txt"), "mine").unwrap();
    // The next write in that folder puts it back where it was.
    let out = run_quick(&level, &dir.path().join("other"), &[]);
    assert_success(&out);
    if Path::new("/proc/self").exists() {
        assert!(!aside.exists(), "{}", stderr(&out));
        let back = dir.path().join(&name).join("metrics.csv");
        assert_eq!(std::fs::read_to_string(back).unwrap(), "previous");
    }
    assert_eq!(
        std::fs::read_to_string(mine.join("keep.txt")).unwrap(),
        "mine"
    );
}

#[test]
fn outputs_are_readable_by_everyone_the_umask_allows() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    // What this process's umask makes of a new file, as `run` and any editor write it.
    let probe = dir.path().join("probe");
    std::fs::File::create(&probe).unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    let expected = mode(&probe);
    let report = dir.path().join("report");
    let out = platbench()
        .arg("report")
        .arg(&level)
        .args(["--backend", "sweep", "--out"])
        .arg(&report)
        .output()
        .unwrap();
    assert_success(&out);
    for f in ["report.html", "report.md"] {
        assert_eq!(mode(&report.join(f)), expected, "{f}");
    }
    let run = dir.path().join("run");
    assert_success(&run_quick(&level, &run, &[]));
    assert_eq!(mode(&run.join("metrics.csv")), expected);
}

// ---- 2. limits: what hung or ran out of memory is refused before any work ----------------

/// Runs `cmd` (stdout discarded), failing the test if it has not ended after `secs` seconds;
/// then it is killed. The guards below are not timings: each is many times what the command
/// takes in a debug build on a loaded 2-core machine, there only so a hang fails the test
/// instead of stalling it.
pub(super) fn output_within(mut cmd: std::process::Command, secs: u64) -> Output {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(secs);
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} did not end within {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A ten-tile floor with one scenario whose extra lines are `extra`.
fn level_with(extra: &str) -> String {
    format!("name = \"h\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\n{extra}\n")
}

#[test]
fn inputs_that_hung_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        // Level::solids_overlapping walked a 1e30-tile box.
        ("size = [1e30, 1e30]", "size width is 1"),
        // The tunneled metric on Rapier never ended.
        ("motion = { gravity = 1e38 }", "motion.gravity is 1"),
        // `n += 1.0` above 2^53 in the jump solver.
        (
            "motion = { jump_height = 1e30 }\ninputs = [ { t = 0.0, jump = true } ]",
            "motion.jump_height is 1",
        ),
        // Zero steps, silently.
        ("dt = 1e30", "dt is 1"),
    ];
    for (extra, needle) in cases {
        let path = dir.path().join("h.toml");
        std::fs::write(&path, level_with(extra)).unwrap();
        let mut cmd = platbench();
        cmd.arg("run")
            .arg(&path)
            .arg("--out")
            .arg(dir.path().join("o"));
        // Refused while parsing: milliseconds; 30 s only guards against a hang.
        assert_error(&output_within(cmd, 30), needle);
    }
    // --dt 1e-9 bypassed the frame cap (7.2 GB in 14 s).
    let path = dir.path().join("ok.toml");
    std::fs::write(&path, level_with("")).unwrap();
    let mut cmd = platbench();
    cmd.arg("run").arg(&path).args(["--dt", "1e-9", "--out"]);
    cmd.arg(dir.path().join("o"));
    assert_error(&output_within(cmd, 30), "--dt");
    // A step allowed alone but too many frames for a scenario: named with the scenario.
    std::fs::write(
        &path,
        level_with("").replace("duration = 1.0", "duration = 100.0"),
    )
    .unwrap();
    let mut cmd = platbench();
    cmd.arg("run").arg(&path).args(["--dt", "1e-6", "--out"]);
    cmd.arg(dir.path().join("o"));
    assert_error(&output_within(cmd, 30), "expected at most 10000000");
}

#[test]
fn maps_that_ran_out_of_memory_or_never_ended_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    // 100000 x 100000 tiles: once an allocation of 480 GB before the size check.
    let big = dir.path().join("big.tmx");
    std::fs::write(
        &big,
        "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"100000\" height=\"100000\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n<layer id=\"1\" name=\"g\" width=\"100000\" height=\"100000\"><data encoding=\"csv\">0</data></layer>\n</map>\n",
    )
    .unwrap();
    let mut cmd = platbench();
    cmd.arg("run")
        .arg(&big)
        .arg("--out")
        .arg(dir.path().join("o"));
    assert_error(&output_within(cmd, 30), "100000 x 100000 tiles");
    // A TOML map over the same tile cap (MAX_TILES in src/limits.rs, a million): 1001 x 1000
    // tiles.
    let row = ".".repeat(1001);
    let rows = vec![row.as_str(); 1000].join("\n");
    let huge = dir.path().join("huge.toml");
    std::fs::write(
        &huge,
        format!("name = \"huge\"\nmap = \"\"\"\n{rows}\n\"\"\"\n"),
    )
    .unwrap();
    let mut cmd = platbench();
    cmd.arg("run")
        .arg(&huge)
        .arg("--out")
        .arg(dir.path().join("o"));
    assert_error(&output_within(cmd, 60), "expected at most 1000000 tiles");
    // A file that never ends, as a level and as a map: a device, refused before it is read
    // (once read up to the 128 MiB input cap).
    if Path::new("/dev/zero").exists() {
        let zero_map = dir.path().join("zero.tmx");
        std::os::unix::fs::symlink("/dev/zero", &zero_map).unwrap();
        for input in [Path::new("/dev/zero"), zero_map.as_path()] {
            let mut cmd = platbench();
            cmd.arg("run")
                .arg(input)
                .arg("--out")
                .arg(dir.path().join("o"));
            assert_error(
                &output_within(cmd, 60),
                "it is a character device; expected a regular file",
            );
        }
    }
}

#[test]
fn a_long_fall_off_the_map_runs_in_time_linear_in_its_frames() {
    // 1e4 s at dt = 0.1: 100,000 frames of a fall that reaches 3e4 tiles per frame. The
    // tunneled metric once walked every tile of each frame's swept gap (1.5e9 tiles here, per
    // configuration); it now walks only the gap's part inside the 4 x 2 map.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fall.toml");
    std::fs::write(
        &path,
        "name = \"fall\"\nmap = \"\"\"\n....\n....\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 10000.0\ndt = 0.1\n",
    )
    .unwrap();
    let out_dir = dir.path().join("o");
    let mut cmd = platbench();
    cmd.arg("run")
        .arg(&path)
        .args(["--backend", "sweep", "--out"])
        .arg(&out_dir);
    // 300,000 character-steps and their metrics: a few seconds in a debug build.
    let out = output_within(cmd, 120);
    assert_success(&out);
    let trace = std::fs::read_to_string(out_dir.join("traces/fall.s.sweep.csv")).unwrap();
    // The header, the spawn row and 100,000 frames.
    assert_eq!(trace.lines().count(), 100_002);
}

// ---- 2b. every numeric parameter of a level file, at the extremes -----------------------

mod extremes {
    use platbench::level::parse_level;
    use platbench::limits::MAX_FRAMES;
    use platbench::metrics::evaluate;
    use platbench::scenario::step_count;
    use platbench::{rapier::ColliderBuilding, shape::CharacterShape};
    use proptest::prelude::*;

    /// Every number of a level file, with a value that makes a valid level.
    const PARAMS: &[(&str, f64)] = &[
        ("ox", 0.0),
        ("oy", 0.0),
        ("px", 6.0),
        ("pw", 2.0),
        ("amp", 2.0),
        ("per", 2.0),
        ("sx", 1.5),
        ("sy", 1.0),
        ("dur", 1.0),
        ("dt", 1.0 / 60.0),
        ("w", 0.8),
        ("h", 0.9),
        ("vx", 0.0),
        ("vy", 0.0),
        ("ey", 1.0),
        ("jh", 3.0),
        ("rs", 6.0),
        ("g", 30.0),
        ("t", 0.0),
        ("slope", 0.5),
    ];

    const TEMPLATE: &str = r#"name = "p"
origin = [{ox}, {oy}]
map = """
..........
..........
....==..s.
##########
"""
[legend]
s = { line = [0.0, {slope}] }
[[platform]]
rect = [{px}, 2.0, {pw}, 0.5]
sine = { amplitude = [{amp}, 0.0], period = {per} }
[[scenario]]
name = "s"
spawn = [{sx}, {sy}]
duration = {dur}
dt = {dt}
size = [{w}, {h}]
velocity = [{vx}, {vy}]
expect_y = {ey}
motion = { jump_height = {jh}, run_speed = {rs}, gravity = {g} }
inputs = [ { t = {t}, right = true, jump = true } ]
"#;

    /// A TOML float literal.
    fn toml(v: f64) -> String {
        if v.is_nan() {
            "nan".into()
        } else if v.is_infinite() {
            if v > 0.0 { "inf" } else { "-inf" }.into()
        } else {
            format!("{v:?}")
        }
    }

    /// 1e-30 to 1e38 either sign, NaN, the infinities, zero.
    fn extreme() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(0.0),
            Just(-0.0),
            (-30i32..=38, 1.0f64..10.0, any::<bool>()).prop_map(|(e, m, neg)| {
                let v = m * 10f64.powi(e);
                if neg {
                    -v
                } else {
                    v
                }
            }),
        ]
    }

    proptest! {
        // 512 cases: most values are refused while parsing (microseconds); an accepted one
        // runs at most 2,000 frames on two configurations (well under a second in a debug
        // build), so the whole test takes seconds.
        #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]
        #[test]
        fn every_parameter_at_the_extremes_is_an_error_or_a_bounded_run(
            which in 0..PARAMS.len(),
            value in extreme(),
        ) {
            let mut text = TEMPLATE.to_string();
            for (k, (name, default)) in PARAMS.iter().enumerate() {
                let v = if k == which { value } else { *default };
                text = text.replace(&format!("{{{name}}}"), &toml(v));
            }
            let level = match parse_level(&text, "p.toml") {
                // A clean error: located and saying what it expected.
                Err(e) => {
                    prop_assert!(e.line > 0 && e.message.contains("expected"), "{e}");
                    return Ok(());
                }
                Ok(l) => l,
            };
            let spec = level.scenarios[0].clone();
            // What the parser accepts runs a bounded number of frames.
            prop_assert!(step_count(&spec) as u64 <= MAX_FRAMES);
            // Run the first 2,000 frames of it: the per-frame work is what is bounded here (the
            // frame count is, above); a run that does not end within the guard is a hang. The
            // guard, 60 s, is over 100 times what 2,000 frames take in a debug build.
            let mut short = spec.clone();
            short.duration = short.duration.min(2000.0 * short.dt);
            let (tx, rx) = std::sync::mpsc::channel();
            let configs = [
                platbench::sweep::kind::run_default(),
                platbench::rapier::kind::run(ColliderBuilding::PerTile, CharacterShape::Capsule),
            ];
            std::thread::spawn(move || {
                for run in &configs {
                    // An error (a parameter a backend refuses) is as good as a run.
                    let _ = evaluate(&level, &short, run);
                }
                let _ = tx.send(());
            });
            prop_assert!(
                rx.recv_timeout(std::time::Duration::from_secs(60)).is_ok(),
                "parameter {} = {value} did not finish", PARAMS[which].0
            );
        }
    }
}

// ---- 3. diff ------------------------------------------------------------------------------

#[test]
fn an_output_name_too_long_to_move_aside_is_refused_before_any_work() {
    // A 255-byte `--out` name was written once, then could not be replaced: the previous output
    // is moved aside as `.platbench-old-<pid>-<n>-NAME`, past a file name's 255 bytes, and that
    // was found only after the run. The longest name allowed is 255 less that prefix at its
    // longest (two u32s: 37 bytes), 218; one byte more is refused at once, naming both.
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    let out = run_quick(&level, &dir.path().join("d".repeat(219)), &[]);
    assert_error(&out, "the folder's name is 219 bytes; expected at most 218");
    assert!(!dir.path().join("d".repeat(219)).exists());
    for _ in 0..2 {
        let out = run_quick(&level, &dir.path().join("d".repeat(218)), &[]);
        common::assert_success(&out);
    }
}

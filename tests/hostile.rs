//! Issue 21, "Nothing lost, nothing hangs": one regression case for each class of hostile input
//! it found, run through the `platbench` binary as a user runs it.
//!
//! 1. outputs: `--out` never replaces what is not a platbench output of the same command;
//! 2. limits: inputs that hung or ran out of memory are refused before any work;
//! 3. diff: NaN, bad tolerances and missing or truncated traces fail the diff;
//! 4. panics: input that panicked inside a dependency is an error;
//! 5. silently accepted input is an error or a warning;
//! 6. the small things (permissions, counts, ignored flags).

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{assert_success, platbench};

/// A quick level: a floor and one 0.5 s scenario.
const QUICK: &str = "name = \"quick\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"stand\"\nspawn = [1.5, 1.0]\nduration = 0.5\n";

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Fails unless the command exited 2 (an error) with `needle` in its message and no panic.
fn assert_error(out: &Output, needle: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(needle), "expected {needle:?} in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

fn quick_level(dir: &Path) -> PathBuf {
    let path = dir.join("quick.toml");
    std::fs::write(&path, QUICK).unwrap();
    path
}

/// `platbench run LEVEL --backend sweep --out OUT EXTRA...`
fn run_quick(level: &Path, out: &Path, extra: &[&str]) -> Output {
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

#[test]
fn a_staging_directory_left_by_a_dead_run_is_removed_and_others_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let level = quick_level(dir.path());
    // The id of a process that has ended: a child we waited for.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_platbench"))
        .arg("--version")
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let dead = child.id();
    child.wait().unwrap();
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

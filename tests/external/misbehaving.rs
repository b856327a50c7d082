//! A fake client that misbehaves at step 2 in each way the protocol forbids: each ends its own
//! run with an error naming the controller, the scenario and the step; nothing hangs, and the
//! rest of a command's runs complete.

use std::time::{Duration, Instant};

use platbench::scenario::{run_scenario, RunError};

use crate::common;
use crate::{configs, controller_file, python, root};

/// Runs `flat_seams.stand` on the fake client in `mode` and returns the error.
fn fail(mode: &str) -> Option<RunError> {
    let py = python("tests/external/misbehaving.rs (a fake client that misbehaves)")?;
    let dir = tempfile::tempdir().unwrap();
    let fake = root().join("tests/external/fake.py");
    let file = controller_file(dir.path(), "fake", &py, &fake, &[mode], "collision", 300);
    let run = &configs(&file)[0];
    let level = common::level("flat_seams");
    let spec = level.scenarios.iter().find(|s| s.name == "stand").unwrap();
    let start = Instant::now();
    let e = run_scenario(&level, spec, run).expect_err(mode);
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "{mode} took {:?}",
        start.elapsed()
    );
    assert!(e.is_failure(), "{mode}: {e}");
    let text = e.to_string();
    assert!(
        text.starts_with("fake/default failed on flat_seams.stand at step 2: "),
        "{mode}: {text}"
    );
    Some(e)
}

/// The error's text must contain `what`.
fn says(mode: &str, what: &str) {
    if let Some(e) = fail(mode) {
        assert!(e.to_string().contains(what), "{mode}: {e}");
    }
}

#[test]
fn a_client_that_crashes_ends_its_run() {
    says("crash", "exited with exit status: 3");
    says("crash", "fake: crashing on purpose");
}

#[test]
fn a_client_that_hangs_is_killed_at_its_timeout() {
    says("hang", "no reply within its timeout of 300 ms");
}

#[test]
fn a_client_that_prints_garbage_ends_its_run() {
    says(
        "garbage",
        "it printed \"this is not JSON\" where a reply was due",
    );
}

#[test]
fn a_client_that_replies_out_of_order_ends_its_run() {
    says("order", "it replied to step 3 when step 2 was asked");
}

#[test]
fn a_client_that_returns_non_finite_numbers_ends_its_run() {
    // NaN is not JSON: a parse error. A number beyond f32 is infinite once read.
    says("nan", "where a reply was due");
    says("huge", "state is not finite");
}

#[test]
fn a_client_that_exceeds_its_timeout_ends_its_run() {
    says("slow", "no reply within its timeout of 300 ms");
}

#[test]
fn a_failed_run_leaves_the_rest_of_the_command_to_complete() {
    let Some(py) = python("tests/external/misbehaving.rs (the rest of a run completes)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let fake = root().join("tests/external/fake.py");
    let file = controller_file(dir.path(), "fake", &py, &fake, &["crash"], "collision", 300);
    let o = common::platbench()
        .args([
            "run",
            "--backend",
            "fake,sweep",
            "--scenario",
            "drops,flat_seams.stand",
        ])
        .arg("--out")
        .arg(dir.path().join("run"))
        .arg("--controller")
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("error: fake/default failed on drops.drop_0_1 at step 2"),
        "{stderr}"
    );
    assert!(
        stderr.contains("runs failed (the others completed"),
        "{stderr}"
    );
    // The sweep's runs all completed and were written.
    let metrics = std::fs::read_to_string(dir.path().join("run/metrics.csv")).unwrap();
    assert!(
        metrics
            .lines()
            .any(|l| l.contains("flat_seams,stand,sweep,")),
        "{metrics}"
    );
    assert!(!metrics.lines().any(|l| l.contains(",fake,")));
}

#[test]
fn a_bad_controller_file_names_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(
        &file,
        "name = \"x\"\ncommand = \"python3\"\nmode = \"fast\"\n",
    )
    .unwrap();
    let o = common::platbench()
        .args(["run", "--controller"])
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr.contains(&format!("{}:3:8: mode \"fast\"", file.display())),
        "{stderr}"
    );
}

#[test]
fn a_tcp_client_that_never_connects_is_killed_at_its_start_timeout() {
    let Some(py) = python("tests/external/misbehaving.rs (a TCP client that never connects)")
    else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("silent.toml");
    std::fs::write(
        &file,
        format!(
            "name = \"silent\"\ncommand = {:?}\nargs = [\"-c\", \"import time; print('waiting', flush=True); time.sleep(100)\"]\nmode = \"collision\"\ntransport = \"tcp\"\nstart_timeout_ms = 2000\n",
            py.display().to_string()
        ),
    )
    .unwrap();
    let start = Instant::now();
    let Err(e) = platbench::external::load(&file) else {
        panic!("it never connects, yet it loaded")
    };
    // 2 s of start timeout (python3 starts in well under that), and the kill: well under the 100 s it would sleep.
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "{:?}",
        start.elapsed()
    );
    let text = e.to_string();
    assert!(
        text.contains(
            "did not connect to port $PLATBENCH_PORT within its start timeout of 2000 ms"
        ),
        "{text}"
    );
    // Over TCP its stdout is free for logs, and quoted as its stderr is.
    assert!(text.contains("its stdout ended: waiting"), "{text}");
}

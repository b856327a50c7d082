//! A fake client that misbehaves at step 2 in each way the protocol forbids: each ends its own
//! run with an error naming the controller, the scenario and the step; nothing hangs, and the
//! rest of a command's runs complete.

use std::time::{Duration, Instant};

use platbench::scenario::{run_scenario, RunError};

use crate::common;
use crate::{configs, controller_file, python, root, write_controller};

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
    let file = write_controller(
        dir.path(),
        "silent",
        &py.display().to_string(),
        &[
            "-c",
            "import time; print('waiting', flush=True); time.sleep(100)",
        ],
        "mode = \"collision\"\ntransport = \"tcp\"\nstart_timeout_ms = 2000\n",
    );
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

/// The live (not zombie) processes whose parent is `pid`, from /proc.
#[cfg(target_os = "linux")]
fn children(pid: u32) -> Vec<u32> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else {
            continue;
        };
        // pid (comm) state ppid ...: the command may hold spaces and parentheses.
        let Some(after) = stat.rfind(')').map(|i| &stat[i + 1..]) else {
            continue;
        };
        let fields: Vec<&str> = after.split_whitespace().collect();
        if fields.len() > 1 && fields[0] != "Z" && fields[1] == pid.to_string() {
            if let Ok(p) = entry.file_name().to_string_lossy().parse() {
                found.push(p);
            }
        }
    }
    found
}

/// Whether process `pid` is gone (or a zombie waiting for its new parent to reap it).
#[cfg(target_os = "linux")]
fn gone(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).map_or(true, |s| {
        s.rfind(')')
            .and_then(|i| s[i + 1..].split_whitespace().next())
            .is_some_and(|state| state == "Z")
    })
}

#[cfg(target_os = "linux")]
#[test]
fn no_controller_outlives_a_killed_platbench() {
    let Some(py) = python("tests/external/misbehaving.rs (platbench killed mid-run)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let script = root().join("controllers/python/client.py");
    let stdio = controller_file(dir.path(), "python", &py, &script, &[], "collision", 5000);
    let tcp = dir.path().join("tcp.toml");
    let text = std::fs::read_to_string(&stdio).unwrap();
    std::fs::write(
        &tcp,
        text.replace("name = \"python\"", "name = \"pytcp\"") + "transport = \"tcp\"\n",
    )
    .unwrap();
    for (file, name) in [(&stdio, "python"), (&tcp, "pytcp")] {
        // platbench killed with SIGKILL (no handler can run) while a controller runs, over
        // each transport: the controller must not outlive it.
        let mut command = common::platbench();
        command
            .args([
                "run",
                "--backend",
                name,
                "--scenario",
                "long_floor,very_long_floor",
            ])
            .arg("--out")
            .arg(dir.path().join(format!("run-{name}")))
            .arg("--controller")
            .arg(file);
        kill_mid_run(command, name);
    }
}

#[test]
fn stress_and_sweep_go_on_past_a_failed_run() {
    let Some(py) = python("tests/external/misbehaving.rs (stress and sweep go on)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let fake = root().join("tests/external/fake.py");
    let file = controller_file(dir.path(), "fake", &py, &fake, &["crash"], "collision", 300);
    // stress: every probe point of the crashing client fails, is heard, and the matrix ends
    // with no error (the library call the CLI makes; the whole stress CLI, with the sweep's
    // points beside, takes minutes in a debug build).
    let runs = configs(&file);
    let mut failures = Vec::new();
    let rows = platbench::stress::stress_matrix_reporting(
        &runs[..1],
        None,
        2,
        |_| {},
        |e| failures.push(e.to_string()),
    )
    .unwrap();
    let points = platbench::stress::points(&runs[..1]).len();
    assert!(rows.is_empty());
    assert_eq!(failures.len(), points, "{failures:?}");
    assert!(
        failures[0].starts_with("fake/default failed on stress."),
        "{}",
        failures[0]
    );
    // sweep: the client's setting gets no row, the sweep's settings do, the files are written,
    // and the command exits 2 naming the failure.
    let o = common::platbench()
        .args(["sweep", "--backend", "fake,sweep", "--scenario", "drops"])
        .arg("--out")
        .arg(dir.path().join("sweep"))
        .arg("--controller")
        .arg(&file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("error: fake/default failed on drops."),
        "{stderr}"
    );
    let csv = std::fs::read_to_string(dir.path().join("sweep/tradeoff.csv")).unwrap();
    assert!(csv.lines().any(|l| l.starts_with("sweep,")), "{csv}");
    assert!(!csv.lines().any(|l| l.starts_with("fake,")), "{csv}");
}

/// Starts `platbench` (a `run` command), waits until it has a controller process (20 s: the
/// handshake's process comes and goes first, and python3 or Godot start in well under a second
/// even on a loaded machine), kills platbench with SIGKILL (no handler can run) and asserts
/// that every controller process it had is gone within 5 s (the kernel's parent-death signal
/// kills it at once on Linux; a controller also exits at the end of its input, as the protocol
/// asks).
#[cfg(target_os = "linux")]
pub(crate) fn kill_mid_run(mut platbench: std::process::Command, what: &str) {
    let mut platbench = platbench
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let mut running = Vec::new();
    while running.is_empty() && start.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(300));
        running = children(platbench.id());
    }
    assert!(!running.is_empty(), "{what}: no controller process seen");
    platbench.kill().unwrap();
    platbench.wait().unwrap();
    assert!(
        all_gone_within(&running, Duration::from_secs(5)),
        "{what}: controller processes {running:?} outlived platbench"
    );
}

/// Whether every process of `pids` is gone within `limit`.
#[cfg(target_os = "linux")]
fn all_gone_within(pids: &[u32], limit: Duration) -> bool {
    let start = Instant::now();
    while !pids.iter().all(|&p| gone(p)) && start.elapsed() < limit {
        std::thread::sleep(Duration::from_millis(20));
    }
    pids.iter().all(|&p| gone(p))
}

#[test]
fn a_client_that_stops_reading_cannot_block_platbench() {
    let Some(py) = python("tests/external/misbehaving.rs (a client that stops reading)") else {
        return;
    };
    // A level whose `run` message (every solid tile listed) is far more than a pipe holds
    // (64 KiB on Linux): written to a client that no longer reads, the write blocks; platbench's
    // wait for the reply must still end at the start timeout.
    let dir = tempfile::tempdir().unwrap();
    let fake = root().join("tests/external/fake.py");
    let file = write_controller(
        dir.path(),
        "deaf",
        &py.display().to_string(),
        &[&fake.display().to_string(), "deaf"],
        "mode = \"collision\"\nstep_timeout_ms = 300\nstart_timeout_ms = 1000\n",
    );
    let row = "#".repeat(600);
    let mut map = String::from(&format!("{}\n", ".".repeat(600)));
    for _ in 0..33 {
        map.push_str(&row);
        map.push('\n');
    }
    let text = format!(
        "name = \"big\"\nmap = '''\n{map}'''\n\n[[scenario]]\nname = \"stand\"\nspawn = [1.5, 34.0]\nduration = 1.0\n"
    );
    let level = platbench::level::parse_level(&text, "big.toml").unwrap();
    let run = &configs(&file)[0];
    let start = Instant::now();
    let e = run_scenario(&level, &level.scenarios[0], run).expect_err("it never replies");
    // 1 s of start timeout and the kill: far from forever.
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
    assert!(
        e.to_string()
            .contains("no reply within its timeout of 1000 ms"),
        "{e}"
    );
}

#[cfg(target_os = "linux")]
#[test]
fn a_wrapper_scripts_own_children_are_killed_with_it() {
    let Some(py) = python("tests/external/misbehaving.rs (a wrapper script)") else {
        return;
    };
    // `sh -c "python3 fake.py hang PIDFILE; :"` keeps the shell as platbench's child and the
    // client as its child: at the timeout both must go (platbench kills the process group).
    let dir = tempfile::tempdir().unwrap();
    let fake = root().join("tests/external/fake.py");
    let pidfile = dir.path().join("client.pid");
    let script = format!(
        "{:?} {:?} hang {:?}; :",
        py.display().to_string(),
        fake.display().to_string(),
        pidfile.display().to_string()
    );
    let file = write_controller(
        dir.path(),
        "wrapped",
        "sh",
        &["-c", &script],
        "mode = \"collision\"\nstep_timeout_ms = 300\n",
    );
    let run = &configs(&file)[0];
    let level = common::level("flat_seams");
    let spec = level.scenarios.iter().find(|s| s.name == "stand").unwrap();
    let e = run_scenario(&level, spec, run).expect_err("it hangs");
    assert!(e.to_string().contains("no reply within its timeout"), "{e}");
    let pid: u32 = std::fs::read_to_string(&pidfile)
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    // Killed with the group at once; 2 s for the kernel on a loaded machine.
    assert!(
        all_gone_within(&[pid], Duration::from_secs(2)),
        "the wrapped client {pid} outlived its run"
    );
}

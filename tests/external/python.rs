//! The Python reference client: protocol conformance, determinism, every built-in scenario it
//! models, the controller file in the repository, and the pipe's overhead.

use platbench::scenario::run_scenario;

use crate::common;
use crate::{configs, controller_file, python, root};

/// The reference client's controller file, written for the interpreter found.
fn client(dir: &std::path::Path, py: &std::path::Path) -> std::path::PathBuf {
    let script = root().join("controllers/python/client.py");
    controller_file(dir, "python", py, &script, &[], "collision", 5000)
}

#[test]
fn the_python_client_answers_the_handshake_and_lands_on_the_floor() {
    let Some(py) = python("tests/external/python.rs (the Python reference client)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let kind = platbench::external::load(&client(dir.path(), &py)).unwrap();
    assert_eq!(kind.name(), "python");
    assert!(
        kind.description().contains("python-aabb"),
        "{}",
        kind.description()
    );
    assert!(kind.description().contains("collision mode"));
    let runs = kind.builtin_configs();
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0].label, "aabb");
    assert_eq!(runs[0].backend.features(), platbench::level::Features::NONE);
    assert!(runs[0]
        .why
        .starts_with("collision mode over the step protocol"));
    // A drop from half a tile: every row finite, the feet flush on the floor's top (y = 1) and
    // grounded once landed, as the trace says.
    let level = common::level("drops");
    let spec = level
        .scenarios
        .iter()
        .find(|s| s.name == "drop_0_5")
        .unwrap();
    let trace = run_scenario(&level, spec, &runs[0]).unwrap();
    assert_eq!(trace.backend, "python");
    assert_eq!(trace.config, "aabb");
    assert_eq!(trace.rows.len(), platbench::scenario::step_count(spec) + 1);
    assert!(trace
        .rows
        .iter()
        .all(|r| r.x.is_finite() && r.y.is_finite()));
    let last = trace.rows.last().unwrap();
    assert_eq!(last.grounded, 1);
    assert!((last.y - 1.0).abs() < 1e-6, "rests at {}", last.y);
    assert_eq!((last.vx, last.vy), (0.0, 0.0));
}

#[test]
fn the_python_client_gives_the_same_trace_twice() {
    let Some(py) = python("tests/external/python.rs (determinism)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let run = &configs(&client(dir.path(), &py))[0];
    let level = common::level("jumps");
    let spec = &level.scenarios[0];
    let a = run_scenario(&level, spec, run).unwrap();
    let b = run_scenario(&level, spec, run).unwrap();
    assert_eq!(a, b);
}

#[test]
fn the_python_client_runs_every_built_in_scenario_it_models() {
    let Some(py) = python("tests/external/python.rs (every built-in scenario)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let run = &configs(&client(dir.path(), &py))[0];
    let (mut ran, mut skipped) = (0, Vec::new());
    for level in common::builtin_levels() {
        for spec in &level.scenarios {
            match run_scenario(&level, spec, run) {
                Ok(trace) => {
                    assert!(
                        trace
                            .rows
                            .iter()
                            .all(|r| r.x.is_finite() && r.y.is_finite()),
                        "{}.{}",
                        level.name,
                        spec.name
                    );
                    ran += 1;
                }
                Err(e) if e.is_unsupported() => {
                    // Skipped for a feature it does not model, said.
                    assert!(
                        !level.features.within(platbench::level::Features::NONE),
                        "{e}"
                    );
                    skipped.push(level.name.clone());
                }
                Err(e) => panic!("{}.{}: {e}", level.name, spec.name),
            }
        }
    }
    assert!(ran >= 30, "ran {ran}");
    assert!(skipped.iter().any(|l| l.starts_with("slope")));
}

#[test]
fn the_repository_controller_file_runs_from_the_command_line() {
    if python("tests/external/python.rs (controllers/python/controller.toml)").is_none() {
        return;
    }
    // The file as committed (python3 on the PATH), beside the sweep; its rows in metrics.csv.
    let out = tempfile::tempdir().unwrap();
    let o = common::platbench()
        .args([
            "run",
            "--backend",
            "python,sweep",
            "--scenario",
            "drops",
            "--out",
        ])
        .arg(out.path().join("run"))
        .arg("--controller")
        .arg(root().join("controllers/python/controller.toml"))
        .output()
        .unwrap();
    common::assert_success(&o);
    let metrics = std::fs::read_to_string(out.path().join("run/metrics.csv")).unwrap();
    assert!(
        metrics.lines().any(|l| l.contains(",python,aabb,")),
        "{metrics}"
    );
    assert!(out
        .path()
        .join("run/traces/drops.drop_1.python.aabb.csv")
        .exists());
}

#[test]
fn pipe_overhead() {
    let Some(py) = python("tests/external/python.rs (the pipe's overhead)") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    crate::print_overhead(
        &configs(&client(dir.path(), &py))[0],
        "the Python client's own",
    );
}

#[test]
fn the_python_client_over_tcp_gives_the_trace_it_gives_over_stdio() {
    let Some(py) = python("tests/external/python.rs (the TCP transport)") else {
        return;
    };
    // `transport = "tcp"`: the same client, its lines over a loopback connection to the port in
    // $PLATBENCH_PORT (Godot's client's transport). The trace must be the pipe's, bit for bit.
    let dir = tempfile::tempdir().unwrap();
    let stdio = client(dir.path(), &py);
    let text = std::fs::read_to_string(&stdio).unwrap();
    let tcp = dir.path().join("tcp.toml");
    std::fs::write(&tcp, format!("{text}transport = \"tcp\"\n")).unwrap();
    let level = common::level("jumps");
    let spec = &level.scenarios[0];
    let a = run_scenario(&level, spec, &configs(&stdio)[0]).unwrap();
    let b = run_scenario(&level, spec, &configs(&tcp)[0]).unwrap();
    assert_eq!(a, b);
}

#[test]
fn a_baseline_of_an_external_controller_is_checked_without_naming_it_again() {
    let Some(py) = python("tests/external/python.rs (baseline and check)") else {
        return;
    };
    // The baseline records `--controller FILE`; `check` loads it again, so the same selection
    // finds nothing missing.
    let dir = tempfile::tempdir().unwrap();
    let file = client(dir.path(), &py);
    let base = dir.path().join("base");
    let o = common::platbench()
        .args(["baseline", "--backend", "python", "--scenario", "drops"])
        .arg("--controller")
        .arg(&file)
        .arg("--baseline")
        .arg(&base)
        .output()
        .unwrap();
    common::assert_success(&o);
    let manifest = std::fs::read_to_string(base.join("manifest.toml")).unwrap();
    assert!(manifest.contains("controllers = ["), "{manifest}");
    let o = common::platbench()
        .arg("check")
        .arg("--baseline")
        .arg(&base)
        .arg("--out")
        .arg(dir.path().join("check"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(stdout.contains("0 failed"), "{stdout}");
}

//! External controllers over the step protocol (docs/protocol.md): the Python reference client
//! (`controllers/python`) conforms, repeats itself bit for bit and runs every built-in scenario
//! it models; a fake client that misbehaves in each way ends only its own run, with an error
//! naming the controller, the scenario and the step; and the pipe's overhead per step, measured.
//! Every test needs `python3` (`PLATBENCH_PYTHON` names another): without it each says loudly
//! that it skipped, unless `PLATBENCH_REQUIRE_PROGRAMS=1`.

#[path = "../common/mod.rs"]
mod common;

mod godot;
mod misbehaving;
mod python;

use std::path::{Path, PathBuf};

use platbench::config::RunConfig;

/// The Python interpreter, or `None` (said loudly) when there is none.
pub(crate) fn python(test: &str) -> Option<PathBuf> {
    common::outside_program(
        test,
        "python3",
        "PLATBENCH_PYTHON",
        "apt-get install -y python3",
    )
}

/// The repository's root.
pub(crate) fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Writes a controller file in `dir` running `script` with `python` and `args`, in `mode`,
/// with a step timeout of `timeout_ms`; returns its path.
pub(crate) fn controller_file(
    dir: &Path,
    name: &str,
    python: &Path,
    script: &Path,
    args: &[&str],
    mode: &str,
    timeout_ms: u64,
) -> PathBuf {
    let script = script.display().to_string();
    let mut all = vec![script.as_str()];
    all.extend(args);
    write_controller(
        dir,
        name,
        &python.display().to_string(),
        &all,
        &format!("mode = {mode:?}\nstep_timeout_ms = {timeout_ms}\n"),
    )
}

/// Writes the controller file `dir/NAME.toml` running `command` with `args`, its other lines
/// `rest` (TOML, the mode among them); returns its path. Rust's `{:?}` of a string is a valid
/// TOML basic string for the paths and scripts these tests write.
pub(crate) fn write_controller(
    dir: &Path,
    name: &str,
    command: &str,
    args: &[&str],
    rest: &str,
) -> PathBuf {
    let args: Vec<String> = args.iter().map(|a| format!("{a:?}")).collect();
    let text = format!(
        "name = {name:?}\ncommand = {command:?}\nargs = [{}]\n{rest}",
        args.join(", ")
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The configurations of the controller file at `path`.
pub(crate) fn configs(path: &Path) -> Vec<RunConfig> {
    platbench::external::load(path)
        .unwrap_or_else(|e| panic!("{e}"))
        .builtin_configs()
}

/// Prints the wall time of a step of `run` minus the time the controller reports for it: what
/// the transport, the JSON on both sides and the other process's scheduling cost, per step
/// (`own` names the controller's reported time in the line).
pub(crate) fn print_overhead(run: &RunConfig, own_label: &str) {
    let level = common::level("long_floor");
    let spec = &level.scenarios[0];
    let mut runner = platbench::scenario::Runner::new(&level);
    let params = platbench::scenario::effective_params(&run.params, spec);
    let ch = [platbench::backend::CharacterSpec::of(spec)];
    let mut backend = runner.build(run, &params, &ch).unwrap();
    let steps = platbench::scenario::step_count(spec);
    let input = [platbench::motion::Input {
        right: true,
        ..Default::default()
    }];
    let start = std::time::Instant::now();
    for _ in 0..steps {
        backend.step(&input, spec.dt);
    }
    let wall = start.elapsed().as_nanos() as f64 / steps as f64;
    assert_eq!(backend.failure(), None);
    let own = backend.reported_ns().unwrap() / steps as f64;
    let overhead = wall - own;
    use std::io::Write as _;
    let _ = writeln!(
        std::io::stderr(),
        "{}: overhead {overhead:.0} ns per step ({wall:.0} ns wall, {own:.0} ns {own_label}, {steps} steps of {}.{})",
        run.label,
        level.name,
        spec.name
    );
    assert!(overhead.is_finite() && own > 0.0);
}

//! External controllers over the step protocol (docs/protocol.md): the Python reference client
//! (`controllers/python`) conforms, repeats itself bit for bit and runs every built-in scenario
//! it models; a fake client that misbehaves in each way ends only its own run, with an error
//! naming the controller, the scenario and the step; and the pipe's overhead per step, measured.
//! Every test needs `python3` (`PLATBENCH_PYTHON` names another): without it each says loudly
//! that it skipped, unless `PLATBENCH_REQUIRE_PROGRAMS=1`.

#[path = "../common/mod.rs"]
mod common;

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
    let mut all = vec![format!("{:?}", script.display().to_string())];
    all.extend(args.iter().map(|a| format!("{a:?}")));
    let text = format!(
        "name = {name:?}\ncommand = {:?}\nargs = [{}]\nmode = {mode:?}\nstep_timeout_ms = {timeout_ms}\n",
        python.display().to_string(),
        all.join(", ")
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

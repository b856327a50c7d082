//! Godot 3's `KinematicBody2D`, built in: the GDScript client of `controllers/godot3/client.gd`,
//! compiled into platbench, run by the Debian package `godot3-server` (Godot 3.2) over the step
//! protocol's TCP transport. `--controller godot3` names it from any directory, and the built-in
//! comparison (`platbench` with no subcommand) includes it when `godot3-server` is on the PATH.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::config::ControllerFile;
use super::ExternalError;
use crate::controller::BackendKind;

/// The name `--controller` takes for the built-in Godot 3 client, and its backend name.
pub const NAME: &str = "godot3";
/// The program that runs it: Debian's and Ubuntu's headless Godot 3 (`apt-get install
/// godot3-server`); the environment variable `PLATBENCH_GODOT3` names another.
pub const PROGRAM: &str = "godot3-server";
/// The environment variable that names the Godot 3 server to run instead of `godot3-server`.
pub const PROGRAM_VARIABLE: &str = "PLATBENCH_GODOT3";
/// How to install it, for messages.
pub const INSTALL: &str = "apt-get install godot3-server";

/// The client's GDScript, its controller file and its project file (which keeps Godot from
/// writing a log file beside it on every run), as in the repository.
const CLIENT: &str = include_str!("../../controllers/godot3/client.gd");
const CONTROLLER: &str = include_str!("../../controllers/godot3/controller.toml");
const PROJECT: &str = include_str!("../../controllers/godot3/project.godot");

/// The Godot 3 server to run: `$PLATBENCH_GODOT3`, else `godot3-server` on the PATH, else
/// `None`.
pub fn program() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os(PROGRAM_VARIABLE).filter(|p| !p.is_empty()) {
        return Some(PathBuf::from(p));
    }
    let paths = std::env::var_os("PATH")?;
    std::env::split_paths(&paths)
        .map(|d| d.join(PROGRAM))
        .find(|p| p.is_file())
}

/// Writes the client and its project file into a directory of its own under the system's
/// temporary directory (named by their content, so that a changed client never runs an old copy),
/// once: each is written to a temporary name and renamed into place, so concurrent platbench
/// processes never read half a file.
fn client_directory() -> Result<PathBuf, String> {
    let hash = crate::input::fnv1a64(CLIENT.bytes().chain(PROJECT.bytes()));
    let dir = std::env::temp_dir().join(format!("platbench-godot3-{hash:016x}"));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    for (name, text) in [("project.godot", PROJECT), ("client.gd", CLIENT)] {
        let path = dir.join(name);
        if std::fs::read_to_string(&path).is_ok_and(|t| t == text) {
            continue;
        }
        let partial = dir.join(format!("{name}.{}.partial", std::process::id()));
        std::fs::write(&partial, text)
            .and_then(|()| std::fs::rename(&partial, &path))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(dir)
}

/// The repository's controller file (`controllers/godot3/controller.toml`: arguments, transport,
/// timeouts), run by `program` in the client's directory.
fn file(program: &Path) -> Result<ControllerFile, ExternalError> {
    let fail = |message: String| ExternalError::Handshake {
        file: format!("built-in {NAME}"),
        name: NAME.into(),
        message,
    };
    let dir = client_directory().map_err(fail)?;
    let mut file = super::config::parse(CONTROLLER, &dir.join("controller.toml"))?;
    file.source = format!("built-in {NAME} (controllers/godot3/controller.toml)");
    file.command = program.to_path_buf();
    Ok(file)
}

/// Why there is no Godot 3 client to run, and how to get one.
pub fn missing() -> String {
    format!("no `{PROGRAM}` on the PATH (nor ${PROGRAM_VARIABLE}); install it with `{INSTALL}`")
}

/// The built-in Godot 3 controller run by `program` (its handshake asked).
pub fn load_with(program: &Path) -> Result<Arc<dyn BackendKind>, ExternalError> {
    super::load_file(file(program)?)
}

/// The built-in Godot 3 controller, or `None` when there is no Godot 3 server ([`program`]).
pub fn load() -> Option<Result<Arc<dyn BackendKind>, ExternalError>> {
    program().map(|p| load_with(&p))
}

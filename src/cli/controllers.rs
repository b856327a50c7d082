//! `--controller FILE`: external controllers registered before the options are parsed (their
//! names are `--backend` values); `--controller godot3` is the built-in Godot 3 client, which the
//! built-in comparison adds by itself when Godot 3 is installed.

use std::path::PathBuf;

use anyhow::{bail, Result};

use super::Harness;
use crate::external::godot3;

/// `harness` with the external controllers of the `--controller FILE` arguments in `args`
/// registered after its own kinds, or `None` when there is none.
pub(super) fn with_controllers(
    harness: &Harness,
    args: &[std::ffi::OsString],
) -> Result<Option<Harness>> {
    let mut files: Vec<PathBuf> = Vec::new();
    let mut it = args.iter().skip(1);
    while let Some(a) = it.next() {
        let Some(a) = a.to_str() else { continue };
        if a == "--" {
            break;
        }
        if a == "--controller" {
            if let Some(f) = it.next() {
                files.push(PathBuf::from(f));
            }
        } else if let Some(f) = a.strip_prefix("--controller=") {
            files.push(PathBuf::from(f));
        }
    }
    if files.is_empty() {
        return Ok(None);
    }
    let mut h = harness.clone();
    for f in &files {
        let kind = load(f)?;
        if h.registry.get(kind.name()).is_some() {
            bail!(
                "{}: a controller named {:?} is already registered; expected a name of its own in the controller file",
                f.display(),
                kind.name()
            );
        }
        h.registry.register(kind);
    }
    Ok(Some(h))
}

/// `harness` with the controller files a baseline recorded (`manifest.toml`'s
/// `selection.controllers`, as given to `baseline`) registered, those whose controller is not
/// registered already (by `--controller` on this command line); `None` when none is added.
pub(super) fn with_recorded(harness: &Harness, files: &[String]) -> Result<Option<Harness>> {
    let mut h = harness.clone();
    let mut added = false;
    for f in files {
        let kind = load(std::path::Path::new(f)).map_err(|e| {
            e.context(format!(
                "the baseline was written with --controller {f}, which check loads again from the directory it runs in"
            ))
        })?;
        if h.registry.get(kind.name()).is_none() {
            h.registry.register(kind);
            added = true;
        }
    }
    Ok(added.then_some(h))
}

/// The controller `--controller f` names: the controller file `f`, or the built-in Godot 3
/// client for `godot3` when no file of that name is there.
fn load(f: &std::path::Path) -> Result<std::sync::Arc<dyn crate::controller::BackendKind>> {
    Ok(if f.as_os_str() == godot3::NAME && !f.is_file() {
        let Some(program) = godot3::program() else {
            bail!("--controller {}: {}", godot3::NAME, godot3::missing());
        };
        godot3::load_with(&program)?
    } else {
        crate::external::load(f)?
    })
}

/// `harness` with the built-in Godot 3 client added for the built-in comparison (`platbench`
/// with no subcommand) when a Godot 3 server is installed; said on stderr either way. `None`
/// when it is not added (no server, already registered, or its handshake failed: said).
pub(super) fn with_builtin_godot3(harness: &Harness) -> Option<Harness> {
    if harness.registry.get(godot3::NAME).is_some() {
        return None;
    }
    match godot3::load() {
        None => {
            eprintln!(
                "note: the comparison leaves out Godot 3's rows: {}, to compare Godot 3's KinematicBody2D too",
                godot3::missing()
            );
            None
        }
        Some(Err(e)) => {
            eprintln!("note: the comparison leaves out Godot 3's rows: {e}");
            None
        }
        Some(Ok(kind)) => {
            eprintln!(
                "note: with Godot 3's rows ({}; `--controller godot3` adds them to any command)",
                kind.description()
            );
            let mut h = harness.clone();
            h.registry.register(kind);
            Some(h)
        }
    }
}

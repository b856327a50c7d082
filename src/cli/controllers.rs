//! `--controller FILE`: external controllers registered before the options are parsed (their
//! names are `--backend` values).

use std::path::PathBuf;

use anyhow::{bail, Result};

use super::Harness;

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
        let kind = crate::external::load(f)?;
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

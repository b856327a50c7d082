//! `platbench levels`: the built-in levels and their scenarios.

use anyhow::Result;

use super::{builtin_levels, out};

pub(crate) fn list_levels() -> Result<()> {
    for level in builtin_levels()? {
        out(&format!(
            "{} ({} x {} tiles): {}",
            level.name, level.width, level.height, level.description
        ));
        for s in &level.scenarios {
            out(&format!("    {}  ({} s)", s.name, s.duration));
        }
    }
    Ok(())
}

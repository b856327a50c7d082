//! The verdict's side of `run` and `report`: what each configuration declares, the game
//! profiles the verdict picks for, and the verdict text the terminal prints.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};

use crate::config::RunConfig;
use crate::report::profile::{builtin_profiles, parse_profile, Profile};
use crate::report::verdict::{
    pick, render_capabilities, render_scorecard, render_verdict, Facts, Scorecard,
};

/// What configuration `run` declares, its why falling back on its controller's description.
pub(crate) fn facts(run: &RunConfig, registry: &crate::registry::Registry) -> Facts {
    let mut f = Facts::of(run);
    if f.why.is_empty() {
        if let Some(k) = registry.get(&f.backend) {
            f.why = k.description().to_string();
        }
    }
    f
}

/// The game profiles of `files`, or the built-in ones when none is given.
pub(crate) fn load_profiles(files: &[PathBuf]) -> Result<Vec<Profile>> {
    if files.is_empty() {
        return Ok(builtin_profiles());
    }
    let mut profiles: Vec<Profile> = Vec::new();
    for f in files {
        // A profile is a small regular file: a pipe or a device would block or never end.
        let meta =
            std::fs::metadata(f).with_context(|| format!("cannot read profile {}", f.display()))?;
        if !meta.is_file() {
            bail!(
                "cannot read profile {}: it is not a regular file; expected a profile file (TOML)",
                f.display()
            );
        }
        let text = crate::limits::read_text_capped(f)
            .with_context(|| format!("cannot read profile {}", f.display()))?;
        let p = parse_profile(&text, &f.display().to_string())?;
        if profiles.iter().any(|q| q.name == p.name) {
            bail!(
                "{}: a profile named {:?} was already given; expected each --profile to have a name of its own",
                f.display(),
                p.name
            );
        }
        profiles.push(p);
    }
    Ok(profiles)
}

/// Where the verdict's profiles come from, as it says.
pub(crate) fn profile_source(files: &[PathBuf]) -> String {
    if files.is_empty() {
        "Profiles: compare/profiles/*.toml; `--profile FILE` judges your own.".into()
    } else {
        let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
        format!("Profiles: {} (--profile).", names.join(", "))
    }
}

/// The verdict of `profiles`, the scorecard and the capability table, as the terminal prints
/// them.
pub(crate) fn verdict_text(card: &Scorecard, profiles: &[Profile], files: &[PathBuf]) -> String {
    let verdicts: Vec<_> = profiles.iter().map(|p| pick(card, p)).collect();
    format!(
        "{}\n{}\n{}",
        render_verdict(card, &verdicts, &profile_source(files)),
        render_scorecard(card),
        render_capabilities(card)
    )
}

//! `platbench inspect MAP`: what a Tiled or LDtk map was read as.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

use super::{out, ImportArgs};

#[derive(Args)]
pub(crate) struct InspectArgs {
    /// The map file: a Tiled map (.tmx, .tmj or .json) or an LDtk project (.ldtk).
    pub(crate) map: PathBuf,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

/// `platbench inspect MAP`: what the import read, for a user to compare with their game.
pub(crate) fn inspect(args: &InspectArgs) -> Result<()> {
    use crate::level::import::ascii_map;
    let opts = args.import.options()?;
    let p = &args.map;
    let r = match crate::level::detect_format(p)? {
        crate::level::LevelFormat::Ldtk => import_ldtk(p, &opts)?,
        crate::level::LevelFormat::Tmx | crate::level::LevelFormat::TiledJson => {
            import_tiled(p, &opts)?
        }
        crate::level::LevelFormat::Level => return Err(not_a_map(p)),
    };
    let l = &r.level;
    let mut text = format!(
        "{}: level {:?}, {} x {} tiles{}\n",
        p.display(),
        l.name,
        l.width,
        l.height,
        if l.features.names().is_empty() {
            String::new()
        } else {
            format!(" ({})", l.features.names().join(", "))
        }
    );
    text.push_str("\nlayers:\n");
    for layer in &r.layers {
        text.push_str(&format!(
            "  {} ({}{}): {} — {}\n",
            crate::input::quoted(&layer.name),
            layer.kind,
            if layer.empty { ", empty" } else { "" },
            layer.role.name(),
            layer.why
        ));
    }
    // Where a convention or a default decided, the line that says what the game means.
    let guessed: Vec<_> = r.layers.iter().filter(|l| l.is_guess()).collect();
    // A name longer than a line is not echoed into the suggestion whole.
    const LONGEST_SHOWN: usize = 200;
    let (shown, long): (Vec<&&_>, Vec<&&_>) =
        guessed.iter().partition(|l| l.name.len() <= LONGEST_SHOWN);
    if !long.is_empty() {
        text.push_str(&format!(
            "
{} guessed layer(s) have names over {LONGEST_SHOWN} bytes, left out of the lines below: rename them in the map to set their role in a side file\n",
            long.len()
        ));
    }
    if !shown.is_empty() {
        // A world's levels repeat their layers' names: one entry per name.
        let mut seen = std::collections::HashSet::new();
        let entries: Vec<String> = shown
            .iter()
            .map(|l| l.side_file_entry())
            .filter(|e| seen.insert(e.clone()))
            .collect();
        text.push_str(&format!(
            "\nguessed: {} layer(s), by name or by default; to make them certain, or to say what your game reads instead, edit and put in {}:\n  [import]\n  layers = {{ {} }}\n",
            shown.len(),
            p.with_extension("toml").display(),
            entries.join(", ")
        ));
    }
    text.push_str("\nspawns (feet, tiles, y up):\n");
    if r.spawns.is_empty() {
        text.push_str("  none\n");
    }
    for (s, why) in r.spawns.iter().zip(&r.spawn_sources) {
        text.push_str(&format!(
            "  {} at ({}, {}) — {why}\n",
            s.name, s.position.x, s.position.y
        ));
    }
    text.push_str("\nplatforms:\n");
    if l.platforms.is_empty() {
        text.push_str("  none\n");
    }
    for (k, pl) in l.platforms.iter().enumerate() {
        let path = match &pl.motion {
            crate::level::PlatformMotion::Waypoints { points, speed } => format!(
                "path {} at {speed} tiles/s",
                points
                    .iter()
                    .map(|q| format!("({}, {})", q.x, q.y))
                    .collect::<Vec<_>>()
                    .join(" -> ")
            ),
            other => format!("{other:?}"),
        };
        text.push_str(&format!(
            "  {k}: {} x {} at ({}, {}){}, {path}\n",
            pl.size.x,
            pl.size.y,
            pl.start.x,
            pl.start.y,
            if pl.one_way { ", one-way" } else { "" }
        ));
    }
    // The probes `run` makes from these spawns, and those the map makes impossible.
    let cfg = crate::level::ProbeConfig::default();
    let (probes, notes) = crate::level::probe_scenarios(l, &r.spawns, &cfg)
        .with_context(|| format!("{}: the map's probes cannot run", p.display()))?;
    text.push_str(&format!("\nprobes: {}\n", probes.len()));
    // Each spawn's probes, `SPAWN-PROBE` (no probe's own name holds a '-'), gathered in one pass.
    let mut by_spawn: std::collections::HashMap<&str, Vec<&str>> = Default::default();
    for q in &probes {
        if let Some((spawn, probe)) = q.name.rsplit_once('-') {
            by_spawn.entry(spawn).or_default().push(probe);
        }
    }
    for s in &r.spawns {
        let run = match by_spawn.get(s.name.as_str()) {
            Some(run) => run.join(", "),
            None => "none".to_string(),
        };
        text.push_str(&format!("  {}: {run}\n", s.name));
    }
    for (subject, note) in &notes {
        text.push_str(&format!("  {subject}: {note}\n"));
    }
    text.push_str(&format!("\nwarnings: {}\n", r.warnings.len()));
    for w in &r.warnings {
        text.push_str(&format!("  {}: {}\n", w.subject, w.message));
    }
    let (map, legend) = ascii_map(l);
    text.push_str("\ngrid (top row first; # solid, = one-way, H ladder, / \\ slopes, . empty):\n");
    text.push_str(&map);
    for (c, s) in legend {
        text.push_str(&format!("  {c} = {s:?}\n"));
    }
    out(text.trim_end());
    Ok(())
}

/// A file that is no map (a platbench level, or anything neither XML nor JSON): what it starts
/// with, where, and what `inspect` reads.
fn not_a_map(p: &std::path::Path) -> anyhow::Error {
    use std::io::Read;
    let mut start = Vec::new();
    let read = crate::input::open(p, crate::limits::MAX_INPUT_BYTES, "input file")
        .map(|f| f.take(64 * 1024).read_to_end(&mut start));
    if let Err(e) = read {
        return e.into();
    }
    let (line, column, found) = crate::level::first_text(&String::from_utf8_lossy(&start));
    anyhow::anyhow!(
        "{}:{line}:{column}: found {found}, which is no map: it starts neither XML (`<`) nor a JSON object (`{{`), so it reads as a platbench level (TOML); platbench inspect expects a Tiled map (.tmx, .tmj or .json) or an LDtk project (.ldtk) and shows how it is imported (a platbench level is run as it is: platbench run {})",
        p.display(),
        p.display()
    )
}

#[cfg(feature = "ldtk")]
fn import_ldtk(
    p: &std::path::Path,
    opts: &crate::level::ImportOptions,
) -> Result<crate::level::MapImport> {
    crate::level::ldtk::import_ldtk_with(p, opts).map_err(|f| {
        for w in &f.warnings {
            eprintln!("warning: {w}");
        }
        anyhow::Error::new(f.error)
    })
}

#[cfg(not(feature = "ldtk"))]
fn import_ldtk(
    p: &std::path::Path,
    _: &crate::level::ImportOptions,
) -> Result<crate::level::MapImport> {
    Err(super::missing_feature(p, "ldtk", "LDtk projects"))
}

#[cfg(feature = "tiled")]
fn import_tiled(
    p: &std::path::Path,
    opts: &crate::level::ImportOptions,
) -> Result<crate::level::MapImport> {
    let t = crate::level::import_tiled_map_with(p, opts).map_err(|f| {
        for w in &f.warnings {
            eprintln!("warning: {w}");
        }
        anyhow::Error::new(f.error)
    })?;
    Ok(crate::level::MapImport {
        level: t.level,
        spawns: t.spawns,
        spawn_sources: t.spawn_sources,
        layers: t.layers,
        warnings: t.warnings,
    })
}

#[cfg(not(feature = "tiled"))]
fn import_tiled(
    p: &std::path::Path,
    _: &crate::level::ImportOptions,
) -> Result<crate::level::MapImport> {
    Err(super::missing_feature(p, "tiled", "Tiled maps"))
}

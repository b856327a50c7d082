//! Reading the level files a command is given: each file's format told by its content, maps
//! through their importer with the command line's overrides ([`ImportArgs`]), warnings printed.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::builtin_levels;
use crate::level::{parse_level, Level};

/// Overrides of the map importers' defaults (docs/formats.md, "Tiled maps" and "LDtk maps").
#[derive(Args, Default, Clone)]
#[command(allow_negative_numbers = true)]
pub(crate) struct ImportArgs {
    /// Read a map layer as ROLE: collision, solid, one_way, ladder, objects or decoration
    /// (NAME in any case; repeatable). Overrides the layer's name and properties.
    #[arg(long = "layer", value_name = "NAME=ROLE")]
    pub(crate) layers: Vec<String>,
    /// Read the tile layers no name or property marks as ROLE: collision, solid, one_way, ladder
    /// or decoration.
    #[arg(long, value_name = "ROLE")]
    pub(crate) tile_layers: Option<String>,
    /// Start the probes here instead of the map's spawns: feet position in tiles, y up
    /// (repeatable).
    #[arg(long = "spawn", value_name = "X,Y", allow_hyphen_values = true)]
    pub(crate) spawns: Vec<String>,
    /// LDtk: make an IntGrid value (its number or name) solid, one_way, ladder or empty
    /// (repeatable).
    #[arg(long = "intgrid", value_name = "VALUE=KIND")]
    pub(crate) intgrid: Vec<String>,
    /// LDtk: import this one level of the world (its identifier) instead of the whole world.
    #[arg(long, value_name = "NAME")]
    pub(crate) level: Option<String>,
    /// The map's left and right sides: walls (a wall outside each side the map leaves open, as
    /// games stop the player at their world's bounds; the bottom stays open) or open. Default:
    /// walls for Tiled maps, open for LDtk projects (docs/maps.md measures both).
    #[arg(long, value_name = "walls|open")]
    pub(crate) edges: Option<String>,
}

impl ImportArgs {
    pub(crate) fn options(&self) -> Result<crate::level::ImportOptions> {
        use crate::level::import::parse_tile_kind;
        use crate::level::{ImportOptions, LayerRole};
        let mut o = ImportOptions::default();
        for l in &self.layers {
            let Some((name, role)) = l.rsplit_once('=') else {
                bail!("--layer {l}: expected NAME=ROLE");
            };
            let Some(r) = LayerRole::parse(role) else {
                bail!("--layer {l}: {role:?} is no role; expected collision, solid, one_way, ladder, objects or decoration");
            };
            o.layer_roles.push((name.to_string(), r));
        }
        if let Some(t) = &self.tile_layers {
            // `objects` names what an object layer holds; a tile layer holds none.
            let role = LayerRole::parse(t).filter(|r| *r != LayerRole::Objects);
            o.tile_layers = Some(role.with_context(|| {
                format!(
                    "--tile-layers {t}: expected collision, solid, one_way, ladder or decoration"
                )
            })?);
        }
        for sp in &self.spawns {
            let v: Vec<f64> = sp
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| anyhow::anyhow!("--spawn {sp}: expected X,Y in tiles"))?;
            let far = crate::limits::MAX_COORD;
            match v[..] {
                [x, y] if x.abs() <= far && y.abs() <= far => {
                    o.spawns.push(glam::Vec2::new(x as f32, y as f32))
                }
                [_, _] => bail!("--spawn {sp}: expected X,Y, two numbers of tiles from -{far:e} to {far:e} (inside the level)"),
                _ => bail!("--spawn {sp}: expected X,Y, two numbers of tiles"),
            }
        }
        for g in &self.intgrid {
            let Some((v, kind)) = g.rsplit_once('=') else {
                bail!("--intgrid {g}: expected VALUE=KIND");
            };
            let Some(t) = parse_tile_kind(kind) else {
                bail!(
                    "--intgrid {g}: {kind:?} is no kind; expected solid, one_way, ladder or empty"
                );
            };
            o.intgrid.push((v.to_string(), t));
        }
        o.level = self.level.clone();
        if let Some(e) = &self.edges {
            o.edges = Some(
                crate::level::import::Edges::parse(e)
                    .with_context(|| format!("--edges {e}: expected walls or open"))?,
            );
        }
        Ok(o)
    }
}

/// The error for a map whose importer this build left out (its Cargo `feature` is off).
#[allow(dead_code)]
pub(crate) fn missing_feature(p: &std::path::Path, feature: &str, what: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "{}: reading {what} needs platbench's `{feature}` Cargo feature, which this build leaves out (it is on by default: drop `default-features = false`, or add `features = [\"{feature}\"]`)",
        p.display()
    )
}

/// Loads a Tiled or LDtk map with the import overrides, printing its warnings — those gathered
/// before a failure too.
#[cfg_attr(not(all(feature = "tiled", feature = "ldtk")), allow(unused_variables))]
pub(crate) fn load_map(p: &std::path::Path, opts: &crate::level::ImportOptions) -> Result<Level> {
    let format = crate::level::detect_format(p)?;
    let result = if format == crate::level::LevelFormat::Ldtk {
        #[cfg(feature = "ldtk")]
        let r = crate::level::ldtk::load_ldtk_with(p, opts)
            .map_err(|f| (anyhow::Error::new(f.error), f.warnings));
        #[cfg(not(feature = "ldtk"))]
        let r = Err::<(Level, Vec<crate::level::ImportWarning>), _>((
            missing_feature(p, "ldtk", "LDtk projects"),
            Vec::<crate::level::ImportWarning>::new(),
        ));
        r
    } else {
        #[cfg(feature = "tiled")]
        let r = crate::level::load_tiled_map_with(p, opts)
            .map_err(|f| (anyhow::Error::new(f.error), f.warnings));
        #[cfg(not(feature = "tiled"))]
        let r = Err::<(Level, Vec<crate::level::ImportWarning>), _>((
            missing_feature(p, "tiled", "Tiled maps"),
            Vec::<crate::level::ImportWarning>::new(),
        ));
        r
    };
    match result {
        Ok((level, warnings)) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            Ok(level)
        }
        Err((e, warnings)) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            Err(e)
        }
    }
}

pub(crate) fn load_levels(paths: &[PathBuf]) -> Result<Vec<Level>> {
    load_levels_with(paths, &ImportArgs::default())
}

pub(crate) fn load_levels_with(paths: &[PathBuf], import: &ImportArgs) -> Result<Vec<Level>> {
    // Each file's format, told by its content; a file that cannot be read is named here.
    let formats = paths
        .iter()
        .map(|p| {
            crate::level::detect_format(p).map_err(|e| anyhow::anyhow!(e.reading("level file")))
        })
        .collect::<Result<Vec<_>>>()?;
    let maps = formats.iter().any(|f| f.is_map());
    if let Some(name) = &import.level {
        if !formats.contains(&crate::level::LevelFormat::Ldtk) {
            eprintln!(
                "warning: --level {name} picks one level of an LDtk project, and no .ldtk file is given, so it changes nothing; to run one level of the set, use --scenario {name}"
            );
        }
    }
    let ldtk = formats.contains(&crate::level::LevelFormat::Ldtk);
    if maps && !ldtk && !import.intgrid.is_empty() {
        eprintln!(
            "warning: --intgrid names LDtk IntGrid values, and no .ldtk file is given, so it changes nothing; a Tiled map's tiles are set with --layer NAME=ROLE"
        );
    }
    if !maps
        && (!import.layers.is_empty()
            || import.tile_layers.is_some()
            || !import.spawns.is_empty()
            || !import.intgrid.is_empty()
            || import.edges.is_some())
    {
        eprintln!(
            "warning: --layer, --tile-layers, --spawn, --intgrid and --edges read Tiled (.tmx, .tmj) and LDtk (.ldtk) maps, and no map file is given, so they change nothing"
        );
    }
    if paths.is_empty() {
        return builtin_levels().context("a built-in level is invalid");
    }
    let opts = import.options()?;
    let mut levels: Vec<Level> = Vec::new();
    for (p, format) in paths.iter().zip(formats) {
        let level = if format.is_map() {
            load_map(p, &opts)?
        } else {
            let text = crate::input::read_text(
                p,
                crate::limits::MAX_TOML_BYTES,
                "TOML level or side file",
            )
            .map_err(|e| anyhow::anyhow!(e.reading("level file")))?;
            parse_level(&text, &p.display().to_string()).map_err(|e| {
                // A file named like a map but not one reads as a level: say so, not only why
                // the TOML failed.
                let toml = p.extension().is_some_and(|x| x.eq_ignore_ascii_case("toml"));
                if toml {
                    anyhow::Error::new(e)
                } else {
                    anyhow::anyhow!("{e} (read as {format}: it starts neither like a Tiled map, XML or JSON, nor like an LDtk project)")
                }
            })?
        };
        if level.scenarios.is_empty() {
            // Nothing would run: a level without scenarios would put a run of zero cost and
            // zero error into every table and onto the trade-off's front.
            let fix = if format.is_map() {
                "every probe is a map problem (the warnings above say why); --spawn X,Y, or a side file beside the map with spawns or [[scenario]] entries, gives it one"
            } else {
                "add a [[scenario]] with a name, spawn and duration"
            };
            eprintln!(
                "warning: {}: the level has no scenario, so nothing runs on it; skipped ({fix})",
                level.source
            );
            continue;
        }
        if let Some(other) = levels.iter().find(|l| l.name == level.name) {
            bail!(
                "{} and {} both name their level {:?}; level names must be unique in a run (they name the trace files)",
                other.source,
                level.source,
                level.name
            );
        }
        levels.push(level);
    }
    if levels.is_empty() {
        bail!("none of the level files has a scenario to run");
    }
    Ok(levels)
}

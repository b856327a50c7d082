//! Import of LDtk projects (`.ldtk`, levels inline or in external `.ldtkl` files; the JSON of
//! LDtk 0.9.3 to 1.5.3, read with serde, every field the import does not need ignored).
//!
//! Collision comes from the IntGrid layers: every non-zero cell is solid unless its value's
//! name says one-way (`platform`, `oneway`, ...), ladder, or hazard (`water`, `spikes`, `acid`,
//! ...: not solid); a separate IntGrid layer named like platforms is one-way; `--intgrid` and
//! `--layer` override. Spawns are entities named `Player`, `Spawn`, `SpawnPoint`, `PlayerSpawn`,
//! `Start_Point` (the spawn names of `import::names`), feet at the bottom centre of the box
//! their pivot places. A world in a GridVania or Free layout is one level in world
//! coordinates; a linear world's first level is imported; `--level NAME` picks one. Tile units,
//! y up, as for Tiled (LDtk is y-down pixels).
//!
//! Split by concern: `json` (the JSON platbench reads, with the bounds on its numbers) and
//! `convert` (the project made into a level: the levels picked, the grid, the IntGrid cells,
//! the entities that are spawns). This file holds the entry points and the error.

use std::path::Path;

use serde::Deserialize;

mod convert;
mod grid;
mod json;
mod values;

use super::import::{ImportFailure, ImportOptions, ImportWarning, MapImport};
use super::probes::{probe_scenarios, ProbeConfig};
use super::toml::{options_beside, read_side, SideFailure};
use super::{parse_scenarios, Level, LevelError};
use convert::import;

/// An LDtk project platbench cannot run as it is.
#[derive(Debug, thiserror::Error)]
pub enum LdtkError {
    /// The file (project or external level) could not be read.
    #[error("{file}: cannot read the LDtk file: {message}")]
    Read {
        /// The file.
        file: String,
        /// The system's message.
        message: String,
    },
    /// The file is not the JSON of an LDtk project or level, or holds a value out of range.
    #[error("{file}:{line}:{column}: {message}")]
    Json {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// Something in the project platbench cannot use, with what was expected.
    #[error("{file}: {message}")]
    Project {
        /// The file.
        file: String,
        /// What was found and what was expected.
        message: String,
    },
    /// The project's side file (`MAP.toml`) could not be read.
    #[error("{file}: cannot read this side file (the [import] table and scenarios beside an LDtk project): {message}")]
    SideRead {
        /// The side file.
        file: String,
        /// Why, without the file's name.
        message: String,
    },
    /// The side file's scenarios are invalid (file, line and column inside).
    #[error(transparent)]
    SideFile(#[from] LevelError),
}

const HOW_TO_SPAWN: &str =
    "add an entity named Player, Spawn or PlayerSpawn in an Entities layer in LDtk";
const HOW_TO_COLLIDE: &str =
    "paint the walls in an IntGrid layer, or pass --intgrid VALUE=solid or --layer NAME=collision";

/// Reads `text`, the file `file`, as the JSON of `what` (`an LDtk project`, `an LDtk level`):
/// its top level must be an object; the error is at its line and column, said once.
fn parse_json<T: for<'de> Deserialize<'de>>(
    text: &str,
    file: &str,
    what: &str,
) -> Result<T, LdtkError> {
    let (line, column, first) = super::format::first_text(text);
    if !super::format::looks_like_json(text) {
        return Err(LdtkError::Json {
            file: file.into(),
            line,
            column,
            message: if text.trim_start_matches('\u{feff}').trim().is_empty() {
                format!("found {first}; expected {what} (a JSON object, `{{`)")
            } else {
                format!("found {first} at the top level; expected {what} (a JSON object, `{{`)")
            },
        });
    }
    if text.starts_with('\u{feff}') {
        return Err(LdtkError::Json {
            file: file.into(),
            line: 1,
            column: 1,
            message: super::format::JSON_BOM.into(),
        });
    }
    serde_json::from_str(text).map_err(|e| json_error(&e, file, what))
}

/// A JSON error at its place, its message without the parser's own "at line L column C" (the
/// error's prefix says where); a syntax error says the file is not JSON, a wrong or
/// out-of-range value says only what it is and what was expected.
fn json_error(e: &serde_json::Error, file: &str, what: &str) -> LdtkError {
    let full = e.to_string();
    let at = format!(" at line {} column {}", e.line(), e.column());
    let bare = full.strip_suffix(&at).unwrap_or(&full);
    // serde's own words for a value of the wrong shape; any other data error is platbench's
    // (a limit), which is about an LDtk file, not a sign it is none.
    const SHAPE: [&str; 7] = [
        "invalid type",
        "invalid value",
        "invalid length",
        "unknown variant",
        "unknown field",
        "missing field",
        "duplicate field",
    ];
    let message = match e.classify() {
        serde_json::error::Category::Data if !SHAPE.iter().any(|p| bare.starts_with(p)) => {
            bare.to_string()
        }
        serde_json::error::Category::Data => format!("not {what}: {bare}"),
        _ => format!("not valid JSON ({bare}); expected {what}"),
    };
    LdtkError::Json {
        file: file.into(),
        line: e.line(),
        column: e.column().max(1),
        message,
    }
}

/// Loads an LDtk project as a runnable level with the command line's overrides: its geometry,
/// and the scenarios of the side file `MAP.toml` next to it, else the standard probes at each
/// spawn. On failure the warnings gathered so far come with the error.
pub fn load_ldtk_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<(Level, Vec<ImportWarning>), ImportFailure<LdtkError>> {
    let MapImport {
        mut level,
        spawns,
        mut warnings,
        ..
    } = import_ldtk_with(path, opts)?;
    if let Some(side) = crate::level::toml::side_file_of(path) {
        let fail = |error: LdtkError, warnings| ImportFailure { error, warnings };
        let text = match read_side(&side) {
            Ok(t) => t,
            Err(e) => return Err(fail(side_error(e), warnings)),
        };
        match parse_scenarios(&text, &side.display().to_string(), &level) {
            Ok(s) => level.scenarios = s,
            Err(e) => return Err(fail(e.into(), warnings)),
        }
        // As for a Tiled map: a side file without [[scenario]] says only how to read the
        // project (its [import]); the standard probes run, as without it.
        if !level.scenarios.is_empty() {
            warnings.retain(|w| !w.message.starts_with("no spawn point found"));
            return Ok((level, warnings));
        }
    }
    if spawns.is_empty() {
        return Err(ImportFailure {
            error: LdtkError::Project {
                file: path.display().to_string(),
                message: format!("no spawn entity and no cell to stand on, so nothing can run; {HOW_TO_SPAWN}, pass --spawn X,Y, or write {} with [[scenario]] entries", path.with_extension("toml").display()),
            },
            warnings,
        });
    }
    let (scenarios, notes) = match probe_scenarios(&level, &spawns, &ProbeConfig::default()) {
        Ok(p) => p,
        Err(e) => {
            return Err(ImportFailure {
                error: LdtkError::Project {
                    file: path.display().to_string(),
                    message: format!("the level's probes cannot run: {e}"),
                },
                warnings,
            })
        }
    };
    level.scenarios = scenarios;
    let file = path.display().to_string();
    warnings.extend(notes.into_iter().map(|(subject, message)| ImportWarning {
        file: file.clone(),
        subject,
        message,
    }));
    Ok((level, warnings))
}

/// Reads an LDtk project's geometry and spawns (no scenarios) with the command line's
/// overrides. On failure the warnings gathered so far come with the error.
pub fn import_ldtk_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<MapImport, ImportFailure<LdtkError>> {
    let mut warnings = Vec::new();
    // The side file's [import] table, under the command line's flags.
    let merged = options_beside(path, opts).map_err(|e| ImportFailure {
        error: side_error(e),
        warnings: Vec::new(),
    })?;
    match import(path, &merged, &mut warnings) {
        Ok(mut m) => {
            warnings.append(&mut m.warnings);
            m.warnings = warnings;
            Ok(m)
        }
        Err(error) => Err(ImportFailure { error, warnings }),
    }
}

/// A side file's failure as the project's error: it names the side file, not the project.
fn side_error(e: SideFailure) -> LdtkError {
    match e {
        SideFailure::Read { file, message } => LdtkError::SideRead { file, message },
        SideFailure::Level(e) => LdtkError::SideFile(e),
    }
}

/// The layers of level `level` of the project at `project`, from its external file `rel`
/// (`externalRelPath`, beside the project): the file must be another one, readable, and hold
/// the level's `layerInstances`; each error names the project and the level that points there.
fn external_level(
    project: &Path,
    level: &str,
    rel: &str,
) -> Result<Vec<json::LayerInstance>, LdtkError> {
    let p = project
        .parent()
        .map_or_else(|| Path::new(rel).to_path_buf(), |d| d.join(rel));
    let file = p.display().to_string();
    let named = format!(
        "level {level:?} of {} names it in externalRelPath {rel:?}",
        project.display()
    );
    let same = p.canonicalize().ok().zip(project.canonicalize().ok());
    if same.is_some_and(|(a, b)| a == b) {
        return Err(LdtkError::Project {
            file: project.display().to_string(),
            message: format!("level {level:?}: externalRelPath {rel:?} is the project itself; expected the level's own file (.ldtkl), which LDtk writes beside the project"),
        });
    }
    let text = read(&p).map_err(|e| match e {
        LdtkError::Read { file, message } => LdtkError::Read {
            file,
            message: format!("{message} ({named})"),
        },
        e => e,
    })?;
    let lvl: json::LdLevel = parse_json(&text, &file, "an LDtk level")?;
    lvl.layer_instances.ok_or_else(|| LdtkError::Project {
        file,
        message: format!(
            "holds no layerInstances; expected an LDtk level's JSON with its layers ({named})"
        ),
    })
}

fn read(path: &Path) -> Result<String, LdtkError> {
    use crate::input::InputError;
    crate::input::read_text(path, crate::limits::MAX_INPUT_BYTES, "input file").map_err(|e| {
        let file = path.display().to_string();
        match e {
            InputError::NotText {
                line,
                column,
                found,
                ..
            } => LdtkError::Json {
                file,
                line,
                column,
                message: crate::input::not_text(&found),
            },
            e => LdtkError::Read {
                file,
                message: e.reason(),
            },
        }
    })
}

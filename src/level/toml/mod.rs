//! The TOML level format (DESIGN.md, "Level format"): metadata, a legend, an ASCII map and
//! `[[scenario]]` entries. Every error names the file, line and column and what was expected.
//!
//! This module reads the file's top level ([`parse_level`]); each part has its own file:
//! `error` (the error and the file:line:column it names), `map` (the map string), `strings`
//! (where each byte of a string's value sits in the file, escapes and all), `legend`
//! (the tiles the map's characters stand for, slopes included), `platforms` (moving
//! platforms), `scenarios` (`[[scenario]]` entries, in a level file or an imported map's side
//! file), `expect` (a scenario's expectations) and `numbers` (the checks of numbers against [`crate::limits`]).

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use crate::limits;

use super::Level;

mod budget;
mod error;
mod exact;
mod expect;
#[cfg(test)]
mod expect_tests;
mod legend;
mod map;
mod numbers;
mod platforms;
mod scenarios;
mod side;
mod strings;
mod syntax;
#[cfg(test)]
mod tests;

pub use error::LevelError;
pub use scenarios::parse_scenarios;
pub use side::side_import_options;
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) use side::{options_beside, read_side, side_file_of, SideFailure};
pub(crate) use syntax::explain as explain_toml_error;

use error::Locator;
use legend::parse_legend;
use map::parse_map;
use numbers::ranged_f64;
use platforms::{parse_platform, RawPlatform};
use scenarios::{scenarios, RawScenario};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLevel {
    name: Option<String>,
    description: Option<String>,
    #[serde(default, deserialize_with = "exact::opt_spanned")]
    origin: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    legend: BTreeMap<Spanned<String>, Spanned<toml::Value>>,
    map: Spanned<String>,
    #[serde(default)]
    platform: Vec<Spanned<RawPlatform>>,
    #[serde(default)]
    scenario: Vec<Spanned<RawScenario>>,
}

/// Parses a level file's text. `file` names it in errors.
pub fn parse_level(text: &str, file: &str) -> Result<Level, LevelError> {
    let loc = Locator { file, text };
    budget::check_budget(&loc)?;
    let raw: RawLevel = toml::from_str(text).map_err(|e| loc.toml(&e))?;

    let legend = parse_legend(&loc, &raw.legend)?;
    let (width, height, tiles) = parse_map(&loc, &raw.map, &legend)?;
    let name = raw.name.unwrap_or_else(|| {
        std::path::Path::new(file)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("level")
            .to_string()
    });
    if !super::valid_name(&name) {
        return Err(loc.err(
            0,
            format!(
                "level name {} must be 1 to {} ASCII letters, digits, '_' or '-' (it names output files)",
                crate::input::quoted(&name),
                crate::limits::MAX_NAME_BYTES
            ),
        ));
    }
    let mut level = Level::from_tiles(&name, width, height, tiles);
    level.description = raw.description.unwrap_or_default();
    if let Some(o) = &raw.origin {
        let [x, y] = *o.get_ref();
        let range = (-limits::MAX_ORIGIN, limits::MAX_ORIGIN);
        level.origin = glam::DVec2::new(
            ranged_f64(&loc, &o.span(), "origin x", x, range, "tiles")?,
            ranged_f64(&loc, &o.span(), "origin y", y, range, "tiles")?,
        );
    }
    level.source = file.to_string();

    for p in &raw.platform {
        level.platforms.push(parse_platform(&loc, p)?);
    }
    level.features.moving_platforms = !level.platforms.is_empty();
    level.scenarios = scenarios(&loc, &level, &raw.scenario)?;
    Ok(level)
}

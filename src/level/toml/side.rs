//! The `[import]` table of a map's side file (`MAP.toml` beside `MAP.tmx`, `.tmj` or `.ldtk`):
//! what the game means where no naming rule fits — the role of each layer, the role of the
//! tile layers nothing marks, IntGrid values and tile properties with their kind, the spawns
//! and the map's sides. The command line's flags override it; it overrides the map's own marks.
//!
//! ```toml
//! [import]
//! layers = { Ground = "collision", Bushes = "decoration", Platforms = "one_way" }
//! tile_layers = "decoration"
//! intgrid = { Spikes = "empty", 2 = "one_way" }
//! tile_properties = { damage = "empty", unisolid = "one_way" }
//! spawns = [[3.5, 2.0]]
//! edges = "open"
//! ```

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::error::Locator;
use super::LevelError;
use crate::level::import::{parse_tile_kind, Edges, ImportOptions, LayerRole};

/// The side file's top level as this module reads it: the `[import]` table, anything else left
/// to the scenario reader.
#[derive(Deserialize)]
struct RawSide {
    #[serde(default)]
    import: Option<RawImport>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImport {
    #[serde(default)]
    layers: BTreeMap<String, Spanned<String>>,
    #[serde(default)]
    tile_layers: Option<Spanned<String>>,
    #[serde(default)]
    intgrid: BTreeMap<String, Spanned<String>>,
    #[serde(default)]
    tile_properties: BTreeMap<String, Spanned<String>>,
    #[serde(default, deserialize_with = "super::exact::spanned_list")]
    spawns: Vec<Spanned<[f32; 2]>>,
    #[serde(default)]
    edges: Option<Spanned<String>>,
}

/// The import options of a side file's `[import]` table laid under `cli` (the command line's
/// options, which win): `cli` itself when the text has no such table. Errors name the side
/// file's line and column.
pub fn side_import_options(
    text: &str,
    file: &str,
    cli: &ImportOptions,
) -> Result<ImportOptions, LevelError> {
    let loc = Locator { file, text };
    super::budget::check_budget(&loc)?;
    let raw: RawSide = toml::from_str(text).map_err(|e| loc.toml(&e))?;
    let Some(raw) = raw.import else {
        return Ok(cli.clone());
    };
    let mut o = ImportOptions::default();
    for (name, role) in &raw.layers {
        let r = LayerRole::parse(role.get_ref()).ok_or_else(|| {
            loc.at(
                &role.span(),
                format!("layers.{name:?} = {:?} is no role; expected collision, solid, one_way, ladder, objects or decoration", role.get_ref()),
            )
        })?;
        o.layer_roles.push((name.clone(), r));
    }
    if let Some(t) = &raw.tile_layers {
        o.tile_layers = Some(LayerRole::parse(t.get_ref()).ok_or_else(|| {
            loc.at(
                &t.span(),
                format!(
                    "tile_layers = {:?}: expected collision or decoration",
                    t.get_ref()
                ),
            )
        })?);
    }
    let kind = |what: &str, key: &str, v: &Spanned<String>| {
        parse_tile_kind(v.get_ref()).ok_or_else(|| {
            loc.at(
                &v.span(),
                format!(
                    "{what}.{key:?} = {:?} is no kind; expected solid, one_way, ladder or empty",
                    v.get_ref()
                ),
            )
        })
    };
    for (k, v) in &raw.intgrid {
        o.intgrid.push((k.clone(), kind("intgrid", k, v)?));
    }
    for (k, v) in &raw.tile_properties {
        o.tile_properties
            .push((k.clone(), kind("tile_properties", k, v)?));
    }
    if let Some(s) = raw.spawns.get(crate::limits::MAX_SPAWNS) {
        return Err(loc.at(
            &s.span(),
            format!(
                "spawns: this is spawn point {} of the side file; expected at most {} (each spawn makes up to five probe scenarios)",
                crate::limits::MAX_SPAWNS + 1,
                crate::limits::MAX_SPAWNS
            ),
        ));
    }
    for s in &raw.spawns {
        let [x, y] = *s.get_ref();
        if !(x.is_finite() && y.is_finite()) {
            return Err(loc.at(&s.span(), "a spawn is not finite; expected [x, y] in tiles"));
        }
        o.spawns.push(glam::Vec2::new(x, y));
    }
    if let Some(e) = &raw.edges {
        o.edges = Some(Edges::parse(e.get_ref()).ok_or_else(|| {
            loc.at(
                &e.span(),
                format!("edges = {:?}: expected walls or open", e.get_ref()),
            )
        })?);
    }
    // The command line's flags win: its roles come later (the last match counts), its values
    // replace the side file's.
    o.layer_roles.extend(cli.layer_roles.iter().cloned());
    o.intgrid.extend(cli.intgrid.iter().cloned());
    o.tile_properties
        .extend(cli.tile_properties.iter().cloned());
    if cli.tile_layers.is_some() {
        o.tile_layers = cli.tile_layers;
    }
    if !cli.spawns.is_empty() {
        o.spawns = cli.spawns.clone();
    }
    if cli.edges.is_some() {
        o.edges = cli.edges;
    }
    if cli.level.is_some() {
        o.level = cli.level.clone();
    }
    Ok(o)
}

/// Why a map's side file could not be read for its `[import]` table.
#[derive(Debug)]
#[cfg_attr(not(any(feature = "tiled", feature = "ldtk")), allow(dead_code))]
pub(crate) enum SideFailure {
    /// The file could not be read (its path and why).
    Read { file: String, message: String },
    /// The table is wrong, at its line and column.
    Level(LevelError),
}

/// The side file of `map` when there is one: whatever is at `MAP.toml` beside it other than the
/// map itself (a map saved as `.toml` has none; it is not read twice). Anything there counts, so
/// that a pipe, a device, a directory or a dangling link is refused when read, not ignored.
#[cfg_attr(not(any(feature = "tiled", feature = "ldtk")), allow(dead_code))]
pub(crate) fn side_file_of(map: &std::path::Path) -> Option<std::path::PathBuf> {
    let side = map.with_extension("toml");
    (side.as_path() != map && std::fs::symlink_metadata(&side).is_ok()).then_some(side)
}

/// The import options for `map`: those of its side file `MAP.toml` (when there is one) under
/// the command line's `cli`.
#[cfg_attr(not(any(feature = "tiled", feature = "ldtk")), allow(dead_code))]
pub(crate) fn options_beside(
    map: &std::path::Path,
    cli: &ImportOptions,
) -> Result<ImportOptions, SideFailure> {
    let Some(side) = side_file_of(map) else {
        return Ok(cli.clone());
    };
    let file = side.display().to_string();
    let text = read_side(&side)?;
    side_import_options(&text, &file, cli).map_err(SideFailure::Level)
}

/// The text of the side file `side`: text that is not UTF-8 is an error at its line and column,
/// as any other fault of the file; a file that cannot be read at all says why.
#[cfg_attr(not(any(feature = "tiled", feature = "ldtk")), allow(dead_code))]
pub(crate) fn read_side(side: &std::path::Path) -> Result<String, SideFailure> {
    use crate::input::InputError;
    let file = side.display().to_string();
    crate::input::read_text(
        side,
        crate::limits::MAX_TOML_BYTES,
        "TOML level or side file",
    )
    .map_err(|e| match e {
        InputError::NotText {
            line,
            column,
            found,
            ..
        } => SideFailure::Level(LevelError {
            file,
            line,
            column,
            message: crate::input::not_text(&found),
        }),
        e => SideFailure::Read {
            file,
            message: e.reason(),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::Tile;

    #[test]
    fn the_table_is_read_and_the_command_line_wins() {
        let text = "[import]\nlayers = { Ground = \"collision\", Bushes = \"decoration\" }\nintgrid = { Spikes = \"empty\" }\nedges = \"open\"\nspawns = [[1.5, 2.0]]\n";
        let o = side_import_options(text, "m.toml", &ImportOptions::default()).unwrap();
        assert_eq!(o.role_of("bushes"), Some(LayerRole::Decoration));
        assert_eq!(o.intgrid, [("Spikes".to_string(), Tile::Empty)]);
        assert_eq!(o.edges, Some(Edges::Open));
        assert_eq!(o.spawns, [glam::Vec2::new(1.5, 2.0)]);
        let cli = ImportOptions {
            layer_roles: vec![("Bushes".into(), LayerRole::Collision)],
            edges: Some(Edges::Walls),
            ..ImportOptions::default()
        };
        let o = side_import_options(text, "m.toml", &cli).unwrap();
        assert_eq!(o.role_of("Bushes"), Some(LayerRole::Collision));
        assert_eq!(o.edges, Some(Edges::Walls));
    }

    #[test]
    fn bad_values_are_located() {
        let e = side_import_options(
            "[import]\nedges = \"sideways\"\n",
            "m.toml",
            &ImportOptions::default(),
        )
        .unwrap_err();
        assert_eq!((e.line, e.column), (2, 9), "{e}");
        assert!(e.to_string().contains("expected walls or open"), "{e}");
        let e = side_import_options(
            "[import]\nlayers = { G = \"lava\" }\n",
            "m.toml",
            &ImportOptions::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("is no role"), "{e}");
        let e = side_import_options(
            "[import]\nlayer = {}\n",
            "m.toml",
            &ImportOptions::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("unknown field"), "{e}");
        // No table: the command line's options as they are.
        assert!(side_import_options(
            "[[scenario]]\nname = \"a\"\n",
            "m.toml",
            &ImportOptions::default()
        )
        .is_ok());
    }
}

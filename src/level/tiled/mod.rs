//! Import of maps made with the Tiled editor (`.tmx`; tilesets inline, in `.tsx` files or in
//! JSON `.tsj` files): tile layers become the level's tiles, object layers give collision
//! rectangles and ramps, moving platforms and spawn points, read the way games mark them (layer
//! names, object names and classes, bool tile properties). docs/formats.md's "Tiled maps" section is
//! the user's side of the mapping; this module is its one implementation, split by concern:
//! `error` (what cannot be imported), `read` (the map read through the `tiled` crate), `map`
//! (the map's orientation, extent and properties), `layers` (which layer is what, and the tile
//! layers), `tiles` (what one tile is), `objects` (spawns, collision objects, platforms),
//! `normalize` (what the `tiled` crate cannot read as Tiled writes it), `json` (Tiled's JSON formats
//! as the XML the crate reads) and `json_walk` (what serde_json's tree of one would hold, counted
//! first), `scan` and `points` (what the crate would allocate without bound) and `refs` (what it would follow by recursion without end:
//! templates and tilesets that loop back, groups nested too deep). This file holds the entry points and the state of one import.
//!
//! Nothing here panics on a map's content: every construct platbench cannot represent is a
//! [`TiledError`] or a [`TiledWarning`] that names the tile (tileset and local id, and a map
//! cell where one is involved), the object (id and name) or the layer.

use std::collections::HashMap;
use std::path::Path;

use tiled::{ObjectShape, PropertyValue};

mod approx;
mod attrs;
mod base64;
mod cells;
mod elements;
mod error;
mod gids;
mod json;
mod json_budget;
mod json_frame;
mod json_values;
mod json_walk;
mod layers;
mod map;
mod normalize;
mod objects;
mod points;
mod read;
mod refs;
mod roles;
mod scan;
mod shapes;
mod tiles;
mod tileset_ids;
mod wellformed;

pub use error::TiledError;
pub use read::import_tiled_map_with;

pub(crate) use tiles::ramp;

use super::import::spawns::{no_solids_warning, settle_spawns};
use super::import::{unmatched_layer_roles, wall_sides};
use super::import::{ImportFailure, ImportOptions, ImportWarning, LayerReport, LayerRole};
use super::probes::{probe_scenarios, ProbeConfig, SpawnPoint};
use super::{parse_scenarios, Level, LevelError};
use super::{Slope, Tile};

/// How far a collision-shape point may be from the tile edge or corner it stands for, in
/// pixels: the editor snaps to whole pixels, so a hand-drawn ramp is exact to about one.
pub(crate) const SHAPE_TOLERANCE_PX: f32 = 1.0;

/// A warning of the Tiled import (the shared [`ImportWarning`]).
pub type TiledWarning = ImportWarning;

/// The map property, tile properties and layer property names platbench reads.
mod names {
    /// Tile property: what the tile is (`solid`, `one_way`, `ladder`, `empty`); on a layer, a
    /// bool or a role.
    pub const COLLISION: &str = "collision";
    /// Tile property: height of a line slope at the tile's left edge, in tiles.
    pub const SLOPE_LEFT: &str = "slope_left";
    /// Tile property: height of a line slope at the tile's right edge, in tiles.
    pub const SLOPE_RIGHT: &str = "slope_right";
    /// Tile property: 16 comma-separated heights in sixteenths of a tile.
    pub const HEIGHTS: &str = "heights";
    /// Object class (or type) of a moving platform (optional: a `path` property suffices).
    pub const PLATFORM: &str = "platform";
    /// Object property: the polyline a platform follows (an object reference).
    pub const PATH: &str = "path";
    /// Object property: a platform's speed along its path, in tiles/s.
    pub const SPEED: &str = "speed";
    /// Object property: whether a platform blocks from above only.
    pub const ONE_WAY: &str = "one_way";
    /// Map property: the level's name.
    pub const NAME: &str = "name";
    /// Map property: the level's description.
    pub const DESCRIPTION: &str = "description";
    /// Map property: the role of tile layers no name or property marks.
    pub const TILE_LAYERS: &str = "tile_layers";
    /// Layer properties (normalized) that mark a tile layer the player does not collide with
    /// (HaxeFlixel's Tiled demo: the unmarked tile layers collide).
    pub const NO_COLLIDE: &[&str] = &["nocollide", "nocollision"];

    /// Whether layer property `key` = `value` is a `nocollide` mark set true (a bool, or the
    /// string "true" as HaxeFlixel's demo writes it).
    pub fn is_no_collide(key: &str, value: &tiled::PropertyValue) -> bool {
        NO_COLLIDE.contains(&crate::level::import::normalize(key).as_str())
            && match value {
                tiled::PropertyValue::BoolValue(b) => *b,
                tiled::PropertyValue::StringValue(s) => s.trim().eq_ignore_ascii_case("true"),
                _ => false,
            }
    }
}

/// How to mark a spawn in Tiled, for the messages that need one.
const HOW_TO_SPAWN: &str = "mark one with a point object named or of class \"spawn\" (or \"player\", \"start\") in an object layer";
/// How to mark collision in Tiled, for the messages that need one.
const HOW_TO_COLLIDE: &str = "name the collision layer (\"collision\", \"ground\", \"walls\", \"platforms\"), give it the property collision = true, or pass --layer NAME=collision";

/// A map imported without its scenarios: the level (geometry and platforms), its spawn points,
/// what each layer was read as, and the warnings raised on the way.
#[derive(Clone, Debug)]
pub struct TiledImport {
    /// The level, with no scenarios yet.
    pub level: Level,
    /// The map's spawn points, in the order of the file (or the fallback spawn `auto`).
    pub spawns: Vec<SpawnPoint>,
    /// Where each spawn point came from (the object, the rule), one per spawn.
    pub spawn_sources: Vec<String>,
    /// Each layer with the role it was given and why, in the file's order.
    pub layers: Vec<LayerReport>,
    /// Everything that was ignored or assumed, each naming its tile, object or layer.
    pub warnings: Vec<TiledWarning>,
}

/// Loads a Tiled map as a runnable level with the default rules; see [`load_tiled_map_with`].
pub fn load_tiled_map(path: &Path) -> Result<(Level, Vec<TiledWarning>), TiledError> {
    load_tiled_map_with(path, &ImportOptions::default()).map_err(|f| f.error)
}

/// Loads a Tiled map as a runnable level: its geometry, platforms and scenarios — those of the
/// side file `MAP.toml` next to it when there is one, else the standard probes at each spawn
/// point ([`super::probes`]). Returns the warnings too, for the caller to show; on failure, the
/// warnings gathered so far come with the error.
pub fn load_tiled_map_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<(Level, Vec<TiledWarning>), ImportFailure<TiledError>> {
    let TiledImport {
        mut level,
        spawns,
        mut warnings,
        ..
    } = import_tiled_map_with(path, opts)?;
    let fail = |error: TiledError, warnings: Vec<TiledWarning>| ImportFailure { error, warnings };
    if let Some(side) = crate::level::toml::side_file_of(path) {
        let text = match crate::limits::read_toml_capped(&side) {
            Ok(t) => t,
            Err(e) => {
                return Err(fail(
                    TiledError::SideFileRead {
                        file: side.display().to_string(),
                        message: e.to_string(),
                    },
                    warnings,
                ))
            }
        };
        level.scenarios = match parse_scenarios(&text, &side.display().to_string(), &level) {
            Ok(s) => s,
            Err(e) => return Err(fail(e.into(), warnings)),
        };
        // A side file without [[scenario]] says only how to read the map (its [import], the
        // lines `inspect` suggests): the standard probes run, as without it.
        if !level.scenarios.is_empty() {
            // The fallback spawn's warning is moot when a side file gives the scenarios.
            warnings.retain(|w| !w.message.starts_with("no spawn point found"));
            if !spawns.is_empty() && spawns[0].name != "auto" {
                warnings.push(TiledWarning {
                    file: path.display().to_string(),
                    subject: "map".into(),
                    message: format!(
                        "the side file {} replaces the probes at its {} spawn point(s)",
                        side.display(),
                        spawns.len()
                    ),
                });
            }
            return Ok((level, warnings));
        }
    }
    if spawns.is_empty() {
        return Err(fail(
            TiledError::NoScenarios {
                file: path.display().to_string(),
                side: path.with_extension("toml").display().to_string(),
            },
            warnings,
        ));
    }
    let (scenarios, probe_warnings) =
        match probe_scenarios(&level, &spawns, &ProbeConfig::default()) {
            Ok(p) => p,
            Err(e) => {
                let file = path.display().to_string();
                let message = format!("the map's probes cannot run: {e}");
                return Err(fail(TiledError::Map { file, message }, warnings));
            }
        };
    level.scenarios = scenarios;
    let file = path.display().to_string();
    warnings.extend(
        probe_warnings
            .into_iter()
            .map(|(subject, message)| TiledWarning {
                file: file.clone(),
                subject,
                message,
            }),
    );
    Ok((level, warnings))
}

/// Reads a Tiled map's geometry, platforms and spawn points (no scenarios) with the default
/// rules; see [`import_tiled_map_with`].
pub fn import_tiled_map(path: &Path) -> Result<TiledImport, TiledError> {
    import_tiled_map_with(path, &ImportOptions::default()).map_err(|f| f.error)
}

/// How an error that names a layer shows a line of the map's text and a Tiled cell.
type CellAt<'m> = &'m dyn Fn(usize, (i64, i64)) -> String;

/// A role and why it was given.
type Reasoned = (LayerRole, String);

/// A tile as the map uses it: tileset index, local id and flips.
type TileKey = (usize, u32, bool, bool, bool);

/// Where the level's cells lie in Tiled's cell coordinates: the map itself, or the part of an
/// infinite map its chunks cover.
#[derive(Clone, Copy, Debug)]
struct Grid {
    /// Tiled column of the level's column 0.
    x0: i32,
    /// Tiled row of the level's top row.
    y0: i32,
    /// Width in tiles.
    w: u32,
    /// Height in tiles.
    h: u32,
}

impl Grid {
    /// The Tiled cell (column, row from the map's top-left) of the level's cell `(i, j)` (row
    /// 0 at the bottom).
    fn tiled_cell(&self, i: i64, j: i64) -> (i64, i64) {
        (
            i + i64::from(self.x0),
            i64::from(self.y0) + i64::from(self.h) - 1 - j,
        )
    }
}

/// The state of one import.
struct Importer<'m> {
    file: String,
    /// The map's XML as the `tiled` crate read it (a JSON map's TMX twin), to find a line in.
    text: &'m str,
    /// A line of `text` in a layer, and a Tiled cell of it, as an error that names the layer
    /// shows them: `FILE:LINE`; for a JSON map, the JSON line of the cell, or of the layer.
    cell_at: CellAt<'m>,
    map: &'m tiled::Map,
    opts: &'m ImportOptions,
    grid: Grid,
    /// The level's cells so far (row 0 at the bottom), with what set each.
    cells: cells::Cells,
    /// Each used tile's meaning, computed once.
    kinds: HashMap<TileKey, Tile>,
    /// Tiles already warned about, so a tile used many times warns once.
    warned: Vec<(usize, u32)>,
    /// Tilesets already noted (oversize art), by index.
    noted_tilesets: Vec<usize>,
    warnings: Vec<TiledWarning>,
    /// Each layer's role and why, in file order.
    reports: Vec<LayerReport>,
    /// Object layers to read once the tiles are known.
    objects: Vec<objects::ObjectLayer<'m>>,
    /// Sides `[left, right]` where collision shapes reach just outside the map (a boundary
    /// drawn outside it): walled whatever `--edges` says.
    drawn_sides: [bool; 2],
}

impl<'m> Importer<'m> {
    fn new(
        (file, text, cell_at): (String, &'m str, CellAt<'m>),
        map: &'m tiled::Map,
        opts: &'m ImportOptions,
    ) -> Self {
        Importer {
            file,
            text,
            cell_at,
            map,
            opts,
            grid: Grid {
                x0: 0,
                y0: 0,
                w: map.width,
                h: map.height,
            },
            cells: cells::Cells::default(),
            kinds: HashMap::new(),
            warned: Vec::new(),
            noted_tilesets: Vec::new(),
            warnings: Vec::new(),
            reports: Vec::new(),
            objects: Vec::new(),
            drawn_sides: [false; 2],
        }
    }

    fn run(&mut self, path: &Path) -> Result<TiledImport, TiledError> {
        let map = self.map;
        self.check_map()?;
        // The size is checked before the cells are allocated.
        self.cells = cells::Cells::new(self.grid.w, self.grid.h);
        let (name, description, tile_default) = self.map_properties(path)?;
        let entries = self.collect_layers()?;
        self.read_layers(entries, tile_default)?;
        self.collision_objects()?;
        let grid = self.grid;
        let (tiles, met) = self
            .cells
            .finish(|i, j| grid.tiled_cell(i.into(), j.into()));
        for (subject, message) in met {
            self.warn(subject, message);
        }
        let mut level = Level::from_tiles(&name, self.grid.w, self.grid.h, tiles);
        level.description = description;
        level.source = self.file.clone();
        let (mut spawns, mut sources) = self.objects(&mut level)?;
        level.features.moving_platforms = !level.platforms.is_empty();
        if let Some(w) = no_solids_warning(&level, &self.file, HOW_TO_COLLIDE) {
            self.warnings.push(w);
        }
        if let Some(w) = wall_sides(
            &mut level,
            &mut spawns,
            self.opts.edges.unwrap_or_default(),
            [false; 2],
            self.drawn_sides,
            &self.file,
        ) {
            self.warnings.push(w);
        }
        if let Some(w) = settle_spawns(
            &level,
            &self.file,
            HOW_TO_SPAWN,
            self.opts,
            &mut spawns,
            &mut sources,
        )
        .map_err(|m| self.map_err(m))?
        {
            self.warnings.push(w);
        }
        let _ = map;
        let unmatched = unmatched_layer_roles(self.opts, &self.reports, &self.file);
        self.warnings.extend(unmatched);
        Ok(TiledImport {
            level,
            spawns,
            spawn_sources: sources,
            layers: std::mem::take(&mut self.reports),
            warnings: std::mem::take(&mut self.warnings),
        })
    }

    fn map_err(&self, message: String) -> TiledError {
        TiledError::Map {
            file: self.file.clone(),
            message,
        }
    }

    fn warn(&mut self, subject: String, message: String) {
        self.warnings.push(TiledWarning {
            file: self.file.clone(),
            subject,
            message,
        });
    }
}

fn kind_of(v: &PropertyValue) -> &'static str {
    match v {
        PropertyValue::BoolValue(_) => "a bool",
        PropertyValue::FloatValue(_) => "a float",
        PropertyValue::IntValue(_) => "an int",
        PropertyValue::ColorValue(_) => "a color",
        PropertyValue::StringValue(_) => "a string",
        PropertyValue::FileValue(_) => "a file",
        PropertyValue::ObjectValue(_) => "an object reference",
        PropertyValue::ListValue(_) => "a list",
        PropertyValue::ClassValue { .. } => "a class value",
    }
}

fn shape_name(s: &ObjectShape) -> &'static str {
    match s {
        ObjectShape::Rect { .. } => "a rectangle",
        ObjectShape::Ellipse { .. } => "an ellipse",
        ObjectShape::Capsule { .. } => "a capsule",
        ObjectShape::Polyline { .. } => "a polyline",
        ObjectShape::Polygon { .. } => "a polygon",
        ObjectShape::Point(..) => "a point",
        ObjectShape::Text { .. } => "a text",
    }
}

fn tile_name(t: &Tile) -> String {
    match t {
        Tile::Empty => "empty".into(),
        Tile::Solid => "solid".into(),
        Tile::OneWay => "one-way".into(),
        Tile::Ladder => "a ladder".into(),
        Tile::Slope(Slope::Line { left, right }) => format!("a line slope ({left}, {right})"),
        Tile::Slope(Slope::Heights(_)) => "a height-array slope".into(),
    }
}

fn number(v: &PropertyValue) -> Option<f32> {
    match v {
        PropertyValue::FloatValue(f) => Some(*f),
        PropertyValue::IntValue(i) => Some(*i as f32),
        _ => None,
    }
}

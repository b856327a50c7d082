//! What a Tiled map that cannot be imported is: [`TiledError`], naming the file, and the
//! layer, tile (tileset, local id, cell) or object at fault; and the reasons the importer's
//! parts give, whose text a [`TiledError`]'s message carries: `TileKindError` (with
//! `HeightsError` and `ShapeError`), `FlipError`, `CellError` and `JsonError`.

use super::{tile_name, LevelError, Tile};

/// A Tiled map that platbench cannot run as it is, with what was found and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum TiledError {
    /// The file could not be read or is not a well-formed Tiled map (the `tiled` crate's error,
    /// with the file it was reading).
    #[error("{file}: cannot load the Tiled map: {message}")]
    Load {
        /// The map, tileset or template file at fault (with its line when known).
        file: String,
        /// What was wrong.
        message: String,
    },
    /// A property of the whole map (orientation, size) that platbench cannot use.
    #[error("{file}: {message}")]
    Map {
        /// The map file.
        file: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A layer that cannot be imported (size, an unexpected property value).
    #[error("{file}: layer {layer:?}: {message}")]
    Layer {
        /// The map file.
        file: String,
        /// The layer's name.
        layer: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A tile whose properties or collision shape platbench cannot represent.
    #[error("{file}: tileset {tileset:?} tile {tile}{}: {message}", cell_text(.cell))]
    Tile {
        /// The map file.
        file: String,
        /// The tileset's name.
        tileset: String,
        /// The tile's id, local to its tileset (as Tiled's tileset editor shows it).
        tile: u32,
        /// The map cell (x, y) where it is used, as Tiled shows it (column and row from the
        /// map's top-left; Tiled's cells are `i32`), when one cell is involved.
        cell: Option<(i32, i32)>,
        /// What was found and what was expected.
        message: String,
    },
    /// An object (platform, spawn, path, collision shape) that cannot be imported.
    #[error("{file}: object {id} {name:?}: {message}")]
    Object {
        /// The map file.
        file: String,
        /// The object's id (unique in the map, as Tiled shows it).
        id: u32,
        /// The object's name (may be empty).
        name: String,
        /// What was found and what was expected.
        message: String,
    },
    /// The map has no spawn point, no cell to stand on and no side file, so nothing can run.
    #[error("{file}: the map has no spawn points, no cell a character can stand on, and no side file {side} with [[scenario]] entries, so nothing can run on it; mark a spawn with a point object named or of class \"spawn\" in an object layer (where the character's feet start), pass --spawn X,Y, or write {side} with [[scenario]] entries (docs/formats.md, \"Tiled maps\")")]
    NoScenarios {
        /// The map file.
        file: String,
        /// Where the side file was looked for.
        side: String,
    },
    /// The side file's scenarios are invalid (file, line and column inside).
    #[error(transparent)]
    SideFile(#[from] LevelError),
    /// The side file exists but cannot be read.
    #[error("{file}: cannot read the side file: {message}")]
    SideFileRead {
        /// The side file.
        file: String,
        /// The system's message.
        message: String,
    },
}

fn cell_text(cell: &Option<(i32, i32)>) -> String {
    match cell {
        Some((x, y)) => {
            format!(" (at cell x = {x}, y = {y}, column and row from the map's top-left)")
        }
        None => String::new(),
    }
}

/// Why a tileset tile's properties, class or collision shape say nothing platbench can
/// represent (`tiles::tile_kind`); a [`TiledError::Tile`] carries its text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum TileKindError {
    /// Two bool properties make the tile two different kinds.
    #[error("property {first:?} makes it {} and property {second:?} makes it {}; expected one", tile_name(.first_tile), tile_name(.second_tile))]
    ConflictingBools {
        /// The property read first (in name order).
        first: String,
        /// What it makes the tile.
        first_tile: Tile,
        /// The property that disagrees.
        second: String,
        /// What that one makes the tile.
        second_tile: Tile,
    },
    /// The `collision` property is neither a string nor a bool.
    #[error("property \"collision\" is {kind}; expected a string (solid, one_way, ladder or empty) or a bool")]
    CollisionType {
        /// The property's type, with its article ("an int").
        kind: &'static str,
    },
    /// `slope_left` or `slope_right` is not a number.
    #[error("property {key:?} is {kind}; expected a float (height in tiles)")]
    SlopeType {
        /// The property's name.
        key: String,
        /// The property's type, with its article.
        kind: &'static str,
    },
    /// `slope_left` or `slope_right` is not a finite height within 16 tiles.
    #[error("property {key:?} = {value}; expected a height between -16 and 16 tiles")]
    SlopeRange {
        /// The property's name.
        key: String,
        /// Its value, tiles.
        value: f32,
    },
    /// The `heights` property is not a string.
    #[error(
        "property \"heights\" is {kind}; expected a string of 16 comma-separated integers 0..16"
    )]
    HeightsType {
        /// The property's type, with its article.
        kind: &'static str,
    },
    /// The `heights` string is not 16 sixteenths.
    #[error(transparent)]
    Heights(#[from] HeightsError),
    /// One of `slope_left` and `slope_right` without the other.
    #[error("it has only one of slope_left and slope_right; expected both (a line slope)")]
    HalfLineSlope,
    /// Both a height array and a line slope.
    #[error("it has both a height array (heights) and a line slope (slope_left/slope_right); expected one")]
    TwoSlopes,
    /// The `collision` string names no tile kind.
    #[error("collision = {value:?}; expected solid, one_way, ladder or empty")]
    CollisionValue {
        /// The property's value.
        value: String,
    },
    /// A `collision` string and slope properties.
    #[error("it has collision = {collision:?} and slope properties; expected one of them (a slope needs no collision property)")]
    CollisionAndSlope {
        /// The `collision` property's value.
        collision: String,
    },
    /// A `collision` string and a bool property that make the tile two different kinds.
    #[error("it has collision = {collision:?} and property {key:?} that makes it {}; expected one", tile_name(.tile))]
    CollisionAndBool {
        /// The `collision` property's value.
        collision: String,
        /// The bool property's name.
        key: String,
        /// What the bool property makes the tile.
        tile: Tile,
    },
    /// A collision object platbench cannot place on the grid.
    #[error(transparent)]
    Shape(#[from] ShapeError),
}

/// Why a tile's `heights` property is not 16 sixteenths of a tile (`tiles::parse_heights`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub(crate) enum HeightsError {
    /// Not 16 entries.
    #[error("heights = {text:?} has {count} entries; {HEIGHTS_EXPECTED}")]
    Count {
        /// The property's value.
        text: String,
        /// How many comma-separated entries it has.
        count: usize,
    },
    /// An entry that is not an integer 0..=16.
    #[error("heights = {text:?}: entry {entry} is {value:?}; {HEIGHTS_EXPECTED}")]
    Entry {
        /// The property's value.
        text: String,
        /// The entry's 1-based position.
        entry: usize,
        /// The entry, trimmed.
        value: String,
    },
}

/// What a `heights` property must be.
const HEIGHTS_EXPECTED: &str =
    "expected 16 comma-separated integers 0..16 (sixteenths of a tile, left to right)";

/// Why a tile's collision shape cannot be read or approximated (`tiles::tile_kind`; partial
/// and compound shapes are approximated, `approx`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum ShapeError {
    /// The object is rotated.
    #[error("its collision shape is rotated by {degrees} degrees; expected no rotation")]
    Rotated {
        /// The rotation, degrees.
        degrees: f32,
    },
}

/// Why a flipped tile has no meaning platbench can represent (`tiles::apply_flips`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub(crate) enum FlipError {
    /// A slope flipped vertically or diagonally: a ceiling or wall slope.
    #[error("it is a slope drawn flipped vertically or rotated, which makes a ceiling or wall slope; expected it unflipped or flipped horizontally (the mirrored ramp)")]
    SlopeTurned,
}

/// Two collision layers or objects that put different kinds of tile into one cell (the
/// importer's `set_cell`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum CellError {
    /// The cell already holds another kind of tile.
    #[error("it is {} but the cell already holds {} from {held_by}; expected one kind of tile per cell across the collision layers", tile_name(.tile), tile_name(.held))]
    Conflict {
        /// The tile being put into the cell.
        tile: Tile,
        /// The tile the cell holds.
        held: Tile,
        /// What put it there (tileset, tile and layer, or object).
        held_by: String,
    },
}

impl JsonError {
    /// The line and column the error points at, if any, and what is wrong without them, for an
    /// error shown as `FILE:LINE:COLUMN: ...`.
    pub(crate) fn located(&self) -> Option<(usize, usize, String)> {
        match self {
            JsonError::Syntax(e) => {
                let m = e.to_string();
                let m = m.rsplit_once(" at line ").map_or(m.as_str(), |p| p.0);
                Some((e.line(), e.column(), format!("not Tiled JSON: {m}")))
            }
            JsonError::Limit {
                line,
                column,
                message,
            }
            | JsonError::Value {
                line,
                column,
                message,
            } => Some((*line, *column, message.clone())),
            _ => None,
        }
    }
}

/// Why a Tiled JSON file (a map, a tileset `.tsj` or a template `.tj`) cannot be read as the XML
/// the `tiled` crate reads (`json`).
#[derive(Debug, thiserror::Error)]
pub(crate) enum JsonError {
    /// Not JSON: the parser's error, with its line and column.
    #[error("line {}, column {}: not Tiled JSON: {}", .0.line(), .0.column(), .0)]
    Syntax(#[source] serde_json::Error),
    /// More than platbench reads, found by the walk before serde_json builds its tree
    /// (`json_walk`): where the count passes, what was found and what was expected.
    #[error("line {line}, column {column}: {message}")]
    Limit {
        /// The 1-based line where the count passes (or the layer or map starts).
        line: usize,
        /// The 1-based column, in bytes as serde_json counts them.
        column: usize,
        /// What passes which limit, naming the layer or object.
        message: String,
    },
    /// A value Tiled does not write where it is (a string for a size, a fractional width, a cell
    /// that is not a tile id, anything but an object at the top), found by the walk
    /// (`json_values`): where it is, what was found and what was expected.
    #[error("line {line}, column {column}: {message}")]
    Value {
        /// The value's 1-based line.
        line: usize,
        /// Its 1-based column, in bytes as serde_json counts them.
        column: usize,
        /// What it is and what was expected, naming the layer or object.
        message: String,
    },
    /// JSON, but not an object at the top.
    #[error("not Tiled JSON: expected an object at the top")]
    NotObject,
    /// A JSON object that is not a Tiled map (a tileset, a template, another program's file).
    #[error("not a Tiled map: {}; expected a map (type \"map\", with layers, width, height, tilewidth, tileheight)", if .kind == "map" { format!("it has no layers (its keys: {})", .keys) } else { format!("it is a Tiled {} (type {:?})", .kind, .kind) })]
    NotAMap {
        /// The `type` the file gives (`map` when it gives none).
        kind: String,
        /// Some of the keys it has, to recognise it by.
        keys: String,
    },
    /// A cell of a tile layer that is not a tile id.
    #[error("layer {layer:?}: cell {index} is {found}; expected a tile id, a whole number from 0 to 4294967295")]
    BadCell {
        /// The layer's name.
        layer: String,
        /// The cell's index in the layer's (or chunk's) data, from 0.
        index: usize,
        /// The value found.
        found: String,
    },
    /// A layer type Tiled does not write.
    #[error(
        "layer {layer:?} has type {found:?}; expected tilelayer, objectgroup, imagelayer or group"
    )]
    LayerType {
        /// The layer's name.
        layer: String,
        /// The type found.
        found: String,
    },
    /// More tiles than platbench reads.
    #[error("it has {count} tiles; expected at most {max}")]
    TooManyTiles {
        /// The tileset's tile count (declared or computed).
        count: u64,
        /// The most tiles platbench reads ([`crate::limits::MAX_TILES`]).
        max: u64,
    },
}

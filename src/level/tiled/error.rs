//! What a Tiled map that cannot be imported is: [`TiledError`], naming the file, and the
//! layer, tile (tileset, local id, cell) or object at fault.

use super::LevelError;

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
        /// The map cell (i, j) where it is used, in platbench's coordinates (j = 0 is the bottom
        /// row), when one cell is involved.
        cell: Option<(u32, u32)>,
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

fn cell_text(cell: &Option<(u32, u32)>) -> String {
    match cell {
        Some((i, j)) => format!(" (at cell i = {i}, j = {j})"),
        None => String::new(),
    }
}

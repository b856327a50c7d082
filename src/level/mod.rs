//! The level model: a grid of tiles one world unit wide, the features a level contains and
//! the scenarios that run on it. It knows nothing of backends.
//!
//! Coordinates: tile `(i, j)` covers `[i, i+1] x [j, j+1]`; `j = 0` is the bottom row and y
//! points up. The text format (`toml`) lists map rows top to bottom; Tiled maps
//! ([`tiled`]) are imported into the same model.
//!
//! The model: `tile` (a cell, a slope's surface), `features`, `model` (the [`Level`]),
//! `geometry` (queries on its tiles), `scenario` (a scenario as a level states it),
//! `platform` (moving platforms) and [`outlines`] (the polygons engines get). The TOML level
//! format: `toml`. The importers: [`tiled`] and [`ldtk`], with what they share in [`import`]
//! and the standard probes for a map without scenarios in [`probes`].

mod cells;
pub(crate) use cells::SlopeKey;
mod features;
mod format;
mod geometry;
pub mod import;
#[cfg(feature = "ldtk")]
pub mod ldtk;
mod model;
pub mod outlines;
mod platform;
pub mod probes;
mod scenario;
mod tile;
#[cfg(feature = "tiled")]
pub mod tiled;
mod toml;

pub use self::toml::{parse_level, parse_scenarios, side_import_options, LevelError};
pub use features::Features;
pub(crate) use format::first_text;
pub use format::{detect_format, LevelFormat};
pub use geometry::{character_box, round_height_up};
pub(crate) use geometry::{surface_walk, SurfaceCell};
pub use import::{
    Edges, ImportFailure, ImportOptions, ImportWarning, LayerReport, LayerRole, MapImport,
};
pub use model::Level;
pub(crate) use platform::Path;
pub use platform::{Platform, PlatformMotion};
pub use probes::{probe_scenarios, ProbeConfig, SpawnPoint};
pub use scenario::{
    valid_name, Deadline, Expectations, InputEvent, MotionOverrides, Reach, ScenarioSpec,
    DEFAULT_CHARACTER_SIZE, DEFAULT_DT,
};
pub use tile::{Slope, Tile};
#[cfg(feature = "tiled")]
pub use tiled::{
    import_tiled_map, import_tiled_map_with, load_tiled_map, load_tiled_map_with, TiledError,
    TiledImport, TiledWarning,
};
pub(crate) use toml::explain_toml_error;

//! The level itself ([`Level`]): its size, origin, tiles, features, scenarios and moving
//! platforms; building one from tiles, its reach from the world's origin, and the tile at a
//! cell. The queries on its tiles are in `geometry`.

use glam::{DVec2, Vec2};

use super::cells::Cells;
use super::{Features, Platform, ScenarioSpec, Tile};

/// A parsed level.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Name, used in file names and tables.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// Where it came from (a path or `builtin:NAME`), for messages.
    pub source: String,
    /// Width in tiles.
    pub width: u32,
    /// Height in tiles.
    pub height: u32,
    /// Where the level's corner (tile (0, 0)'s lower left) sits in the backends' world, in
    /// tiles, in f64 so that a far offset is exact (1e12 is not an f32). Controllers compute in
    /// world coordinates, where rounding depends on the magnitude: an f32 backend places the
    /// level at this origin rounded to the nearest f32 ([`Level::origin_f32`]), an f64 backend
    /// at the origin itself; traces and metrics stay in level coordinates. Default: the origin.
    pub origin: DVec2,
    /// Tiles row by row from the bottom (`j * width + i`), a byte each and shared between
    /// copies ([`Cells`]).
    pub(super) tiles: Cells,
    /// What the level contains.
    pub features: Features,
    /// The scenarios that run on it.
    pub scenarios: Vec<ScenarioSpec>,
    /// Moving platforms.
    pub platforms: Vec<Platform>,
}

impl Level {
    /// Builds a level from rows given bottom first; computes its features.
    pub fn from_tiles(name: &str, width: u32, height: u32, tiles: Vec<Tile>) -> Level {
        Self::with_cells(name, width, height, &tiles)
    }

    /// [`Level::from_tiles`] from a slice; the level keeps its tiles a byte each.
    pub(crate) fn with_cells(name: &str, width: u32, height: u32, tiles: &[Tile]) -> Level {
        assert_eq!(tiles.len(), width as usize * height as usize);
        let tiles = Cells::new(tiles, width);
        let features = Features {
            one_way: tiles.any_distinct(|t| *t == Tile::OneWay),
            ladders: tiles.any_distinct(|t| *t == Tile::Ladder),
            slopes: tiles.any_distinct(|t| matches!(t, Tile::Slope(_))),
            ..Features::default()
        };
        Level {
            name: name.to_string(),
            description: String::new(),
            source: format!("builtin:{name}"),
            width,
            height,
            origin: DVec2::ZERO,
            tiles,
            features,
            scenarios: Vec::new(),
            platforms: Vec::new(),
        }
    }

    /// The origin as an f32 backend places the level: [`Level::origin`] rounded to the nearest
    /// f32 (exact for every origin a level file could give before origins were f64, up to 1e7
    /// tiles).
    pub fn origin_f32(&self) -> Vec2 {
        self.origin.as_vec2()
    }

    /// How far the level reaches from the world's origin, in tiles: the largest distance on
    /// either axis of its tile faces (its corner [`Level::origin`] plus 0 to its width and
    /// height) and of the boxes its platforms sweep ([`Platform::reach`]), in f64.
    pub fn reach(&self) -> f64 {
        let size = DVec2::new(self.width as f64, self.height as f64);
        let mut far = self
            .origin
            .abs()
            .max((self.origin + size).abs())
            .max_element();
        for p in &self.platforms {
            let (lo, hi) = p.reach();
            far = far
                .max((self.origin + lo).abs().max_element())
                .max((self.origin + hi).abs().max_element());
        }
        far
    }

    /// A copy of the level's geometry without its scenarios, for a backend to keep. The tiles
    /// are shared with this level, not copied.
    pub fn geometry(&self) -> Level {
        Level {
            name: self.name.clone(),
            description: String::new(),
            source: self.source.clone(),
            width: self.width,
            height: self.height,
            origin: self.origin,
            tiles: self.tiles.clone(),
            features: self.features,
            scenarios: Vec::new(),
            platforms: self.platforms.clone(),
        }
    }

    /// Replaces the level's tiles with `tiles` (`width` columns, its rows), leaving its
    /// features as they are.
    pub(crate) fn set_tiles(&mut self, width: u32, tiles: &[Tile]) {
        assert_eq!(tiles.len(), width as usize * self.height as usize);
        self.tiles = Cells::new(tiles, width);
        self.width = width;
    }

    /// The distinct tiles the level holds, each once (a handful: the plain kinds and its slopes),
    /// for what is built per kind of tile rather than per cell.
    pub(crate) fn distinct_tiles(&self) -> impl Iterator<Item = Tile> + '_ {
        self.tiles.distinct()
    }

    /// The tile at column `i`, row `j` (from the bottom); outside the map is empty.
    pub fn tile(&self, i: i64, j: i64) -> Tile {
        self.cell(i, j).map_or(Tile::Empty, |k| self.tiles.get(k))
    }

    /// The index in the cells (`j * width + i`) of column `i`, row `j`; none outside the map.
    #[inline]
    pub(super) fn cell(&self, i: i64, j: i64) -> Option<usize> {
        let inside = i >= 0 && j >= 0 && i < self.width as i64 && j < self.height as i64;
        inside.then(|| (j as usize) * self.width as usize + i as usize)
    }
}

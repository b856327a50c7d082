//! The level model: a grid of tiles one world unit wide, the features a level contains and
//! the scenarios that run on it. It knows nothing of backends.
//!
//! Coordinates: tile `(i, j)` covers `[i, i+1] x [j, j+1]`; `j = 0` is the bottom row and y
//! points up. The text format (`parse`) lists map rows top to bottom; Tiled maps
//! ([`tiled`]) are imported into the same model.

pub mod import;
#[cfg(feature = "ldtk")]
pub mod ldtk;
pub mod outlines;
mod parse;
mod platform;
pub mod probes;
#[cfg(feature = "tiled")]
pub mod tiled;

pub use import::{ImportFailure, ImportOptions, ImportWarning, LayerReport, LayerRole, MapImport};
pub use parse::{parse_level, parse_scenarios, LevelError};
pub use platform::{Platform, PlatformMotion};
pub use probes::{probe_scenarios, ProbeConfig, SpawnPoint};
#[cfg(feature = "tiled")]
pub use tiled::{
    import_tiled_map, import_tiled_map_with, load_tiled_map, load_tiled_map_with, TiledError,
    TiledImport, TiledWarning,
};

use glam::{DVec2, Vec2};
use parry2d::bounding_volume::Aabb;

/// What one grid cell holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tile {
    /// Nothing: characters pass.
    Empty,
    /// A full solid square.
    Solid,
    /// A platform that blocks only from above (`=`).
    OneWay,
    /// A ladder (`H`).
    Ladder,
    /// A sloped tile.
    Slope(Slope),
}

/// The surface of a sloped tile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slope {
    /// The seed's integer height array: 16 heights in sixteenths of a tile, left to right.
    Heights([u8; 16]),
    /// The seed's line slope: surface heights at the tile's left and right edge, in tiles.
    /// Heights outside 0..=1 describe a line that leaves the tile through its top or bottom;
    /// the surface is clamped into the tile, so a straight ramp of any angle spans rows exactly.
    Line {
        /// Height of the line at the tile's left edge, in tiles.
        left: f32,
        /// Height of the line at the tile's right edge, in tiles.
        right: f32,
    },
}

impl Slope {
    /// The tile's solid part as an outline in tile-local coordinates, counter-clockwise from
    /// the bottom: the tile cut by its surface. Where the surface lies on the tile's bottom (a
    /// line that enters through the bottom edge, or zero heights), the outline starts or ends
    /// where the surface leaves the bottom, so that a convex hull of these points is exactly
    /// the solid part (a hull spanning a bottom corner the surface never reaches would add a
    /// false step to a ramp). Empty when the tile holds no solid area.
    pub fn outline(&self) -> Vec<Vec2> {
        let mut pts = vec![Vec2::ZERO];
        pts.extend(self.surface_points());
        pts.push(Vec2::X);
        pts.dedup_by(|a, b| (*a - *b).length() < 1e-6);
        // Drop bottom points whose neighbours both lie on the bottom too: collinear points
        // along the bottom edge and spurs back to a corner the surface does not reach.
        let on_bottom = |p: Vec2| p.y.abs() < 1e-6;
        let mut i = 0;
        while i < pts.len() && pts.len() >= 3 {
            let n = pts.len();
            let (prev, next) = (pts[(i + n - 1) % n], pts[(i + 1) % n]);
            if on_bottom(prev) && on_bottom(pts[i]) && on_bottom(next) {
                pts.remove(i);
                i = i.saturating_sub(1);
            } else {
                i += 1;
            }
        }
        if pts.len() < 3 || pts.iter().all(|p| on_bottom(*p)) {
            pts.clear();
        }
        pts
    }

    /// Surface height above the tile's bottom, in tiles, at `u` (0..=1 across the tile).
    ///
    /// Height arrays are the seed's step function: the entry under `u` (sixteenths of a tile).
    /// Line slopes interpolate from `left` at u = 0 to `right` at u = 1. (The seed's slide writes
    /// `Lerp(a, b, alpha) = a * alpha + b * (1 - alpha)` with `a` the left height, which would
    /// put the right height at the left edge; the surface here runs the intended way.)
    pub fn height_at(&self, u: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Slope::Heights(h) => h[((u * 16.0) as usize).min(15)] as f32 / 16.0,
            Slope::Line { left, right } => (left + (right - left) * u).clamp(0.0, 1.0),
        }
    }

    /// Surface height just left of `u`, in tiles: the same as [`Slope::height_at`] except at a
    /// column boundary of a height array, where it is the column to the left's.
    pub fn height_left_of(&self, u: f32) -> f32 {
        match self {
            Slope::Heights(h) => {
                let k = (u.clamp(0.0, 1.0) * 16.0).ceil() as usize;
                h[k.clamp(1, 16) - 1] as f32 / 16.0
            }
            Slope::Line { .. } => self.height_at(u),
        }
    }

    /// Heights at the tile's left and right edges, in tiles.
    pub fn edges(&self) -> (f32, f32) {
        (self.height_at(0.0), self.height_at(1.0))
    }

    /// The surface as a polyline in tile-local coordinates (x and y in 0..=1), left to right:
    /// the line itself, or for a height array its 16 columns as steps (the flat top of each
    /// column, with a vertical riser where two columns differ), the very surface the sweep
    /// stands on and the metrics measure, so that every controller collides with the same
    /// geometry.
    pub fn surface_points(&self) -> Vec<Vec2> {
        match self {
            Slope::Line { left, right } => {
                // The clamped line: its ends, and where it crosses the tile's bottom or top.
                let mut us = vec![0.0, 1.0];
                for level in [0.0f32, 1.0] {
                    if right != left {
                        let u = (level - left) / (right - left);
                        if u > 0.0 && u < 1.0 {
                            us.push(u);
                        }
                    }
                }
                us.sort_by(f32::total_cmp);
                us.into_iter()
                    .map(|u| Vec2::new(u, self.height_at(u)))
                    .collect()
            }
            Slope::Heights(h) => {
                let mut pts: Vec<Vec2> = Vec::with_capacity(32);
                for (i, v) in h.iter().enumerate() {
                    let y = *v as f32 / 16.0;
                    let (x0, x1) = (i as f32 / 16.0, (i + 1) as f32 / 16.0);
                    // Extend the previous column's top when this one is as high.
                    match pts.last_mut() {
                        Some(last) if last.y == y => last.x = x1,
                        _ => pts.extend([Vec2::new(x0, y), Vec2::new(x1, y)]),
                    }
                }
                pts
            }
        }
    }
}

/// What a level contains beyond solid tiles; backends build and run only what is set here.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Features {
    /// The level has sloped tiles.
    pub slopes: bool,
    /// The level has one-way platforms.
    pub one_way: bool,
    /// The level has ladders.
    pub ladders: bool,
    /// The level has moving platforms.
    pub moving_platforms: bool,
}

impl Features {
    /// A level of solid tiles only.
    pub const NONE: Features = Features {
        slopes: false,
        one_way: false,
        ladders: false,
        moving_platforms: false,
    };

    /// Every feature the level format has.
    pub const ALL: Features = Features {
        slopes: true,
        one_way: true,
        ladders: true,
        moving_platforms: true,
    };

    /// Whether every feature set here is also set in `modelled`.
    pub fn within(&self, modelled: Features) -> bool {
        self.missing_from(modelled) == Features::NONE
    }

    /// The features set here and not in `modelled`.
    pub fn missing_from(&self, modelled: Features) -> Features {
        Features {
            slopes: self.slopes && !modelled.slopes,
            one_way: self.one_way && !modelled.one_way,
            ladders: self.ladders && !modelled.ladders,
            moving_platforms: self.moving_platforms && !modelled.moving_platforms,
        }
    }

    /// Names of the features that are set, for messages.
    pub fn names(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.slopes {
            v.push("slopes");
        }
        if self.one_way {
            v.push("one-way platforms");
        }
        if self.ladders {
            v.push("ladders");
        }
        if self.moving_platforms {
            v.push("moving platforms");
        }
        v
    }
}

/// One timed change of the held buttons in a scenario's input script. Buttons not named keep
/// their previous state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InputEvent {
    /// Time at which the change takes effect, in seconds from the start.
    pub t: f32,
    /// New state of the left button, if it changes.
    pub left: Option<bool>,
    /// New state of the right button, if it changes.
    pub right: Option<bool>,
    /// New state of the up button, if it changes.
    pub up: Option<bool>,
    /// New state of the down button, if it changes.
    pub down: Option<bool>,
    /// New state of the jump button, if it changes.
    pub jump: Option<bool>,
}

/// Per-scenario changes to the run's motion parameters.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionOverrides {
    /// Replaces the jump height, in tiles.
    pub jump_height: Option<f32>,
    /// Replaces the run speed, in tiles/s.
    pub run_speed: Option<f32>,
    /// Replaces the gravity, in tiles/s².
    pub gravity: Option<f32>,
}

/// A scenario as the level file states it: one character, its spawn and its input script.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioSpec {
    /// Name, unique within the level.
    pub name: String,
    /// Spawn position of the character's feet (bottom centre of its box), in tiles.
    pub spawn: Vec2,
    /// Width and height of the character's box, in tiles.
    pub size: Vec2,
    /// Initial velocity, in tiles/s.
    pub velocity: Vec2,
    /// Length of the run, in seconds.
    pub duration: f32,
    /// Time step, in seconds.
    pub dt: f32,
    /// Input changes, in time order.
    pub inputs: Vec<InputEvent>,
    /// Changes to the motion parameters for this scenario.
    pub motion: MotionOverrides,
    /// Where the character's feet should end (y, in tiles), for scenarios whose outcome is a
    /// place: which side of a one-way platform, or the top of a ladder.
    pub expect_y: Option<f32>,
    /// The moving platform (index in the level's list) this scenario rides, for the carry
    /// metrics.
    pub ride: Option<u32>,
}

impl ScenarioSpec {
    /// A scenario with the default character, time step and motion, from rest, no expected end
    /// place and no platform ridden: the fields other code then sets what it needs of.
    pub fn new(name: String, spawn: Vec2, duration: f32, inputs: Vec<InputEvent>) -> Self {
        ScenarioSpec {
            name,
            spawn,
            size: DEFAULT_CHARACTER_SIZE,
            velocity: Vec2::ZERO,
            duration,
            dt: DEFAULT_DT,
            inputs,
            motion: MotionOverrides::default(),
            expect_y: None,
            ride: None,
        }
    }
}

/// Whether `name` can name a level or scenario: non-empty ASCII letters, digits, '_' or '-',
/// since it names output files (and '.' separates the parts of a trace file's name).
pub fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Default character box: 0.8 x 0.9 tiles, the size of the reference measurements.
pub const DEFAULT_CHARACTER_SIZE: Vec2 = Vec2::new(0.8, 0.9);
/// Default time step: 1/60 s.
pub const DEFAULT_DT: f32 = 1.0 / 60.0;

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
    /// Tiles row by row from the bottom (`j * width + i`).
    tiles: Vec<Tile>,
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
        assert_eq!(tiles.len(), (width * height) as usize);
        let mut features = Features::default();
        for t in &tiles {
            match t {
                Tile::OneWay => features.one_way = true,
                Tile::Ladder => features.ladders = true,
                Tile::Slope(_) => features.slopes = true,
                Tile::Empty | Tile::Solid => {}
            }
        }
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

    /// A copy of the level's geometry without its scenarios, for a backend to keep.
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

    /// The tile at column `i`, row `j` (from the bottom); outside the map is empty.
    pub fn tile(&self, i: i64, j: i64) -> Tile {
        if i < 0 || j < 0 || i >= self.width as i64 || j >= self.height as i64 {
            return Tile::Empty;
        }
        self.tiles[(j as usize) * self.width as usize + i as usize]
    }

    /// The box of tile `(i, j)`.
    pub fn tile_box(i: i64, j: i64) -> Aabb {
        Aabb::new(
            Vec2::new(i as f32, j as f32),
            Vec2::new(i as f32 + 1.0, j as f32 + 1.0),
        )
    }

    /// Every solid tile's box, in row order.
    pub fn solid_boxes(&self) -> impl Iterator<Item = Aabb> + '_ {
        let w = self.width as usize;
        self.tiles
            .iter()
            .enumerate()
            .filter(|(_, t)| **t == Tile::Solid)
            .map(move |(k, _)| Self::tile_box((k % w) as i64, (k / w) as i64))
    }

    /// Solid tiles merged into rectangles: each row's runs of solid tiles, grown upward while
    /// the rows above hold the same run. Every solid tile is in exactly one rectangle.
    pub fn merged_solid_rects(&self) -> Vec<Aabb> {
        let (w, h) = (self.width as usize, self.height as usize);
        let solid = |i: usize, j: usize| self.tiles[j * w + i] == Tile::Solid;
        let mut used = vec![false; w * h];
        let mut out = Vec::new();
        for j in 0..h {
            let mut i = 0;
            while i < w {
                if !solid(i, j) || used[j * w + i] {
                    i += 1;
                    continue;
                }
                let mut i1 = i + 1;
                while i1 < w && solid(i1, j) && !used[j * w + i1] {
                    i1 += 1;
                }
                let mut j1 = j + 1;
                while j1 < h && (i..i1).all(|k| solid(k, j1) && !used[j1 * w + k]) {
                    j1 += 1;
                }
                for jj in j..j1 {
                    for k in i..i1 {
                        used[jj * w + k] = true;
                    }
                }
                out.push(Aabb::new(
                    Vec2::new(i as f32, j as f32),
                    Vec2::new(i1 as f32, j1 as f32),
                ));
                i = i1;
            }
        }
        out
    }

    /// Solid tiles whose boxes overlap `area` with positive area (touching does not count).
    /// Only the part of `area` inside the map is walked (outside is empty), so the work is
    /// bounded by the map however large or non-finite the area is.
    pub fn solids_overlapping(&self, area: &Aabb) -> impl Iterator<Item = Aabb> + '_ {
        let (w, h) = (self.width as i64, self.height as i64);
        let i0 = (area.mins.x.floor() as i64).clamp(0, w);
        let i1 = (area.maxs.x.ceil() as i64).clamp(0, w);
        let j0 = (area.mins.y.floor() as i64).clamp(0, h);
        let j1 = (area.maxs.y.ceil() as i64).clamp(0, h);
        let a = *area;
        (j0..j1)
            .flat_map(move |j| (i0..i1).map(move |i| (i, j)))
            .filter(move |&(i, j)| self.tile(i, j) == Tile::Solid)
            .map(|(i, j)| Self::tile_box(i, j))
            .filter(move |b| {
                b.mins.x < a.maxs.x
                    && a.mins.x < b.maxs.x
                    && b.mins.y < a.maxs.y
                    && a.mins.y < b.maxs.y
            })
    }

    /// The highest solid or one-way top at or below `y + tolerance` under the horizontal span
    /// `[x0, x1]` (open at both ends), or `None` if nothing is below.
    pub fn support_below(&self, x0: f32, x1: f32, y: f32, tolerance: f32) -> Option<f32> {
        // Columns outside the map hold nothing: the walk stays within it.
        let i0 = (x0.floor() as i64).clamp(0, self.width as i64);
        let i1 = (x1.ceil() as i64).clamp(0, self.width as i64);
        let top_row = ((y + tolerance).floor() as i64 - 1).min(self.height as i64 - 1);
        let mut best: Option<f32> = None;
        for i in i0..i1 {
            if (i as f32 + 1.0) <= x0 || i as f32 >= x1 {
                continue;
            }
            let mut j = top_row;
            while j >= 0 {
                if self.tile(i, j) == Tile::Solid || self.is_one_way(i, j) {
                    let top = j as f32 + 1.0;
                    best = Some(best.map_or(top, |b: f32| b.max(top)));
                    break;
                }
                j -= 1;
            }
        }
        best
    }
}

impl Level {
    /// The highest ground surface in column `floor(x)` at or below `top`, looking down at most
    /// `depth` tiles: a solid tile's top or a slope's surface at `x`. Returns the height and, for
    /// a slope, its tile.
    pub fn surface_at(&self, x: f32, top: f32, depth: f32) -> Option<(f32, Option<(i64, i64)>)> {
        let i = x.floor() as i64;
        let lowest = top - depth;
        // Rows above the map hold nothing: the walk starts at most at its top row.
        let mut j = (top.floor() as i64).min(self.height as i64 - 1);
        while j as f32 + 1.0 > lowest && j >= 0 {
            match self.tile(i, j) {
                Tile::Solid => {
                    let h = j as f32 + 1.0;
                    return (h <= top && h >= lowest).then_some((h, None));
                }
                Tile::Slope(s) => {
                    // Where the surface is at the tile's bottom, this tile holds nothing at x.
                    let local = s.height_at(x - i as f32);
                    let h = j as f32 + local;
                    if local > 0.0 && h <= top {
                        return (h >= lowest).then_some((h, Some((i, j))));
                    }
                }
                _ => {}
            }
            j -= 1;
        }
        None
    }

    /// The slope surface's normal at `x` in slope tile `(i, j)`, from the gradient over a
    /// sixteenth of a tile around `x` (the width of one height-array column).
    pub fn slope_normal(&self, i: i64, j: i64, x: f32) -> Vec2 {
        let Tile::Slope(s) = self.tile(i, j) else {
            return Vec2::Y;
        };
        let u = x - i as f32;
        let (a, b) = ((u - 1.0 / 32.0).max(0.0), (u + 1.0 / 32.0).min(1.0));
        let grad = (s.height_at(b) - s.height_at(a)) / (b - a).max(1e-6);
        Vec2::new(-grad, 1.0).normalize()
    }

    /// Whether tile `(i, j)` is a solid tile carrying a slope tile: part of a ramp's mass, which
    /// the centre-column slope rules govern rather than the box sweep.
    pub fn supports_slope(&self, i: i64, j: i64) -> bool {
        self.tile(i, j) == Tile::Solid && matches!(self.tile(i, j + 1), Tile::Slope(_))
    }

    /// Whether tile `(i, j)` can be stood on from above only: a one-way platform, or the top
    /// tile of a ladder (which the seed makes walkable like a one-way platform).
    pub fn is_one_way(&self, i: i64, j: i64) -> bool {
        match self.tile(i, j) {
            Tile::OneWay => true,
            Tile::Ladder => self.tile(i, j + 1) != Tile::Ladder,
            _ => false,
        }
    }

    /// The run of ladder tiles in column `i` that contains row `j`, as (bottom, top) heights.
    pub fn ladder_extent(&self, i: i64, j: i64) -> Option<(f32, f32)> {
        if self.tile(i, j) != Tile::Ladder {
            return None;
        }
        let (mut lo, mut hi) = (j, j);
        while self.tile(i, lo - 1) == Tile::Ladder {
            lo -= 1;
        }
        while self.tile(i, hi + 1) == Tile::Ladder {
            hi += 1;
        }
        Some((lo as f32, hi as f32 + 1.0))
    }

    /// Boxes of every one-way tile (see [`Level::is_one_way`]), in row order.
    pub fn one_way_boxes(&self) -> impl Iterator<Item = Aabb> + '_ {
        (0..self.height as i64)
            .flat_map(move |j| (0..self.width as i64).map(move |i| (i, j)))
            .filter(move |&(i, j)| self.is_one_way(i, j))
            .map(|(i, j)| Self::tile_box(i, j))
    }

    /// Every slope tile with its column and row.
    pub fn slopes(&self) -> impl Iterator<Item = (i64, i64, Slope)> + '_ {
        let w = self.width as usize;
        self.tiles
            .iter()
            .enumerate()
            .filter_map(move |(k, t)| match t {
                Tile::Slope(s) => Some(((k % w) as i64, (k / w) as i64, *s)),
                _ => None,
            })
    }
}

/// A height `h` (tiles, from the level's corner) on a grid of `per_tile` steps per tile, as
/// whole steps: the one rounding of surface heights that integer positions use (the sweep's
/// `Grid::round_height`, and the metrics' declared stance for it). A height within 1e-4 of a
/// step (f32 noise of a surface already on the grid) is that step; any other is rounded *up*,
/// so feet put on a surface are never below it and at most one step above it.
pub fn round_height_up(h: f32, per_tile: i64) -> i64 {
    let v = h as f64 * per_tile as f64;
    let r = v.round();
    if (v - r).abs() < 1e-4 {
        r as i64
    } else {
        v.ceil() as i64
    }
}

/// The box of a character whose feet (bottom centre) are at `pos`.
pub fn character_box(pos: Vec2, size: Vec2) -> Aabb {
    Aabb::new(
        Vec2::new(pos.x - size.x * 0.5, pos.y),
        Vec2::new(pos.x + size.x * 0.5, pos.y + size.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> Level {
        // Row 0: solid floor of 4 tiles; row 1: one solid at i = 3.
        let mut t = vec![Tile::Solid; 4];
        t.extend([Tile::Empty, Tile::Empty, Tile::Empty, Tile::Solid]);
        t.extend([Tile::Empty; 4]);
        Level::from_tiles("small", 4, 3, t)
    }

    #[test]
    fn tile_lookup_and_bounds() {
        let l = small();
        assert_eq!(l.tile(0, 0), Tile::Solid);
        assert_eq!(l.tile(3, 1), Tile::Solid);
        assert_eq!(l.tile(-1, 0), Tile::Empty);
        assert_eq!(l.tile(0, 3), Tile::Empty);
        assert_eq!(l.solid_boxes().count(), 5);
        assert_eq!(l.features, Features::default());
    }

    #[test]
    fn support_below_finds_the_highest_top() {
        let l = small();
        assert_eq!(l.support_below(0.5, 1.5, 1.0, 0.0), Some(1.0));
        assert_eq!(l.support_below(2.5, 3.5, 2.0, 0.0), Some(2.0));
        assert_eq!(l.support_below(2.5, 3.5, 1.5, 0.0), Some(1.0));
        assert_eq!(l.support_below(5.0, 6.0, 1.0, 0.0), None);
    }

    #[test]
    fn slope_surfaces_run_left_to_right() {
        let up = Slope::Line {
            left: 0.0,
            right: 0.5,
        };
        assert_eq!(up.height_at(0.0), 0.0);
        assert_eq!(up.height_at(1.0), 0.5);
        assert_eq!(up.height_at(0.5), 0.25);
        let seed = Slope::Heights([12, 11, 10, 8, 7, 6, 5, 5, 5, 5, 5, 4, 3, 2, 1, 1]);
        assert_eq!(seed.height_at(0.0), 12.0 / 16.0);
        assert_eq!(seed.height_at(3.5 / 16.0), 8.0 / 16.0);
        assert_eq!(seed.height_at(1.0), 1.0 / 16.0);
        // 11 runs of equal heights (12, 11, 10, 8, 7, 6, 5 x5, 4, 3, 2, 1 x2), two points each.
        assert_eq!(seed.surface_points().len(), 22);
        assert_eq!(seed.height_left_of(3.0 / 16.0), 10.0 / 16.0);
        assert_eq!(seed.height_at(3.0 / 16.0), 8.0 / 16.0);
    }

    #[test]
    fn heights_round_up_to_the_grid_unless_on_it() {
        // On the grid (up to f32 noise): that step. Off it: the next step up, never down.
        assert_eq!(round_height_up(0.75, 32), 24);
        assert_eq!(round_height_up(0.75 + 1e-7, 32), 24);
        assert_eq!(round_height_up(0.414_213_57, 32), 14); // 13.25 subpixels
        assert_eq!(round_height_up(-0.414_213_57, 32), -13);
    }

    #[test]
    fn surface_at_finds_solids_and_slopes() {
        // Row 0 solid; row 1: a '/' at i = 1.
        let mut t = vec![Tile::Solid; 3];
        t.extend([
            Tile::Empty,
            Tile::Slope(Slope::Line {
                left: 0.0,
                right: 1.0,
            }),
            Tile::Empty,
        ]);
        t.extend([Tile::Empty; 3]);
        let l = Level::from_tiles("s", 3, 3, t);
        assert_eq!(l.surface_at(0.5, 2.5, 2.0), Some((1.0, None)));
        assert_eq!(l.surface_at(1.25, 2.5, 2.0), Some((1.25, Some((1, 1)))));
        // Below the slope surface the slope is not "at or below": the solid under it is found.
        assert_eq!(l.surface_at(1.75, 1.5, 2.0), Some((1.0, None)));
        assert_eq!(l.surface_at(1.75, 1.5, 0.2), None);
        let n = l.slope_normal(1, 1, 1.5);
        assert!((n - Vec2::new(-1.0, 1.0).normalize()).length() < 1e-5);
    }

    #[test]
    fn merged_rects_cover_every_solid_tile_once() {
        let l = small();
        let rects = l.merged_solid_rects();
        // The floor row is one run; the single tile above it at i = 3 is its own rectangle.
        assert_eq!(rects.len(), 2, "{rects:?}");
        let area: f32 = rects.iter().map(|r| r.extents().x * r.extents().y).sum();
        assert_eq!(area, l.solid_boxes().count() as f32);
        // A solid 3 x 2 block becomes one rectangle.
        let block = Level::from_tiles("b", 3, 2, vec![Tile::Solid; 6]);
        assert_eq!(block.merged_solid_rects().len(), 1);
    }

    #[test]
    fn walks_over_tiles_stay_within_the_map() {
        // An area of 1e30 tiles (once a hang: `size = [1e30, 1e30]`) or a non-finite one
        // visits only the map's 12 tiles, and finds its 5 solids.
        let l = small();
        let huge = Aabb::new(Vec2::splat(-1e30), Vec2::splat(1e30));
        assert_eq!(l.solids_overlapping(&huge).count(), 5);
        let inf = Aabb::new(Vec2::splat(f32::NEG_INFINITY), Vec2::splat(f32::INFINITY));
        assert_eq!(l.solids_overlapping(&inf).count(), 5);
        let nan = Aabb::new(Vec2::splat(f32::NAN), Vec2::splat(f32::NAN));
        assert_eq!(l.solids_overlapping(&nan).count(), 0);
        assert_eq!(l.surface_at(0.5, 1e30, f32::INFINITY), Some((1.0, None)));
        assert_eq!(l.support_below(-1e30, 1e30, 1e30, 0.0), Some(2.0));
    }

    #[test]
    fn overlap_ignores_touching() {
        let l = small();
        let b = character_box(Vec2::new(1.0, 1.0), Vec2::new(0.8, 0.9));
        assert_eq!(l.solids_overlapping(&b).count(), 0);
        let sunk = character_box(Vec2::new(1.0, 0.99), Vec2::new(0.8, 0.9));
        assert_eq!(l.solids_overlapping(&sunk).count(), 2);
    }
}

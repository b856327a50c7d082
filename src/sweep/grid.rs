//! Integer positions: the seed's "store positions with integers and you're fine" (the slide
//! "Collision Resolution – A Problem"), as Celeste and TowerFall ship it.
//!
//! In this mode a character's box lives on a grid of `per_tile` subpixels per tile: its corner
//! is a whole number of subpixels in the world (`i64`), its size is rounded up to whole
//! subpixels, and the motion's float displacement is turned into a whole move per axis with the
//! fraction kept as a remainder for the next step. Tile faces are whole subpixels too, so snapping
//! flush is exact integer arithmetic: no overlap can be left by rounding, and no epsilon is
//! needed. Levels and traces stay in tiles; the conversion happens here, at the edges.
//!
//! The broadphase still holds the tiles as parry2d f32 boxes. Their faces are whole tiles, exact
//! in f32 up to 2^24 tiles from the origin, so a level placed farther is refused; the query box is
//! widened by two f32 spacings so that its own rounding far from the origin never hides a tile.

use glam::{DVec2, I64Vec2, Vec2};
use parry2d::bounding_volume::{Aabb, BoundingVolume};

use super::broadphase::{BoxKind, NearCache, StaticTiles};
use super::resolve::Axis;
use crate::backend::BackendError;

/// The largest distance from the origin, in tiles, at which tile faces are exact in the
/// broadphase's f32 boxes (2^24).
pub const MAX_GRID_EXTENT: f64 = 16_777_216.0;

/// A box on the grid, in world subpixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GridBox {
    /// Lower-left corner.
    pub min: I64Vec2,
    /// Upper-right corner.
    pub max: I64Vec2,
}

/// The subpixel grid of one level: its resolution and where the level's corner sits on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Subpixels per tile.
    pub per_tile: i64,
    /// The level's corner (tile (0, 0)'s lower left) in world subpixels.
    pub origin: I64Vec2,
}

impl Grid {
    /// The grid for a level placed at `origin` (tiles); refuses an origin that is not a whole
    /// number of subpixels or lies beyond [`MAX_GRID_EXTENT`].
    pub fn new(per_tile: u32, origin: Vec2, level: &str) -> Result<Grid, BackendError> {
        if !(1..=65_536).contains(&per_tile) {
            return Err(BackendError::InvalidParameter {
                name: "per_tile",
                value: per_tile.to_string(),
                expected: "1 to 65536 subpixels per tile",
            });
        }
        let s = per_tile as f64;
        let o = origin.as_dvec2() * s;
        let far = origin.as_dvec2().abs().max_element() > MAX_GRID_EXTENT;
        if far || o.round() != o {
            return Err(BackendError::Unsupported {
                backend: "sweep (integer positions)",
                feature: format!(
                    "a level origin of ({}, {}) tiles (integer positions need an origin on the \
                     subpixel grid, within 2^24 tiles of the world's origin)",
                    origin.x, origin.y
                ),
                level: level.to_string(),
                beyond_bound: true,
            });
        }
        Ok(Grid {
            per_tile: per_tile as i64,
            origin: o.as_i64vec2(),
        })
    }

    /// A size in tiles as whole subpixels, rounded up (so the grid box holds the float box);
    /// a size already on the grid up to f32 rounding stays as it is.
    pub fn size(&self, size: Vec2) -> I64Vec2 {
        subpixel_size(size, self.per_tile)
    }

    /// The box of size `size` (subpixels) whose feet (bottom centre) are nearest `feet`
    /// (level coordinates, tiles).
    pub fn place(&self, feet: Vec2, size: I64Vec2) -> GridBox {
        let s = self.per_tile as f64;
        let min = DVec2::new(
            (feet.x as f64 * s - size.x as f64 * 0.5).round(),
            (feet.y as f64 * s).round(),
        )
        .as_i64vec2()
            + self.origin;
        GridBox {
            min,
            max: min + size,
        }
    }

    /// The feet (bottom centre) of `b` in level coordinates, in tiles: exact in f32 for any
    /// level under 2^24 / `per_tile` tiles across.
    pub fn feet(&self, b: &GridBox) -> Vec2 {
        let s = self.per_tile as f64;
        let local = b.min - self.origin;
        Vec2::new(
            ((local.x as f64 + (b.max.x - b.min.x) as f64 * 0.5) / s) as f32,
            (local.y as f64 / s) as f32,
        )
    }

    /// A height in level coordinates (tiles) as whole subpixels above the level's corner: the
    /// one rounding of surface heights on the grid (slopes' resolve-up and follow-down),
    /// [`crate::level::round_height_up`]: up to the next subpixel unless already on one, so
    /// the centre column never sinks into a slope and stands at most one subpixel above it.
    pub fn round_height(&self, y: f32) -> i64 {
        crate::level::round_height_up(y, self.per_tile)
    }

    /// A broadphase box (world tiles, f32, faces on whole tiles) on the grid.
    pub fn from_aabb(&self, b: &Aabb) -> GridBox {
        let s = self.per_tile as f64;
        GridBox {
            min: (b.mins.as_dvec2() * s).round().as_i64vec2(),
            max: (b.maxs.as_dvec2() * s).round().as_i64vec2(),
        }
    }

    /// The broadphase area that holds every tile `b` may touch: `b` in world tiles, widened by
    /// two f32 spacings at its magnitude against the rounding of its corners (a ten-thousandth
    /// of a tile near the origin, two tiles at 1e7).
    fn query_area(&self, b: &GridBox) -> Aabb {
        let s = self.per_tile as f64;
        let (lo, hi) = (b.min.as_dvec2() / s, b.max.as_dvec2() / s);
        let magnitude = lo.abs().max(hi.abs()).max_element().max(1.0) as f32;
        Aabb::new(lo.as_vec2(), hi.as_vec2()).loosened(2.0 * magnitude * f32::EPSILON)
    }
}

/// A character's place on the grid: its box and the fractions of a subpixel its moves have
/// not used yet.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridPos {
    /// The box, in world subpixels.
    pub b: GridBox,
    /// The unused fraction of the last moves, per axis, in subpixels (|r| <= 0.5).
    pub remainder: Vec2,
}

impl GridPos {
    /// The character of size `size` (tiles) whose feet are at `feet` (level coordinates), with
    /// nothing carried yet.
    pub fn spawn(grid: &Grid, feet: Vec2, size: Vec2) -> Self {
        GridPos {
            b: grid.place(feet, grid.size(size)),
            remainder: Vec2::ZERO,
        }
    }

    /// Turns a move of `delta` tiles along `axis` into whole subpixels, keeping the fraction.
    pub fn whole_move(&mut self, grid: &Grid, axis: Axis, delta: f32) -> i64 {
        let a = axis.index();
        let total = delta * grid.per_tile as f32 + self.remainder[a];
        let n = total.round();
        self.remainder[a] = total - n;
        n as i64
    }
}

/// Moves `p` by `n` subpixels along `axis`, stopping flush at the closest box ahead among the
/// static tiles and the `extra` boxes (moving platforms where they are now, on the grid): the
/// seed's sweep, in integers: a box is beside the mover when the two overlap across the move
/// by at least one subpixel, and ahead when its face lies within the move. With `commit` false
/// nothing moves and only a box whose face touches the mover's leading side counts: a probe
/// for a contact in the direction of `n`. Returns the kind of the box that stopped the move.
#[allow(clippy::too_many_arguments)]
pub fn move_axis_grid(
    tiles: &StaticTiles,
    near: &mut NearCache,
    grid: &Grid,
    p: &mut GridPos,
    axis: Axis,
    n: i64,
    commit: bool,
    extra: &[(GridBox, BoxKind)],
    skip: impl Fn(&GridBox, BoxKind) -> bool,
) -> Option<BoxKind> {
    if n == 0 {
        return None;
    }
    let a = axis.index();
    let o = 1 - a;
    let b = p.b;
    let mut swept = b;
    if n > 0 {
        swept.max[a] += n;
    } else {
        swept.min[a] += n;
    }
    let area = grid.query_area(&swept);
    let mut closest: Option<(i64, BoxKind)> = None;
    let statics = near
        .query(tiles, &area)
        .map(|(t, kind)| (grid.from_aabb(t), kind));
    let moving = extra.iter().copied().filter(|(t, _)| {
        t.min.x <= swept.max.x
            && t.max.x >= swept.min.x
            && t.min.y <= swept.max.y
            && t.max.y >= swept.min.y
    });
    for (t, kind) in statics.chain(moving) {
        if skip(&t, kind) || b.max[o].min(t.max[o]) - b.min[o].max(t.min[o]) <= 0 {
            continue;
        }
        if n > 0 {
            let face = t.min[a];
            let reach = if commit { swept.max[a] } else { b.max[a] };
            if face >= b.max[a] && face <= reach && closest.is_none_or(|(c, _)| face < c) {
                closest = Some((face, kind));
            }
        } else {
            let face = t.max[a];
            let reach = if commit { swept.min[a] } else { b.min[a] };
            if face <= b.min[a] && face >= reach && closest.is_none_or(|(c, _)| face > c) {
                closest = Some((face, kind));
            }
        }
    }
    let size = b.max[a] - b.min[a];
    let new_min = match closest {
        None => b.min[a] + n,
        Some((face, _)) if n > 0 => face - size,
        Some((face, _)) => face,
    };
    if commit {
        p.b.min[a] = new_min;
        p.b.max[a] = new_min + size;
    }
    closest.map(|(_, k)| k)
}

/// `size` (tiles) as whole subpixels of a `per_tile` grid, rounded up so the grid box holds the
/// float box; a size already on the grid up to f32 rounding stays as it is (see [`Grid::size`]).
pub fn subpixel_size(size: Vec2, per_tile: i64) -> I64Vec2 {
    let s = size.as_dvec2() * per_tile as f64;
    let snap = |v: f64| {
        if (v - v.round()).abs() < 1e-4 {
            v.round()
        } else {
            v.ceil()
        }
    };
    I64Vec2::new(snap(s.x) as i64, snap(s.y) as i64).max(I64Vec2::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{Level, Tile};

    /// A floor row at j = 0 and a wall column at i = 10 (rows 1..4), 20 x 5 tiles.
    fn room(origin: Vec2) -> (StaticTiles, Grid) {
        let (w, h) = (20u32, 5u32);
        let mut t = vec![Tile::Empty; (w * h) as usize];
        for i in 0..w {
            t[i as usize] = Tile::Solid;
        }
        for j in 1..h {
            t[(j * w + 10) as usize] = Tile::Solid;
        }
        let mut l = Level::from_tiles("room", w, h, t);
        l.origin = origin.as_dvec2();
        (StaticTiles::new(&l), Grid::new(16, origin, "room").unwrap())
    }

    fn at(grid: &Grid, feet: Vec2) -> GridPos {
        GridPos::spawn(grid, feet, Vec2::new(0.8, 0.9))
    }

    #[test]
    fn sizes_round_up_to_whole_subpixels_and_feet_round_trip() {
        let (_, g) = room(Vec2::ZERO);
        // 0.8 x 0.9 tiles is 12.8 x 14.4 sixteenths: 13 x 15.
        assert_eq!(g.size(Vec2::new(0.8, 0.9)), I64Vec2::new(13, 15));
        assert_eq!(g.size(Vec2::new(1.0, 0.5)), I64Vec2::new(16, 8));
        let p = at(&g, Vec2::new(2.5, 1.0));
        // 13 wide: the feet sit half a subpixel off 2.5, on the 1/32 grid.
        assert_eq!(g.feet(&p.b), Vec2::new(2.5 + 1.0 / 32.0, 1.0));
    }

    #[test]
    fn a_fall_snaps_exactly_onto_the_floor_far_from_the_origin() {
        for origin in [0.0, 1e6, 1e7] {
            let (tiles, g) = room(Vec2::splat(origin));
            let mut p = at(&g, Vec2::new(2.5, 3.0));
            let n = p.whole_move(&g, Axis::Y, -5.0);
            let hit = move_axis_grid(
                &tiles,
                &mut NearCache::default(),
                &g,
                &mut p,
                Axis::Y,
                n,
                true,
                &[],
                |_, _| false,
            );
            assert_eq!(hit, Some(BoxKind::Solid), "origin {origin}");
            assert_eq!(g.feet(&p.b).y, 1.0, "origin {origin}");
        }
    }

    #[test]
    fn a_wall_stops_a_fast_mover_flush_and_a_probe_moves_nothing() {
        let (tiles, g) = room(Vec2::splat(1e6));
        let mut p = at(&g, Vec2::new(2.5, 1.0));
        let mut near = NearCache::default();
        let n = p.whole_move(&g, Axis::X, 1000.0);
        let hit = move_axis_grid(
            &tiles,
            &mut near,
            &g,
            &mut p,
            Axis::X,
            n,
            true,
            &[],
            |_, _| false,
        );
        assert!(hit.is_some());
        // Flush: the box's right side is on the wall's face, x = 10 tiles.
        assert_eq!(p.b.max.x - g.origin.x, 160);
        let before = p;
        let probe = move_axis_grid(
            &tiles,
            &mut near,
            &g,
            &mut p,
            Axis::X,
            1,
            false,
            &[],
            |_, _| false,
        );
        assert!(probe.is_some());
        assert_eq!(p, before);
        // One subpixel away from the wall, the probe finds nothing.
        p.b.min.x -= 1;
        p.b.max.x -= 1;
        let probe = move_axis_grid(
            &tiles,
            &mut near,
            &g,
            &mut p,
            Axis::X,
            1,
            false,
            &[],
            |_, _| false,
        );
        assert!(probe.is_none());
    }

    #[test]
    fn moves_below_a_subpixel_accumulate_in_the_remainder() {
        let (_, g) = room(Vec2::ZERO);
        let mut p = at(&g, Vec2::new(2.5, 1.0));
        // 0.01 tiles is 0.16 subpixels: nothing for three steps, then one subpixel.
        let moves: Vec<i64> = (0..7).map(|_| p.whole_move(&g, Axis::X, 0.01)).collect();
        assert_eq!(moves, vec![0, 0, 0, 1, 0, 0, 0]);
        assert!(p.remainder.x.abs() <= 0.5);
    }

    #[test]
    fn an_origin_off_the_grid_or_beyond_2_24_tiles_is_refused() {
        assert!(Grid::new(16, Vec2::new(0.01, 0.0), "l").is_err());
        assert!(Grid::new(16, Vec2::new(3e7, 0.0), "l").is_err());
        assert!(Grid::new(0, Vec2::ZERO, "l").is_err());
        assert!(Grid::new(16, Vec2::splat(1e7), "l").is_ok());
    }
}

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

use super::space::Rect;
use crate::backend::BackendError;
use crate::rounding::{ceil64, floor64, round_to_i64};

/// The largest distance from the origin, in tiles, at which tile faces are exact in the
/// broadphase's f32 boxes (2^24).
pub const MAX_GRID_EXTENT: f64 = 16_777_216.0;

/// The subpixel grid of one level: its resolution and where the level's corner sits on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Grid {
    /// Subpixels per tile.
    pub per_tile: i64,
    /// The level's corner (tile (0, 0)'s lower left) in world subpixels.
    pub origin: I64Vec2,
    /// `1 / per_tile` when that is exact (`per_tile` a power of two: 16 and 32 are), else 0:
    /// dividing by `per_tile` is then multiplying by it, the same bits for a cheaper
    /// instruction ([`Grid::tiles`]).
    recip: f64,
}

impl Grid {
    /// The grid for a level placed at `origin` (tiles); refuses an origin that is not a whole
    /// number of subpixels or lies beyond [`MAX_GRID_EXTENT`].
    pub(crate) fn new(per_tile: u32, origin: Vec2, level: &str) -> Result<Grid, BackendError> {
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
            recip: if per_tile.is_power_of_two() {
                1.0 / s
            } else {
                0.0
            },
        })
    }

    /// `v` subpixels in tiles: `v / per_tile`, bit for bit. When `per_tile` is a power of two
    /// its reciprocal is exact, and `v * recip` and `v / per_tile` are the same real number
    /// rounded once, so the same f64.
    #[inline]
    pub(crate) fn tiles(&self, v: f64) -> f64 {
        if self.recip != 0.0 {
            v * self.recip
        } else {
            v / self.per_tile as f64
        }
    }

    /// A size in tiles as whole subpixels, rounded up (so the grid box holds the float box);
    /// a size already on the grid up to f32 rounding stays as it is.
    #[inline]
    pub(crate) fn size(&self, size: Vec2) -> I64Vec2 {
        subpixel_size(size, self.per_tile)
    }

    /// The box of size `size` (subpixels) whose feet (bottom centre) are nearest `feet`
    /// (level coordinates, tiles).
    #[inline]
    pub(crate) fn place(&self, feet: Vec2, size: I64Vec2) -> Rect<i64> {
        let s = self.per_tile as f64;
        let min = I64Vec2::new(
            round_to_i64(feet.x as f64 * s - size.x as f64 * 0.5),
            round_to_i64(feet.y as f64 * s),
        ) + self.origin;
        Rect {
            min: min.to_array(),
            max: (min + size).to_array(),
        }
    }

    /// The feet (bottom centre) of `b` in level coordinates, in tiles: exact in f32 for any
    /// level under 2^24 / `per_tile` tiles across.
    #[inline]
    pub(crate) fn feet(&self, b: &Rect<i64>) -> Vec2 {
        let local = I64Vec2::from_array(b.min) - self.origin;
        Vec2::new(
            self.tiles(local.x as f64 + (b.max[0] - b.min[0]) as f64 * 0.5) as f32,
            self.tiles(local.y as f64) as f32,
        )
    }

    /// A height in level coordinates (tiles) as whole subpixels above the level's corner: the
    /// one rounding of surface heights on the grid (slopes' resolve-up and follow-down),
    /// [`crate::level::round_height_up`]: up to the next subpixel unless already on one, so
    /// the centre column never sinks into a slope and stands at most one subpixel above it.
    #[inline]
    pub(crate) fn round_height(&self, y: f32) -> i64 {
        crate::level::round_height_up(y, self.per_tile)
    }

    /// A broadphase box (world tiles, f32, faces on whole tiles) on the grid.
    #[inline]
    pub(crate) fn box_of(&self, b: &Aabb) -> Rect<i64> {
        let s = self.per_tile as f64;
        let on_grid = |v: f32| round_to_i64(v as f64 * s);
        Rect {
            min: [on_grid(b.mins.x), on_grid(b.mins.y)],
            max: [on_grid(b.maxs.x), on_grid(b.maxs.y)],
        }
    }

    /// A box of whole subpixels inside the broadphase area `a` (world tiles), short of its
    /// sides by two subpixels and the widening [`Grid::query_area`] adds at its magnitude, so
    /// that the area of the box lies inside `a` (the near cache checks it).
    #[inline]
    pub(crate) fn inside(&self, a: &Aabb) -> Rect<i64> {
        let s = self.per_tile as f64;
        let magnitude = a.mins.abs().max(a.maxs.abs()).max_element().max(1.0) as f64;
        let m = 2 + ceil64(4.0 * magnitude * f32::EPSILON as f64 * s) as i64;
        Rect {
            min: [
                ceil64(a.mins.x as f64 * s) as i64 + m,
                ceil64(a.mins.y as f64 * s) as i64 + m,
            ],
            max: [
                floor64(a.maxs.x as f64 * s) as i64 - m,
                floor64(a.maxs.y as f64 * s) as i64 - m,
            ],
        }
    }

    /// The broadphase area that holds every tile `b` may touch: `b` in world tiles, widened by
    /// two f32 spacings at its magnitude against the rounding of its corners (a ten-thousandth
    /// of a tile near the origin, two tiles at 1e7).
    #[inline]
    pub(crate) fn query_area(&self, b: &Rect<i64>) -> Aabb {
        let tiles = |v: [i64; 2]| DVec2::new(self.tiles(v[0] as f64), self.tiles(v[1] as f64));
        let (lo, hi) = (tiles(b.min), tiles(b.max));
        let magnitude = lo.abs().max(hi.abs()).max_element().max(1.0) as f32;
        Aabb::new(lo.as_vec2(), hi.as_vec2()).loosened(2.0 * magnitude * f32::EPSILON)
    }
}

/// `size` (tiles) as whole subpixels of a `per_tile` grid, rounded up so the grid box holds the
/// float box; a size already on the grid up to f32 rounding stays as it is (see [`Grid::size`]).
pub(crate) fn subpixel_size(size: Vec2, per_tile: i64) -> I64Vec2 {
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
    use crate::sweep::broadphase::{BoxKind, NearCache, StaticTiles};
    use crate::sweep::resolve::{move_axis, touching, Axis, Obstacles};
    use crate::sweep::space::{Body, GridSpace, Space};

    /// A floor row at j = 0 and a wall column at i = 10 (rows 1..4), 20 x 5 tiles.
    fn room(origin: Vec2) -> (StaticTiles, GridSpace) {
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
        let grid = Grid::new(16, origin, "room").unwrap();
        (StaticTiles::new(&l), GridSpace { grid })
    }

    fn at(s: &GridSpace, feet: Vec2) -> Body<i64> {
        s.spawn(feet, Vec2::new(0.8, 0.9))
    }

    fn obstacles<'a>(s: &'a GridSpace, tiles: &'a StaticTiles) -> Obstacles<'a, GridSpace> {
        Obstacles {
            space: s,
            tiles,
            moving: None,
            eps: 0,
        }
    }

    #[test]
    fn sizes_round_up_to_whole_subpixels_and_feet_round_trip() {
        let (_, s) = room(Vec2::ZERO);
        let g = s.grid;
        // 0.8 x 0.9 tiles is 12.8 x 14.4 sixteenths: 13 x 15.
        assert_eq!(g.size(Vec2::new(0.8, 0.9)), I64Vec2::new(13, 15));
        assert_eq!(g.size(Vec2::new(1.0, 0.5)), I64Vec2::new(16, 8));
        let p = at(&s, Vec2::new(2.5, 1.0));
        // 13 wide: the feet sit half a subpixel off 2.5, on the 1/32 grid.
        assert_eq!(g.feet(&p.rect()), Vec2::new(2.5 + 1.0 / 32.0, 1.0));
        assert_eq!(p.size, Vec2::new(13.0, 15.0) / 16.0);
    }

    #[test]
    fn a_fall_snaps_exactly_onto_the_floor_far_from_the_origin() {
        for origin in [0.0, 1e6, 1e7] {
            let (tiles, s) = room(Vec2::splat(origin));
            let mut p = at(&s, Vec2::new(2.5, 3.0));
            let n = s.whole_move(&mut p, Axis::Y, -5.0, false);
            let mut near = NearCache::default();
            let o = obstacles(&s, &tiles);
            let hit = move_axis(&o, &mut near, &mut p, Axis::Y, n, |_, _| false);
            assert_eq!(hit, Some(BoxKind::Solid), "origin {origin}");
            assert_eq!(s.grid.feet(&p.rect()).y, 1.0, "origin {origin}");
        }
    }

    #[test]
    fn a_wall_stops_a_fast_mover_flush_and_a_probe_moves_nothing() {
        let (tiles, s) = room(Vec2::splat(1e6));
        let o = obstacles(&s, &tiles);
        let mut p = at(&s, Vec2::new(2.5, 1.0));
        let mut near = NearCache::default();
        let n = s.whole_move(&mut p, Axis::X, 1000.0, false);
        let hit = move_axis(&o, &mut near, &mut p, Axis::X, n, |_, _| false);
        assert!(hit.is_some());
        // Flush: the box's right side is on the wall's face, x = 10 tiles.
        assert_eq!(p.rect().max[0] - s.grid.origin.x, 160);
        let before = p;
        let probe = touching(&o, &mut near, &mut p, Axis::X, 1, |_, _| false);
        assert!(probe.is_some());
        assert_eq!(p, before);
        // One subpixel away from the wall, the probe finds nothing and moves nothing.
        p.at[0] -= 1;
        let before = p;
        let probe = touching(&o, &mut near, &mut p, Axis::X, 1, |_, _| false);
        assert!(probe.is_none());
        assert_eq!(p, before);
    }

    #[test]
    fn moves_below_a_subpixel_accumulate_in_the_remainder() {
        let (_, s) = room(Vec2::ZERO);
        let mut p = at(&s, Vec2::new(2.5, 1.0));
        // 0.01 tiles is 0.16 subpixels: nothing for three steps, then one subpixel.
        let moves: Vec<i64> = (0..7)
            .map(|_| s.whole_move(&mut p, Axis::X, 0.01, false))
            .collect();
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

//! How the sweep stores positions: the one thing its three modes do differently.
//!
//! The seed's "Collision Resolution – A Problem" slide: "if you store positions with integers
//! you're fine; for floating point positions, placing an object tangent to another involves a
//! subtraction, introduces floating point error, \[so\] allow a fudge factor for overlap". The
//! step ([`super::step`]), every stage it calls and the one sweep-and-snap
//! ([`super::resolve::move_axis`]) are written once, over a [`Space`] and its [`Coord`]; the
//! three implementations are the three storages:
//!
//! - [`FloatSpace`]: f32 feet in world tiles, snapped flush with the seed's epsilon fudge.
//! - [`DoubleSpace`]: the float rules with f64 feet in world tiles, swept and snapped in f64
//!   with the same epsilon, the static boxes asked of the f32 broadphase in level coordinates.
//! - [`GridSpace`]: a box of whole subpixels (`i64`) with each axis's unused fraction carried
//!   ([`super::grid`]), snapped flush in exact integer arithmetic, no epsilon.
//!
//! A character's [`Body`] is one position in the space's coordinate. The stages read and write
//! feet in the space's *frame*: an f32 point with the level's corner at [`Frame::origin`] (the
//! world for float, the level's own coordinates for f64 and the grid, where positions on the
//! grid are exact in f32). Comparisons against box faces (the sweep, the one-way and slope
//! rules) are done in the space's [`Coord`], so the grid compares integers exactly.

use std::ops::{Add, Neg, Sub};

use glam::{DVec2, Vec2};
use parry2d::bounding_volume::Aabb;

use super::broadphase::{BoxKind, NearCache, StaticTiles};
use super::grid::Grid;
use super::platforms::PlatformState;
use super::resolve::Axis;
use crate::rounding::{ceil64, floor64, round32};

/// A coordinate in which box faces compare: world tiles (f32, f64) or world subpixels (i64).
/// Its `Default` is zero.
pub(crate) trait Coord:
    Copy + Default + PartialOrd + Add<Output = Self> + Sub<Output = Self> + Neg<Output = Self>
{
    /// The smallest move the storage makes: one subpixel; 0 in float, where any move moves.
    const UNIT: Self;
    /// The smaller of two (the type's own `min`).
    fn min(self, other: Self) -> Self;
    /// The larger of two (the type's own `max`).
    fn max(self, other: Self) -> Self;
    /// Whether the offset `v` is longer than `eps`: its Euclidean length in float, any offset
    /// on the grid.
    fn longer_than(v: [Self; 2], eps: Self) -> bool;
}

impl Coord for f32 {
    const UNIT: f32 = 0.0;
    #[inline]
    fn min(self, other: f32) -> f32 {
        f32::min(self, other)
    }
    #[inline]
    fn max(self, other: f32) -> f32 {
        f32::max(self, other)
    }
    #[inline]
    fn longer_than(v: [f32; 2], eps: f32) -> bool {
        Vec2::from_array(v).length() > eps
    }
}

impl Coord for f64 {
    const UNIT: f64 = 0.0;
    #[inline]
    fn min(self, other: f64) -> f64 {
        f64::min(self, other)
    }
    #[inline]
    fn max(self, other: f64) -> f64 {
        f64::max(self, other)
    }
    #[inline]
    fn longer_than(v: [f64; 2], eps: f64) -> bool {
        DVec2::from_array(v).length() > eps
    }
}

impl Coord for i64 {
    const UNIT: i64 = 1;
    #[inline]
    fn min(self, other: i64) -> i64 {
        Ord::min(self, other)
    }
    #[inline]
    fn max(self, other: i64) -> i64 {
        Ord::max(self, other)
    }
    #[inline]
    fn longer_than(v: [i64; 2], _eps: i64) -> bool {
        v != [0, 0]
    }
}

/// A box in a space's [`Coord`]: its lower-left and upper-right corners, `[x, y]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rect<C> {
    /// Lower-left corner.
    pub min: [C; 2],
    /// Upper-right corner.
    pub max: [C; 2],
}

impl<C: Coord> Rect<C> {
    /// Whether the two boxes touch or overlap (inclusive, as parry2d's AABB test).
    #[inline]
    pub fn touches(&self, other: &Rect<C>) -> bool {
        // Four comparisons and one branch: most boxes a move asks about are not in its way.
        (self.min[0] <= other.max[0])
            & (self.max[0] >= other.min[0])
            & (self.min[1] <= other.max[1])
            & (self.max[1] >= other.min[1])
    }

    /// Whether `other` lies inside this box (inclusive).
    #[inline]
    pub fn contains(&self, other: &Rect<C>) -> bool {
        (0..2).all(|k| self.min[k] <= other.min[k] && other.max[k] <= self.max[k])
    }
}

impl From<Aabb> for Rect<f32> {
    #[inline]
    fn from(b: Aabb) -> Self {
        Rect {
            min: [b.mins.x, b.mins.y],
            max: [b.maxs.x, b.maxs.y],
        }
    }
}

/// A character's box in a space's [`Coord`]: one anchor point and how the box reaches from it,
/// so that a move and its snap change the anchor alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Body<C> {
    /// The anchor: the feet (bottom centre) in float, the lower-left corner on the grid.
    pub at: [C; 2],
    /// How far the box reaches left of the anchor (half the width in float, 0 on the grid).
    pub left: C,
    /// How far it reaches right of the anchor (half the width in float, the width on the grid).
    pub right: C,
    /// How far it reaches up from the anchor: its height.
    pub height: C,
    /// The size of the box it really moves, in tiles (on the grid: rounded up to subpixels).
    pub size: Vec2,
    /// The fraction of a storage unit its moves have not used yet, per axis (the grid's,
    /// |r| <= 0.5; always 0 in float).
    pub remainder: Vec2,
}

impl<C: Coord> Body<C> {
    /// The box.
    #[inline]
    pub fn rect(&self) -> Rect<C> {
        Rect {
            min: [self.at[0] - self.left, self.at[1]],
            max: [self.at[0] + self.right, self.at[1] + self.height],
        }
    }
}

/// The stages' frame in one storage: where the level's corner is in it, and what the storage
/// tolerates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame<C> {
    /// Where the level's corner is in the frame (tiles).
    pub origin: Vec2,
    /// The overlap tolerance, in frame tiles: the seed's epsilon, or 0 on the grid.
    pub eps: f32,
    /// The overlap tolerance as a [`Coord`].
    pub eps_coord: C,
    /// The smallest move the storage makes, in tiles: one subpixel on the grid, 0 in float (any
    /// fall moves).
    pub unit: f32,
}

/// A storage of positions the step is generic over: what differs between f32, f64 and whole
/// subpixels, and nothing else.
pub(crate) trait Space {
    /// The coordinate box faces compare in.
    type Coord: Coord;

    /// The frame the stages work in, and the tolerances.
    fn frame(&self) -> Frame<Self::Coord>;
    /// A character of size `size` (tiles) with its feet at `feet` (level coordinates).
    fn spawn(&self, feet: Vec2, size: Vec2) -> Body<Self::Coord>;
    /// The feet (bottom centre) of `b` in the frame, in tiles.
    fn feet(&self, b: &Body<Self::Coord>) -> Vec2;
    /// Lets `f` change `b`'s feet (frame tiles); a changed position is put back on the storage
    /// (on the grid: placed on the nearest subpixels, fractions dropped).
    fn with_feet(&self, b: &mut Body<Self::Coord>, f: impl FnOnce(&mut Vec2));
    /// A frame height (tiles) as a [`Coord`] (on the grid: rounded to whole subpixels by
    /// [`Grid::round_height`], the one rounding of surface heights).
    fn coord_y(&self, y: f32) -> Self::Coord;
    /// A length in tiles as a [`Coord`] (on the grid: rounded up to whole subpixels).
    fn length_up(&self, tiles: f32) -> Self::Coord;
    /// A length in [`Coord`] as tiles.
    fn to_tiles(&self, v: Self::Coord) -> f32;
    /// This step's move of `delta` tiles along `axis` in the storage: as it is in float; on the
    /// grid whole subpixels, the fraction carried in `b`'s remainder, and with `min_fall` at
    /// least one subpixel down (a drop through a one-way platform must leave its top).
    fn whole_move(
        &self,
        b: &mut Body<Self::Coord>,
        axis: Axis,
        delta: f32,
        min_fall: bool,
    ) -> Self::Coord;
    /// The static boxes around `swept`, with their kind, in the broadphase's order, asked
    /// through the mover's `near` cache: every box that touches `swept` and maybe others near
    /// it (the cache's whole region; in f64 and on the grid the broadphase is asked in f32 with
    /// a margin), so the sweep tests each box again in [`Coord`].
    fn statics<'a>(
        &'a self,
        tiles: &StaticTiles,
        near: &'a mut NearCache<Self::Coord>,
        swept: Rect<Self::Coord>,
    ) -> &'a [(Rect<Self::Coord>, BoxKind)];
    /// Moving platform `p`'s box at time `t` (seconds) as the space places it: its exact path
    /// in float, its path rounded to the nearest subpixel on the grid
    /// ([`crate::level::Platform::grid_box`]).
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<Self::Coord>;
    /// A box that holds moving platform `p`'s box at every time, as [`Space::platform_at`]
    /// places it: its reach over its whole motion grown by a margin wider than the space's
    /// rounding (a wider box only costs a platform placed that need not be).
    fn reach(&self, p: &PlatformState) -> Rect<Self::Coord>;
}

/// [`PlatformState::reach_world`] grown by two tiles and a relative margin far wider than the
/// rounding of placing a box in `f32` or `f64`, as f64 corners.
fn grown_reach(p: &PlatformState) -> ([f64; 2], [f64; 2]) {
    let (lo, hi) = p.reach_world();
    let m = |v: f64| 2.0 + 1e-5 * v.abs();
    (
        [lo.x - m(lo.x), lo.y - m(lo.y)],
        [hi.x + m(hi.x), hi.y + m(hi.y)],
    )
}

/// f32 world positions with the seed's epsilon fudge.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FloatSpace {
    /// The seed's overlap tolerance, tiles.
    pub eps: f32,
    /// The level's corner in the world, tiles.
    pub origin: Vec2,
}

impl Space for FloatSpace {
    type Coord = f32;

    #[inline]
    fn frame(&self) -> Frame<f32> {
        Frame {
            origin: self.origin,
            eps: self.eps,
            eps_coord: self.eps,
            unit: 0.0,
        }
    }
    #[inline]
    fn spawn(&self, feet: Vec2, size: Vec2) -> Body<f32> {
        Body {
            at: (feet + self.origin).to_array(),
            left: size.x * 0.5,
            right: size.x * 0.5,
            height: size.y,
            size,
            remainder: Vec2::ZERO,
        }
    }
    #[inline]
    fn feet(&self, b: &Body<f32>) -> Vec2 {
        Vec2::from_array(b.at)
    }
    #[inline]
    fn with_feet(&self, b: &mut Body<f32>, f: impl FnOnce(&mut Vec2)) {
        let mut feet = Vec2::from_array(b.at);
        f(&mut feet);
        b.at = feet.to_array();
    }
    #[inline]
    fn coord_y(&self, y: f32) -> f32 {
        y
    }
    #[inline]
    fn length_up(&self, tiles: f32) -> f32 {
        tiles
    }
    #[inline]
    fn to_tiles(&self, v: f32) -> f32 {
        v
    }
    #[inline]
    fn whole_move(&self, _: &mut Body<f32>, _: Axis, delta: f32, _: bool) -> f32 {
        delta
    }
    #[inline(always)]
    fn statics<'a>(
        &'a self,
        tiles: &StaticTiles,
        near: &'a mut NearCache<f32>,
        swept: Rect<f32>,
    ) -> &'a [(Rect<f32>, BoxKind)] {
        let area = Aabb::new(Vec2::from_array(swept.min), Vec2::from_array(swept.max));
        near.query(tiles, area, |t| (*t).into())
    }
    #[inline]
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<f32> {
        p.aabb(t).into()
    }
    fn reach(&self, p: &PlatformState) -> Rect<f32> {
        let (min, max) = grown_reach(p);
        Rect {
            min: min.map(|v| v as f32),
            max: max.map(|v| v as f32),
        }
    }
}

/// How far beyond the swept box (tiles) the f64 mode asks the f32 broadphase: level coordinates
/// within a few thousand tiles of the level's corner round by under 1e-3 tile in f32.
pub(crate) const F64_QUERY_MARGIN: f32 = 1e-2;

/// f64 world positions with the seed's epsilon fudge: [`FloatSpace`]'s rules with the feet in
/// f64 and every move swept and snapped in f64. The static boxes are kept in the level's own
/// coordinates (the broadphase built at origin 0, where f32 is exact for tile faces) and placed
/// at the origin in f64: the broadphase is asked in f32 level coordinates with a margin of
/// [`F64_QUERY_MARGIN`] so that its rounding never hides a box, and the sweep tests the boxes
/// it returns again in f64. The stages' frame is the level's own coordinates (as on the grid),
/// where f32 is fine for the slope and ladder rules; a position they do not change keeps its
/// f64 bits. Moving platforms are f64 world boxes: their path in level coordinates placed at
/// the origin in f64 ([`PlatformState::aabb_f64`]), and they carry, push and crush by f64
/// displacements.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DoubleSpace {
    /// The seed's overlap tolerance, tiles.
    pub eps: f32,
    /// The level's corner in the world, tiles.
    pub origin: DVec2,
}

impl Space for DoubleSpace {
    type Coord = f64;

    #[inline]
    fn frame(&self) -> Frame<f64> {
        Frame {
            origin: Vec2::ZERO,
            eps: self.eps,
            eps_coord: self.eps as f64,
            unit: 0.0,
        }
    }
    #[inline]
    fn spawn(&self, feet: Vec2, size: Vec2) -> Body<f64> {
        let half = size.x as f64 * 0.5;
        Body {
            at: (feet.as_dvec2() + self.origin).to_array(),
            left: half,
            right: half,
            height: size.y as f64,
            size,
            remainder: Vec2::ZERO,
        }
    }
    #[inline]
    fn feet(&self, b: &Body<f64>) -> Vec2 {
        (DVec2::from_array(b.at) - self.origin).as_vec2()
    }
    #[inline]
    fn with_feet(&self, b: &mut Body<f64>, f: impl FnOnce(&mut Vec2)) {
        let mut feet = self.feet(b);
        let before = feet;
        f(&mut feet);
        for k in 0..2 {
            if feet[k] != before[k] {
                b.at[k] = self.origin[k] + feet[k] as f64;
            }
        }
    }
    #[inline]
    fn coord_y(&self, y: f32) -> f64 {
        self.origin.y + y as f64
    }
    #[inline]
    fn length_up(&self, tiles: f32) -> f64 {
        tiles as f64
    }
    #[inline]
    fn to_tiles(&self, v: f64) -> f32 {
        v as f32
    }
    #[inline]
    fn whole_move(&self, _: &mut Body<f64>, _: Axis, delta: f32, _: bool) -> f64 {
        delta as f64
    }
    #[inline(always)]
    fn statics<'a>(
        &'a self,
        tiles: &StaticTiles,
        near: &'a mut NearCache<f64>,
        swept: Rect<f64>,
    ) -> &'a [(Rect<f64>, BoxKind)] {
        let origin = self.origin;
        let area_of = move |r: &Rect<f64>| {
            let (smin, smax) = (DVec2::from_array(r.min), DVec2::from_array(r.max));
            Aabb::new(
                (smin - origin).as_vec2() - Vec2::splat(F64_QUERY_MARGIN),
                (smax - origin).as_vec2() + Vec2::splat(F64_QUERY_MARGIN),
            )
        };
        // The region in the world, less twice the query's margin (checked by the cache).
        let inside = move |a: &Aabb| {
            let m = 2.0 * F64_QUERY_MARGIN as f64;
            Rect {
                min: (a.mins.as_dvec2() + origin + m).to_array(),
                max: (a.maxs.as_dvec2() + origin - m).to_array(),
            }
        };
        near.query_rect(tiles, swept, area_of, inside, move |t| Rect {
            min: (t.mins.as_dvec2() + origin).to_array(),
            max: (t.maxs.as_dvec2() + origin).to_array(),
        })
    }
    #[inline]
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<f64> {
        p.aabb_f64(t)
    }
    fn reach(&self, p: &PlatformState) -> Rect<f64> {
        let (min, max) = grown_reach(p);
        Rect { min, max }
    }
}

/// Whole subpixels on a level's grid, fractions carried.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GridSpace {
    /// The level's subpixel grid.
    pub grid: Grid,
}

impl Space for GridSpace {
    type Coord = i64;

    #[inline]
    fn frame(&self) -> Frame<i64> {
        Frame {
            origin: Vec2::ZERO,
            eps: 0.0,
            eps_coord: 0,
            unit: 1.0 / self.grid.per_tile as f32,
        }
    }
    #[inline]
    fn spawn(&self, feet: Vec2, size: Vec2) -> Body<i64> {
        let b = self.grid.place(feet, self.grid.size(size));
        let (width, height) = (b.max[0] - b.min[0], b.max[1] - b.min[1]);
        Body {
            at: b.min,
            left: 0,
            right: width,
            height,
            size: Vec2::new(width as f32, height as f32) / self.grid.per_tile as f32,
            remainder: Vec2::ZERO,
        }
    }
    #[inline]
    fn feet(&self, b: &Body<i64>) -> Vec2 {
        self.grid.feet(&b.rect())
    }
    #[inline]
    fn with_feet(&self, b: &mut Body<i64>, f: impl FnOnce(&mut Vec2)) {
        // The rules work in level coordinates, exact for the feet on the grid.
        let mut feet = self.feet(b);
        let before = feet;
        f(&mut feet);
        if feet != before {
            b.at = self.grid.place(feet, [b.right, b.height].into()).min;
            b.remainder = Vec2::ZERO;
        }
    }
    #[inline]
    fn coord_y(&self, y: f32) -> i64 {
        self.grid.origin.y + self.grid.round_height(y)
    }
    #[inline]
    fn length_up(&self, tiles: f32) -> i64 {
        ceil64(tiles as f64 * self.grid.per_tile as f64) as i64
    }
    #[inline]
    fn to_tiles(&self, v: i64) -> f32 {
        self.grid.tiles(v as f64) as f32
    }
    #[inline]
    fn whole_move(&self, b: &mut Body<i64>, axis: Axis, delta: f32, min_fall: bool) -> i64 {
        let a = axis.index();
        let total = delta * self.grid.per_tile as f32 + b.remainder[a];
        let n = round32(total);
        b.remainder[a] = total - n;
        if min_fall && n as i64 == 0 {
            // The first step of a drop through a one-way platform falls less than a subpixel;
            // it must still leave the top, or the next step (no longer dropping) lands on it.
            b.remainder[a] = 0.0;
            return -1;
        }
        n as i64
    }
    #[inline(always)]
    fn statics<'a>(
        &'a self,
        tiles: &StaticTiles,
        near: &'a mut NearCache<i64>,
        swept: Rect<i64>,
    ) -> &'a [(Rect<i64>, BoxKind)] {
        let grid = self.grid;
        near.query_rect(
            tiles,
            swept,
            move |r| grid.query_area(r),
            move |a| grid.inside(a),
            move |t| grid.box_of(t),
        )
    }
    #[inline]
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<i64> {
        p.grid_box(&self.grid, t)
    }
    fn reach(&self, p: &PlatformState) -> Rect<i64> {
        // In level subpixels, grown by two tiles and two subpixels beyond the rounding of the
        // corner and the size (at least one subpixel) that `grid_box` does.
        let (lo, hi) = p.reach_level();
        let n = self.grid.per_tile as f64;
        let m = 2 * self.grid.per_tile + 2;
        let o = self.grid.origin;
        Rect {
            min: [
                floor64(lo.x * n) as i64 - m + o.x,
                floor64(lo.y * n) as i64 - m + o.y,
            ],
            max: [
                ceil64(hi.x * n) as i64 + m + o.x,
                ceil64(hi.y * n) as i64 + m + o.y,
            ],
        }
    }
}

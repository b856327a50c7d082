//! How the sweep stores positions: the one thing its three modes do differently.
//!
//! The seed's "Collision Resolution – A Problem" slide: "if you store positions with integers
//! you're fine; for floating point positions, placing an object tangent to another involves a
//! subtraction, introduces floating point error, [so] allow a fudge factor for overlap". The
//! step ([`super::step`]) and every stage it calls are written once, over [`Space`]; the three
//! implementations are the three storages:
//!
//! - [`FloatSpace`]: f32 feet in world tiles, moves snapped flush by [`super::resolve::move_axis`]
//!   with the seed's epsilon fudge.
//! - [`DoubleSpace`]: the float rules with f64 feet in world tiles, moves swept and snapped in
//!   f64 with the same epsilon, moving platforms as f64 world boxes.
//! - [`GridSpace`]: a box of whole subpixels (`i64`) with each axis's unused fraction carried
//!   ([`super::grid`]), moves snapped flush in exact integer arithmetic, no epsilon.
//!
//! The stages read and write feet in the space's *frame*: an f32 point with the level's corner
//! at [`Space::origin`] (the world for float, the level's own coordinates for the grid, where
//! positions on the grid are exact in f32). Comparisons against box faces (the one-way and slope
//! rules) are done in the space's [`Space::Coord`] (f32 world tiles, or world subpixels), so the
//! grid compares integers exactly.

use std::ops::{Add, Neg, Sub};

use glam::{I64Vec2, Vec2};
use parry2d::bounding_volume::Aabb;

use super::broadphase::{BoxKind, StaticTiles};
use super::grid::{move_axis_grid, Grid, GridBox, GridPos};
use super::platforms::{PlatformState, Platforms};
use super::resolve::{move_axis, Axis};
use super::{Character, World};
use crate::level::character_box;
use crate::motion::MotionState;

/// A box in a space's [`Space::Coord`]: its lower-left and upper-right corners, `[x, y]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect<C> {
    /// Lower-left corner.
    pub min: [C; 2],
    /// Upper-right corner.
    pub max: [C; 2],
}

impl From<Aabb> for Rect<f32> {
    fn from(b: Aabb) -> Self {
        Rect {
            min: [b.mins.x, b.mins.y],
            max: [b.maxs.x, b.maxs.y],
        }
    }
}

impl From<GridBox> for Rect<i64> {
    fn from(b: GridBox) -> Self {
        Rect {
            min: [b.min.x, b.min.y],
            max: [b.max.x, b.max.y],
        }
    }
}

impl From<Rect<i64>> for GridBox {
    fn from(r: Rect<i64>) -> Self {
        GridBox {
            min: I64Vec2::from_array(r.min),
            max: I64Vec2::from_array(r.max),
        }
    }
}

/// A storage of positions the step is generic over (float with epsilon, or integer subpixels).
pub trait Space {
    /// A coordinate in which box faces compare: world tiles (f32) or world subpixels (i64).
    /// Its `Default` is zero.
    type Coord: Copy
        + Default
        + PartialOrd
        + Add<Output = Self::Coord>
        + Sub<Output = Self::Coord>
        + Neg<Output = Self::Coord>;
    /// A character's position saved before a move, to undo it.
    type Saved: Copy;

    /// The overlap tolerance, in frame tiles: the seed's epsilon, or 0 on the grid.
    fn eps(&self) -> f32;
    /// The smallest move the storage makes, in tiles: one subpixel on the grid, 0 in float (any
    /// fall moves).
    fn unit(&self) -> f32;
    /// The overlap tolerance as a [`Self::Coord`].
    fn eps_coord(&self) -> Self::Coord;
    /// Where the level's corner is in the frame (tiles).
    fn origin(&self) -> Vec2;
    /// The feet (bottom centre) of `c` in the frame, in tiles.
    fn feet(&self, c: &Character) -> Vec2;
    /// The size of the box the space really moves for `c`, in tiles.
    fn size(&self, c: &Character) -> Vec2;
    /// The bottom of `c`'s box as a [`Self::Coord`].
    fn bottom(&self, c: &Character) -> Self::Coord;
    /// A frame height (tiles) as a [`Self::Coord`] (on the grid: rounded to whole subpixels by
    /// [`Grid::round_height`], the one rounding of surface heights).
    fn coord_y(&self, y: f32) -> Self::Coord;
    /// `c`'s position, to restore with [`Space::restore_x`].
    fn save(&self, c: &Character) -> Self::Saved;
    /// The feet of a saved position, in the frame.
    fn saved_feet(&self, s: &Self::Saved) -> Vec2;
    /// Puts `c` back at the x of `s` (a move undone, as a wall would have stopped it).
    fn restore_x(&self, c: &mut Character, s: &Self::Saved);
    /// Lets `f` change `c`'s feet (frame tiles) and motion; a changed position is put back on
    /// the storage (on the grid: placed on the nearest subpixels, fractions dropped).
    fn with_feet(&self, c: &mut Character, f: impl FnOnce(&mut Vec2, &mut MotionState));
    /// Puts `c`'s feet at frame height `y` (on the grid: [`Grid::round_height`], the y fraction
    /// dropped).
    fn set_feet_y(&self, c: &mut Character, y: f32);
    /// Moves `c` by `delta` tiles along `axis`, stopping flush at the closest obstacle that
    /// `skip` (given a box's top as a [`Self::Coord`] and its kind) does not exclude. With
    /// `min_fall` a downward move of less than one storage unit still moves one (a drop through
    /// a one-way platform must leave its top). Returns the kind of what stopped the move; on the
    /// grid a fall too small to move a subpixel reports the ground it rests on.
    fn move_axis(
        &self,
        w: &World,
        c: &mut Character,
        axis: Axis,
        delta: f32,
        min_fall: bool,
        skip: impl Fn(Self::Coord, BoxKind) -> bool,
    ) -> Option<BoxKind>;

    /// `c`'s box, as [`Self::Coord`]s.
    fn rect(&self, c: &Character) -> Rect<Self::Coord>;
    /// Moving platform `p`'s box at time `t` (seconds) as the space places it: its exact path
    /// in float, its path rounded to the nearest subpixel on the grid
    /// ([`crate::level::Platform::grid_box`]).
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<Self::Coord>;
    /// Where platform `i` is now (the box the characters just moved against).
    fn platform_now(&self, ps: &Platforms, i: usize) -> Rect<Self::Coord>;
    /// Puts platform `i` at `r`.
    fn set_platform(&self, ps: &mut Platforms, i: usize, r: Rect<Self::Coord>);
    /// A length in [`Self::Coord`] as tiles.
    fn to_tiles(&self, v: Self::Coord) -> f32;
    /// A length in tiles as a [`Self::Coord`] (on the grid: rounded up to whole subpixels).
    fn length_up(&self, tiles: f32) -> Self::Coord;
    /// Moves `c` by `delta` (x, then y) against the static level only, as a moving platform
    /// carries or pushes it; returns whether the level stopped any part of the move.
    fn shove(&self, tiles: &StaticTiles, c: &mut Character, delta: [Self::Coord; 2]) -> bool;
}

/// f32 world positions with the seed's epsilon fudge.
#[derive(Clone, Copy, Debug)]
pub struct FloatSpace {
    /// The seed's overlap tolerance, tiles.
    pub eps: f32,
    /// The level's corner in the world, tiles.
    pub origin: Vec2,
}

impl Space for FloatSpace {
    type Coord = f32;
    type Saved = Vec2;

    fn eps(&self) -> f32 {
        self.eps
    }
    fn unit(&self) -> f32 {
        0.0
    }
    fn eps_coord(&self) -> f32 {
        self.eps
    }
    fn origin(&self) -> Vec2 {
        self.origin
    }
    fn feet(&self, c: &Character) -> Vec2 {
        c.pos
    }
    fn size(&self, c: &Character) -> Vec2 {
        c.size
    }
    fn bottom(&self, c: &Character) -> f32 {
        c.pos.y
    }
    fn coord_y(&self, y: f32) -> f32 {
        y
    }
    fn save(&self, c: &Character) -> Vec2 {
        c.pos
    }
    fn saved_feet(&self, s: &Vec2) -> Vec2 {
        *s
    }
    fn restore_x(&self, c: &mut Character, s: &Vec2) {
        c.pos.x = s.x;
    }
    fn with_feet(&self, c: &mut Character, f: impl FnOnce(&mut Vec2, &mut MotionState)) {
        f(&mut c.pos, &mut c.motion);
    }
    fn set_feet_y(&self, c: &mut Character, y: f32) {
        c.pos.y = y;
    }
    fn move_axis(
        &self,
        w: &World,
        c: &mut Character,
        axis: Axis,
        delta: f32,
        _min_fall: bool,
        skip: impl Fn(f32, BoxKind) -> bool,
    ) -> Option<BoxKind> {
        move_axis(
            w.tiles,
            &mut c.near,
            w.platform_boxes,
            &mut c.pos,
            c.size,
            axis,
            delta,
            self.eps,
            |t, k| skip(t.maxs.y, k),
        )
    }
    fn rect(&self, c: &Character) -> Rect<f32> {
        character_box(c.pos, c.size).into()
    }
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<f32> {
        p.aabb(t).into()
    }
    fn platform_now(&self, ps: &Platforms, i: usize) -> Rect<f32> {
        ps.boxes[i].0.into()
    }
    fn set_platform(&self, ps: &mut Platforms, i: usize, r: Rect<f32>) {
        ps.boxes[i].0 = Aabb::new(Vec2::from_array(r.min), Vec2::from_array(r.max));
    }
    fn to_tiles(&self, v: f32) -> f32 {
        v
    }
    fn length_up(&self, tiles: f32) -> f32 {
        tiles
    }
    fn shove(&self, tiles: &StaticTiles, c: &mut Character, delta: [f32; 2]) -> bool {
        let skip = |_: &Aabb, k: BoxKind| matches!(k, BoxKind::OneWay | BoxKind::Platform { .. });
        let delta = Vec2::from_array(delta);
        let start = c.pos;
        for (axis, d) in [(Axis::X, delta.x), (Axis::Y, delta.y)] {
            move_axis(
                tiles,
                &mut c.near,
                &[],
                &mut c.pos,
                c.size,
                axis,
                d,
                self.eps,
                skip,
            );
        }
        (c.pos - start - delta).length() > self.eps
    }
}

/// f64 world positions with the seed's epsilon fudge: [`FloatSpace`]'s rules with the feet kept
/// in f64 (`Character::pos64`) and every move swept and snapped in f64
/// ([`super::resolve::move_axis_f64`]). The stages' frame is the level's own coordinates (as on
/// the grid), where f32 is fine for the slope and ladder rules; a position they do not change
/// keeps its f64 bits. Moving platforms are f64 world boxes (`Platforms::double_boxes`): their
/// path in level coordinates placed at the origin in f64, and they carry, push and crush by
/// f64 displacements.
#[derive(Clone, Copy, Debug)]
pub struct DoubleSpace {
    /// The seed's overlap tolerance, tiles.
    pub eps: f32,
    /// The level's corner in the world, tiles.
    pub origin: glam::DVec2,
}

impl Space for DoubleSpace {
    type Coord = f64;
    type Saved = glam::DVec2;

    fn eps(&self) -> f32 {
        self.eps
    }
    fn unit(&self) -> f32 {
        0.0
    }
    fn eps_coord(&self) -> f64 {
        self.eps as f64
    }
    fn origin(&self) -> Vec2 {
        Vec2::ZERO
    }
    fn feet(&self, c: &Character) -> Vec2 {
        (c.pos64 - self.origin).as_vec2()
    }
    fn size(&self, c: &Character) -> Vec2 {
        c.size
    }
    fn bottom(&self, c: &Character) -> f64 {
        c.pos64.y
    }
    fn coord_y(&self, y: f32) -> f64 {
        self.origin.y + y as f64
    }
    fn save(&self, c: &Character) -> glam::DVec2 {
        c.pos64
    }
    fn saved_feet(&self, s: &glam::DVec2) -> Vec2 {
        (*s - self.origin).as_vec2()
    }
    fn restore_x(&self, c: &mut Character, s: &glam::DVec2) {
        c.pos64.x = s.x;
    }
    fn with_feet(&self, c: &mut Character, f: impl FnOnce(&mut Vec2, &mut MotionState)) {
        let mut feet = self.feet(c);
        let before = feet;
        f(&mut feet, &mut c.motion);
        if feet.x != before.x {
            c.pos64.x = self.origin.x + feet.x as f64;
        }
        if feet.y != before.y {
            c.pos64.y = self.origin.y + feet.y as f64;
        }
    }
    fn set_feet_y(&self, c: &mut Character, y: f32) {
        c.pos64.y = self.coord_y(y);
    }
    fn move_axis(
        &self,
        w: &World,
        c: &mut Character,
        axis: Axis,
        delta: f32,
        _min_fall: bool,
        skip: impl Fn(f64, BoxKind) -> bool,
    ) -> Option<BoxKind> {
        super::resolve::move_axis_f64(
            w.tiles,
            &mut c.near,
            w.platform_double,
            self.origin,
            &mut c.pos64,
            c.size,
            axis,
            delta as f64,
            self.eps,
            skip,
        )
    }
    fn rect(&self, c: &Character) -> Rect<f64> {
        let half = c.size.x as f64 * 0.5;
        Rect {
            min: [c.pos64.x - half, c.pos64.y],
            max: [c.pos64.x + half, c.pos64.y + c.size.y as f64],
        }
    }
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<f64> {
        p.aabb_f64(t)
    }
    fn platform_now(&self, ps: &Platforms, i: usize) -> Rect<f64> {
        ps.double_boxes[i].0
    }
    fn set_platform(&self, ps: &mut Platforms, i: usize, r: Rect<f64>) {
        ps.double_boxes[i].0 = r;
    }
    fn to_tiles(&self, v: f64) -> f32 {
        v as f32
    }
    fn length_up(&self, tiles: f32) -> f64 {
        tiles as f64
    }
    fn shove(&self, tiles: &StaticTiles, c: &mut Character, delta: [f64; 2]) -> bool {
        let skip = |_: f64, k: BoxKind| matches!(k, BoxKind::OneWay | BoxKind::Platform { .. });
        let start = c.pos64;
        for (axis, d) in [(Axis::X, delta[0]), (Axis::Y, delta[1])] {
            super::resolve::move_axis_f64(
                tiles,
                &mut c.near,
                &[],
                self.origin,
                &mut c.pos64,
                c.size,
                axis,
                d,
                self.eps,
                skip,
            );
        }
        (c.pos64 - start - glam::DVec2::from_array(delta)).length() > self.eps as f64
    }
}

/// Whole subpixels on a level's grid, fractions carried.
#[derive(Clone, Copy, Debug)]
pub struct GridSpace {
    /// The level's subpixel grid.
    pub grid: Grid,
}

impl Space for GridSpace {
    type Coord = i64;
    type Saved = GridPos;

    fn eps(&self) -> f32 {
        0.0
    }
    fn unit(&self) -> f32 {
        1.0 / self.grid.per_tile as f32
    }
    fn eps_coord(&self) -> i64 {
        0
    }
    fn origin(&self) -> Vec2 {
        Vec2::ZERO
    }
    fn feet(&self, c: &Character) -> Vec2 {
        self.grid.feet(&c.on_grid.b)
    }
    fn size(&self, c: &Character) -> Vec2 {
        (c.on_grid.b.max - c.on_grid.b.min).as_vec2() / self.grid.per_tile as f32
    }
    fn bottom(&self, c: &Character) -> i64 {
        c.on_grid.b.min.y
    }
    fn coord_y(&self, y: f32) -> i64 {
        self.grid.origin.y + self.grid.round_height(y)
    }
    fn save(&self, c: &Character) -> GridPos {
        c.on_grid
    }
    fn saved_feet(&self, s: &GridPos) -> Vec2 {
        self.grid.feet(&s.b)
    }
    fn restore_x(&self, c: &mut Character, s: &GridPos) {
        c.on_grid.b.min.x = s.b.min.x;
        c.on_grid.b.max.x = s.b.max.x;
        c.on_grid.remainder.x = 0.0;
    }
    fn with_feet(&self, c: &mut Character, f: impl FnOnce(&mut Vec2, &mut MotionState)) {
        // The rules work in level coordinates, exact for the feet on the grid.
        let mut feet = self.grid.feet(&c.on_grid.b);
        let before = feet;
        f(&mut feet, &mut c.motion);
        if feet != before {
            let size = c.on_grid.b.max - c.on_grid.b.min;
            c.on_grid.b = self.grid.place(feet, size);
            c.on_grid.remainder = Vec2::ZERO;
        }
    }
    fn set_feet_y(&self, c: &mut Character, y: f32) {
        let b = &mut c.on_grid.b;
        let h = b.max.y - b.min.y;
        b.min.y = self.coord_y(y);
        b.max.y = b.min.y + h;
        c.on_grid.remainder.y = 0.0;
    }
    fn move_axis(
        &self,
        w: &World,
        c: &mut Character,
        axis: Axis,
        delta: f32,
        min_fall: bool,
        skip: impl Fn(i64, BoxKind) -> bool,
    ) -> Option<BoxKind> {
        let g = &self.grid;
        let p = &mut c.on_grid;
        let mut n = p.whole_move(g, axis, delta);
        if min_fall && n == 0 {
            // The first step of a drop through a one-way platform falls less than a subpixel;
            // it must still leave the top, or the next step (no longer dropping) lands on it.
            n = -1;
            p.remainder[axis.index()] = 0.0;
        }
        let skip = |t: &GridBox, k: BoxKind| skip(t.max.y, k);
        let extra = w.platform_grid;
        let mut hit = move_axis_grid(w.tiles, &mut c.near, g, p, axis, n, true, extra, skip);
        if axis == Axis::Y && n == 0 && delta < 0.0 {
            // A fall of less than a subpixel this step moves nothing: the ground is there if
            // the box rests on it (Celeste's "collide check one pixel down"). A move of a
            // subpixel or more that ends on a face has already reported it.
            hit = move_axis_grid(w.tiles, &mut c.near, g, p, axis, -1, false, extra, skip);
        }
        if hit.is_some() {
            p.remainder[axis.index()] = 0.0;
        }
        hit
    }
    fn rect(&self, c: &Character) -> Rect<i64> {
        c.on_grid.b.into()
    }
    fn platform_at(&self, p: &PlatformState, t: f64) -> Rect<i64> {
        p.grid_box(&self.grid, t).into()
    }
    fn platform_now(&self, ps: &Platforms, i: usize) -> Rect<i64> {
        ps.grid_boxes[i].0.into()
    }
    fn set_platform(&self, ps: &mut Platforms, i: usize, r: Rect<i64>) {
        ps.grid_boxes[i].0 = r.into();
    }
    fn to_tiles(&self, v: i64) -> f32 {
        (v as f64 / self.grid.per_tile as f64) as f32
    }
    fn length_up(&self, tiles: f32) -> i64 {
        (tiles as f64 * self.grid.per_tile as f64).ceil() as i64
    }
    fn shove(&self, tiles: &StaticTiles, c: &mut Character, delta: [i64; 2]) -> bool {
        let skip =
            |_: &GridBox, k: BoxKind| matches!(k, BoxKind::OneWay | BoxKind::Platform { .. });
        let start = c.on_grid.b.min;
        for (axis, n) in [(Axis::X, delta[0]), (Axis::Y, delta[1])] {
            let p = &mut c.on_grid;
            move_axis_grid(tiles, &mut c.near, &self.grid, p, axis, n, true, &[], skip);
        }
        c.on_grid.b.min - start != I64Vec2::from_array(delta)
    }
}

//! How the sweep stores positions: the one thing its two modes do differently.
//!
//! The seed's "Collision Resolution – A Problem" slide: "if you store positions with integers
//! you're fine; for floating point positions, placing an object tangent to another involves a
//! subtraction, introduces floating point error, [so] allow a fudge factor for overlap". The
//! step ([`super::step`]) and every stage it calls are written once, over [`Space`]; the two
//! implementations are the two storages:
//!
//! - [`FloatSpace`]: f32 feet in world tiles, moves snapped flush by [`super::resolve::move_axis`]
//!   with the seed's epsilon fudge.
//! - [`GridSpace`]: a box of whole subpixels (`i64`) with each axis's unused fraction carried
//!   ([`super::grid`]), moves snapped flush in exact integer arithmetic, no epsilon.
//!
//! The stages read and write feet in the space's *frame*: an f32 point with the level's corner
//! at [`Space::origin`] (the world for float, the level's own coordinates for the grid, where
//! positions on the grid are exact in f32). Comparisons against box faces (the one-way and slope
//! rules) are done in the space's [`Space::Coord`] (f32 world tiles, or world subpixels), so the
//! grid compares integers exactly.

use std::ops::{Add, Sub};

use glam::Vec2;

use super::broadphase::BoxKind;
use super::grid::{move_axis_grid, Grid, GridPos};
use super::resolve::{move_axis, Axis};
use super::{Character, World};
use crate::motion::MotionState;

/// A storage of positions the step is generic over (float with epsilon, or integer subpixels).
pub trait Space {
    /// A coordinate in which box faces compare: world tiles (f32) or world subpixels (i64).
    type Coord: Copy + PartialOrd + Add<Output = Self::Coord> + Sub<Output = Self::Coord>;
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
        let skip = |t: &super::grid::GridBox, k: BoxKind| skip(t.max.y, k);
        let mut hit = move_axis_grid(w.tiles, &mut c.near, g, p, axis, n, true, skip);
        if axis == Axis::Y && n == 0 && delta < 0.0 {
            // A fall of less than a subpixel this step moves nothing: the ground is there if
            // the box rests on it (Celeste's "collide check one pixel down"). A move of a
            // subpixel or more that ends on a face has already reported it.
            hit = move_axis_grid(w.tiles, &mut c.near, g, p, axis, -1, false, skip);
        }
        if hit.is_some() {
            p.remainder[axis.index()] = 0.0;
        }
        hit
    }
}

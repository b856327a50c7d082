//! Slopes, the seed's way: the surface under the character's centre decides its height.
//!
//! Slope tiles are not in the broadphase: their solid part is handled here, per column, from
//! the surface under the centre x (the seed: "use x position (center of object) to index into
//! height array", and "set object's y position to y index only if y position is lower", so a
//! character can jump onto and off slopes). Three rules, all on the centre column:
//!
//! - **Climb limit**: after the x move, the ground under the centre may have risen by at most
//!   `tan(max_climb_angle) * |dx|`; a steeper rise blocks the move like a wall. Running into
//!   the high side of a slope is such a rise, so it blocks wherever the level exposes that side.
//! - **Resolve up**: after the y move, feet below the surface (walking uphill, or landing) are
//!   put on it.
//! - **Follow down**: a character that was grounded and did not jump, and found no ground this
//!   step, is put back on the surface if it is within the drop that walking down the steepest
//!   walkable slope at this speed produces, instead of launching into the air.
//!
//! The box's corners overhang a slope's surface: only the centre stands on it (the seed's model).

use glam::Vec2;

use super::space::{Body, Space};
use super::{Character, SweepStats, World};
use crate::level::{surface_walk, Level, SurfaceCell};
use crate::rounding::floor_to_i64;

/// Ground found under the centre: its height (world) and normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ground {
    /// Surface height, world y.
    pub y: f32,
    /// Surface normal.
    pub normal: Vec2,
}

/// How many rows of a column [`Column`] keeps: a step's lookups under the centre read the rows
/// from one above the feet to one below.
const ROWS: usize = 4;

/// The cells of the column under one x (level coordinates) that the slope rules have read, kept
/// between their lookups: a step looks under the centre four or five times, at the x it
/// started from and the x the x move ended at, and the next step starts at that x again. A
/// lookup at an x not kept (another x is another column, or the same column's slopes at other
/// heights) starts afresh; the cells kept are what [`Level::surface_cell`] gives for that x, so
/// every answer is the level's own ([`Level::surface_at`]'s walk over the same cells).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Column {
    /// The x the cells are read at (its bits; a new column's are a NaN no arithmetic on
    /// numbers makes, so its first lookup reads the column whatever the x), and its column
    /// `floor(x)`.
    x: u32,
    i: i64,
    /// Whether the column holds a slope tile ([`SlopeColumns`]).
    slopes: bool,
    /// The lowest row kept: rows `base..base + ROWS`, `None` where not read yet.
    base: i64,
    cells: [Option<SurfaceCell>; ROWS],
    /// The slope normal found at this x, and the row of the slope tile it is of: a character
    /// at rest on a slope stands on the same tile at the same x step after step.
    normal: Option<(i64, Vec2)>,
}

impl Default for Column {
    fn default() -> Self {
        Column {
            x: u32::MAX,
            i: 0,
            slopes: false,
            base: 0,
            cells: [None; ROWS],
            normal: None,
        }
    }
}

impl Column {
    /// [`Level::surface_at`] at `x` (level coordinates, the x the column was last moved to by
    /// [`Column::move_to`]), reading the cells through this column. Inlined into each rule, so
    /// that a lookup of kept rows costs no call.
    #[inline(always)]
    fn surface_at(
        &mut self,
        level: &Level,
        x: f32,
        top: f32,
        depth: f32,
    ) -> Option<(f32, Option<(i64, i64)>)> {
        let i = self.i;
        surface_walk(level.height, i, top, depth, |j| {
            let k = j.wrapping_sub(self.base);
            match self.cells.get(k as usize) {
                Some(&Some(cell)) => cell,
                _ => self.read(level, j, x),
            }
        })
    }

    /// Makes `x` (level coordinates) the column's x: a new x keeps no cells.
    #[inline(always)]
    fn move_to(&mut self, x: f32, slope_columns: &SlopeColumns) {
        if x.to_bits() != self.x {
            self.x = x.to_bits();
            self.i = floor_to_i64(x);
            self.slopes = slope_columns.has(self.i);
            self.cells = [None; ROWS];
            self.normal = None;
        }
    }

    /// [`Level::slope_normal`] of the slope tile in row `j` of this column at its x (the one
    /// [`Column::surface_at`] found), kept until the x changes.
    #[inline]
    fn normal(&mut self, level: &Level, j: i64) -> Vec2 {
        match self.normal {
            Some((row, n)) if row == j => n,
            _ => {
                let n = level.slope_normal(self.i, j, f32::from_bits(self.x));
                self.normal = Some((j, n));
                n
            }
        }
    }

    /// Reads row `j` from the level and keeps it (the rows kept become two below to one
    /// above `j`, the rest of a step's lookups, when `j` is not among them). Not inlined, so
    /// that a lookup of rows already kept does none of its work.
    #[inline(never)]
    fn read(&mut self, level: &Level, j: i64, x: f32) -> SurfaceCell {
        // The walk reads rows 0 to the map's top only, so `j - 2` does not overflow.
        if !(self.base..self.base + ROWS as i64).contains(&j) {
            self.base = j - 2;
            self.cells = [None; ROWS];
        }
        let cell = level.surface_cell(self.i, j, x);
        self.cells[(j - self.base) as usize] = Some(cell);
        cell
    }
}

/// Which columns of a level hold at least one slope tile: under the centre in any other column
/// there is no slope to find, so [`slope_under`] answers without walking it (on a level with
/// slopes, the flat stretches between them cost what a level without slopes costs there).
#[derive(Clone, Debug, Default)]
pub(crate) struct SlopeColumns {
    /// Bit `i % 64` of word `i / 64` is set when column `i` holds a slope; empty on a level
    /// without slopes.
    bits: Vec<u64>,
}

impl SlopeColumns {
    /// The slope columns of `level` (a walk over its tiles only when it has slopes).
    pub(crate) fn new(level: &Level) -> Self {
        let mut bits = Vec::new();
        if level.features.slopes {
            bits = vec![0; (level.width as usize).div_ceil(64)];
            for (i, _, _) in level.slopes() {
                bits[i as usize / 64] |= 1 << (i % 64);
            }
        }
        SlopeColumns { bits }
    }

    /// Whether column `i` holds a slope tile (none outside the map: a negative `i` is a word
    /// index past the end).
    #[inline]
    fn has(&self, i: i64) -> bool {
        let i = i as u64;
        self.bits
            .get((i / 64) as usize)
            .is_some_and(|w| w >> (i % 64) & 1 != 0)
    }
}

/// The surface under the centre at frame `x` from frame height `top` down `depth` tiles: its
/// height (frame) and, on a slope, the slope's tile.
fn surface<S: Space>(
    w: &World<S>,
    column: &mut Column,
    x: f32,
    top: f32,
    depth: f32,
) -> Option<(f32, Option<(i64, i64)>)> {
    let origin = w.frame.origin;
    let (lx, ltop) = (x - origin.x, top - origin.y);
    column.move_to(lx, w.slope_columns);
    column
        .surface_at(w.level, lx, ltop, depth)
        .map(|(h, slope)| (h + origin.y, slope))
}

/// The ground at height `y` (frame) that `column`'s last lookup found: its normal, a slope's
/// if on one (`slope`, a tile of that column).
fn ground_at<S: Space>(
    w: &World<S>,
    column: &mut Column,
    y: f32,
    slope: Option<(i64, i64)>,
) -> Ground {
    Ground {
        y,
        normal: slope.map_or(Vec2::Y, |(_, j)| column.normal(w.level, j)),
    }
}

/// The height of the slope under the centre, if the ground under the centre (from `reach`
/// above the feet down to one tile below) is a slope; `None` at once in a column without one.
fn slope_under<S: Space>(w: &World<S>, column: &mut Column, feet: Vec2, reach: f32) -> Option<f32> {
    let origin = w.frame.origin;
    let x = feet.x - origin.x;
    column.move_to(x, w.slope_columns);
    if !column.slopes {
        return None;
    }
    column
        .surface_at(w.level, x, feet.y - origin.y + reach, reach + 1.0)
        .and_then(|(h, slope)| slope.map(|_| h + origin.y))
}

/// Whether the ground under the centre at `x` rises above `feet + rise_allow` (within one tile
/// above the feet): the climb limit.
fn climb_blocked<S: Space>(
    w: &World<S>,
    column: &mut Column,
    x: f32,
    feet: f32,
    rise_allow: f32,
) -> bool {
    surface(w, column, x, feet + 1.0, 1.0).is_some_and(|(y, _)| y > feet + rise_allow && y > feet)
}

/// Puts feet that ended below the surface under the centre back on it. `from` is the feet
/// height before the y move, `rise_allow` how far the surface may be above it (uphill walking).
fn resolve_up<S: Space>(
    w: &World<S>,
    column: &mut Column,
    pos: &mut Vec2,
    from: f32,
    rise_allow: f32,
) -> Option<Ground> {
    let top = from.max(pos.y) + rise_allow;
    let (y, slope) = surface(w, column, pos.x, top, top - pos.y + 1.0)?;
    (pos.y < y).then(|| {
        pos.y = y;
        ground_at(w, column, y, slope)
    })
}

/// Follows the ground down by at most `max_drop`.
fn follow_down<S: Space>(
    w: &World<S>,
    column: &mut Column,
    pos: &mut Vec2,
    max_drop: f32,
) -> Option<Ground> {
    let (y, slope) = surface(w, column, pos.x, pos.y, max_drop)?;
    pos.y = y;
    Some(ground_at(w, column, y, slope))
}

/// The overhang of the seed's box over a slope, in frame tiles: half the moved width times the
/// climb gradient, plus the storage's tolerance. Solids whose top lies within this height
/// above the slope under the centre belong to the slope rules, not to the sweep.
fn overhang<S: Space>(w: &World<S>, c: &Character<S::Coord>) -> f32 {
    c.body.size.x * 0.5 * w.climb_gradient + w.frame.eps
}

/// The height (frame) of the slope under the centre of `c` with its feet at `feet`, looking
/// from the overhang above the feet down to one tile below; `None` when no slope is under the
/// centre or the level has none. Both moves' ramp rules read it ([`ramp_top_for_x`],
/// [`ramp_band_for_y`]).
#[inline]
pub(super) fn under<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    feet: Vec2,
) -> Option<f32> {
    if !w.level.features.slopes {
        return None;
    }
    let overhang = overhang(w, c);
    slope_under(w, &mut c.column, feet, overhang)
}

/// [`under`] the feet at `feet` after the x move, given `under_start`, the slope under them at
/// `start` before it: feet the move left where they were (at rest, or stopped) have the same
/// slope under them, so the lookup is not repeated.
#[inline]
pub(super) fn under_moved<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    feet: Vec2,
    start: Vec2,
    under_start: Option<f32>,
) -> Option<f32> {
    if !w.level.features.slopes {
        return None;
    }
    let bits = |v: Vec2| v.to_array().map(f32::to_bits);
    if bits(feet) == bits(start) {
        under_start
    } else {
        under(w, c, feet)
    }
}

/// Before the x move (step 3): the highest top, as a coordinate of the storage, of a solid the
/// x move skips because it lies within the overhang above the slope under the centre (the mass
/// under a ramp), from that slope's height [`under`] the feet.
#[inline]
pub(super) fn ramp_top_for_x<S: Space>(
    w: &World<S>,
    c: &Character<S::Coord>,
    under: Option<f32>,
) -> Option<S::Coord> {
    let h = under?;
    Some(w.space.coord_y(h + overhang(w, c)))
}

/// Before the y move (step 5): the band of solid tops (above, at most) that the y move skips
/// because the slope rules under the centre own them (steps up within the overhang), from the
/// slope's height [`under`] the feet.
#[inline]
pub(super) fn ramp_band_for_y<S: Space>(
    w: &World<S>,
    c: &Character<S::Coord>,
    under: Option<f32>,
) -> Option<(S::Coord, S::Coord)> {
    let h = under?;
    Some((
        w.space.coord_y(h + w.frame.eps),
        w.space.coord_y(h + overhang(w, c)),
    ))
}

/// `c`'s feet in the frame for the slope rules ([`World::feet`]; on the grid a conversion from
/// subpixels, so the step finds each once and hands it on), zero on a level without slopes,
/// where nothing reads them.
#[inline]
pub(super) fn feet<S: Space>(w: &World<S>, c: &Character<S::Coord>) -> Vec2 {
    if w.level.features.slopes {
        w.feet(c)
    } else {
        Vec2::ZERO
    }
}

/// How far the ground under the centre may rise during the x move from feet `start` to feet
/// `now`: the climb gradient times the horizontal distance, plus the tolerance (frame tiles);
/// 0 on a level without slopes, where nothing reads it.
#[inline]
pub(super) fn rise_allow<S: Space>(w: &World<S>, now: Vec2, start: Vec2) -> f32 {
    if !w.level.features.slopes {
        return 0.0;
    }
    w.climb_gradient * (now.x - start.x).abs() + w.frame.eps
}

/// Step 4, the climb limit: if the ground under the centre (`c`'s feet now at `feet`) rose
/// more than `rise_allow` during the x move, the move is undone (back to `start`'s x) as a wall
/// would stop it, which puts the feet back where they were before it. Returns whether it was.
#[inline]
pub(super) fn climb_limit<S: Space>(
    w: &World<S>,
    stats: &mut SweepStats,
    c: &mut Character<S::Coord>,
    start: &Body<S::Coord>,
    feet: Vec2,
    rise_allow: f32,
) -> bool {
    if !w.level.features.slopes {
        return false;
    }
    stats.slope_steps += 1;
    let blocked = climb_blocked(w, &mut c.column, feet.x, feet.y, rise_allow);
    if blocked {
        c.body.at[0] = start.at[0];
        c.body.remainder.x = 0.0;
    }
    blocked
}

/// Puts `c`'s feet at frame height `y` (on the grid: [`crate::sweep::grid::Grid::round_height`],
/// the y fraction dropped).
fn set_feet_y<S: Space>(w: &World<S>, c: &mut Character<S::Coord>, y: f32) {
    c.body.at[1] = w.space.coord_y(y);
    c.body.remainder.y = 0.0;
}

/// Step 6, ground on slopes: feet that ended below the surface under the centre are put on it
/// (walking uphill, or landing: "set object's y position to y index only if y position is
/// lower"); a character that was grounded, found no ground this step and is not rising is put
/// back on a surface within the drop that walking down the steepest walkable slope at this
/// speed gives (plus `snap_down` and this step's fall). Returns the ground stood on, and
/// whether it is the resolve-up case (which replaces a one-way landing).
#[inline]
pub(super) fn ground_on_slopes<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    from: f32,
    rise_allow: f32,
    grounded: bool,
    was_grounded: bool,
    dy: f32,
) -> Option<(Ground, bool)> {
    if !w.level.features.slopes {
        return None;
    }
    let mut feet = w.feet(c);
    if let Some(g) = resolve_up(w, &mut c.column, &mut feet, from, rise_allow) {
        set_feet_y(w, c, feet.y);
        return Some((g, true));
    }
    let unit = w.frame.unit;
    if unit > 0.0 && !grounded && dy < 0.0 && feet.y == from {
        // On the grid, a fall of less than a subpixel moves nothing, and feet put on a slope
        // stand at most a subpixel above it (`Grid::round_height`): the slope is under them if
        // it is within that subpixel (the grid's "collide check one pixel down", as for solids).
        if let Some(g) = follow_down(w, &mut c.column, &mut feet, unit) {
            set_feet_y(w, c, feet.y);
            return Some((g, false));
        }
    }
    if !grounded && was_grounded && dy <= 0.0 {
        let max_drop = rise_allow + w.snap_down - dy.min(0.0);
        if let Some(g) = follow_down(w, &mut c.column, &mut feet, max_drop) {
            set_feet_y(w, c, feet.y);
            return Some((g, false));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{Slope, Tile};

    #[test]
    fn slope_columns_are_the_columns_holding_a_slope_tile() {
        // 70 columns (two words of bits), slopes in columns 3 and 66 at different rows.
        let (w, h) = (70usize, 3usize);
        let mut t = vec![Tile::Empty; w * h];
        t[..w].fill(Tile::Solid);
        let ramp = Tile::Slope(Slope::Line {
            left: 0.0,
            right: 1.0,
        });
        t[w + 3] = ramp;
        t[2 * w + 66] = ramp;
        let cols = SlopeColumns::new(&Level::from_tiles("ramps", w as u32, h as u32, t));
        let with: Vec<i64> = (-2..w as i64 + 2).filter(|&i| cols.has(i)).collect();
        assert_eq!(with, vec![3, 66]);
        assert!(!cols.has(i64::MIN) && !cols.has(i64::MAX));
        // A level without slopes keeps no bits and has none anywhere.
        let flat = SlopeColumns::new(&Level::from_tiles("flat", 4, 1, vec![Tile::Solid; 4]));
        assert!(flat.bits.is_empty() && !flat.has(0));
    }

    #[test]
    fn a_kept_slope_normal_is_the_levels_at_the_columns_x() {
        // A curved slope (its gradient changes along x) on solid ground, in column 0.
        let curve = Slope::Heights([0, 0, 1, 1, 2, 3, 4, 5, 6, 8, 9, 10, 12, 13, 15, 16]);
        let level = Level::from_tiles("curve", 1, 2, vec![Tile::Solid, Tile::Slope(curve)]);
        let cols = SlopeColumns::new(&level);
        let mut c = Column::default();
        for x in [0.2, 0.2, 0.7, 0.7, 0.2] {
            c.move_to(x, &cols);
            assert_eq!(c.normal(&level, 1), level.slope_normal(0, 1, x), "x = {x}");
        }
        // The normals differ along the curve, so a kept one would have been caught.
        assert_ne!(level.slope_normal(0, 1, 0.2), level.slope_normal(0, 1, 0.7));
    }

    #[test]
    fn a_new_column_learns_its_slopes_at_its_first_x_even_at_zero() {
        // A slope in column 0: a character whose first lookup is at x = 0 finds it.
        let mut t = vec![Tile::Solid; 2];
        t[0] = Tile::Slope(Slope::Line {
            left: 0.0,
            right: 1.0,
        });
        let level = Level::from_tiles("edge", 2, 1, t);
        let cols = SlopeColumns::new(&level);
        for x in [0.0, -0.0, 0.5] {
            let mut c = Column::default();
            c.move_to(x, &cols);
            assert!(c.slopes, "x = {x}");
        }
    }
}

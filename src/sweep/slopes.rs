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
use crate::level::Level;

/// Ground found under the centre: its height (world) and normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ground {
    /// Surface height, world y.
    pub y: f32,
    /// Surface normal.
    pub normal: Vec2,
}

fn ground(level: &Level, origin: Vec2, x: f32, top: f32, depth: f32) -> Option<Ground> {
    let (lx, ltop) = (x - origin.x, top - origin.y);
    level.surface_at(lx, ltop, depth).map(|(h, slope)| Ground {
        y: h + origin.y,
        normal: slope.map_or(Vec2::Y, |(i, j)| level.slope_normal(i, j, lx)),
    })
}

/// The height of the slope under the centre, if the ground under the centre (from `reach`
/// above the feet down to one tile below) is a slope.
pub(crate) fn slope_under(level: &Level, origin: Vec2, feet: Vec2, reach: f32) -> Option<f32> {
    level
        .surface_at(feet.x - origin.x, feet.y - origin.y + reach, reach + 1.0)
        .and_then(|(h, slope)| slope.map(|_| h + origin.y))
}

/// Whether the ground under the centre at `x` rises above `feet + rise_allow` (within one tile
/// above the feet): the climb limit.
pub(crate) fn climb_blocked(
    level: &Level,
    origin: Vec2,
    x: f32,
    feet: f32,
    rise_allow: f32,
) -> bool {
    ground(level, origin, x, feet + 1.0, 1.0).is_some_and(|g| g.y > feet + rise_allow && g.y > feet)
}

/// Puts feet that ended below the surface under the centre back on it. `from` is the feet
/// height before the y move, `rise_allow` how far the surface may be above it (uphill walking).
pub(crate) fn resolve_up(
    level: &Level,
    origin: Vec2,
    pos: &mut Vec2,
    from: f32,
    rise_allow: f32,
) -> Option<Ground> {
    let top = from.max(pos.y) + rise_allow;
    let g = ground(level, origin, pos.x, top, top - pos.y + 1.0)?;
    (pos.y < g.y).then(|| {
        pos.y = g.y;
        g
    })
}

/// Follows the ground down by at most `max_drop`.
pub(crate) fn follow_down(
    level: &Level,
    origin: Vec2,
    pos: &mut Vec2,
    max_drop: f32,
) -> Option<Ground> {
    let g = ground(level, origin, pos.x, pos.y, max_drop)?;
    pos.y = g.y;
    Some(g)
}

/// The overhang of the seed's box over a slope, in frame tiles: half the moved width times the
/// climb gradient, plus the storage's tolerance. Solids whose top lies within this height
/// above the slope under the centre belong to the slope rules, not to the sweep.
fn overhang<S: Space>(w: &World<S>, c: &Character<S::Coord>) -> f32 {
    c.body.size.x * 0.5 * w.climb_gradient + w.frame.eps
}

/// Before the x move (step 3): the highest top, as a coordinate of the storage, of a solid the
/// x move skips because it lies within the overhang above the slope under the centre (the mass
/// under a ramp); `None` when no slope is under the centre or the level has none.
pub(super) fn ramp_top_for_x<S: Space>(w: &World<S>, c: &Character<S::Coord>) -> Option<S::Coord> {
    if !w.level.features.slopes {
        return None;
    }
    let overhang = overhang(w, c);
    slope_under(w.level, w.frame.origin, w.feet(c), overhang).map(|h| w.space.coord_y(h + overhang))
}

/// Before the y move (step 5): the band of solid tops (above, at most) that the y move skips
/// because the slope rules under the centre own them (steps up within the overhang).
pub(super) fn ramp_band_for_y<S: Space>(
    w: &World<S>,
    c: &Character<S::Coord>,
) -> Option<(S::Coord, S::Coord)> {
    if !w.level.features.slopes {
        return None;
    }
    let overhang = overhang(w, c);
    slope_under(w.level, w.frame.origin, w.feet(c), overhang).map(|h| {
        (
            w.space.coord_y(h + w.frame.eps),
            w.space.coord_y(h + overhang),
        )
    })
}

/// How far the ground under the centre may rise during the x move that started at `start`:
/// the climb gradient times the horizontal distance, plus the tolerance (frame tiles);
/// 0 on a level without slopes, where nothing reads it.
pub(super) fn rise_allow<S: Space>(
    w: &World<S>,
    c: &Character<S::Coord>,
    start: &Body<S::Coord>,
) -> f32 {
    if !w.level.features.slopes {
        return 0.0;
    }
    w.climb_gradient * (w.feet(c).x - w.space.feet(start).x).abs() + w.frame.eps
}

/// Step 4, the climb limit: if the ground under the centre rose more than `rise_allow` during
/// the x move, the move is undone (back to `start`'s x) as a wall would stop it. Returns
/// whether it was.
pub(super) fn climb_limit<S: Space>(
    w: &World<S>,
    stats: &mut SweepStats,
    c: &mut Character<S::Coord>,
    start: &Body<S::Coord>,
    rise_allow: f32,
) -> bool {
    if !w.level.features.slopes {
        return false;
    }
    stats.slope_steps += 1;
    let feet = w.feet(c);
    let blocked = climb_blocked(w.level, w.frame.origin, feet.x, feet.y, rise_allow);
    if blocked {
        c.body.at[0] = start.at[0];
        c.body.remainder.x = 0.0;
    }
    blocked
}

/// The feet's height before the y move (frame tiles), for [`ground_on_slopes`]; 0 on a level
/// without slopes, where nothing reads it.
pub(super) fn feet_before_y<S: Space>(w: &World<S>, c: &Character<S::Coord>) -> f32 {
    if w.level.features.slopes {
        w.feet(c).y
    } else {
        0.0
    }
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
    let origin = w.frame.origin;
    let mut feet = w.feet(c);
    if let Some(g) = resolve_up(w.level, origin, &mut feet, from, rise_allow) {
        set_feet_y(w, c, feet.y);
        return Some((g, true));
    }
    let unit = w.frame.unit;
    if unit > 0.0 && !grounded && dy < 0.0 && feet.y == from {
        // On the grid, a fall of less than a subpixel moves nothing, and feet put on a slope
        // stand at most a subpixel above it (`Grid::round_height`): the slope is under them if
        // it is within that subpixel (the grid's "collide check one pixel down", as for solids).
        if let Some(g) = follow_down(w.level, origin, &mut feet, unit) {
            set_feet_y(w, c, feet.y);
            return Some((g, false));
        }
    }
    if !grounded && was_grounded && dy <= 0.0 {
        let max_drop = rise_allow + w.snap_down - dy.min(0.0);
        if let Some(g) = follow_down(w.level, origin, &mut feet, max_drop) {
            set_feet_y(w, c, feet.y);
            return Some((g, false));
        }
    }
    None
}

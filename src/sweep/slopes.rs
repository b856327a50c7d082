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

use crate::level::Level;

/// Ground found under the centre: its height (world) and normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ground {
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
pub fn slope_under(level: &Level, origin: Vec2, feet: Vec2, reach: f32) -> Option<f32> {
    level
        .surface_at(feet.x - origin.x, feet.y - origin.y + reach, reach + 1.0)
        .and_then(|(h, slope)| slope.map(|_| h + origin.y))
}

/// Whether the ground under the centre at `x` rises above `feet + rise_allow` (within one tile
/// above the feet): the climb limit.
pub fn climb_blocked(level: &Level, origin: Vec2, x: f32, feet: f32, rise_allow: f32) -> bool {
    ground(level, origin, x, feet + 1.0, 1.0).is_some_and(|g| g.y > feet + rise_allow && g.y > feet)
}

/// Puts feet that ended below the surface under the centre back on it. `from` is the feet
/// height before the y move, `rise_allow` how far the surface may be above it (uphill walking).
pub fn resolve_up(
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
pub fn follow_down(level: &Level, origin: Vec2, pos: &mut Vec2, max_drop: f32) -> Option<Ground> {
    let g = ground(level, origin, pos.x, pos.y, max_drop)?;
    pos.y = g.y;
    Some(g)
}

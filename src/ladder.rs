//! Ladders, the seed's way: two states, normal and on-ladder (the on-ladder motion is in
//! [`crate::motion`]), and the rules to enter and leave the ladder state, shared by both
//! backends so that only collision handling differs.
//!
//! - Enter: the box overlaps a ladder in the column under its centre and up is held (unless it
//!   stands on that ladder's top: there is nothing above to climb), or the character stands on
//!   a ladder's top and down is held. Entering clamps x to the ladder's centre. "Stands on the
//!   top" is grounded with the feet within the backend's top tolerance of it
//!   ([`TOP_TOLERANCE`] unless the backend holds its feet otherwise, see [`enter_within`]).
//! - Leave: on jump (in the motion), when the feet rise above the ladder's top (the top is then
//!   walkable like a one-way platform), when the box no longer overlaps the ladder, or when it
//!   reaches the ground while climbing down.

use glam::Vec2;

use crate::level::Level;
use crate::motion::{Input, MotionState};
use crate::rounding::{ceil_to_i64, floor_to_i64};

/// How close above a ladder's top the feet count as standing on it, in tiles: Rapier's offset
/// and rounding, well under a climbing step.
pub const TOP_TOLERANCE: f32 = 0.02;

/// The ladder run under the centre column that the box overlaps: (centre x, top), world.
///
/// Only the run's top is walked to: its bottom is at or below the ladder row found, which lies
/// below the box's top (`j < ceil(y + h)` gives `j < y + h`), so the box always reaches above it.
fn ladder_here(level: &Level, origin: Vec2, feet: Vec2, size: Vec2) -> Option<(f32, f32)> {
    let local = feet - origin;
    let i = floor_to_i64(local.x);
    let (j0, j1) = (floor_to_i64(local.y), ceil_to_i64(local.y + size.y));
    (j0..j1)
        .find_map(|j| level.ladder_top(i, j))
        .filter(|top| local.y < *top)
        .map(|t| (i as f32 + 0.5 + origin.x, t + origin.y))
}

/// Before the motion integrates: enters the ladder state if the input and position allow it,
/// clamping x to the ladder's centre; feet within [`TOP_TOLERANCE`] of a ladder's top stand on
/// it.
pub fn enter(
    level: &Level,
    origin: Vec2,
    m: &mut MotionState,
    pos: &mut Vec2,
    size: Vec2,
    input: &Input,
) {
    enter_within(level, origin, m, pos, size, input, TOP_TOLERANCE)
}

/// [`enter`] for a backend whose grounded feet rest up to `top_tolerance` tiles from the
/// surface they stand on (Box2D's pogo spring holds them below it by its sag).
pub fn enter_within(
    level: &Level,
    origin: Vec2,
    m: &mut MotionState,
    pos: &mut Vec2,
    size: Vec2,
    input: &Input,
    top_tolerance: f32,
) {
    if m.on_ladder || !level.features.ladders {
        return;
    }
    let on_top = |top: f32| m.grounded && (pos.y - top).abs() <= top_tolerance;
    let grab = if input.up {
        // Feet standing on the ladder's top (sunk into it by less than the tolerance) have
        // nothing above to climb.
        ladder_here(level, origin, *pos, size).filter(|(_, top)| !on_top(*top))
    } else if input.down && m.grounded {
        // Standing on a ladder's top: the ladder is in the tile just below the feet.
        ladder_here(level, origin, *pos - Vec2::new(0.0, 0.5), size).filter(|(_, top)| on_top(*top))
    } else {
        None
    };
    if let Some((x, _)) = grab {
        m.on_ladder = true;
        m.vel = Vec2::ZERO;
        m.grounded = false;
        pos.x = x;
    }
}

/// After the move: leaves the ladder state when the character is past the ladder's top, off the
/// ladder, or on the ground while climbing down.
pub fn leave(
    level: &Level,
    origin: Vec2,
    m: &mut MotionState,
    pos: Vec2,
    size: Vec2,
    input: &Input,
) {
    if !m.on_ladder {
        return;
    }
    let off = match ladder_here(level, origin, pos, size) {
        None => true,
        Some((_, top)) => pos.y >= top,
    };
    if off || (m.grounded && input.down) {
        m.on_ladder = false;
        m.vel = Vec2::ZERO;
    }
}

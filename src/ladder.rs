//! Ladders, the seed's way: two states, normal and on-ladder (the on-ladder motion is in
//! [`crate::motion`]), and the rules to enter and leave the ladder state, shared by both
//! backends so that only collision handling differs.
//!
//! - Enter: the box overlaps a ladder in the column under its centre and up is held, or the
//!   character stands on a ladder's top and down is held. Entering clamps x to the ladder's
//!   centre.
//! - Leave: on jump (in the motion), when the feet rise above the ladder's top (the top is then
//!   walkable like a one-way platform), when the box no longer overlaps the ladder, or when it
//!   reaches the ground while climbing down.

use glam::Vec2;

use crate::level::Level;
use crate::motion::{Input, MotionState};

/// How close above a ladder's top the feet count as standing on it, in tiles: Rapier's offset
/// and rounding, well under a climbing step.
pub const TOP_TOLERANCE: f32 = 0.02;

/// The ladder run under the centre column that the box overlaps: (centre x, bottom, top), world.
fn ladder_here(level: &Level, origin: Vec2, feet: Vec2, size: Vec2) -> Option<(f32, f32, f32)> {
    let local = feet - origin;
    let i = local.x.floor() as i64;
    let (j0, j1) = (local.y.floor() as i64, (local.y + size.y).ceil() as i64);
    (j0..j1)
        .find_map(|j| level.ladder_extent(i, j))
        .filter(|(bottom, top)| local.y < *top && local.y + size.y > *bottom)
        .map(|(b, t)| (i as f32 + 0.5 + origin.x, b + origin.y, t + origin.y))
}

/// Before the motion integrates: enters the ladder state if the input and position allow it,
/// clamping x to the ladder's centre.
pub fn enter(
    level: &Level,
    origin: Vec2,
    m: &mut MotionState,
    pos: &mut Vec2,
    size: Vec2,
    input: &Input,
) {
    if m.on_ladder || !level.features.ladders {
        return;
    }
    let grab = if input.up {
        ladder_here(level, origin, *pos, size)
    } else if input.down && m.grounded {
        // Standing on a ladder's top: the ladder is in the tile just below the feet.
        ladder_here(level, origin, *pos - Vec2::new(0.0, 0.5), size)
            .filter(|(_, _, top)| (pos.y - top).abs() <= TOP_TOLERANCE)
    } else {
        None
    };
    if let Some((x, _, _)) = grab {
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
        Some((_, _, top)) => pos.y >= top,
    };
    if off || (m.grounded && input.down) {
        m.on_ladder = false;
        m.vel = Vec2::ZERO;
    }
}

//! Ladders, the seed's two states: the steps that enter and leave the ladder state, around the
//! move (the climbing itself, "no gravity, no left or right integration, only move up/down",
//! is the shared motion's, [`crate::motion`]).
//!
//! The seed: "most code will be for exit/enter ladder state". To enter: the box overlaps a
//! ladder and the player hits up, or stands on its top and hits down; x is clamped to the
//! ladder's. To leave: the player jumps, or the feet are outside the ladder's y extent. The rules
//! are [`crate::ladder`]'s, shared with every backend; here they run on the sweep's feet, in
//! whichever storage the step uses.

use super::space::Space;
use super::{Character, SweepStats, World};
use crate::motion::Input;

/// Step 1: enters the ladder state if the input and position allow it, clamping x to the
/// ladder's centre. Runs only on levels with ladders.
#[inline]
pub(super) fn enter<S: Space>(
    w: &World<S>,
    stats: &mut SweepStats,
    c: &mut Character<S::Coord>,
    input: &Input,
) {
    if !w.level.features.ladders {
        return;
    }
    stats.ladder_steps += 1;
    let (origin, size, motion) = (w.frame.origin, c.size, &mut c.motion);
    w.space.with_feet(&mut c.body, |feet| {
        crate::ladder::enter(w.level, origin, motion, feet, size, input)
    });
}

/// The last step: leaves the ladder state when the character is past the ladder's top, off
/// it, or on the ground while climbing down.
#[inline]
pub(super) fn leave<S: Space>(w: &World<S>, c: &mut Character<S::Coord>, input: &Input) {
    // Off a ladder there is nothing to leave (the shared rule's own first test), and the feet
    // need not be found.
    if !w.level.features.ladders || !c.motion.on_ladder {
        return;
    }
    let feet = w.feet(c);
    crate::ladder::leave(w.level, w.frame.origin, &mut c.motion, feet, c.size, input);
}

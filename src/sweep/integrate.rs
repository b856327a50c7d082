//! Forces, integration and the contacts' effect on velocity: the seed's "Integration" and
//! "Friction" slides, as the shared motion ([`crate::motion`]) implements them for every
//! backend.
//!
//! Symplectic Euler, not explicit: the velocity takes the accumulated forces (gravity, and any
//! added to the accumulator) first, then the position moves by the new velocity. The jump is an
//! impulse on the velocity, sized for an exact height. After the moves, a blocked axis loses its
//! velocity and the other gets the friction constant.

use glam::Vec2;

use super::space::Space;
use super::{Character, World};
use crate::motion::{Contacts, Input};

/// Step 2: applies input, the jump impulse and the force accumulator to the velocity, and
/// returns the displacement the character wants this step, `v * dt` (tiles).
pub(super) fn forces_and_velocity<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    input: &Input,
    dt: f32,
) -> Vec2 {
    c.motion.integrate(w.params, input, dt)
}

/// Applies what the moves ran into: zero velocity on a blocked axis, friction on the other,
/// and the grounded state.
pub(super) fn apply_contacts<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    input: &Input,
    contacts: Contacts,
) {
    c.motion.apply_contacts(w.params, input, contacts);
}

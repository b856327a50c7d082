//! The sweep's step for one character, as the seed's steps in the order they run.
//!
//! One function, [`step`], reads as the numbered steps; each step is a named function in the
//! file of its stage (ladders, integrate, resolve, slopes, oneway). It is generic over how
//! positions are stored ([`Space`]: f32 or f64 with the seed's epsilon, or whole subpixels), so
//! no stage is written twice. Moving platforms are the step's last part, run once for every
//! platform after every character has stepped (the seed: "update platforms *after* all other
//! objects"; [`super::platforms`]).
//!
//! The stages are `#[inline]`: each begins by testing whether the level has its feature
//! (slopes, ladders), and as a call its prologue cost more than that test on the levels
//! without it.

use glam::Vec2;

use super::space::Space;
use super::{integrate, ladders, oneway, resolve, slopes};
use super::{Character, SweepStats, World};
use crate::motion::{Contacts, Input};
use crate::oneway::OneWayCheck;

/// Moves one character by one step of `dt` seconds under `input`.
pub(super) fn step<S: Space>(
    w: &World<S>,
    stats: &mut SweepStats,
    c: &mut Character<S::Coord>,
    input: &Input,
    dt: f32,
) {
    // 1. Ladder: enter the ladder state ("AABB vs AABB player to ladder && up", or "stand on
    //    top and hit down"), x clamped to the ladder.
    ladders::enter(w, stats, c, input);

    // 2. Forces and integration: symplectic Euler, velocity first, then this step's move.
    let was_grounded = c.motion.grounded;
    let delta = integrate::forces_and_velocity(w, c, input, dt);
    let start = c.body;
    // The feet the slope rules read, before and after the x move (zero without slopes).
    let start_feet = slopes::feet(w, c);

    // 3. x move: sweep and snap flush; one-way boxes and the mass under a ramp do not block.
    let under_start = slopes::under(w, c, start_feet);
    let ramp_top = slopes::ramp_top_for_x(w, c, under_start);
    let mut wall = resolve::move_x(w, c, delta.x, ramp_top);

    // 4. Climb limit: a slope rising faster than the steepest walkable one stops the x move
    //    (and puts the feet back where they started).
    let moved_feet = slopes::feet(w, c);
    let rise_allow = slopes::rise_allow(w, moved_feet, start_feet);
    let climb_blocked = slopes::climb_limit(w, stats, c, &start, moved_feet, rise_allow);
    wall |= climb_blocked;
    let feet = if climb_blocked {
        start_feet
    } else {
        moved_feet
    };

    // 5. y move: sweep and snap flush; a one-way box blocks only a fall that started entirely
    //    above it. `from`: the feet's height before it, for step 6.
    let from = feet.y;
    let under = slopes::under_moved(w, c, feet, start_feet, under_start);
    let ramp_band = slopes::ramp_band_for_y(w, c, under);
    if w.level.features.one_way || w.level.features.ladders {
        stats.one_way_steps += 1;
    }
    // The shared one-way rule (crate::oneway) in the storage's coordinate and tolerance: a move
    // that does not fall, drops through or climbs passes every one-way box.
    let fall = OneWayCheck {
        feet: c.body.at[1],
        tolerance: w.frame.eps_coord,
        passes_all: c.motion.drop_through || c.motion.on_ladder || delta.y >= 0.0,
        dropping_through: None,
    };
    let hit_y = resolve::move_y(w, c, delta.y, &fall, ramp_band);
    let mut ground = hit_y.is_some() && delta.y < 0.0;
    let ceiling = hit_y.is_some() && delta.y > 0.0;
    let mut one_way = hit_y.is_some_and(oneway::is_one_way);
    // Landing on a moving platform makes the character its rider (the seed's rider list).
    c.riding = match hit_y {
        Some(super::broadphase::BoxKind::Platform { index, .. }) if ground => Some(index),
        _ => None,
    };

    // 6. Ground on slopes: resolve up onto the surface under the centre, or follow it down.
    let mut normal = Vec2::Y;
    let on_slope = slopes::ground_on_slopes(w, c, from, rise_allow, ground, was_grounded, delta.y);
    if let Some((g, up)) = on_slope {
        (ground, normal) = (true, g.normal);
        if up {
            one_way = false;
        }
    }

    // 7. Contacts: a blocked axis loses its velocity, the other gets friction.
    let contacts = Contacts {
        wall,
        ground,
        ceiling,
        one_way,
    };
    integrate::apply_contacts(w, c, input, contacts);

    // 8. Ladder: leave the ladder state (jumped, past its ends, or grounded climbing down).
    ladders::leave(w, c, input);
    c.ground_normal = if ground { normal } else { Vec2::ZERO };
}

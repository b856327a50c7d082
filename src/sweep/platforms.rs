//! Moving platforms, the seed's way: they move after every character has moved, carry their
//! riders by their displacement (a carried rider still collides with the static level, so a
//! platform cannot carry it into a wall), and push characters they move into; a character
//! pushed into the level is crushed, reported, and left where the level stopped it.
//!
//! Riders: the seed keeps a doubly linked list per platform for O(1) removal. Here each
//! character names the platform it rides (`riding`), set when it lands on it and cleared when it
//! leaves (jumps up, walks off, or the platform's x extent no longer overlaps its own): a
//! platform's riders are found by one pass over the characters, with no list to maintain and
//! nothing allocated.
//!
//! How a rider follows a descending platform is a setting ([`super::RiderFollow`]): by default
//! only as far as it could fall from the platform's previous speed under gravity in one step, so
//! a platform that drops away faster (starts or speeds up downward more sharply than gravity)
//! leaves its rider airborne, as it would in the world; or, Celeste's rule, with every move of
//! the platform, so a rider stays on an elevator that turns from up to down.

use glam::Vec2;
use parry2d::bounding_volume::Aabb;

use super::broadphase::{BoxKind, StaticTiles};
use super::resolve::{move_axis, Axis};
use super::{Character, RiderFollow, SweepBackend};
use crate::level::{character_box, Platform};

/// A platform's motion and where it is.
pub struct PlatformState {
    spec: Platform,
    origin: Vec2,
    /// Its downward speed during the last step, in tiles/s (0 when rising or level).
    down_speed: f32,
}

impl PlatformState {
    /// The platform at t = 0, placed at the level's origin.
    pub fn new(spec: &Platform, origin: Vec2) -> Self {
        PlatformState {
            spec: spec.clone(),
            origin,
            down_speed: 0.0,
        }
    }

    /// Its box in the world at time `t`.
    fn aabb(&self, t: f64) -> Aabb {
        self.spec.aabb(t).translated(self.origin)
    }
}

/// Moves `c` by `delta` against the static level only (x, then y); returns whether the level
/// stopped any part of the move.
fn shove(tiles: &StaticTiles, c: &mut Character, delta: Vec2, eps: f32) -> bool {
    let skip = |_: &Aabb, k: BoxKind| matches!(k, BoxKind::OneWay | BoxKind::Platform { .. });
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
            eps,
            skip,
        );
    }
    (c.pos - start - delta).length() > eps
}

/// Overlap of two boxes on each axis (negative when apart).
fn overlap(a: &Aabb, b: &Aabb) -> Vec2 {
    a.maxs.min(b.maxs) - a.mins.max(b.mins)
}

impl SweepBackend {
    /// Moves every platform from this step's time to the next, carrying and pushing characters.
    pub(super) fn move_platforms(&mut self, dt: f32) {
        let eps = self.config.epsilon;
        let g = self.params.gravity;
        let rule = self.config.rider_follow;
        let t1 = (self.frame + 1) as f64 * dt as f64;
        for (i, p) in self.platforms.iter_mut().enumerate() {
            self.stats.platform_moves += 1;
            // Its box now is the one the characters just moved against.
            let (old, new) = (self.platform_boxes[i].0, p.aabb(t1));
            let delta = new.mins - old.mins;
            // How far a rider can follow downward in one step: from the platform's last speed,
            // under gravity.
            let follow = p.down_speed * dt + g * dt * dt + eps;
            for c in self.characters.iter_mut() {
                if c.riding == Some(i as u32) {
                    let mut carry = delta;
                    let left_behind = rule == RiderFollow::Gravity && delta.y < -follow;
                    if left_behind {
                        carry.y = -follow;
                    }
                    shove(&self.tiles, c, carry, eps);
                    let cb = character_box(c.pos, c.size);
                    if left_behind || overlap(&cb, &new).x <= 0.0 {
                        // Left behind by a platform dropping away, or no longer over it.
                        c.riding = None;
                        c.motion.grounded = false;
                        if left_behind {
                            c.motion.vel.y = carry.y / dt;
                        }
                    }
                    continue;
                }
                let cb = character_box(c.pos, c.size);
                let o = overlap(&cb, &new);
                if o.x <= eps || o.y <= eps {
                    continue;
                }
                // A one-way platform only pushes what stood entirely above it.
                if p.spec.one_way && c.pos.y < old.maxs.y - eps {
                    continue;
                }
                // Push along the axis the platform moved on that needs the smaller push.
                let push_x = match delta.x {
                    d if d > 0.0 => new.maxs.x - cb.mins.x,
                    d if d < 0.0 => new.mins.x - cb.maxs.x,
                    _ => f32::INFINITY,
                };
                let push_y = match delta.y {
                    d if d > 0.0 => new.maxs.y - cb.mins.y,
                    d if d < 0.0 => new.mins.y - cb.maxs.y,
                    _ => f32::INFINITY,
                };
                let push = if push_x.abs() <= push_y.abs() {
                    Vec2::new(push_x, 0.0)
                } else {
                    Vec2::new(0.0, push_y)
                };
                if !push.is_finite() {
                    continue;
                }
                let blocked = shove(&self.tiles, c, push, eps);
                let after = overlap(&character_box(c.pos, c.size), &new);
                if blocked && after.x > eps && after.y > eps {
                    c.crushed = true;
                } else if push.y > 0.0 {
                    // Lifted from below: it now stands on the platform.
                    c.riding = Some(i as u32);
                    c.motion.grounded = true;
                    c.ground_normal = Vec2::Y;
                    c.motion.vel.y = 0.0;
                }
            }
            p.down_speed = (-delta.y / dt).max(0.0);
            self.platform_boxes[i].0 = new;
        }
    }
}

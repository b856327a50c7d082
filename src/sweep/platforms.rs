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
//!
//! Written once over [`Space`]: in float the platforms follow their exact path and the moves
//! are f32 with the seed's epsilon; on the subpixel grid a platform's box is its path rounded to
//! the nearest subpixel at each step ([`crate::level::Platform::grid_box`]: its motion stays a
//! function of time, a step's move is the difference of two rounded positions, so no rounding
//! accumulates), and riders are carried, characters pushed and crushes found in whole
//! subpixels, as Celeste's and TowerFall's solids move their actors.

use glam::Vec2;
use parry2d::bounding_volume::Aabb;

use super::broadphase::{BoxKind, StaticTiles};
use super::grid::{Grid, GridBox};
use super::space::{Rect, Space};
use super::{Character, RiderFollow};
use crate::level::Platform;

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
    pub(super) fn aabb(&self, t: f64) -> Aabb {
        self.spec.aabb(t).translated(self.origin)
    }

    /// Its box on `grid` at time `t`, in world subpixels: its path rounded to the nearest
    /// subpixel ([`Platform::grid_box`]), placed at the level's corner on the grid.
    pub(super) fn grid_box(&self, grid: &Grid, t: f64) -> GridBox {
        let (min, max) = self.spec.grid_box(t, grid.per_tile);
        GridBox {
            min: min + grid.origin,
            max: max + grid.origin,
        }
    }
}

/// The moving platforms of a level, their boxes where the characters move against them, and the
/// rider-follow rule.
pub(super) struct Platforms {
    pub states: Vec<PlatformState>,
    /// Their boxes at the current frame, in float world tiles (float mode).
    pub boxes: Vec<(Aabb, BoxKind)>,
    /// Their boxes at the current frame on the subpixel grid (integer mode; empty otherwise).
    pub grid_boxes: Vec<(GridBox, BoxKind)>,
    /// How a rider follows a descending platform.
    pub rule: RiderFollow,
    /// Gravity, tiles/s² (for [`RiderFollow::Gravity`]).
    pub gravity: f32,
}

impl Platforms {
    /// `level`'s platforms at t = 0 (on `grid` too, in integer mode).
    pub fn new(
        level: &crate::level::Level,
        grid: Option<&Grid>,
        rule: RiderFollow,
        gravity: f32,
    ) -> Self {
        let states: Vec<PlatformState> = level
            .platforms
            .iter()
            .map(|p| PlatformState::new(p, level.origin))
            .collect();
        let kind = |i: usize, p: &Platform| BoxKind::Platform {
            index: i as u32,
            one_way: p.one_way,
        };
        let boxes = level
            .platforms
            .iter()
            .enumerate()
            .map(|(i, p)| (p.aabb(0.0).translated(level.origin), kind(i, p)))
            .collect();
        let grid_boxes = match grid {
            Some(g) => states
                .iter()
                .enumerate()
                .map(|(i, p)| (p.grid_box(g, 0.0), kind(i, &p.spec)))
                .collect(),
            None => Vec::new(),
        };
        Platforms {
            states,
            boxes,
            grid_boxes,
            rule,
            gravity,
        }
    }

    /// Moves every platform to its place at time `t1` (the end of this step of `dt` seconds),
    /// carrying its riders and pushing the characters it moves into, in the space `s`.
    pub(super) fn step<S: Space>(
        &mut self,
        s: &S,
        tiles: &StaticTiles,
        characters: &mut [Character],
        t1: f64,
        dt: f32,
    ) {
        let zero = S::Coord::default();
        let eps = s.eps_coord();
        let g = self.gravity;
        for i in 0..self.states.len() {
            // Its box now is the one the characters just moved against.
            let old = s.platform_now(self, i);
            let p = &mut self.states[i];
            let new = s.platform_at(p, t1);
            let delta = [new.min[0] - old.min[0], new.min[1] - old.min[1]];
            // How far a rider can follow downward in one step: from the platform's last speed,
            // under gravity.
            let follow = s.length_up(p.down_speed * dt + g * dt * dt + s.eps());
            for c in characters.iter_mut() {
                if c.riding == Some(i as u32) {
                    let mut carry = delta;
                    let left_behind = self.rule == RiderFollow::Gravity && delta[1] < -follow;
                    if left_behind {
                        carry[1] = -follow;
                    }
                    let blocked = s.shove(tiles, c, carry);
                    let after = overlap(&s.rect(c), &new);
                    if blocked && after[0] > eps && after[1] > eps {
                        // Carried into the level (lifted into a ceiling, pressed into a wall):
                        // squeezed between it and the platform, crushed on this very move.
                        c.crushed = true;
                        c.riding = None;
                        continue;
                    }
                    if left_behind || after[0] <= zero {
                        // Left behind by a platform dropping away, or no longer over it.
                        c.riding = None;
                        c.motion.grounded = false;
                        if left_behind {
                            c.motion.vel.y = s.to_tiles(carry[1]) / dt;
                        }
                    }
                    continue;
                }
                let cb = s.rect(c);
                let o = overlap(&cb, &new);
                if o[0] <= eps || o[1] <= eps {
                    continue;
                }
                // A one-way platform only pushes what stood entirely above it.
                if p.spec.one_way && s.bottom(c) < old.max[1] - eps {
                    continue;
                }
                // Push along the axis the platform moved on that needs the smaller push.
                let push_on = |a: usize| match delta[a] {
                    d if d > zero => Some(new.max[a] - cb.min[a]),
                    d if d < zero => Some(new.min[a] - cb.max[a]),
                    _ => None,
                };
                let push = match (push_on(0), push_on(1)) {
                    (Some(x), Some(y)) if abs(x) <= abs(y) => [x, zero],
                    (Some(x), None) => [x, zero],
                    (_, Some(y)) => [zero, y],
                    (None, None) => continue,
                };
                let blocked = s.shove(tiles, c, push);
                let after = overlap(&s.rect(c), &new);
                if blocked && after[0] > eps && after[1] > eps {
                    c.crushed = true;
                } else if push[1] > zero {
                    // Lifted from below: it now stands on the platform.
                    c.riding = Some(i as u32);
                    c.motion.grounded = true;
                    c.ground_normal = Vec2::Y;
                    c.motion.vel.y = 0.0;
                }
            }
            p.down_speed = (-s.to_tiles(delta[1]) / dt).max(0.0);
            s.set_platform(self, i, new);
        }
    }
}

/// The smaller of two coordinates.
fn min<C: PartialOrd>(a: C, b: C) -> C {
    if b < a {
        b
    } else {
        a
    }
}

/// The larger of two coordinates.
fn max<C: PartialOrd>(a: C, b: C) -> C {
    if b > a {
        b
    } else {
        a
    }
}

/// The magnitude of a coordinate.
fn abs<C: PartialOrd + Default + std::ops::Neg<Output = C>>(a: C) -> C {
    if a < C::default() {
        -a
    } else {
        a
    }
}

/// Overlap of two boxes on each axis (negative when apart).
fn overlap<C: Copy + PartialOrd + std::ops::Sub<Output = C>>(a: &Rect<C>, b: &Rect<C>) -> [C; 2] {
    [0, 1].map(|k| min(a.max[k], b.max[k]) - max(a.min[k], b.min[k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlap_is_signed_per_axis() {
        let a = Rect {
            min: [0i64, 0],
            max: [10, 10],
        };
        let b = Rect {
            min: [8i64, 12],
            max: [20, 20],
        };
        assert_eq!(overlap(&a, &b), [2, -2]);
        assert_eq!(abs(-3i64), 3);
        assert_eq!(abs(2.5f32), 2.5);
    }
}

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
//! Celeste's rule, with every move of the platform, so a rider stays on an elevator that turns
//! from up to down; or only as far as it could fall from the platform's previous speed under
//! gravity in one step, so a platform that drops away faster (starts or speeds up downward more
//! sharply than gravity) leaves its rider airborne, as it would in the world.
//!
//! Written once over `Space`, the boxes in its coordinate: in float the platforms follow their
//! exact path and the moves are f32 with the seed's epsilon; in f64
//! ([`super::Positions::Double`]) they follow the same path (its f32 level coordinates, the
//! float mode's at the origin) placed at the level's origin in f64, and the moves are f64 with
//! the same epsilon, so a platform far from the origin moves as one at the origin does, up to
//! the f64 spacing there; on the subpixel grid a platform's box is its path rounded to the
//! nearest subpixel at each step ([`crate::level::Platform::grid_box`]: its motion stays a
//! function of time, a step's move is the difference of two rounded positions, so no rounding
//! accumulates), and riders are carried, characters pushed and crushes found in whole
//! subpixels, as Celeste's and TowerFall's solids move their actors.

use std::cell::Cell;

use glam::{DVec2, Vec2};
use parry2d::bounding_volume::Aabb;

use super::broadphase::{BoxKind, StaticTiles};
use super::grid::Grid;
use super::resolve::{shove, Obstacles};
use super::space::{Rect, Space};
use super::{Character, RiderFollow};
use crate::level::{Path, Platform};
use crate::oneway::OneWayCheck;

/// A platform's motion and where it is.
pub(crate) struct PlatformState {
    spec: Platform,
    /// What placing it computes whatever the time (a waypoint path's lengths), computed once.
    path: Path,
    /// The level's corner in the world, tiles.
    origin: DVec2,
}

impl PlatformState {
    /// The platform at t = 0, placed at the level's origin.
    pub(super) fn new(spec: &Platform, origin: DVec2) -> Self {
        PlatformState {
            spec: spec.clone(),
            path: spec.path(),
            origin,
        }
    }

    /// Its lower-left corner at time `t`, level tiles ([`Platform::position`]).
    #[inline]
    fn position(&self, t: f64) -> Vec2 {
        self.spec.position_on(&self.path, t)
    }

    /// The box it stays inside over its whole motion, in world tiles (lower left, upper right):
    /// [`Platform::reach`] placed at the origin.
    pub(super) fn reach_world(&self) -> (DVec2, DVec2) {
        let (lo, hi) = self.spec.reach();
        (lo + self.origin, hi + self.origin)
    }

    /// Its box in level tiles over its whole motion ([`Platform::reach`]).
    pub(super) fn reach_level(&self) -> (DVec2, DVec2) {
        self.spec.reach()
    }

    /// Its box in the world at time `t`, in f32 (the float mode): its box in level
    /// coordinates placed at the origin rounded to f32.
    pub(super) fn aabb(&self, t: f64) -> Aabb {
        self.spec
            .aabb_at(self.position(t))
            .translated(self.origin.as_vec2())
    }

    /// Its box in the world at time `t`, in f64 (the f64 mode): its corner in level coordinates
    /// ([`Platform::position`], the float mode's at the origin) placed at the origin in f64,
    /// rounded once to the f64 spacing at the world position, and its size added in f64. The
    /// far faces are not the float mode's f32 sums: a rider carried by the corner's exact f64
    /// moves stays exactly on the top `corner + height` (an f32-rounded top would sit up to half
    /// an f32 spacing off it, more than an epsilon of 1e-7 tile, and the rider would fall
    /// through).
    pub(super) fn aabb_f64(&self, t: f64) -> Rect<f64> {
        let min = self.position(t).as_dvec2() + self.origin;
        Rect {
            min: min.to_array(),
            max: (min + self.spec.size.as_dvec2()).to_array(),
        }
    }

    /// Its box on `grid` at time `t`, in world subpixels: its path rounded to the nearest
    /// subpixel ([`Platform::grid_box`]), placed at the level's corner on the grid.
    pub(super) fn grid_box(&self, grid: &Grid, t: f64) -> Rect<i64> {
        let (min, max) = self.spec.grid_box_at(self.position(t), grid.per_tile);
        Rect {
            min: (min + grid.origin).to_array(),
            max: (max + grid.origin).to_array(),
        }
    }
}

/// The moving platforms of a level, their boxes where the characters move against them (in the
/// space's coordinate `C`), and the rider-follow rule.
///
/// A platform's place is a function of time, so it is placed only where something can meet it:
/// a character's move asks for the platforms whose reach (the box they stay inside over their
/// whole motion) its swept box touches, and each is placed at the current time when first
/// asked; a platform no character touches the reach of is not moved at all. Far platforms cost
/// one box test per character, as a box does; the traces are the ones every platform moved at
/// every step gives, since a box placed later at the same time is the same box.
pub(super) struct Platforms<C> {
    pub states: Vec<PlatformState>,
    /// Each platform's box where it was last placed, and its kind.
    boxes: Vec<Cell<(Rect<C>, BoxKind)>>,
    /// The time (s) each of `boxes` is at.
    placed_at: Vec<Cell<f64>>,
    /// The box each platform stays inside over its whole motion, grown by a margin that
    /// covers the space's rounding.
    reach: Vec<Rect<C>>,
    /// Each platform's downward speed (tiles/s) over the step that ended at the time given
    /// beside it, kept when the platform moved so that the next step need not place it twice.
    down: Vec<(f64, f32)>,
    /// Per platform, whether a character rode it when this step's pass began (kept here so
    /// that the pass allocates nothing).
    ridden: Vec<bool>,
    /// The time the platforms are at: the end of the last step.
    now: f64,
    /// The start and length (s) of the last step, none before the first (a rider's follow
    /// under gravity reads the platform's speed over it).
    last: Option<(f64, f32)>,
    /// How a rider follows a descending platform.
    pub rule: RiderFollow,
    /// Gravity, tiles/s² (for [`RiderFollow::Gravity`]).
    pub gravity: f32,
}

impl<C: super::space::Coord> Platforms<C> {
    /// `level`'s platforms at t = 0, placed as the space `s` places them.
    pub fn new<S: Space<Coord = C>>(
        level: &crate::level::Level,
        s: &S,
        rule: RiderFollow,
        gravity: f32,
    ) -> Self {
        let states: Vec<PlatformState> = level
            .platforms
            .iter()
            .map(|p| PlatformState::new(p, level.origin))
            .collect();
        let boxes = states
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let kind = BoxKind::Platform {
                    index: i as u32,
                    one_way: p.spec.one_way,
                };
                Cell::new((s.platform_at(p, 0.0), kind))
            })
            .collect();
        Platforms {
            placed_at: vec![Cell::new(0.0); states.len()],
            down: vec![(0.0, 0.0); states.len()],
            ridden: vec![false; states.len()],
            reach: states.iter().map(|p| s.reach(p)).collect(),
            states,
            boxes,
            now: 0.0,
            last: None,
            rule,
            gravity,
        }
    }

    /// Platform `i`'s box at the current time, and its kind (placed now if it was not yet).
    #[inline]
    fn box_now<S: Space<Coord = C>>(&self, s: &S, i: usize) -> (Rect<C>, BoxKind) {
        if self.placed_at[i].get() != self.now {
            self.place_now(s, i);
        }
        self.boxes[i].get()
    }

    /// Places platform `i` at the current time (once per step, for the first move that meets
    /// it).
    #[inline(never)]
    fn place_now<S: Space<Coord = C>>(&self, s: &S, i: usize) {
        let (_, kind) = self.boxes[i].get();
        self.boxes[i].set((s.platform_at(&self.states[i], self.now), kind));
        self.placed_at[i].set(self.now);
    }

    /// Calls `f` with each platform at the current time whose reach touches `swept`, in their
    /// order: every platform whose box can touch it.
    #[inline(always)]
    pub(super) fn near<S: Space<Coord = C>>(
        &self,
        s: &S,
        swept: Rect<C>,
        mut f: impl FnMut(Rect<C>, BoxKind),
    ) {
        for (i, reach) in self.reach.iter().enumerate() {
            if reach.touches(&swept) {
                let (t, kind) = self.box_now(s, i);
                f(t, kind);
            }
        }
    }

    /// Makes every platform's reach the whole plane, so that every platform is placed and
    /// moved at every step (what the lazy placement must equal).
    #[cfg(test)]
    fn reach_everywhere<S: Space<Coord = C>>(&mut self, s: &S) {
        let everywhere = PlatformState::new(
            &Platform {
                start: Vec2::ZERO,
                size: Vec2::ONE,
                motion: crate::level::PlatformMotion::Sine {
                    amplitude: Vec2::splat(1e5),
                    period: 1.0,
                },
                one_way: false,
            },
            DVec2::ZERO,
        );
        let r = s.reach(&everywhere);
        self.reach.iter_mut().for_each(|x| *x = r);
    }

    /// Platform `i`'s downward speed during the last step, tiles/s (0 when it rose or stayed,
    /// and before the first step): kept from its move, or found from its two places when it
    /// did not move (no character met it).
    fn down_speed<S: Space<Coord = C>>(&self, s: &S, i: usize) -> f32 {
        if self.down[i].0 == self.now {
            return self.down[i].1;
        }
        let Some((t0, dt)) = self.last else {
            return 0.0;
        };
        let before = s.platform_at(&self.states[i], t0);
        let now = self.box_now(s, i).0;
        (-s.to_tiles(now.min[1] - before.min[1]) / dt).max(0.0)
    }

    /// Moves every platform to its place at time `t1` (the end of this step of `dt` seconds),
    /// carrying its riders and pushing the characters it moves into, in the space `s`.
    pub(super) fn step<S: Space<Coord = C>>(
        &mut self,
        s: &S,
        tiles: &StaticTiles,
        characters: &mut [Character<C>],
        t1: f64,
        dt: f32,
    ) {
        let zero = C::default();
        let frame = s.frame();
        let eps = frame.eps_coord;
        let level = Obstacles {
            space: s,
            tiles,
            moving: None,
            eps,
        };
        let g = self.gravity;
        // What the pass tests each platform against first: the platforms ridden when it began
        // (a character's ride changes in the pass only to the platform moving it, or to none),
        // and a box holding every character (grown as they are moved): a platform neither
        // ridden nor reaching that box meets nobody, with one test for all the characters.
        self.ridden.fill(false);
        let mut all: Option<Rect<C>> = None;
        for c in characters.iter() {
            if let Some(r) = c.riding.and_then(|k| self.ridden.get_mut(k as usize)) {
                *r = true;
            }
            all = Some(cover(all, &c.body.rect()));
        }
        let mut next = 0;
        // The next platform from `next` on that is ridden or reaches the characters' box (one
        // scan over the platforms; the others meet nobody).
        while let Some(k) = (self.reach[next..].iter().zip(&self.ridden[next..]))
            .position(|(reach, &ridden)| ridden || all.is_some_and(|a| a.touches(reach)))
        {
            let i = next + k;
            next = i + 1;
            // A platform no character rides or touches the reach of meets nobody this step.
            let reach = self.reach[i];
            let met = characters
                .iter()
                .any(|c| c.riding == Some(i as u32) || c.body.rect().touches(&reach));
            if !met {
                continue;
            }
            // Its box now is the one the characters just moved against.
            let (old, kind) = self.box_now(s, i);
            let p = &self.states[i];
            let new = s.platform_at(p, t1);
            let delta = [new.min[0] - old.min[0], new.min[1] - old.min[1]];
            // How far a rider can follow downward in one step: from the platform's last speed,
            // under gravity.
            let follow = if self.rule == RiderFollow::Gravity {
                s.length_up(self.down_speed(s, i) * dt + g * dt * dt + frame.eps)
            } else {
                zero
            };
            for c in characters.iter_mut() {
                if c.riding == Some(i as u32) {
                    let mut carry = delta;
                    let left_behind = self.rule == RiderFollow::Gravity && delta[1] < -follow;
                    if left_behind {
                        carry[1] = -follow;
                    }
                    let blocked = shove(&level, c, carry);
                    all = Some(cover(all, &c.body.rect()));
                    let after = overlap(&c.body.rect(), &new);
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
                let cb = c.body.rect();
                let o = overlap(&cb, &new);
                if o[0] <= eps || o[1] <= eps {
                    continue;
                }
                // A one-way platform only pushes what stood entirely above it (the shared rule).
                let stood_above = OneWayCheck {
                    feet: c.body.at[1],
                    tolerance: eps,
                    passes_all: false,
                    dropping_through: None,
                };
                if p.spec.one_way && !stood_above.blocks(old.max[1]) {
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
                let blocked = shove(&level, c, push);
                all = Some(cover(all, &c.body.rect()));
                let after = overlap(&c.body.rect(), &new);
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
            self.boxes[i].set((new, kind));
            self.placed_at[i].set(t1);
            self.down[i] = (t1, (-s.to_tiles(delta[1]) / dt).max(0.0));
        }
        self.last = Some((self.now, dt));
        self.now = t1;
    }
}

/// The box holding `a` (if any) and `b`.
fn cover<C: super::space::Coord>(a: Option<Rect<C>>, b: &Rect<C>) -> Rect<C> {
    match a {
        None => *b,
        Some(a) => Rect {
            min: [0, 1].map(|k| a.min[k].min(b.min[k])),
            max: [0, 1].map(|k| a.max[k].max(b.max[k])),
        },
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
    use crate::backend::CharacterSpec;
    use crate::motion::{Input, MotionParams};
    use crate::sweep::{Mode, Positions, SweepBackend, SweepConfig};

    /// Every state of `n` characters spread over the built-in platforms level, each walking
    /// and jumping on its own rhythm for 20 s, in `positions` with `rule`; with every platform
    /// placed at every step when `everywhere`.
    fn run(positions: Positions, rule: RiderFollow, everywhere: bool) -> Vec<String> {
        let text = include_str!("../../compare/levels/platforms.toml");
        let level = crate::level::parse_level(text, "platforms.toml").unwrap();
        let config = SweepConfig {
            positions,
            rider_follow: rule,
            ..SweepConfig::default()
        };
        let mut b = SweepBackend::new(&level, MotionParams::default(), config).unwrap();
        let n = 36;
        for k in 0..n {
            let spec = CharacterSpec {
                spawn: Vec2::new(1.5 + 2.0 * k as f32, 1.0 + (k % 9) as f32),
                size: Vec2::new(0.8, 0.9),
                velocity: Vec2::ZERO,
            };
            b.add_character(spec).unwrap();
        }
        if everywhere {
            match &mut b.mode {
                Mode::Float(s) => s.platforms.reach_everywhere(&s.space),
                Mode::Double(s) => s.platforms.reach_everywhere(&s.space),
                Mode::Integer(s) => s.platforms.reach_everywhere(&s.space),
            }
        }
        let mut out = Vec::new();
        for f in 0..1200u32 {
            let inputs: Vec<Input> = (0..n)
                .map(|k| Input {
                    left: (f / (60 + k)) % 3 == 1,
                    right: (f / (60 + k)) % 3 == 0,
                    jump: (f + 7 * k) % 97 < 20,
                    down: (f + k) % 150 < 10,
                    ..Input::default()
                })
                .collect();
            b.step(&inputs, 1.0 / 60.0);
            for k in 0..n as usize {
                out.push(format!("{:?}", b.state(k)));
            }
        }
        out
    }

    #[test]
    fn placing_platforms_only_where_a_character_can_meet_them_changes_no_state() {
        for positions in [
            Positions::Float,
            Positions::Double,
            Positions::Integer { per_tile: 16 },
        ] {
            for rule in [RiderFollow::Solid, RiderFollow::Gravity] {
                let lazy = run(positions, rule, false);
                let every = run(positions, rule, true);
                let first = lazy.iter().zip(&every).position(|(a, b)| a != b);
                assert!(first.is_none(), "{positions:?} {rule:?}: {first:?}");
                // The characters meet platforms: some ride one at some step.
                assert!(
                    lazy.iter().any(|s| s.contains("platform: Some")),
                    "{positions:?}"
                );
            }
        }
    }

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

    #[test]
    fn in_f64_a_platform_far_out_moves_as_at_the_origin_up_to_the_f64_spacing() {
        let spec = Platform {
            start: Vec2::new(12.0, 6.0),
            size: Vec2::new(12.0, 0.5),
            motion: crate::level::PlatformMotion::Sine {
                amplitude: Vec2::new(4.0, 0.0),
                period: 4.0,
            },
            one_way: false,
        };
        let near = PlatformState::new(&spec, DVec2::ZERO);
        let origin = DVec2::splat(1e12);
        let far = PlatformState::new(&spec, origin);
        // f64 spacing at 1e12 (2^39 <= 1e12 < 2^40): 2^(39-52) = 2^-13 tile. Placing the box is
        // one rounded addition, so each face is within half a spacing of the origin's face
        // moved out; in f32 the same box would move in steps of 2^(39-23) = 65536 tiles.
        let half = 0.5 * 2f64.powi(-13);
        for k in [0u32, 1, 7, 59, 600] {
            let t = k as f64 / 60.0;
            let (a, b) = (near.aabb_f64(t), far.aabb_f64(t));
            for i in 0..2 {
                assert!((b.min[i] - origin[i] - a.min[i]).abs() <= half, "t {t}");
                assert!((b.max[i] - origin[i] - a.max[i]).abs() <= half, "t {t}");
            }
            // At the origin its corner is the float mode's, bit for bit, and its far faces the
            // corner plus the size, exact in f64 (the float mode's are rounded to f32).
            let float = Rect::from(near.aabb(t));
            assert_eq!(float.min.map(f64::from), a.min);
            for i in 0..2 {
                assert_eq!(a.max[i], a.min[i] + spec.size[i] as f64);
                assert!((float.max[i] as f64 - a.max[i]).abs() <= 1e-6);
            }
        }
    }
}

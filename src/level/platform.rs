//! Moving platforms: a box and a motion that is a function of time only, so every backend sees
//! the same platform at the same frame.

use glam::{DVec2, I64Vec2, Vec2};

use crate::rounding::round_to_i64;

/// How a platform moves. Positions are of the platform's lower-left corner, in tiles.
#[derive(Clone, Debug, PartialEq)]
pub enum PlatformMotion {
    /// Visits the waypoints in order and back, at constant speed (tiles/s), turning at the ends.
    Waypoints {
        /// Corner positions, the first being the start.
        points: Vec<Vec2>,
        /// Speed along the path, in tiles/s.
        speed: f32,
    },
    /// `start + amplitude * sin(2 pi t / period)`: smooth back and forth along a line.
    Sine {
        /// Largest offset from the start, in tiles (its direction is the line).
        amplitude: Vec2,
        /// Period, in seconds.
        period: f32,
    },
    /// Around a circle through the start, counter-clockwise: `start + radius (cos a - 1, sin a)`
    /// with `a = 2 pi t / period`.
    Circle {
        /// Radius, in tiles.
        radius: f32,
        /// Period, in seconds.
        period: f32,
    },
}

/// A moving platform.
#[derive(Clone, Debug, PartialEq)]
pub struct Platform {
    /// Lower-left corner at t = 0, in tiles.
    pub start: Vec2,
    /// Width and height, in tiles.
    pub size: Vec2,
    /// How it moves.
    pub motion: PlatformMotion,
    /// Whether it blocks only from above, like a one-way tile.
    pub one_way: bool,
}

impl Platform {
    /// The lower-left corner at time `t` (seconds), computed in f64 and rounded once, so that
    /// every backend gets the same bits.
    pub fn position(&self, t: f64) -> Vec2 {
        match &self.motion {
            PlatformMotion::Waypoints { points, speed } => {
                // No allocation: this runs every step (a controller that places a platform
                // often keeps its [`Path`] instead).
                let length: f64 = points.windows(2).map(segment).sum();
                along(self.start, points, *speed, t, length, |k| {
                    segment(&points[k..k + 2])
                })
            }
            _ => self.smooth_position(t),
        }
    }

    /// What [`Platform::position`] computes whatever the time, computed once: a waypoint
    /// path's segment lengths and their sum.
    pub(crate) fn path(&self) -> Path {
        match &self.motion {
            PlatformMotion::Waypoints { points, .. } => {
                let segments: Vec<f64> = points.windows(2).map(segment).collect();
                Path {
                    length: segments.iter().sum(),
                    segments,
                }
            }
            _ => Path::default(),
        }
    }

    /// [`Platform::position`] from the platform's [`Platform::path`], bit for bit.
    #[inline]
    pub(crate) fn position_on(&self, path: &Path, t: f64) -> Vec2 {
        match &self.motion {
            PlatformMotion::Waypoints { points, speed } => {
                along(self.start, points, *speed, t, path.length, |k| {
                    path.segments[k]
                })
            }
            _ => self.smooth_position(t),
        }
    }

    /// [`Platform::position`] of a sine or circle motion (the start for a waypoint path).
    #[inline]
    fn smooth_position(&self, t: f64) -> Vec2 {
        let start = self.start.as_dvec2();
        let tau = std::f64::consts::TAU;
        let p = match &self.motion {
            PlatformMotion::Sine { amplitude, period } => {
                start + amplitude.as_dvec2() * (tau * t / *period as f64).sin()
            }
            PlatformMotion::Circle { radius, period } => {
                let a = tau * t / *period as f64;
                start + *radius as f64 * DVec2::new(a.cos() - 1.0, a.sin())
            }
            PlatformMotion::Waypoints { .. } => start,
        };
        p.as_vec2()
    }

    /// The box the platform sweeps over its whole motion, in level tiles (lower left, upper
    /// right), in f64: its waypoints' box, its sine's start plus and minus the amplitude, or
    /// its circle's box, each grown by the platform's size.
    pub fn reach(&self) -> (DVec2, DVec2) {
        let start = self.start.as_dvec2();
        let (lo, hi) = match &self.motion {
            PlatformMotion::Waypoints { points, .. } => {
                points.iter().fold((start, start), |(lo, hi), p| {
                    (lo.min(p.as_dvec2()), hi.max(p.as_dvec2()))
                })
            }
            PlatformMotion::Sine { amplitude, .. } => {
                let a = amplitude.as_dvec2().abs();
                (start - a, start + a)
            }
            PlatformMotion::Circle { radius, .. } => {
                // start + r (cos a - 1, sin a): x in start.x - 2r..start.x, y within r.
                let r = (*radius as f64).abs();
                (start - DVec2::new(2.0 * r, r), start + DVec2::new(0.0, r))
            }
        };
        (lo, hi + self.size.as_dvec2())
    }

    /// The platform's box at time `t`.
    pub fn aabb(&self, t: f64) -> parry2d::bounding_volume::Aabb {
        self.aabb_at(self.position(t))
    }

    /// The platform's box with its lower-left corner at `p`.
    #[inline]
    pub(crate) fn aabb_at(&self, p: Vec2) -> parry2d::bounding_volume::Aabb {
        parry2d::bounding_volume::Aabb::new(p, p + self.size)
    }

    /// Its box at time `t` on a grid of `per_tile` subpixels per tile, in level subpixels
    /// (min, max): the lower-left corner is [`Platform::position`] rounded to the nearest
    /// subpixel and the size rounded to whole subpixels (at least one). The motion stays a
    /// function of time: a step's move is the difference of two rounded positions, so the
    /// rounding never accumulates (Celeste's solids move a whole pixel at a time, their
    /// remainder carried).
    pub fn grid_box(&self, t: f64, per_tile: i64) -> (I64Vec2, I64Vec2) {
        self.grid_box_at(self.position(t), per_tile)
    }

    /// [`Platform::grid_box`] with the lower-left corner at `p` (level tiles).
    #[inline]
    pub(crate) fn grid_box_at(&self, p: Vec2, per_tile: i64) -> (I64Vec2, I64Vec2) {
        let n = per_tile as f64;
        let round = |v: DVec2| I64Vec2::new(round_to_i64(v.x), round_to_i64(v.y));
        let min = round(p.as_dvec2() * n);
        let size = round(self.size.as_dvec2() * n).max(I64Vec2::ONE);
        (min, min + size)
    }

    /// Its box at time `t` as a controller places it: on a grid of `per_tile` subpixels per
    /// tile ([`Platform::grid_box`], in tiles), or on its exact path when `per_tile` is 0.
    pub fn placed_aabb(&self, t: f64, per_tile: u32) -> parry2d::bounding_volume::Aabb {
        if per_tile == 0 {
            return self.aabb(t);
        }
        let n = per_tile as f64;
        let (min, max) = self.grid_box(t, per_tile as i64);
        parry2d::bounding_volume::Aabb::new(
            (min.as_dvec2() / n).as_vec2(),
            (max.as_dvec2() / n).as_vec2(),
        )
    }
}

/// A waypoint path's segment lengths and their sum ([`Platform::path`]); empty for the other
/// motions.
#[derive(Clone, Debug, Default)]
pub(crate) struct Path {
    segments: Vec<f64>,
    length: f64,
}

/// The length of the segment between the two points of `w`.
fn segment(w: &[Vec2]) -> f64 {
    (w[1].as_dvec2() - w[0].as_dvec2()).length()
}

/// Where a platform starting at `start` is at time `t` going back and forth along `points` at
/// `speed`, the path `length` long and its segment `k` `len(k)` long.
#[inline]
fn along(
    start: Vec2,
    points: &[Vec2],
    speed: f32,
    t: f64,
    length: f64,
    len: impl Fn(usize) -> f64,
) -> Vec2 {
    if length <= 0.0 {
        return start;
    }
    let mut s = wrap(speed as f64 * t, 2.0 * length);
    if s > length {
        s = 2.0 * length - s;
    }
    let mut at = start.as_dvec2();
    for (k, w) in points.windows(2).enumerate() {
        let (a, b) = (w[0].as_dvec2(), w[1].as_dvec2());
        let len = len(k);
        if s <= len {
            at = a + (b - a) * (s / len);
            break;
        }
        s -= len;
        at = b;
    }
    at.as_vec2()
}

/// `x.rem_euclid(m)` for `m > 0`, bit for bit, without the remainder's division for the
/// first two laps: `x` itself below `m`, and `x - m` below `2m` (exact there: Sterbenz).
#[inline]
fn wrap(x: f64, m: f64) -> f64 {
    if (0.0..m).contains(&x) {
        x
    } else if (m..2.0 * m).contains(&x) {
        x - m
    } else {
        x.rem_euclid(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waypoints_go_back_and_forth_at_speed() {
        let p = Platform {
            start: Vec2::new(2.0, 4.0),
            size: Vec2::new(3.0, 0.5),
            motion: PlatformMotion::Waypoints {
                points: vec![Vec2::new(2.0, 4.0), Vec2::new(8.0, 4.0)],
                speed: 2.0,
            },
            one_way: false,
        };
        assert_eq!(p.position(0.0), Vec2::new(2.0, 4.0));
        assert_eq!(p.position(1.5), Vec2::new(5.0, 4.0));
        assert_eq!(p.position(3.0), Vec2::new(8.0, 4.0));
        assert_eq!(p.position(4.5), Vec2::new(5.0, 4.0));
        assert_eq!(p.position(6.0), Vec2::new(2.0, 4.0));
    }

    #[test]
    fn on_a_grid_the_box_is_the_rounded_path_and_its_moves_never_accumulate_error() {
        let p = Platform {
            start: Vec2::new(2.0, 4.0),
            size: Vec2::new(3.0, 0.5),
            motion: PlatformMotion::Sine {
                amplitude: Vec2::new(0.0, 2.0),
                period: 4.0,
            },
            one_way: false,
        };
        let dt = 1.0 / 60.0;
        for k in [0u32, 1, 7, 59, 600] {
            let t = k as f64 * dt;
            let (min, max) = p.grid_box(t, 32);
            // Within half a subpixel of the path at every time, however many steps before.
            let exact = p.position(t).as_dvec2() * 32.0;
            assert!((min.as_dvec2() - exact).abs().max_element() <= 0.5, "t {t}");
            assert_eq!(max - min, I64Vec2::new(96, 16));
            assert_eq!(p.placed_aabb(t, 32).mins, (min.as_dvec2() / 32.0).as_vec2());
        }
        // No grid: the exact path.
        assert_eq!(p.placed_aabb(0.3, 0), p.aabb(0.3));
    }

    #[test]
    fn sine_and_circle_start_at_the_start() {
        let sine = Platform {
            start: Vec2::new(1.0, 1.0),
            size: Vec2::ONE,
            motion: PlatformMotion::Sine {
                amplitude: Vec2::new(0.0, 2.0),
                period: 4.0,
            },
            one_way: false,
        };
        assert_eq!(sine.position(0.0), Vec2::new(1.0, 1.0));
        assert!((sine.position(1.0) - Vec2::new(1.0, 3.0)).length() < 1e-6);
        let circle = Platform {
            motion: PlatformMotion::Circle {
                radius: 1.0,
                period: 4.0,
            },
            ..sine
        };
        assert_eq!(circle.position(0.0), Vec2::new(1.0, 1.0));
        assert!((circle.position(1.0) - Vec2::new(0.0, 2.0)).length() < 1e-6);
    }
}

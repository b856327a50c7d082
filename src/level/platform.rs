//! Moving platforms: a box and a motion that is a function of time only, so every backend sees
//! the same platform at the same frame.

use glam::{DVec2, I64Vec2, Vec2};

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
            PlatformMotion::Waypoints { points, speed } => {
                // No allocation: this runs every step.
                let seg = |w: &[Vec2]| (w[1].as_dvec2() - w[0].as_dvec2()).length();
                let length: f64 = points.windows(2).map(seg).sum();
                if length <= 0.0 {
                    return self.start;
                }
                let mut s = (*speed as f64 * t).rem_euclid(2.0 * length);
                if s > length {
                    s = 2.0 * length - s;
                }
                let mut at = start;
                for w in points.windows(2) {
                    let (a, b) = (w[0].as_dvec2(), w[1].as_dvec2());
                    let len = (b - a).length();
                    if s <= len {
                        at = a + (b - a) * (s / len);
                        break;
                    }
                    s -= len;
                    at = b;
                }
                at
            }
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
        let p = self.position(t);
        parry2d::bounding_volume::Aabb::new(p, p + self.size)
    }

    /// Its box at time `t` on a grid of `per_tile` subpixels per tile, in level subpixels
    /// (min, max): the lower-left corner is [`Platform::position`] rounded to the nearest
    /// subpixel and the size rounded to whole subpixels (at least one). The motion stays a
    /// function of time: a step's move is the difference of two rounded positions, so the
    /// rounding never accumulates (Celeste's solids move a whole pixel at a time, their
    /// remainder carried).
    pub fn grid_box(&self, t: f64, per_tile: i64) -> (I64Vec2, I64Vec2) {
        let n = per_tile as f64;
        let min = (self.position(t).as_dvec2() * n).round().as_i64vec2();
        let size = (self.size.as_dvec2() * n)
            .round()
            .as_i64vec2()
            .max(I64Vec2::ONE);
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

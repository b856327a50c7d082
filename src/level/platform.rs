//! Moving platforms: a box and a motion that is a function of time only, so every backend sees
//! the same platform at the same frame.

use glam::{DVec2, Vec2};

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

    /// The platform's box at time `t`.
    pub fn aabb(&self, t: f64) -> parry2d::bounding_volume::Aabb {
        let p = self.position(t);
        parry2d::bounding_volume::Aabb::new(p, p + self.size)
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

//! Shared motion: the game's rules that turn per-frame input into a velocity.
//!
//! Both backends run exactly this code, so a difference between their traces comes from
//! collision handling alone. It follows the seed slides: forces go into an accumulator that
//! is cleared after each integration, and integration is symplectic Euler (velocity first,
//! then position from the new velocity). Positions are not integrated here: the caller gets
//! the desired displacement `v * dt` and hands it to its collision resolution.

use glam::Vec2;
use serde::Deserialize;

/// How the jump impulse is solved from [`MotionParams::jump_height`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JumpMode {
    /// The seed's formula `v = sqrt(2 g h)`: exact for continuous motion, but symplectic Euler
    /// at a finite step undershoots the apex by about `v * dt / 2`.
    Continuous,
    /// The impulse whose apex under symplectic Euler at the run's `dt` is exactly the
    /// requested height (see [`jump_speed`]).
    ExactDiscrete,
}

impl JumpMode {
    /// Short label used in configs and CSV files.
    pub fn label(self) -> &'static str {
        match self {
            JumpMode::Continuous => "continuous",
            JumpMode::ExactDiscrete => "exact-discrete",
        }
    }
}

/// The game's movement rules, shared by every backend. All lengths are in tiles, times in
/// seconds.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionParams {
    /// Magnitude of gravity, in tiles/s², pulling toward -y.
    pub gravity: f32,
    /// Horizontal speed the character runs at while left or right is held, in tiles/s.
    pub run_speed: f32,
    /// Rate at which the horizontal speed approaches the run speed while a direction is held,
    /// in tiles/s².
    pub run_accel: f32,
    /// Height of a jump, in tiles, from the feet at take-off to the feet at the apex.
    pub jump_height: f32,
    /// How the jump impulse is solved from `jump_height`.
    pub jump_mode: JumpMode,
    /// The seed's friction on a vertical contact (ground or ceiling): the horizontal velocity
    /// is multiplied by this factor (dimensionless, 0..=1) on each frame with such a contact
    /// and no horizontal input. Input drives the feet, so friction only stops a character
    /// that is not being steered.
    pub ground_friction: f32,
    /// Horizontal speed below which ground friction stops a character with no horizontal
    /// input, in tiles/s: its velocity becomes exactly 0. Multiplying by `ground_friction`
    /// alone only halves the speed forever (2e-17 tiles/s minutes later), and a controller that
    /// reads any horizontal velocity as intent keeps moving on it: Rapier's slope rule tests
    /// only the sign of the desired move, so a vanishing downhill speed lets gravity slide the
    /// character down a ramp. Default 0.01 tiles/s: 1/6000 of a tile per 60 Hz frame, a pixel
    /// of a 16-pixel tile every 6 seconds.
    pub stop_speed: f32,
    /// The seed's friction on a horizontal contact (a wall): the vertical velocity is
    /// multiplied by this factor (dimensionless, 0..=1) on each frame with such a contact.
    /// 1 means no wall drag.
    pub wall_friction: f32,
    /// Steepest ground the character can walk up, in radians from horizontal: steeper slopes
    /// block. Rapier's climb and slide angles are set from it.
    pub max_climb_angle: f32,
    /// Climbing speed on a ladder, in tiles/s.
    pub ladder_speed: f32,
}

impl Default for MotionParams {
    fn default() -> Self {
        MotionParams {
            gravity: 30.0,
            run_speed: 6.0,
            run_accel: 60.0,
            jump_height: 3.0,
            jump_mode: JumpMode::ExactDiscrete,
            ground_friction: 0.5,
            stop_speed: 0.01,
            wall_friction: 1.0,
            max_climb_angle: std::f32::consts::FRAC_PI_4,
            ladder_speed: 4.0,
        }
    }
}

/// A motion parameter out of its range: its name, its value and what was expected (a
/// controller's build reports it as [`crate::backend::BackendError::InvalidParameter`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid parameter {name} = {value}: {expected}")]
pub struct InvalidParam {
    /// Parameter name.
    pub name: &'static str,
    /// Its value, printed.
    pub value: String,
    /// What was expected.
    pub expected: &'static str,
}

impl MotionParams {
    /// Checks every parameter against its meaning: finite, not negative, within the ranges of
    /// [`crate::limits`] (gravity and run acceleration to 1e5 tiles/s², speeds to 1e4 tiles/s,
    /// the jump height to 1e4 tiles), frictions within 0..=1, the climb angle within 0..90
    /// degrees.
    pub fn validate(&self) -> Result<(), InvalidParam> {
        use crate::limits::{MAX_ACCEL, MAX_JUMP_HEIGHT, MAX_SPEED};
        let invalid = |name: &'static str, value: f32, expected: &'static str| InvalidParam {
            name,
            value: format!("{value:?}"),
            expected,
        };
        let non_negative = [
            (
                "gravity",
                self.gravity,
                MAX_ACCEL,
                "a number 0..=1e5 (tiles/s²)",
            ),
            (
                "run_speed",
                self.run_speed,
                MAX_SPEED,
                "a number 0..=1e4 (tiles/s)",
            ),
            (
                "run_accel",
                self.run_accel,
                MAX_ACCEL,
                "a number 0..=1e5 (tiles/s²)",
            ),
            (
                "jump_height",
                self.jump_height,
                MAX_JUMP_HEIGHT,
                "a number 0..=1e4 (tiles)",
            ),
            (
                "ladder_speed",
                self.ladder_speed,
                MAX_SPEED,
                "a number 0..=1e4 (tiles/s)",
            ),
            (
                "stop_speed",
                self.stop_speed,
                MAX_SPEED,
                "a number 0..=1e4 (tiles/s)",
            ),
        ];
        for (name, v, max, expected) in non_negative {
            if !(v.is_finite() && v >= 0.0 && v as f64 <= max) {
                return Err(invalid(name, v, expected));
            }
        }
        for (name, v) in [
            ("ground_friction", self.ground_friction),
            ("wall_friction", self.wall_friction),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return Err(invalid(name, v, "a factor between 0 and 1"));
            }
        }
        if !(self.max_climb_angle >= 0.0 && self.max_climb_angle < std::f32::consts::FRAC_PI_2) {
            return Err(invalid(
                "max_climb_angle",
                self.max_climb_angle,
                "an angle in radians, 0 <= angle < pi/2",
            ));
        }
        Ok(())
    }
}

/// The buttons held during one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Input {
    /// Run toward -x.
    pub left: bool,
    /// Run toward +x.
    pub right: bool,
    /// Climb (ladders).
    pub up: bool,
    /// Descend (ladders, dropping through one-way platforms).
    pub down: bool,
    /// Jump; the impulse fires on the frame the button goes down while grounded.
    pub jump: bool,
}

impl Input {
    /// The horizontal direction asked for: -1, 0 or 1 (left and right together cancel).
    pub fn horizontal(&self) -> f32 {
        (self.right as i32 - self.left as i32) as f32
    }
}

/// Which axes were blocked during a move, as reported by a backend's collision resolution.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Contacts {
    /// The horizontal move was stopped by a wall.
    pub wall: bool,
    /// The vertical move was stopped by something below (the character stands on it).
    pub ground: bool,
    /// The vertical move was stopped by something above.
    pub ceiling: bool,
    /// The ground is a one-way platform (which down + jump drops through).
    pub one_way: bool,
}

/// Per-character motion state: velocity, the force accumulator and what the previous frame
/// left behind (grounded, jump button).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionState {
    /// Velocity in tiles/s.
    pub vel: Vec2,
    /// Force accumulator (unit mass, so tiles/s²), cleared after every integration.
    pub force: Vec2,
    /// Whether the last move ended standing on something.
    pub grounded: bool,
    /// Whether jump was held on the previous frame (jumps fire on the press, not the hold).
    pub jump_held: bool,
    /// Whether the ground under the character is a one-way platform.
    pub on_one_way: bool,
    /// Set for the step in which down + jump asked to drop through the one-way platform under
    /// the character: the backend ignores one-way platforms during that step.
    pub drop_through: bool,
    /// The seed's ladder state: no gravity, no horizontal move, only climbing.
    pub on_ladder: bool,
}

impl MotionState {
    /// A character at rest with the given initial velocity.
    pub fn with_velocity(vel: Vec2) -> Self {
        MotionState {
            vel,
            ..Default::default()
        }
    }

    /// Adds a force (tiles/s², unit mass) to the accumulator for this frame.
    pub fn add_force(&mut self, f: Vec2) {
        self.force += f;
    }

    /// Applies input, the jump impulse and gravity, integrates the velocity (symplectic
    /// Euler: velocity first) and returns the displacement the character wants to make this
    /// frame, `v * dt`, for the backend to resolve against the level.
    pub fn integrate(&mut self, p: &MotionParams, input: &Input, dt: f32) -> Vec2 {
        let pressed = input.jump && !self.jump_held;
        if self.on_ladder {
            if pressed {
                // The seed: leave the ladder when the player hits jump. The jump then takes off
                // as from the ground, so its apex is the same.
                self.on_ladder = false;
                self.vel = Vec2::ZERO;
                self.grounded = true;
            } else {
                // On the ladder: no gravity, no left or right, only up and down at ladder speed.
                self.jump_held = input.jump;
                self.drop_through = false;
                self.force = Vec2::ZERO;
                let climb = (input.up as i32 - input.down as i32) as f32;
                self.vel = Vec2::new(0.0, p.ladder_speed * climb);
                return self.vel * dt;
            }
        }
        let dir = input.horizontal();
        if dir != 0.0 {
            self.vel.x = approach(self.vel.x, dir * p.run_speed, p.run_accel * dt);
        }
        self.jump_held = input.jump;
        self.drop_through = false;
        if pressed && self.grounded {
            if input.down && self.on_one_way {
                // Down + jump on a one-way platform drops through it instead of jumping.
                self.drop_through = true;
            } else {
                // The seed: "just apply impulse to velocity".
                self.vel.y += jump_speed(p, dt);
            }
            self.grounded = false;
        }
        self.add_force(Vec2::new(0.0, -p.gravity));
        self.vel += self.force * dt;
        self.force = Vec2::ZERO;
        self.vel * dt
    }

    /// Applies what the backend's move ran into: a blocked axis loses its velocity and the
    /// other axis gets the seed's friction constant. As with friction, held input keeps
    /// driving the feet: a wall stops a character that coasts into it, while one that is
    /// steered into it keeps its run speed (and is blocked again next frame).
    pub fn apply_contacts(&mut self, p: &MotionParams, input: &Input, c: Contacts) {
        if c.wall {
            if input.horizontal() * self.vel.x <= 0.0 {
                self.vel.x = 0.0;
            }
            self.vel.y *= p.wall_friction;
        }
        if c.ground || c.ceiling {
            self.vel.y = 0.0;
            if input.horizontal() == 0.0 {
                self.vel.x *= p.ground_friction;
                if self.vel.x.abs() < p.stop_speed {
                    self.vel.x = 0.0;
                }
            }
        }
        self.grounded = c.ground;
        self.on_one_way = c.ground && c.one_way;
    }
}

/// Moves `v` toward `target` by at most `max_delta`.
fn approach(v: f32, target: f32, max_delta: f32) -> f32 {
    if v < target {
        (v + max_delta).min(target)
    } else {
        (v - max_delta).max(target)
    }
}

/// The vertical speed the jump impulse gives, for the params' jump mode at step `dt`.
pub fn jump_speed(p: &MotionParams, dt: f32) -> f32 {
    match p.jump_mode {
        JumpMode::Continuous => (2.0 * p.gravity * p.jump_height).sqrt(),
        JumpMode::ExactDiscrete => exact_discrete_jump_speed(p.gravity, p.jump_height, dt),
    }
}

/// The take-off speed whose apex under symplectic Euler is exactly `h`.
///
/// With the impulse applied before gravity in the take-off frame, after `n` steps the feet have
/// risen `n v dt - g dt² n(n+1)/2`. The rise grows while `v - k g dt > 0`, so the apex is
/// reached after `N = floor(v / (g dt))` steps and equals `N v dt - g dt² N(N+1)/2`. That is
/// continuous and increasing in `v`, so for the `N` with `g dt² N(N-1)/2 <= h < g dt² N(N+1)/2`
/// the speed is `v = (h + g dt² N(N+1)/2) / (N dt)`. Solved in f64, then rounded to f32.
pub(crate) fn exact_discrete_jump_speed(g: f32, h: f32, dt: f32) -> f32 {
    let (g, h, dt) = (g as f64, h as f64, dt as f64);
    if h <= 0.0 || g <= 0.0 || dt <= 0.0 {
        return 0.0;
    }
    let step = g * dt * dt;
    // Largest N with step*N(N-1)/2 <= h, from the quadratic, then corrected for rounding.
    let mut n = ((1.0 + (1.0 + 8.0 * h / step).sqrt()) / 2.0)
        .floor()
        .max(1.0);
    // The estimate is within a step or two of N; the corrections are bounded, since above
    // 2^53 `n + 1.0 == n` and an unbounded `n += 1.0` would never end (jump_height = 1e30).
    for _ in 0..4 {
        if n > 1.0 && step * n * (n - 1.0) / 2.0 > h {
            n -= 1.0;
        }
    }
    for _ in 0..4 {
        if step * (n + 1.0) * n / 2.0 <= h {
            n += 1.0;
        }
    }
    ((h + step * n * (n + 1.0) / 2.0) / (n * dt)) as f32
}

/// The apex (feet rise) that symplectic Euler reaches from take-off speed `v`: the reference
/// the `apex_error` metric and the tests compare against.
pub fn discrete_apex(g: f32, v: f32, dt: f32) -> f64 {
    let (g, v, dt) = (g as f64, v as f64, dt as f64);
    let n = (v / (g * dt)).floor();
    n * v * dt - g * dt * dt * n * (n + 1.0) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates a jump with the same f32 arithmetic the backends use and returns the apex.
    fn simulate_apex(p: &MotionParams, dt: f32) -> f32 {
        let mut s = MotionState {
            grounded: true,
            ..Default::default()
        };
        let jump = Input {
            jump: true,
            ..Default::default()
        };
        let (mut y, mut apex) = (0.0f32, 0.0f32);
        for _ in 0..10_000 {
            y += s.integrate(p, &jump, dt).y;
            apex = apex.max(y);
            if s.vel.y < 0.0 {
                break;
            }
        }
        apex
    }

    #[test]
    fn exact_discrete_apex_matches_requested_height() {
        for &dt in &[1.0 / 30.0, 1.0 / 60.0, 1.0 / 144.0, 1.0 / 480.0] {
            for h in [0.25f32, 1.0, 2.0, 3.0, 4.5, 6.0] {
                let p = MotionParams {
                    jump_height: h,
                    ..Default::default()
                };
                let apex = simulate_apex(&p, dt);
                // Bound: f32 accumulation of up to ~300 increments near y ~ 6 tiles, each
                // rounded to half an ulp (~2.4e-7), stays far below the exact jump's 1e-4 bound on
                // apex_error (tests/behaviour/sweep_builtin.rs).
                assert!((apex - h).abs() < 1e-4, "dt {dt} h {h}: apex {apex}");
            }
        }
    }

    #[test]
    fn absurd_jump_heights_end_instead_of_looping() {
        // 1e30 tiles once looped forever (`n += 1.0` stalls above 2^53); now it ends with a
        // finite speed, and validation refuses such a height before any run.
        let v = exact_discrete_jump_speed(30.0, 1e30, 1.0 / 60.0);
        assert!(v.is_finite() && v > 0.0, "{v}");
        let p = MotionParams {
            jump_height: 1e30,
            ..Default::default()
        };
        assert!(p.validate().is_err());
    }

    #[test]
    fn continuous_formula_undershoots_by_about_half_a_step() {
        let p = MotionParams {
            jump_mode: JumpMode::Continuous,
            ..Default::default()
        };
        let dt = 1.0 / 60.0;
        let v = jump_speed(&p, dt);
        let err = simulate_apex(&p, dt) - p.jump_height;
        // Symplectic Euler loses between 0 and v*dt of height (the discrete sum vs the
        // integral); the analytic discrete apex must agree with the simulation to f32 noise.
        assert!(err < 0.0 && err > -v * dt, "err {err}");
        let analytic = discrete_apex(p.gravity, v, dt) - p.jump_height as f64;
        assert!((analytic - err as f64).abs() < 1e-4);
    }

    #[test]
    fn accumulator_is_cleared_after_integration() {
        let mut s = MotionState::default();
        s.add_force(Vec2::new(5.0, 0.0));
        let p = MotionParams::default();
        s.integrate(&p, &Input::default(), 0.1);
        assert_eq!(s.force, Vec2::ZERO);
        // Symplectic: velocity updated first (5 - 30) * 0.1 per axis.
        assert!((s.vel.x - 0.5).abs() < 1e-6 && (s.vel.y + 3.0).abs() < 1e-6);
    }

    #[test]
    fn jump_fires_on_press_only_when_grounded() {
        let p = MotionParams::default();
        let jump = Input {
            jump: true,
            ..Default::default()
        };
        let mut airborne = MotionState::default();
        airborne.integrate(&p, &jump, 1.0 / 60.0);
        assert!(airborne.vel.y < 0.0, "no jump in the air");
        let mut held = MotionState {
            grounded: true,
            jump_held: true,
            ..Default::default()
        };
        held.integrate(&p, &jump, 1.0 / 60.0);
        assert!(held.vel.y < 0.0, "holding jump does not re-fire");
    }

    #[test]
    fn a_wall_stops_a_coasting_character_but_not_a_steered_one() {
        let p = MotionParams::default();
        let wall = Contacts {
            wall: true,
            ..Default::default()
        };
        let mut coasting = MotionState::with_velocity(Vec2::new(-1000.0, 0.0));
        coasting.apply_contacts(&p, &Input::default(), wall);
        assert_eq!(coasting.vel.x, 0.0);
        let left = Input {
            left: true,
            ..Default::default()
        };
        let mut steered = MotionState::with_velocity(Vec2::new(-6.0, 0.0));
        steered.apply_contacts(&p, &left, wall);
        assert_eq!(steered.vel.x, -6.0);
        let mut reversing = MotionState::with_velocity(Vec2::new(6.0, 0.0));
        reversing.apply_contacts(&p, &left, wall);
        assert_eq!(reversing.vel.x, 0.0);
    }

    #[test]
    fn friction_applies_only_without_input() {
        let p = MotionParams::default();
        let ground = Contacts {
            ground: true,
            ..Default::default()
        };
        let mut s = MotionState::with_velocity(Vec2::new(4.0, -1.0));
        s.apply_contacts(&p, &Input::default(), ground);
        assert_eq!(s.vel, Vec2::new(4.0 * p.ground_friction, 0.0));
        let mut driven = MotionState::with_velocity(Vec2::new(4.0, -1.0));
        let right = Input {
            right: true,
            ..Default::default()
        };
        driven.apply_contacts(&p, &right, ground);
        assert_eq!(driven.vel, Vec2::new(4.0, 0.0));
    }

    #[test]
    fn friction_brings_a_coasting_character_to_rest() {
        let p = MotionParams::default();
        let ground = Contacts {
            ground: true,
            ..Default::default()
        };
        let mut s = MotionState::with_velocity(Vec2::new(p.run_speed, 0.0));
        // Halving from 6 tiles/s passes below 0.01 tiles/s after log2(600) = 9.2 frames.
        for _ in 0..10 {
            s.apply_contacts(&p, &Input::default(), ground);
        }
        assert_eq!(s.vel.x, 0.0);
        // Without the stop speed the same frames leave a speed that never reaches 0.
        let mut halving = MotionState::with_velocity(Vec2::new(p.run_speed, 0.0));
        let no_stop = MotionParams {
            stop_speed: 0.0,
            ..p.clone()
        };
        // 100 halvings: 6 * 2^-100 = 5e-30, still a normal f32 (below 2^-149 it would be 0).
        for _ in 0..100 {
            halving.apply_contacts(&no_stop, &Input::default(), ground);
        }
        assert!(halving.vel.x > 0.0, "{}", halving.vel.x);
    }
}

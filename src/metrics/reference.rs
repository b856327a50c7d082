//! Analytic references for the metrics: what the shared motion model predicts with no
//! collision error, computed in f64.

use std::borrow::Borrow;

use crate::motion::{Input, MotionParams};

/// The first step count `n >= 1` after which a body dropped from `height` above the ground
/// with initial vertical speed `vy0` has reached the ground under symplectic Euler:
/// `vy0 n dt - g dt² n(n+1)/2 <= -height`. `None` if it never does.
pub fn predicted_landing_frame(height: f64, vy0: f64, g: f64, dt: f64) -> Option<usize> {
    if g <= 0.0 || dt <= 0.0 || !height.is_finite() {
        return None;
    }
    // Solve the quadratic for the real root, then correct for rounding.
    let a = g * dt * dt / 2.0;
    let b = a - vy0 * dt;
    let n_real = (-b + (b * b + 4.0 * a * height).sqrt()) / (2.0 * a);
    let mut n = n_real.floor().max(1.0) as usize;
    let drop = |n: usize| -(vy0 * dt * n as f64) + a * (n * (n + 1)) as f64;
    while n > 1 && drop(n - 1) >= height {
        n -= 1;
    }
    while drop(n) < height {
        n += 1;
        if n > 100_000_000 {
            return None;
        }
    }
    Some(n)
}

/// Horizontal distance the shared motion model commands over the script, on flat ground with no
/// obstacle: the run acceleration while a direction is held, the ground friction otherwise.
pub fn commanded_distance(
    p: &MotionParams,
    script: impl IntoIterator<Item = impl Borrow<Input>>,
    vx0: f32,
    dt: f32,
) -> f64 {
    commanded_steps(p, script, vx0, dt).sum()
}

/// The horizontal displacement the shared motion model commands at each step of the script,
/// on flat ground with no obstacle (see [`commanded_distance`]), computed as it is read.
pub fn commanded_steps<I: IntoIterator<Item = impl Borrow<Input>>>(
    p: &MotionParams,
    script: I,
    vx0: f32,
    dt: f32,
) -> impl Iterator<Item = f64> {
    let (mut vx, dt) = (vx0 as f64, dt as f64);
    let (run_speed, run_accel, friction) = (
        p.run_speed as f64,
        p.run_accel as f64,
        p.ground_friction as f64,
    );
    script.into_iter().map(move |i| {
        let dir = i.borrow().horizontal() as f64;
        if dir != 0.0 {
            let target = dir * run_speed;
            let step = run_accel * dt;
            vx = if vx < target {
                (vx + step).min(target)
            } else {
                (vx - step).max(target)
            };
        }
        let d = vx * dt;
        if dir == 0.0 {
            vx *= friction;
        }
        d
    })
}

/// An iterator read forward by index: `get(k)` is its `k`-th item, for `k` never below the one
/// asked last (a metric walking the frames forward reads the commanded steps as it goes).
pub(crate) struct Cursor<I: Iterator> {
    it: I,
    next: usize,
    last: Option<I::Item>,
}

impl<I: Iterator> Cursor<I>
where
    I::Item: Copy,
{
    /// A cursor before the first item.
    pub fn new(it: I) -> Self {
        Cursor {
            it,
            next: 0,
            last: None,
        }
    }

    /// Item `k`, or `None` past the end. Panics if `k` is below the item asked last.
    pub fn get(&mut self, k: usize) -> Option<I::Item> {
        assert!(
            k + 1 >= self.next,
            "item {k} read after item {}",
            self.next - 1
        );
        while self.next <= k {
            self.last = self.it.next();
            self.next += 1;
        }
        self.last
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn landing_frame_for_a_drop() {
        // g dt² = 30/3600; n(n+1)/2 * 30/3600 >= 0.1 first holds at n = 5 (15 * 0.00833 = 0.125).
        assert_eq!(predicted_landing_frame(0.1, 0.0, 30.0, 1.0 / 60.0), Some(5));
        // Exactly on a boundary: 1 step of a 1-unit/step² fall reaches 1.0.
        assert_eq!(predicted_landing_frame(1.0, 0.0, 2.0, 1.0), Some(1));
        assert_eq!(predicted_landing_frame(1.0, 0.0, 0.0, 1.0), None);
    }

    #[test]
    fn commanded_walk() {
        let p = MotionParams::default();
        let right = Input {
            right: true,
            ..Default::default()
        };
        let script = vec![right; 600];
        let d = commanded_distance(&p, &script, 0.0, 1.0 / 60.0);
        // 10 s at 6 tiles/s, minus the ramp-up: accel 60 t/s² reaches 6 t/s in 0.1 s (6
        // frames), losing sum_{k=1..6} (6 - k) / 60 = 15/60 = 0.25 tiles against full speed.
        // Tolerance: dt is the f32 nearest 1/60, 6.6e-10 s too long, over 3,585 tile-frames.
        assert!((d - (60.0 - 0.25)).abs() < 1e-5, "{d}");
    }
}

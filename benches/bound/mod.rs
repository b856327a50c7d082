//! The bound: the seed's model with nothing in it but what a walk on a floor needs. A direct
//! tile-grid x-then-y AABB sweep (no broadphase structure, no slopes, one-way boxes, ladders or
//! platforms), the same character, gravity, run speed and step as the built-in scenarios,
//! walking back and forth on a floor under gravity. What one character step of the sweep costs
//! on a built-in scenario is reported as a ratio to this step (see [`ratios`]).

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::Criterion;

pub mod ratios;

/// A grid of solid tiles, row 0 at the bottom (y up, one unit per tile).
pub struct Grid {
    width: usize,
    height: usize,
    solid: Vec<bool>,
}

impl Grid {
    /// A `width` x `height` map whose bottom row is solid: the floor of the walk.
    pub fn floor(width: usize, height: usize) -> Self {
        let mut solid = vec![false; width * height];
        solid[..width].fill(true);
        Grid {
            width,
            height,
            solid,
        }
    }

    /// Whether tile `(x, y)` is solid; outside the map is empty.
    fn at(&self, x: i64, y: i64) -> bool {
        x >= 0
            && y >= 0
            && (x as usize) < self.width
            && (y as usize) < self.height
            && self.solid[y as usize * self.width + x as usize]
    }
}

/// The seed's epsilon: a box snapped flush stops this far short of the tile it hit (tiles).
const EPS: f32 = 1e-4;

/// A character box: bottom-left corner and size (tiles), velocity (tiles/s).
pub struct Body {
    pub min: [f32; 2],
    pub size: [f32; 2],
    pub vel: [f32; 2],
    pub grounded: bool,
}

/// The first solid tile column (or row) a box edge moving from `from` to `to` along an axis
/// enters, scanning the tiles `lo..=hi` across it; `None` if the move is free.
fn first_hit(g: &Grid, along_x: bool, from: f32, to: f32, lo: f32, hi: f32) -> Option<i64> {
    let (a, b) = (lo.floor() as i64, (hi - EPS).floor() as i64);
    let (start, end) = (from.floor() as i64, to.floor() as i64);
    let step: i64 = if to > from { 1 } else { -1 };
    let mut t = start;
    loop {
        for s in a..=b {
            let hit = if along_x { g.at(t, s) } else { g.at(s, t) };
            if hit && t != start {
                return Some(t);
            }
        }
        if t == end {
            return None;
        }
        t += step;
    }
}

/// One step of `dt` seconds: gravity into velocity (symplectic Euler), then the x move, then
/// the y move, each swept through the grid and snapped flush on a hit.
pub fn step(g: &Grid, b: &mut Body, dir: f32, gravity: f32, speed: f32, dt: f32) {
    b.vel[0] = dir * speed;
    b.vel[1] -= gravity * dt;
    for axis in 0..2 {
        let d = b.vel[axis] * dt;
        if d == 0.0 {
            continue;
        }
        let other = 1 - axis;
        let (lo, hi) = (b.min[other], b.min[other] + b.size[other]);
        // The leading edge: the right (top) side moving +, the left (bottom) side moving -.
        let edge = if d > 0.0 {
            b.min[axis] + b.size[axis] - EPS
        } else {
            b.min[axis] + EPS
        };
        match first_hit(g, axis == 0, edge, edge + d, lo, hi) {
            Some(t) => {
                b.min[axis] = if d > 0.0 {
                    t as f32 - b.size[axis] - EPS
                } else {
                    t as f32 + 1.0 + EPS
                };
                b.vel[axis] = 0.0;
                if axis == 1 {
                    b.grounded = d < 0.0;
                }
            }
            None => {
                b.min[axis] += d;
                if axis == 1 {
                    b.grounded = false;
                }
            }
        }
    }
}

/// Benches the bound on a floor 2,200 and 1.1 million tiles large: the character walks right
/// for two seconds, then left for two, on the level's default character, gravity, run speed
/// and 60 Hz step.
pub fn bench(c: &mut Criterion) {
    check();
    let params = platbench::motion::MotionParams::default();
    let size = platbench::level::DEFAULT_CHARACTER_SIZE;
    let dt = 1.0 / 60.0;
    let mut group = c.benchmark_group("bound");
    for (name, w, h) in [("floor_2200", 220, 10), ("floor_1100000", 11_000, 100)] {
        let grid = Grid::floor(w, h);
        group.bench_function(name, |bench| {
            bench.iter_custom(|iters| {
                let mut body = Body {
                    min: [w as f32 / 2.0, 1.0 + EPS],
                    size: [size.x, size.y],
                    vel: [0.0, 0.0],
                    grounded: true,
                };
                let start = Instant::now();
                for i in 0..iters {
                    // Two seconds each way (120 steps), so the walk stays on the floor.
                    let dir = if (i / 120) % 2 == 0 { 1.0 } else { -1.0 };
                    step(
                        black_box(&grid),
                        &mut body,
                        dir,
                        params.gravity,
                        params.run_speed,
                        dt,
                    );
                }
                let t: Duration = start.elapsed();
                black_box(&body);
                t
            });
        });
    }
    group.finish();
}

/// Checks the bound before it is timed, so a broken bound cannot flatter the sweep's ratio: on a
/// floor with a wall tile, the character lands, walks right and stops flush against the wall.
/// Panics (ending the bench run) if it does not.
fn check() {
    let mut g = Grid::floor(10, 4);
    g.solid[g.width + 8] = true; // a wall tile at (8, 1)
    let mut b = Body {
        min: [2.0, 1.5],
        size: [0.8, 0.9],
        vel: [0.0, 0.0],
        grounded: false,
    };
    for _ in 0..120 {
        step(&g, &mut b, 1.0, 30.0, 6.0, 1.0 / 60.0);
    }
    // Feet on the floor's top (y = 1), right side flush with the wall's left side (x = 8), to
    // within the seed's epsilon and f32 rounding (1e-3 tiles).
    let on_floor = b.grounded && (b.min[1] - 1.0).abs() < 1e-3;
    let at_wall = (b.min[0] + 0.8 - 8.0).abs() < 1e-3;
    assert!(
        on_floor && at_wall,
        "the bound's sweep is wrong: {:?}",
        b.min
    );
}

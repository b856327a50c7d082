//! How a step's cost scales (criterion): with the number of characters on one level (1 to
//! 10,000), and with the level's size (1e3 to 1e6 tiles) for a fixed 10 characters. Reported per
//! character-step (criterion's throughput in elements), for every registered backend's stress
//! configurations. Benches measure; no test asserts a time.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec2;
use platbench::backend::{Backend, CharacterSpec};
use platbench::config::RunConfig;
use platbench::level::{Level, Tile};
use platbench::motion::Input;
use platbench::registry::Registry;

/// A level of about `tiles` tiles, four times wider than high: a floor and solid blocks at 10%
/// density above it (a fixed pseudo-random pattern, so every run builds the same level).
fn level(tiles: usize) -> Level {
    let h = ((tiles as f64 / 4.0).sqrt() as u32).max(4);
    let w = (tiles as u32 / h).max(8);
    let mut t = vec![Tile::Empty; (w * h) as usize];
    let mut seed: u32 = 12345;
    for j in 0..h {
        for i in 0..w {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let solid = j == 0 || (j >= 3 && j + 2 < h && (seed >> 24) < 26);
            if solid {
                t[(j * w + i) as usize] = Tile::Solid;
            }
        }
    }
    Level::from_tiles("scaling", w, h, t)
}

/// The backend of `run` over `level` with `characters` placed, built afresh.
fn backend(run: &RunConfig, level: &Level, characters: &[CharacterSpec]) -> Box<dyn Backend> {
    platbench::scenario::Runner::new(level)
        .build(run, &run.params, characters)
        .expect("every registered backend models a level of solid tiles")
}

/// The configurations to scale: every registered backend's stress configurations (the sweep,
/// integer positions, Rapier per tile and merged), named `backend label`.
fn configs() -> Vec<(String, RunConfig)> {
    let configs = Registry::builtin().stress_configs();
    assert!(!configs.is_empty());
    configs
        .into_iter()
        .map(|r| (format!("{} {}", r.backend.backend(), r.label), r))
        .collect()
}

/// Times steps of `n` characters walking right on the floor of `level`.
fn bench_steps(
    c: &mut Criterion,
    group: &str,
    (name, run): &(String, RunConfig),
    id: usize,
    level: &Level,
    n: usize,
) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    g.bench_with_input(BenchmarkId::new(name.as_str(), id), &n, |b, &n| {
        let inputs = vec![
            Input {
                right: true,
                ..Default::default()
            };
            n
        ];
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            let mut left = iters;
            while left > 0 {
                let walkers: Vec<CharacterSpec> = (0..n)
                    .map(|k| CharacterSpec {
                        spawn: Vec2::new(
                            1.5 + (k as f32 * 0.37) % (level.width as f32 - 60.0),
                            1.01,
                        ),
                        size: Vec2::new(0.8, 0.9),
                        velocity: Vec2::ZERO,
                    })
                    .collect();
                let mut be = backend(run, level, &walkers);
                // Up to 300 steps (5 s) per build: the walkers stay on the floor.
                let steps = left.min(300);
                let start = Instant::now();
                for _ in 0..steps {
                    be.step(black_box(&inputs), 1.0 / 60.0);
                }
                total += start.elapsed();
                left -= steps;
            }
            total
        });
    });
    g.finish();
}

fn characters(c: &mut Criterion) {
    let l = level(20_000);
    for config in &configs() {
        for n in [1usize, 10, 100, 1000, 10_000] {
            bench_steps(c, "scaling/characters", config, n, &l, n);
        }
    }
}

fn level_size(c: &mut Criterion) {
    for tiles in [1_000usize, 10_000, 100_000, 1_000_000] {
        let l = level(tiles);
        for config in &configs() {
            bench_steps(c, "scaling/level", config, tiles, &l, 10);
        }
    }
}

criterion_group!(benches, characters, level_size);
criterion_main!(benches);

//! Property tests (proptest) over random levels and random input scripts, on both backends:
//! nothing non-finite, the sweep never enters a solid beyond its epsilon nor tunnels, the same
//! inputs give the same bits, and the level parser never panics. Case counts are sized so the
//! whole file runs in well under a minute in CI's dev profile.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use glam::Vec2;
use platbench::config::RunConfig;
use platbench::level::{parse_level, InputEvent, Level, ScenarioSpec, Tile};
use platbench::metrics::evaluate;
use platbench::rapier::{CharacterShape, ColliderBuilding};
use platbench::sweep::SweepConfig;
use proptest::prelude::*;

/// A random level: a solid floor, then rows of random tiles; `slopes` adds 45-degree slopes.
fn level_strategy(slopes: bool) -> impl Strategy<Value = (u32, u32, Vec<u8>)> {
    (6u32..18, 5u32..10).prop_flat_map(move |(w, h)| {
        let kinds = if slopes { 0u8..12 } else { 0u8..10 };
        (
            Just(w),
            Just(h),
            proptest::collection::vec(kinds, (w * (h - 1)) as usize),
        )
    })
}

fn build(w: u32, h: u32, kinds: &[u8]) -> Level {
    let mut tiles = vec![Tile::Solid; w as usize];
    tiles.extend(kinds.iter().map(|k| match k {
        0..=5 => Tile::Empty,
        6 | 7 => Tile::Solid,
        8 => Tile::OneWay,
        9 => Tile::Ladder,
        10 => Tile::Slope(platbench::level::Slope::Line {
            left: 0.0,
            right: 1.0,
        }),
        _ => Tile::Slope(platbench::level::Slope::Line {
            left: 1.0,
            right: 0.0,
        }),
    }));
    Level::from_tiles("prop", w, h, tiles)
}

/// The first spawn (feet on a tile boundary) whose 0.8 x 0.9 box overlaps no tile of any kind.
fn spawn(level: &Level) -> Option<Vec2> {
    for j in 1..level.height as i64 {
        for i in 0..level.width as i64 {
            let free = |i: i64, j: i64| level.tile(i, j) == Tile::Empty;
            if free(i, j) {
                return Some(Vec2::new(i as f32 + 0.5, j as f32));
            }
        }
    }
    None
}

fn inputs() -> impl Strategy<Value = Vec<InputEvent>> {
    proptest::collection::vec((0u32..100, any::<[bool; 5]>()), 0..8).prop_map(|mut evs| {
        evs.sort_by_key(|(t, _)| *t);
        evs.into_iter()
            .map(|(t, b)| InputEvent {
                t: t as f32 * 0.1,
                left: Some(b[0]),
                right: Some(b[1]),
                up: Some(b[2]),
                down: Some(b[3]),
                jump: Some(b[4]),
            })
            .collect()
    })
}

fn scenario(at: Vec2, inputs: Vec<InputEvent>, seconds: f32) -> ScenarioSpec {
    ScenarioSpec {
        name: "p".into(),
        spawn: at,
        size: Vec2::new(0.8, 0.9),
        velocity: Vec2::ZERO,
        duration: seconds,
        dt: 1.0 / 60.0,
        inputs,
        motion: Default::default(),
        expect_y: None,
        ride: None,
        expect: Default::default(),
    }
}

fn runs() -> Vec<RunConfig> {
    vec![
        platbench::sweep::kind::run_default(),
        platbench::rapier::kind::run(ColliderBuilding::PerTile, CharacterShape::Capsule),
        platbench::rapier::kind::run(ColliderBuilding::Merged, CharacterShape::Cuboid),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// 1,200 steps (20 s) of random input on random solid/one-way/ladder levels.
    #[test]
    fn sweep_keeps_out_of_solids_and_every_backend_stays_finite_and_deterministic(
        (w, h, kinds) in level_strategy(false),
        script in inputs(),
    ) {
        let level = build(w, h, &kinds);
        let at = spawn(&level);
        prop_assume!(at.is_some());
        let spec = scenario(at.unwrap(), script, 20.0);
        for run in runs() {
            let a = evaluate(&level, &spec, &run).unwrap();
            for r in &a.trace.rows {
                prop_assert!(
                    [r.x, r.y, r.vx, r.vy].iter().all(|v| v.is_finite()),
                    "{}: non-finite at frame {}", run.label, r.frame
                );
            }
            let b = evaluate(&level, &spec, &run).unwrap();
            prop_assert!(a.trace.rows == b.trace.rows, "{}: two runs differ", run.label);
            if run.backend.backend() == "sweep" {
                let get = |m: &str| a.metrics.iter().find(|r| r.metric == m).unwrap().value;
                // The sweep's guarantees: no overlap with a solid beyond its epsilon, no tunneling.
                prop_assert!(get("max_penetration") <= SweepConfig::default().epsilon as f64,
                    "max_penetration {}", get("max_penetration"));
                prop_assert_eq!(get("tunneled"), 0.0);
            }
        }
    }

    /// Slopes too: finite and deterministic on both backends, no tunneling for the sweep.
    #[test]
    fn with_slopes_every_backend_stays_finite_and_deterministic(
        (w, h, kinds) in level_strategy(true),
        script in inputs(),
    ) {
        let level = build(w, h, &kinds);
        let at = spawn(&level);
        prop_assume!(at.is_some());
        let spec = scenario(at.unwrap(), script, 10.0);
        for run in runs() {
            let a = evaluate(&level, &spec, &run).unwrap();
            prop_assert!(a.trace.rows.iter().all(|r| r.x.is_finite() && r.y.is_finite()));
            let b = evaluate(&level, &spec, &run).unwrap();
            prop_assert!(a.trace.rows == b.trace.rows);
            if run.backend.backend() == "sweep" {
                let t = a.metrics.iter().find(|r| r.metric == "tunneled").unwrap().value;
                prop_assert_eq!(t, 0.0);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Arbitrary text is an error or a level, never a panic.
    #[test]
    fn the_parser_never_panics_on_text(text in "\\PC{0,300}") {
        let _ = parse_level(&text, "fuzz.toml");
    }

    /// Text shaped like a level (random map characters, random scenario numbers) too.
    #[test]
    fn the_parser_never_panics_on_level_like_text(
        rows in proptest::collection::vec("[#.=H/\\\\ xa]{0,12}", 0..6),
        spawn in (-1e9f64..1e9, -1e9f64..1e9),
        duration in proptest::num::f64::ANY,
        t in proptest::num::f64::ANY,
    ) {
        let text = format!(
            "map = \"\"\"\n{}\n\"\"\"\n[legend]\na = {{ line = [0.0, {t}] }}\n[[scenario]]\nname = \"s\"\nspawn = [{}, {}]\nduration = {duration}\ninputs = [ {{ t = {t}, jump = true }} ]\n",
            rows.join("\n"), spawn.0, spawn.1
        );
        let _ = parse_level(&text, "fuzz.toml");
    }
}

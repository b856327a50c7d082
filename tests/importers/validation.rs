//! Library calls with non-finite or out-of-range inputs return an error naming the parameter,
//! never a panic or a NaN trace.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use glam::Vec2;
use platbench::backend::{BackendError, CharacterSpec};
use platbench::level::{parse_level, Level, Tile};
use platbench::motion::MotionParams;
use platbench::rapier::{RapierBackend, RapierConfig};
use platbench::scenario::run_scenario;
use platbench::sweep::{SweepBackend, SweepConfig};

fn floor() -> Level {
    let mut t = vec![Tile::Solid; 4];
    t.extend(vec![Tile::Empty; 8]);
    Level::from_tiles("f", 4, 3, t)
}

fn named(e: BackendError, name: &str) {
    match e {
        BackendError::InvalidParameter { name: n, .. } => assert_eq!(n, name),
        other => panic!("expected {name} to be refused, got {other}"),
    }
}

/// A run the harness refuses before building anything: its own input error, not a controller's.
fn refused_input(e: platbench::scenario::RunError, name: &str) {
    match e {
        platbench::scenario::RunError::Input(p) => assert_eq!(p.name, name),
        other => panic!("expected {name} to be refused, got {other}"),
    }
}

#[test]
fn motion_parameters_are_checked_by_both_backends() {
    let bad = [
        (
            MotionParams {
                gravity: f32::NAN,
                ..Default::default()
            },
            "gravity",
        ),
        (
            MotionParams {
                run_speed: -1.0,
                ..Default::default()
            },
            "run_speed",
        ),
        (
            MotionParams {
                jump_height: f32::INFINITY,
                ..Default::default()
            },
            "jump_height",
        ),
        (
            MotionParams {
                ground_friction: 1.5,
                ..Default::default()
            },
            "ground_friction",
        ),
        (
            MotionParams {
                max_climb_angle: 2.0,
                ..Default::default()
            },
            "max_climb_angle",
        ),
    ];
    for (p, name) in bad {
        named(
            SweepBackend::new(&floor(), p.clone(), SweepConfig::default())
                .err()
                .unwrap(),
            name,
        );
        named(
            RapierBackend::new(&floor(), p, RapierConfig::default())
                .err()
                .unwrap(),
            name,
        );
    }
    let e = SweepBackend::new(
        &floor(),
        MotionParams::default(),
        SweepConfig {
            epsilon: f32::NAN,
            ..Default::default()
        },
    );
    named(e.err().unwrap(), "epsilon");
}

#[test]
fn characters_and_time_steps_are_checked() {
    let spec = |spawn: Vec2, size: Vec2| CharacterSpec {
        spawn,
        size,
        velocity: Vec2::ZERO,
    };
    let mut b =
        SweepBackend::new(&floor(), MotionParams::default(), SweepConfig::default()).unwrap();
    named(
        b.add_character(spec(Vec2::new(f32::NAN, 1.0), Vec2::ONE))
            .unwrap_err(),
        "spawn",
    );
    named(
        b.add_character(spec(Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)))
            .unwrap_err(),
        "size",
    );
    let mut r =
        RapierBackend::new(&floor(), MotionParams::default(), RapierConfig::default()).unwrap();
    named(
        r.add_character(spec(Vec2::new(1.0, f32::INFINITY), Vec2::ONE))
            .unwrap_err(),
        "spawn",
    );
    let level = parse_level(
        "map = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\n",
        "v.toml",
    )
    .unwrap();
    let mut spec = level.scenarios[0].clone();
    spec.dt = 0.0;
    refused_input(
        run_scenario(&level, &spec, &platbench::sweep::kind::run_default()).unwrap_err(),
        "dt",
    );
    spec.dt = f32::NAN;
    refused_input(
        run_scenario(&level, &spec, &platbench::sweep::kind::run_default()).unwrap_err(),
        "dt",
    );
}

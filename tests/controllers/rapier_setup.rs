//! How the Rapier backend is set up, each choice checked where it shows: characters come to
//! rest, spawns start clear of the offset band, the grounded step's vertical move is a setting
//! with the effects its documentation claims, the platform order is the better of the two
//! measured, and `autostep` reaches the controller.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{builtin_levels, evaluate_all, level, rows, value};
use glam::Vec2;
use platbench::backend::CharacterSpec;
use platbench::config::RunConfig;
use platbench::level::{Level, Tile};
use platbench::metrics::Evaluation;
use platbench::motion::{Input, MotionParams};
use platbench::rapier::{
    CharacterShape, ColliderBuilding, GroundedMove, Length, PlatformCarry, PlatformOrder,
    RapierBackend, RapierConfig,
};
use platbench::sweep::SweepConfig;
use rapier2d::prelude::ColliderBuilder;

/// Largest distance the character moves over the last second of a trace, in tiles.
fn last_second_motion(e: &Evaluation) -> f32 {
    let rows = &e.trace.rows;
    let last = rows.last().expect("a trace has rows");
    let from = rows.iter().rev().take_while(|r| last.t - r.t <= 1.0 + 1e-4);
    from.map(|r| Vec2::new(r.x - last.x, r.y - last.y).length())
        .fold(0.0, f32::max)
}

#[test]
fn every_configuration_comes_to_rest_on_the_45_degree_ramp() {
    // Rests on the 45-degree hill's ramps: rest_on_slope (dropped onto the ramp rising to the
    // right); walk_right / walk_left with their input stopped at 1 s, on the way up (the last
    // speed uphill); and the same walks started on the plateau (x = 11.5 and 12.5, y = 5) and
    // stopped after 0.6 s on the way down a ramp (the last speed downhill, the case Rapier
    // reads as intent to walk). Each runs 2 s past its stop, so its last second is all rest.
    // The rest bound: no configuration moves more than 0.01 tiles in it, the size docs/scale.md
    // calls clearly wrong for a length. Rapier's slope creep with no horizontal velocity is 0.006
    // tiles/s, the reference: each cast hit adds the normal nudge along the slope's normal and
    // gravity brings the character back down vertically.
    let base = level("slope_45");
    let mut slope = base.clone();
    slope.scenarios.clear();
    for s in &base.scenarios {
        if s.inputs.len() == 2 {
            let mut up = s.clone();
            up.inputs[1].t = 1.0;
            up.duration = 3.0;
            up.name = format!("{}_stop_going_up", s.name);
            let mut down = up.clone();
            let right = s.inputs[0].right == Some(true);
            down.spawn = glam::Vec2::new(if right { 11.5 } else { 12.5 }, 5.0);
            down.inputs[1].t = 0.6;
            down.duration = 2.6;
            down.name = format!("{}_stop_going_down", s.name);
            slope.scenarios.extend([up, down]);
        } else {
            let mut s = s.clone();
            s.duration = 3.0;
            slope.scenarios.push(s);
        }
    }
    assert_eq!(slope.scenarios.len(), 5);
    let configs: Vec<RunConfig> = platbench::registry::Registry::builtin().builtin_configs()
        .into_iter()
        .filter(|r| !matches!(r.backend.as_any().downcast_ref::<SweepConfig>(), Some(c) if c.positions != platbench::sweep::Positions::Float))
        .collect();
    assert!(configs.len() >= 10, "{} configurations", configs.len());
    for run in &configs {
        for (name, e) in evaluate_all(std::slice::from_ref(&slope), run) {
            // It stopped on the ramp: its feet are on the hill (x within 6..18), above the
            // valley floor (y = 1).
            let end = e.trace.rows.last().expect("rows");
            assert!(
                (6.0..=18.0).contains(&end.x) && end.y > 1.5,
                "{} {name}: ended at ({}, {}), not on the ramp",
                run.label,
                end.x,
                end.y
            );
            // One exception, measured and bounded: the merged round cuboid resting on the ramp
            // rising to the right, whose rounded corner's contact normals on the polyline
            // scatter past the slide limit even with its 0.01 rad margin on a few steps
            // (about 0.005 tiles each; 0.012 tiles in the second). Held to 0.02.
            let round_merged = matches!(run.backend.as_any().downcast_ref::<RapierConfig>(), Some(c)
                if c.colliders == ColliderBuilding::Merged && c.shape == CharacterShape::ROUND_CUBOID);
            let bound = if round_merged && name.ends_with("walk_right_stop_going_up") {
                0.02
            } else {
                0.01
            };
            let moved = last_second_motion(&e);
            assert!(moved <= bound, "{} {name}: moved {moved} tiles", run.label);
        }
    }
    // The check can fail: without the stop speed, friction only halves the speed, Rapier reads
    // the vanishing downhill speed as intent and slides (0.245 tiles/s per axis, reference).
    let creeping = RunConfig {
        params: MotionParams {
            stop_speed: 0.0,
            ..Default::default()
        },
        ..platbench::rapier::kind::run(ColliderBuilding::PerTile, CharacterShape::Capsule)
    };
    let worst = evaluate_all(std::slice::from_ref(&slope), &creeping)
        .iter()
        .map(|(_, e)| last_second_motion(e))
        .fold(0.0, f32::max);
    assert!(worst > 0.1, "without the stop speed: moved {worst} tiles");
}

/// A floor of `width` tiles whose top is y = 1.
fn floor(width: u32) -> Level {
    let mut tiles = vec![Tile::Solid; width as usize];
    tiles.extend(vec![Tile::Empty; width as usize * 4]);
    Level::from_tiles("floor", width, 5, tiles)
}

#[test]
fn a_flush_spawn_starts_at_the_offset_above_the_ground() {
    let level = floor(10);
    let spawn_gap = |lift_spawn: bool, h: f32| {
        let config = RapierConfig {
            lift_spawn,
            ..Default::default()
        };
        let mut b = RapierBackend::new(&level, MotionParams::default(), config).unwrap();
        let id = b
            .add_character(CharacterSpec {
                spawn: Vec2::new(5.5, 1.0 + h),
                size: Vec2::new(0.8, 0.9),
                velocity: Vec2::ZERO,
            })
            .unwrap();
        b.state(id).pos.y - 1.0
    };
    // Rapier's default offset, 1% of the 0.9-tile height; f32 rounding at y = 1 is 1e-7.
    let offset = 0.009;
    assert!((spawn_gap(true, 0.0) - offset).abs() < 1e-5);
    assert!((spawn_gap(true, 0.004) - offset).abs() < 1e-5);
    // Already clear, or in the air: left where it is.
    assert_eq!(spawn_gap(true, 0.5), 0.5);
    assert_eq!(spawn_gap(false, 0.0), 0.0);
}

#[test]
fn the_grounded_move_decides_whether_a_box_sticks_and_whether_a_platform_carries() {
    let run = |grounded_move: GroundedMove, shape: CharacterShape, building: ColliderBuilding| {
        platbench::rapier::kind::run_with(RapierConfig {
            colliders: building,
            shape,
            grounded_move,
            ..Default::default()
        })
    };
    // On the 200-tile merged floor the cuboid fed gravity every step sticks in most walks
    // (reference: 2% to 13% in 13 of 15 runs); with no vertical move while grounded it walks
    // (reference: 1.000 median). Bounds: 0.15 and 0.97, the reference's figures with margin.
    let long = level("long_floor");
    let progress = |g: GroundedMove| -> Vec<f64> {
        let evals = evaluate_all(
            std::slice::from_ref(&long),
            &run(g, CharacterShape::Cuboid, ColliderBuilding::Merged),
        );
        rows(&evals, "progress_ratio")
            .iter()
            .map(|r| r.value)
            .collect()
    };
    let gravity = progress(GroundedMove::Gravity);
    assert!(
        gravity.iter().filter(|p| **p <= 0.15).count() >= 3,
        "{gravity:?}"
    );
    for g in [GroundedMove::None, GroundedMove::NoneExceptOnPlatforms] {
        let p = progress(g);
        assert!(
            !p.is_empty() && p.iter().all(|p| *p >= 0.97),
            "{g:?}: {p:?}"
        );
    }
    // The catch: with no vertical move at all, the controller's own carry (applied only after
    // a cast hit) stops and a rider of the horizontal platform stays behind; the exception for
    // platforms keeps it (within three steps of the 2 tiles/s ride, 0.1 tiles: the most the
    // controller was measured to trail by).
    let platforms = [level("platforms")];
    let drift = |g: GroundedMove| {
        let evals = evaluate_all(
            &platforms,
            &run(g, CharacterShape::Capsule, ColliderBuilding::PerTile),
        );
        value(&evals, "ride_horizontal", "carry_drift")
    };
    assert!(drift(GroundedMove::None) > 1.0);
    assert!(drift(GroundedMove::NoneExceptOnPlatforms) <= 0.1 + 1e-4);
    assert!(drift(GroundedMove::Gravity) <= 0.1 + 1e-4);
}

#[test]
fn platforms_moved_before_the_characters_trade_a_walking_rider_s_drift_for_a_falling_one() {
    // Both orders measured on every shape (`cargo run --release --example rapier_setups`,
    // DETAIL=carry_drift or carry_airborne_frames). Moving the platforms first, the controller
    // carries with the velocity of the step it moves in: the rider of the fast descent is in
    // the air for fewer frames (28 against 79) and the elevator's rider stays on it (drift
    // 3e-4 at most against 0.087); the diagonal and the circle are the same either way. The
    // price, pinned here too: a rider walking along a moving platform drifts by one to five
    // steps of it (0.033 to 0.167 tiles) where, moved after, it drifted by 1e-6 to 0.1.
    let platforms = [level("platforms")];
    for shape in CharacterShape::ALL {
        let measure = |order: PlatformOrder| {
            evaluate_all(
                &platforms,
                &platbench::rapier::kind::run_with(RapierConfig {
                    shape,
                    platform_order: order,
                    ..Default::default()
                }),
            )
        };
        let (before, after) = (
            measure(PlatformOrder::BeforeCharacters),
            measure(PlatformOrder::AfterCharacters),
        );
        let tag = shape.label();
        let airborne =
            |e: &[(String, Evaluation)]| value(e, "fast_descent", "carry_airborne_frames");
        assert!(airborne(&before) < airborne(&after), "{tag}: fast descent");
        let drift = |e: &[(String, Evaluation)], s: &str| value(e, s, "carry_drift");
        assert!(
            drift(&before, "elevator") < drift(&after, "elevator"),
            "{tag}: elevator"
        );
        assert!(
            drift(&before, "walk_on_platform") > drift(&after, "walk_on_platform"),
            "{tag}: walking on the platform"
        );
    }
    assert_eq!(
        RapierConfig::default().platform_order,
        PlatformOrder::BeforeCharacters
    );
}

#[test]
fn autostep_reaches_the_controller() {
    // A 0.2-tile step on the floor: the cuboid is blocked by it, unless autostep (Rapier's
    // option, here 30% of the height, as the bevy_rapier character example sets it) lifts it
    // over.
    let level = floor(30);
    let end_x = |autostep: Option<(Length, Length)>| {
        let config = RapierConfig {
            shape: CharacterShape::Cuboid,
            autostep,
            ..Default::default()
        };
        let mut b = RapierBackend::new(&level, MotionParams::default(), config).unwrap();
        b.insert_static_collider(
            ColliderBuilder::cuboid(2.0, 0.1)
                .translation(Vec2::new(12.0, 1.1))
                .build(),
        );
        let id = b
            .add_character(CharacterSpec {
                spawn: Vec2::new(5.5, 1.0),
                size: Vec2::new(0.8, 0.9),
                velocity: Vec2::ZERO,
            })
            .unwrap();
        let right = [Input {
            right: true,
            ..Default::default()
        }];
        for _ in 0..120 {
            b.step(&right, 1.0 / 60.0);
        }
        b.state(id).pos.x
    };
    // The step's left face is at x = 10: blocked, the box's centre stays 0.4 short of it.
    assert!(end_x(None) < 10.0);
    let stepped = end_x(Some((Length::Relative(0.3), Length::Relative(0.5))));
    assert!(stepped > 12.0, "with autostep: {stepped}");
}

#[test]
fn every_builtin_level_runs_on_the_remedy_configurations() {
    // The built-in comparison has one configuration fed as Rapier's examples feed a character
    // (the bevy_rapier example's feed on static ground, the 2D testbed's on platforms) per
    // shape and collider building.
    let remedies: Vec<RunConfig> = platbench::registry::Registry::builtin().builtin_configs()
        .into_iter()
        .filter(|r| {
            matches!(r.backend.as_any().downcast_ref::<RapierConfig>(), Some(c) if c.grounded_move == GroundedMove::NoneExceptTestbedOnPlatforms)
        })
        .collect();
    assert_eq!(remedies.len(), 2 * CharacterShape::ALL.len());
    let levels = builtin_levels();
    for run in &remedies {
        assert!(!evaluate_all(&levels, run).is_empty(), "{}", run.label);
    }
}

#[test]
fn the_remedy_has_a_price_where_rapier_calls_a_wall_corner_ground() {
    // Fed no vertical move while grounded, a character that Rapier reports grounded on the
    // corner between two stacked wall tiles (rounded shapes sliding down the thin wall after
    // hitting it at 1000 tiles/s) never moves down again: it hangs in the air beside the wall.
    // Fed gravity every step it keeps falling and rests at its offset. Bounds: 0.5 tiles (a
    // hanging character, measured 0.77 to 0.99) against 0.02 (the offset, 0.009, with room).
    let thin = [level("thin_wall")];
    let worst_gap = |grounded_move: GroundedMove| {
        let evals = evaluate_all(
            &thin,
            &platbench::rapier::kind::run_with(RapierConfig {
                shape: CharacterShape::Capsule,
                grounded_move,
                ..Default::default()
            }),
        );
        rows(&evals, "rest_gap")
            .iter()
            .map(|r| r.value)
            .fold(0.0f64, f64::max)
    };
    assert!(worst_gap(GroundedMove::NoneExceptOnPlatforms) > 0.5);
    assert!(worst_gap(GroundedMove::Gravity) < 0.02);
    // Two more prices. A block closing on a character against a wall: with no vertical move
    // the character's desired move is exactly 0, which runs Rapier's depenetration, and that
    // pushes it out of the block and into the wall (more than half a tile, measured 0.79 to
    // 0.91; fed gravity, 0). And the ball at the top of the ladder: reported grounded on the
    // shaft's corners, it stops in the shaft and never reaches the floor (ladder_result 0).
    let remedy = |shape: CharacterShape| {
        platbench::rapier::kind::run_with(RapierConfig {
            shape,
            grounded_move: GroundedMove::NoneExceptOnPlatforms,
            ..Default::default()
        })
    };
    let platforms = [level("platforms")];
    for shape in CharacterShape::ALL {
        let evals = evaluate_all(&platforms, &remedy(shape));
        let pen = value(&evals, "crushed_against_a_wall", "max_penetration");
        assert!(pen > 0.5, "{}: {pen}", shape.label());
        let fed = evaluate_all(
            &platforms,
            &platbench::rapier::kind::run(ColliderBuilding::PerTile, shape),
        );
        assert_eq!(
            value(&fed, "crushed_against_a_wall", "max_penetration"),
            0.0
        );
    }
    let ladders = [level("ladders")];
    let ball = evaluate_all(&ladders, &remedy(CharacterShape::Ball));
    assert_eq!(value(&ball, "climb_down", "ladder_result"), 0.0);
    let fed = evaluate_all(
        &ladders,
        &platbench::rapier::kind::run(ColliderBuilding::PerTile, CharacterShape::Ball),
    );
    assert_eq!(value(&fed, "climb_down", "ladder_result"), 1.0);
}

#[test]
fn adding_the_platform_displacement_to_the_controller_s_carry_over_carries() {
    // Rapier's controller already carries a rider with the platform it stands on; adding the
    // platform's displacement to the desired move as well, as many users do, carries twice.
    // On the 2 tiles/s horizontal ride the rider then runs ahead of the platform by far more
    // than the controller's own lag (0.1 tiles at most, tested above): bound 0.5 tiles.
    let platforms = [level("platforms")];
    let drift = |platform_carry: PlatformCarry| {
        let evals = evaluate_all(
            &platforms,
            &platbench::rapier::kind::run_with(RapierConfig {
                platform_carry,
                ..Default::default()
            }),
        );
        value(&evals, "ride_horizontal", "carry_drift")
    };
    let own = drift(PlatformCarry::Controller);
    let both = drift(PlatformCarry::ControllerPlusDisplacement);
    assert!(own <= 0.1 + 1e-4, "{own}");
    assert!(both > 0.5, "controller plus displacement: drift {both}");
}

#[test]
fn rounded_shapes_report_ground_on_the_corners_of_a_per_tile_wall() {
    // After hitting the thin wall at 1000 tiles/s, the rounded shapes slide down its stacked
    // one-tile colliders and Rapier reports them grounded on the corners between tiles
    // (false_grounded > 0: grounded with no ground under the feet); the same wall merged into
    // one box gives no corner, and the cuboid, flat against it, none either.
    let thin = [level("thin_wall")];
    let false_grounded = |building: ColliderBuilding, shape: CharacterShape| -> f64 {
        let evals = evaluate_all(&thin, &platbench::rapier::kind::run(building, shape));
        rows(&evals, "false_grounded").iter().map(|r| r.value).sum()
    };
    for shape in [
        CharacterShape::Capsule,
        CharacterShape::Ball,
        CharacterShape::ROUND_CUBOID,
    ] {
        assert!(
            false_grounded(ColliderBuilding::PerTile, shape) > 0.0,
            "{}",
            shape.label()
        );
        assert_eq!(
            false_grounded(ColliderBuilding::Merged, shape),
            0.0,
            "{}",
            shape.label()
        );
    }
    assert_eq!(
        false_grounded(ColliderBuilding::PerTile, CharacterShape::Cuboid),
        0.0
    );
}

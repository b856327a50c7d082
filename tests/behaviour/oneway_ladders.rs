//! One-way platforms and ladders on both backends (the seed's one-way rule, ladders climbed at the
//! configured speed, entered and left), from traces and metrics of the built-in `oneway` and
//! `ladders` levels.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{evaluate_all, level, rows, some_rows};
use glam::Vec2;
use platbench::backend::CharacterSpec;
use platbench::config::RunConfig;
use platbench::motion::{Input, MotionParams};
use platbench::rapier::{CharacterShape, ColliderBuilding};
use platbench::sweep::{SweepBackend, SweepConfig};

fn every_config() -> Vec<RunConfig> {
    let mut runs = vec![platbench::sweep::kind::run_default()];
    for shape in CharacterShape::ALL {
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            runs.push(platbench::rapier::kind::run(building, shape));
        }
    }
    runs
}

#[test]
fn one_way_scenarios_end_as_the_seed_intends_on_sweep() {
    let evals = evaluate_all(&[level("oneway")], &platbench::sweep::kind::run_default());
    let results = rows(&evals, "oneway_result");
    // Jump through from below, land on top, drop through on down + jump, and the mid-jump fall.
    assert_eq!(results.len(), 4);
    for r in results {
        assert_eq!(
            r.value, 1.0,
            "{}: did not end at its expected height",
            r.scenario
        );
    }
    // The mid-jump fall really starts falling inside the platform (feet between its bottom 3
    // and top 4 at the apex): the case "collide only if falling" gets wrong.
    let (_, fall) = evals
        .iter()
        .find(|(n, _)| n.ends_with("mid_jump_fall"))
        .unwrap();
    let apex = fall.trace.rows.iter().map(|r| r.y).fold(f32::MIN, f32::max);
    assert!(apex > 3.0 && apex < 4.0, "apex feet {apex}");
    // And it lands back on the floor, never on the platform top.
    assert!(fall
        .trace
        .rows
        .iter()
        .all(|r| !(r.is_grounded() && r.y > 3.9)));
}

#[test]
fn rapier_one_way_filter_reproduces_the_seed_rule() {
    // The query-filter predicate (keep a one-way collider only for feet entirely above its top at
    // the start of the move; never while dropping) gives Rapier the same four outcomes.
    for run in every_config().into_iter().skip(1) {
        let evals = evaluate_all(&[level("oneway")], &run);
        for r in some_rows(&evals, "oneway_result") {
            assert_eq!(r.value, 1.0, "{} {}", run.label, r.scenario);
        }
    }
}

#[test]
fn ladders_climb_at_the_configured_speed_and_are_entered_and_left() {
    for run in every_config() {
        let evals = evaluate_all(&[level("ladders")], &run);
        for r in some_rows(&evals, "ladder_speed_error") {
            // Required: the climbing speed is the configured ladder speed (`ladder_speed_error`'s
            // reference), within 1e-4 (sweep). The ladder motion is shared, so Rapier climbs at it
            // too (f32 noise on y ~ 6 tiles).
            assert!(
                r.value.abs() <= 1e-4,
                "{} {}: {}",
                run.label,
                r.scenario,
                r.value
            );
        }
        let results = rows(&evals, "ladder_result");
        // Climbed up and exited at the top, climbed down from the top, walked off at the top,
        // jumped off.
        assert_eq!(results.len(), 4);
        for r in results {
            assert_eq!(r.value, 1.0, "{} {}", run.label, r.scenario);
        }
    }
}

#[test]
fn the_ladder_state_has_no_gravity_and_no_horizontal_motion() {
    let evals = evaluate_all(&[level("ladders")], &platbench::sweep::kind::run_default());
    let (_, climb) = evals.iter().find(|(n, _)| n.ends_with("climb_up")).unwrap();
    let on: Vec<_> = climb.trace.rows.iter().filter(|r| r.ladder == 1).collect();
    assert!(on.len() > 30, "{} frames on the ladder", on.len());
    for r in on {
        // Clamped to the ladder's centre (column 8), no horizontal velocity.
        assert_eq!((r.x, r.vx), (8.5, 0.0), "frame {}", r.frame);
    }
}

#[test]
fn a_level_without_one_way_platforms_or_ladders_runs_none_of_their_code() {
    let right = Input {
        right: true,
        ..Default::default()
    };
    let run = |name: &str| {
        let l = level(name);
        let mut b = SweepBackend::new(&l, MotionParams::default(), SweepConfig::default()).unwrap();
        b.add_character(CharacterSpec {
            spawn: l.scenarios[0].spawn,
            size: Vec2::new(0.8, 0.9),
            velocity: Vec2::ZERO,
        })
        .expect("valid character");
        for _ in 0..120 {
            b.step(&[right], 1.0 / 60.0);
        }
        b.stats()
    };
    let flat = run("flat_seams");
    assert_eq!((flat.one_way_steps, flat.ladder_steps), (0, 0));
    // The counters count where the features exist.
    assert_eq!(run("oneway").one_way_steps, 120);
    assert_eq!(run("ladders").ladder_steps, 120);
}

//! Slopes on both backends (walkable ramps followed, too-steep ones blocked), asserted from traces
//! and metrics of the built-in slope levels: slope_22_5, slope_26_6, slope_45 (hills walked up,
//! over the crest and down into the valley), slope_63_4 (steeper than the 45-degree climb limit)
//! and seed_tile (the seed's height-array tile).
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
use platbench::level::Tile;
use platbench::motion::{Input, MotionParams};
use platbench::rapier::{CharacterShape, ColliderBuilding};
use platbench::sweep::{SweepBackend, SweepConfig};

const WALKABLE: [&str; 4] = ["slope_22_5", "slope_26_6", "slope_45", "seed_tile"];

#[test]
fn sweep_walks_every_walkable_slope_without_leaving_it() {
    for name in WALKABLE {
        let evals = evaluate_all(&[level(name)], &platbench::sweep::kind::run_default());
        let airborne = rows(&evals, "slope_airborne_frames");
        assert!(!airborne.is_empty(), "{name}: slope walks measured");
        for r in airborne {
            // Required: a walkable slope is followed with 0 airborne frames, walking down and up
            // (`slope_airborne_frames`' reference: grounded all the way).
            assert_eq!(r.value, 0.0, "{name}.{}: airborne {}", r.scenario, r.value);
        }
        // The seed's promise: the box stands on the surface under its centre and overhangs the
        // ramp by at most half its width times the climb gradient (0.4 tiles at 45 degrees),
        // whose depth along a 45-degree ramp's normal is 0.4 sin 45 = 0.2828.
        let overhang = 0.4 * std::f64::consts::FRAC_PI_4.sin() + 1e-4;
        for r in some_rows(&evals, "slope_gap_max") {
            // Required: touching the surface (`slope_gap_max`'s reference, gap 0), never above it
            // by more than 1e-3 tiles; inside it only by the designed overhang.
            assert!(r.value <= 1e-3, "{name}.{}: gap {}", r.scenario, r.value);
            assert!(
                r.value >= -overhang,
                "{name}.{}: gap {}",
                r.scenario,
                r.value
            );
        }
        let overlap = |scenario: &str| {
            rows(&evals, "slope_overlap")
                .into_iter()
                .find(|r| r.scenario == scenario)
                .map_or(0.0, |r| r.value)
        };
        for r in some_rows(&evals, "max_penetration") {
            // No solid is entered beyond the ramp the box overhangs by design.
            assert!(
                r.value <= overlap(&r.scenario) + SweepConfig::default().epsilon as f64,
                "{name}.{}",
                r.scenario
            );
        }
    }
    // On straight ramps the sweep keeps its horizontal run speed (the seed's optional slope
    // acceleration is not applied): ratio 1 within the speed-up at the foot and crest (1%).
    for name in ["slope_22_5", "slope_26_6", "slope_45"] {
        let evals = evaluate_all(&[level(name)], &platbench::sweep::kind::run_default());
        for r in some_rows(&evals, "slope_speed_ratio") {
            assert!(
                (r.value - 1.0).abs() <= 0.01,
                "{name}.{}: {}",
                r.scenario,
                r.value
            );
        }
    }
}

#[test]
fn the_seed_height_array_tile_is_followed_within_a_sixteenth() {
    let seed = level("seed_tile");
    let evals = evaluate_all(
        std::slice::from_ref(&seed),
        &platbench::sweep::kind::run_default(),
    );
    let (_, down) = evals
        .iter()
        .find(|(n, _)| n.ends_with("walk_down"))
        .unwrap();
    // The tile is column 10, row 1; its surface under the centre is the seed's step function.
    let Tile::Slope(tile) = seed.tile(10, 1) else {
        panic!("column 10 is the seed tile")
    };
    let over: Vec<_> = down
        .trace
        .rows
        .iter()
        .filter(|r| r.x > 10.0 && r.x < 11.0)
        .collect();
    assert!(over.len() >= 5, "{} frames over the tile", over.len());
    for r in over {
        let surface = 1.0 + tile.height_at(r.x - 10.0);
        // Required: the seed's tile is followed to within 1/16 tile, one step of its height array
        // (sixteenths of a tile).
        assert!(
            (r.y - surface).abs() <= 1.0 / 16.0,
            "frame {}: feet {} surface {surface}",
            r.frame,
            r.y
        );
    }
}

#[test]
fn a_slope_over_the_climb_limit_blocks_both_backends() {
    let steep = level("slope_63_4");
    let mut runs = vec![platbench::sweep::kind::run_default()];
    for shape in CharacterShape::ALL {
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            runs.push(platbench::rapier::kind::run(building, shape));
        }
    }
    for run in &runs {
        let evals = evaluate_all(std::slice::from_ref(&steep), run);
        let r = rows(&evals, "steep_blocked")
            .into_iter()
            .find(|r| r.scenario == "walk_into_steep")
            .unwrap();
        // Required: a slope over the 45-degree climb limit blocks the climb (`steep_blocked`'s
        // reference); the 63.4-degree slope (rising to the right) does on both.
        assert_eq!(r.value, 1.0, "{}: steep_blocked", run.label);
    }
    // The same ramp rising to the left: the sweep blocks it too.
    let evals = evaluate_all(
        std::slice::from_ref(&steep),
        &platbench::sweep::kind::run_default(),
    );
    let left = rows(&evals, "steep_blocked")
        .into_iter()
        .find(|r| r.scenario == "walk_into_steep_leftward")
        .unwrap();
    assert_eq!(left.value, 1.0);
}

#[test]
fn rapier_climbs_a_steep_slope_rising_to_the_left_on_every_collider_building() {
    // Measured, and pinned so a Rapier upgrade that changes it is a reviewed change: every
    // shape walks up the 63.4-degree ramp that rises to the left, on one polyline and on
    // per-tile polygons cut by the slope line alike, while the same ramp rising to the right
    // blocks it (the test above). Rapier 2D measures the slope as `up.angle_to(normal)`, a
    // signed angle that is negative for surfaces rising to the left, so its wall test
    // (`angle >= max_slope_climb_angle`) never fires for them (rapier2d 0.36.1,
    // src/control/character_controller.rs); tests/controllers/rapier_steep_slope_left.rs is the same
    // scene in rapier2d alone.
    let steep = level("slope_63_4");
    for shape in CharacterShape::ALL {
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            let evals = evaluate_all(
                std::slice::from_ref(&steep),
                &platbench::rapier::kind::run(building, shape),
            );
            let r = rows(&evals, "steep_blocked")
                .into_iter()
                .find(|r| r.scenario == "walk_into_steep_leftward")
                .unwrap();
            assert_eq!(r.value, 0.0, "{} {building:?}: leftward", shape.label());
        }
    }
}

#[test]
fn rapier_walks_the_per_tile_22_5_degree_hill() {
    // With per-tile polygons cut by the slope line, every shape walks over the 22.5-degree
    // hill: its tiles cross rows, and a polygon spanning a corner the line never reaches put
    // a 0.17-tile step into the ramp where every shape stuck (at x = 7.6). Bound: the speed
    // on the slope at least 0.85 of the flat speed (measured 0.90 to 0.92), far above a stop.
    let hill = level("slope_22_5");
    for shape in CharacterShape::ALL {
        let evals = evaluate_all(
            std::slice::from_ref(&hill),
            &platbench::rapier::kind::run(ColliderBuilding::PerTile, shape),
        );
        let speeds: Vec<f64> = rows(&evals, "slope_speed_ratio")
            .iter()
            .map(|r| r.value)
            .collect();
        assert!(!speeds.is_empty(), "{}", shape.label());
        for v in speeds {
            assert!(v >= 0.85, "{}: slope speed ratio {v}", shape.label());
        }
    }
}

#[test]
fn rapier_follows_walkable_slopes_at_its_offset() {
    for name in ["slope_22_5", "slope_26_6", "slope_45"] {
        for shape in CharacterShape::ALL {
            let evals = evaluate_all(
                &[level(name)],
                &platbench::rapier::kind::run(ColliderBuilding::Merged, shape),
            );
            for r in some_rows(&evals, "slope_airborne_frames") {
                // Measured 0 on merged ramps: snap-to-ground keeps Rapier on the slope.
                assert_eq!(r.value, 0.0, "{name}.{} {}", r.scenario, shape.label());
            }
            for r in some_rows(&evals, "slope_gap_max") {
                // Rapier keeps `offset` (0.009) along the normal: up to offset / cos(45 deg)
                // vertically, 0.0127; rounded shapes rest a little higher on the crest's corner
                // (measured up to 0.08).
                assert!(
                    r.value <= 0.1,
                    "{name}.{} {}: {}",
                    r.scenario,
                    shape.label(),
                    r.value
                );
            }
        }
    }
}

#[test]
fn a_level_without_slopes_runs_none_of_the_slope_code() {
    let params = MotionParams::default();
    let right = Input {
        right: true,
        ..Default::default()
    };
    let spec = |x: f32, y: f32| CharacterSpec {
        spawn: Vec2::new(x, y),
        size: Vec2::new(0.8, 0.9),
        velocity: Vec2::ZERO,
    };
    let flat = level("flat_seams");
    assert!(!flat.features.slopes);
    let mut b = SweepBackend::new(&flat, params.clone(), SweepConfig::default()).unwrap();
    b.add_character(spec(3.5, 1.0)).expect("valid character");
    for _ in 0..600 {
        b.step(&[right], 1.0 / 60.0);
    }
    assert_eq!(
        b.stats().slope_steps,
        0,
        "no slope rule ran on a flat level"
    );
    let hill = level("slope_45");
    assert!(hill.features.slopes);
    let mut b = SweepBackend::new(&hill, params, SweepConfig::default()).unwrap();
    b.add_character(spec(2.5, 1.0)).expect("valid character");
    for _ in 0..600 {
        b.step(&[right], 1.0 / 60.0);
    }
    // Counter check that the counter counts: every step on a slope level runs the rules.
    assert_eq!(b.stats().slope_steps, 600);
}

//! The sweep on integer positions (`positions=integer/32`, docs/sweep.md), asserted from the traces
//! and metrics of the built-in set: exact rest, no penetration, no jitter, also far from the origin
//! where the float mode breaks.

use crate::common;

use common::{builtin_levels, evaluate_all, level, rows, value};
use platbench::config::RunConfig;
use platbench::metrics::evaluate;
use platbench::sweep::{RiderFollow, SweepConfig, INTEGER_SUPPORTED};

const PER_TILE: u32 = 32;

/// The built-in levels without moving platforms (the platform tests below take the others).
fn integer_levels() -> Vec<platbench::level::Level> {
    builtin_levels()
        .into_iter()
        .filter(|l| !l.features.moving_platforms)
        .collect()
}

#[test]
fn rest_gap_penetration_and_jitter_are_exactly_zero_on_every_scenario_without_slopes() {
    let levels: Vec<_> = integer_levels()
        .into_iter()
        .filter(|l| !l.features.slopes)
        .collect();
    // flat_seams, drops, jumps, corridor, thin_wall, oneway, ladders, long_floor,
    // very_long_floor: the nine built-in levels without slopes or moving platforms.
    assert_eq!(levels.len(), 9, "levels run");
    let evals = evaluate_all(&levels, &platbench::sweep::kind::run_integer(PER_TILE));
    // Exactly 0, no tolerance (what integer positions promise, docs/sweep.md): the grid snaps flush
    // in integers.
    for m in ["rest_gap", "max_penetration", "rest_jitter"] {
        let rs = rows(&evals, m);
        assert!(rs.len() >= 20, "{m} measured on {} scenarios", rs.len());
        for r in rs {
            assert_eq!(r.value, 0.0, "{}.{}: {m} {}", r.level, r.scenario, r.value);
        }
    }
}

#[test]
fn on_every_slope_scenario_rest_penetration_and_jitter_are_exactly_zero_against_the_moved_box() {
    let levels: Vec<_> = integer_levels()
        .into_iter()
        .filter(|l| l.features.slopes)
        .collect();
    // slope_22_5, slope_26_6, slope_45, slope_63_4, seed_tile: every built-in level with
    // slopes (none of them has moving platforms).
    assert_eq!(levels.len(), 5, "slope levels run");
    let evals = evaluate_all(&levels, &platbench::sweep::kind::run_integer(PER_TILE));
    // Exactly 0, no tolerance (integer positions on slopes, docs/sweep.md), measured on the box the
    // integer mode moves (26 x 29 subpixels) against its declared stance: the seed's centre column
    // on the surface rounded up to its subpixel (`level::round_height_up`), the box overhanging the
    // ramp by half its width times the climb gradient. rest_gap and max_penetration themselves read
    // that overhang (0.15 to 0.36 tiles, by design), so the declared forms are the ones held to 0.
    for m in [
        "rest_gap_declared",
        "penetration_beyond_declared",
        "rest_jitter",
        "grounded_flicker",
    ] {
        let rs = rows(&evals, m);
        // 3 + 3 + 3 + 2 + 2 scenarios.
        assert_eq!(rs.len(), 13, "{m} measured on {} scenarios", rs.len());
        for r in rs {
            if m == "penetration_beyond_declared" && r.scenario.starts_with("walk_into_steep") {
                // The declared overlap is capped at what a walkable ramp gives, and the metric
                // hides nothing beyond it: at the foot of the too-steep 63.4-degree ramp the moved
                // box (0.8125 wide) stands with its leading half inside it, deeper than the design
                // allows on a walkable ramp: 0.40625 (sin 63.4 - sin 45), less the allowance's 1e-4
                // slack (no epsilon on integer positions); 1e-5: f32.
                let excess = 0.40625 * (2f64.atan().sin() - std::f64::consts::FRAC_PI_4.sin());
                assert!(
                    (r.value - (excess - 1e-4)).abs() < 1e-5,
                    "{}.{}: {m} {}",
                    r.level,
                    r.scenario,
                    r.value
                );
                continue;
            }
            assert_eq!(r.value, 0.0, "{}.{}: {m} {}", r.level, r.scenario, r.value);
        }
    }
    // Walking down a walkable slope never leaves it (also down the seed's stepped tile, where
    // a first fall smaller than a subpixel must still find the slope under the feet).
    for r in rows(&evals, "slope_airborne_frames") {
        assert_eq!(r.value, 0.0, "{}.{}", r.level, r.scenario);
    }
    // The climb limit blocks the 63.4-degree ramp and the seed tile's high side as in float.
    for r in rows(&evals, "steep_blocked") {
        assert_eq!(r.value, 1.0, "{}.{}", r.level, r.scenario);
    }
}

#[test]
fn a_surface_off_the_grid_is_stood_on_rounded_up_to_its_subpixel() {
    // 22.5 degrees: the ramp's heights are irrational; the feet rest on the next subpixel up,
    // less than one subpixel (1/32 tile) above the surface, never below it.
    let l = level("slope_22_5");
    let spec = l
        .scenarios
        .iter()
        .find(|s| s.name == "rest_on_slope")
        .expect("slope_22_5.rest_on_slope");
    let e = evaluate(&l, spec, &platbench::sweep::kind::run_integer(PER_TILE)).expect("runs");
    let last = e.trace.rows.last().expect("rows");
    let (h, slope) = l
        .surface_at(last.x, last.y + 0.5, 1.5)
        .expect("a surface under the centre");
    assert!(slope.is_some(), "rests on the ramp");
    let above = last.y as f64 - h as f64;
    assert!(
        above > 0.0 && above < 1.0 / PER_TILE as f64,
        "{above} tiles above the surface"
    );
    assert_eq!(
        (last.y as f64 * PER_TILE as f64).fract(),
        0.0,
        "feet on the grid"
    );
}

#[test]
fn far_from_the_origin_the_integer_mode_rests_exactly_where_the_float_mode_sinks() {
    // drops.drop_1 placed 1e7 tiles from the origin, where f32 positions are whole tiles apart.
    let mut l = level("drops");
    l.origin = glam::DVec2::splat(1e7);
    let spec = l
        .scenarios
        .iter()
        .find(|s| s.name == "drop_1")
        .expect("drops.drop_1")
        .clone();
    let value = |run: &RunConfig, m: &str| {
        evaluate(&l, &spec, run)
            .unwrap()
            .metrics
            .iter()
            .find(|r| r.metric == m)
            .map(|r| r.value)
            .unwrap_or_else(|| panic!("no {m}"))
    };
    let float = platbench::sweep::kind::run_default();
    let int = platbench::sweep::kind::run_integer(PER_TILE);
    // The float mode breaks there: its feet land a rounding of a whole tile off the floor's top
    // (`platbench stress`: it sinks 0.4 tiles). Its tolerance is its epsilon, 0.001.
    assert!(
        value(&float, "max_penetration") > 0.001 || value(&float, "rest_gap").abs() > 0.001,
        "the float mode was expected to break at 1e7 tiles"
    );
    for m in ["rest_gap", "max_penetration", "rest_jitter"] {
        assert_eq!(value(&int, m), 0.0, "integer mode {m} at 1e7 tiles");
    }
}

#[test]
fn the_exact_discrete_jump_reaches_its_height_to_the_subpixel() {
    let evals = evaluate_all(
        &[level("jumps")],
        &platbench::sweep::kind::run_integer(PER_TILE),
    );
    let apex = rows(&evals, "apex_error");
    assert!(apex.len() >= 6, "apex measured on {} jumps", apex.len());
    for r in apex {
        // Bound: one subpixel (1/32 tile), the grid's resolution. The apex lands on the requested
        // height to the subdivision: the moves are the float moves rounded with the remainder
        // carried, so the position is never more than a subpixel from the float jump, whose
        // discrete apex is exact.
        assert!(
            r.value.abs() <= 1.0 / PER_TILE as f64,
            "{}: apex_error {}",
            r.scenario,
            r.value
        );
    }
}

#[test]
fn every_built_in_scenario_runs_none_skipped() {
    // The integer mode models every feature the level format has, so it runs the whole built-in set
    // (64 scenarios), moving platforms included.
    assert_eq!(INTEGER_SUPPORTED, platbench::level::Features::ALL);
    let levels = builtin_levels();
    let scenarios: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    let evals = evaluate_all(&levels, &platbench::sweep::kind::run_integer(PER_TILE));
    assert_eq!(evals.len(), scenarios);
    assert_eq!(scenarios, 64, "the built-in set");
}

/// The rides of the built-in set (every scenario that names a platform to ride, on the three
/// platform levels) on integer positions, with rider-follow rule `rule`.
fn rides(rule: RiderFollow) -> Vec<(String, platbench::metrics::Evaluation)> {
    let run = RunConfig::new(
        "integer",
        SweepConfig {
            positions: platbench::sweep::Positions::Integer { per_tile: PER_TILE },
            rider_follow: rule,
            ..SweepConfig::default()
        },
    );
    evaluate_all(&[level("platforms"), level("elevator")], &run)
}

#[test]
fn riders_are_carried_in_whole_subpixels_with_no_drift_at_all() {
    let evals = rides(RiderFollow::Solid);
    let drift = rows(&evals, "carry_drift");
    // platforms: 8 scenarios name a platform to ride; elevator: 1.
    assert_eq!(drift.len(), 9, "rides measured");
    for r in drift {
        // Exactly 0, no tolerance (the carry on integer positions, docs/sweep.md). The platform
        // moves by the difference of two positions rounded to the grid and the rider by the same
        // whole subpixels, so its place on the platform (measured against the rounded platform the
        // mode moves) never changes; one lost subpixel would read 1/32 tile. The fast drop (20
        // tiles/s from rest) and the turning elevator included: Celeste's rule moves the rider with
        // every move.
        assert_eq!(r.value, 0.0, "{}: carry_drift {}", r.scenario, r.value);
    }
    for r in rows(&evals, "carry_airborne_frames") {
        assert_eq!(r.value, 0.0, "{}: airborne while riding", r.scenario);
    }
    // Jumping off and back on: it rides platform 0 again at the end, after frames off it.
    let back = &evals
        .iter()
        .find(|(n, _)| n.ends_with("jump_off_and_back_on"))
        .expect("scenario")
        .1;
    assert_eq!(back.trace.rows.last().expect("rows").platform, Some(0));
    assert!(back
        .trace
        .rows
        .iter()
        .any(|r| r.platform.is_none() && r.frame > 0));
}

#[test]
fn a_ten_second_ride_keeps_the_rider_exactly_in_place() {
    // The 10 s ride docs/sweep.md quotes: the turning elevator (3 tiles/s up, turning to 3 down at
    // the top and back at the bottom, 4 turns) and the platforms level's sine elevator and
    // horizontal shuttle.
    let run = platbench::sweep::kind::run_integer(PER_TILE);
    for (lvl, name) in [
        ("elevator", "ride_turning_elevator"),
        ("platforms", "elevator"),
        ("platforms", "ride_horizontal"),
    ] {
        let l = level(lvl);
        let mut spec = l
            .scenarios
            .iter()
            .find(|s| s.name == name)
            .expect("scenario")
            .clone();
        spec.duration = 10.0;
        let e = evaluate(&l, &spec, &run).expect("runs");
        let get = |m: &str| e.metrics.iter().find(|r| r.metric == m).map(|r| r.value);
        // 601 rows: 10 s at 60 Hz and the spawn.
        assert_eq!(e.trace.rows.len(), 601, "{name}");
        assert_eq!(get("carry_drift"), Some(0.0), "{name}");
        assert_eq!(get("carry_airborne_frames"), Some(0.0), "{name}");
    }
}

#[test]
fn platforms_push_in_whole_subpixels_and_crush_against_the_level() {
    let evals = evaluate_all(
        &[level("platforms"), level("moving_wall")],
        &platbench::sweep::kind::run_integer(PER_TILE),
    );
    let find = |name: &str| {
        &evals
            .iter()
            .find(|(n, _)| n.ends_with(name))
            .unwrap_or_else(|| panic!("{name}"))
            .1
    };
    // Pushed along the floor by a block sliding at 2 tiles/s: it moves with the block (the
    // block travels 7 tiles; the character starts 1.1 tiles ahead of it), and never overlaps it:
    // the push snaps it flush in integers, so push_penetration is exactly 0, no epsilon.
    let pushed = find("pushed_across_the_floor");
    let (first, last) = (
        pushed.trace.rows[0].x,
        pushed.trace.rows.last().expect("rows").x,
    );
    assert!(last - first > 2.0, "pushed {} tiles", last - first);
    assert_eq!(
        value(&evals, "pushed_across_the_floor", "push_penetration"),
        0.0
    );
    assert_eq!(value(&evals, "pushed_across_the_floor", "crush_count"), 0.0);
    // Crushed against the wall: flagged in the trace, so the crush is the one the scenario
    // designs and the crush rule counts none (docs/metrics.md, "the crush rule"), and never
    // left inside the static level (max_penetration exactly 0: it stays flush against the
    // wall, overlapping the platform, which push_penetration leaves to the rule).
    let crushed = find("crushed_against_a_wall");
    assert!(crushed.trace.rows.iter().any(|r| r.crushed == 1));
    assert_eq!(value(&evals, "crushed_against_a_wall", "crush_count"), 0.0);
    assert_eq!(
        value(&evals, "crushed_against_a_wall", "push_penetration"),
        0.0
    );
    assert_eq!(
        value(&evals, "crushed_against_a_wall", "max_penetration"),
        0.0
    );
    // A wall sliding up and down flush beside a standing character neither carries nor pushes
    // it: zero overlap is not a contact on the grid.
    let wall = find("wall_passes_flush_beside");
    let ys: Vec<f32> = wall.trace.rows.iter().map(|r| r.y).collect();
    assert!(ys[1..].iter().all(|&y| y == 1.0), "lifted by the wall");
    assert!(wall
        .trace
        .rows
        .iter()
        .all(|r| r.crushed == 0 && r.platform.is_none()));
}

#[test]
fn the_gravity_rule_leaves_the_rider_of_a_fast_drop_behind_on_the_grid_too() {
    // The rider-follow setting holds in both modes: under today's rule the 20 tiles/s drop from
    // rest leaves its rider in the air (it can fall only g dt^2 + its last speed's step), where
    // Celeste's rule (the test above) keeps it on with no drift.
    let evals = rides(RiderFollow::Gravity);
    assert!(value(&evals, "fast_descent", "carry_airborne_frames") > 0.0);
    assert_eq!(value(&evals, "fast_descent", "crush_count"), 0.0);
}

#[test]
fn the_metrics_measure_the_box_the_integer_mode_moves() {
    // 0.8 x 0.9 tiles at 32 per tile is 25.6 x 28.8 subpixels, rounded up to 26 x 29:
    // 0.8125 x 0.90625 tiles (docs/sweep.md, "The sweep on integer positions").
    let run = platbench::sweep::kind::run_integer(PER_TILE);
    let moved = run.backend.moved_size(glam::Vec2::new(0.8, 0.9));
    assert_eq!(moved, glam::Vec2::new(0.8125, 0.90625));
    // Float positions move the box they are given.
    let float = platbench::sweep::kind::run_default().backend;
    assert_eq!(
        float.moved_size(glam::Vec2::new(0.8, 0.9)),
        glam::Vec2::new(0.8, 0.9)
    );
    // That is the box that ends flush: walking into the corridor's right wall (x = 19), the feet
    // stop half the moved width from it, not half the requested width.
    let corridor = level("corridor");
    let spec = corridor
        .scenarios
        .iter()
        .find(|s| s.name == "walk_into_right_wall")
        .expect("scenario");
    let e = evaluate(&corridor, spec, &run).expect("runs");
    let last = e.trace.rows.last().expect("rows");
    assert_eq!(last.x + moved.x * 0.5, 19.0);
}

#[test]
fn at_2_24_tiles_out_the_integer_mode_runs_as_at_the_origin_and_a_tile_farther_is_refused() {
    use platbench::backend::runs;
    let run = platbench::sweep::kind::run_integer(PER_TILE);
    // 2^24 tiles: how far an f32 tile face is exact (sweep::grid::MAX_GRID_EXTENT); the levels
    // are placed so that their farthest tile face or platform box lies exactly there.
    let edge = 16_777_216.0;
    for name in ["flat_seams", "platforms"] {
        let at_origin = level(name);
        let mut far = at_origin.clone();
        let o = edge - at_origin.reach();
        far.origin = glam::DVec2::splat(o);
        assert_eq!(far.reach(), edge, "{name}");
        assert!(runs(&*run.backend, &far), "{name} at {o}");
        let near = evaluate_all(std::slice::from_ref(&at_origin), &run);
        let there = evaluate_all(std::slice::from_ref(&far), &run);
        // Whole subpixels in i64 and exact tile faces: every metric as at the origin, to the
        // bit (none is measured: the positions are the origin's plus a whole number of tiles).
        for ((n, a), (_, b)) in near.iter().zip(&there) {
            for (x, y) in a.metrics.iter().zip(&b.metrics) {
                assert_eq!((x.metric, x.value), (y.metric, y.value), "{n} at {o} tiles");
            }
        }
        // One tile farther the level's last face is 2^24 + 1, which an f32 rounds to 2^24 (the
        // floor of flat_seams at origin 2^24 lost its height: max_penetration 0.84): refused.
        far.origin = glam::DVec2::splat(o + 1.0);
        assert!(!runs(&*run.backend, &far), "{name} at {}", o + 1.0);
        let spec = &far.scenarios[0];
        let e = evaluate(&far, spec, &run).err();
        assert!(
            e.as_ref().is_some_and(|e| e.is_unsupported()),
            "{name}: {e:?}"
        );
    }
}

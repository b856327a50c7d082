//! Moving platforms on both backends (riders carried, characters pushed, crushes reported), from
//! traces and metrics of the built-in `platforms` level.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{evaluate_all, level, rows, some_rows, value};
use platbench::config::RunConfig;
use platbench::metrics::Evaluation;
use platbench::rapier::{CharacterShape, ColliderBuilding};
use platbench::sweep::{RiderFollow, SweepConfig};

fn find<'a>(evals: &'a [(String, Evaluation)], name: &str) -> &'a Evaluation {
    &evals.iter().find(|(n, _)| n.ends_with(name)).unwrap().1
}

/// Rides whose platform never drops away faster than a rider can fall: horizontal waypoints,
/// smooth sines and a circle whose accelerations are far under gravity.
const FOLLOWABLE: [&str; 7] = [
    "ride_horizontal",
    "elevator",
    "diagonal",
    "circle",
    "walk_on_platform",
    "jump_off_and_back_on",
    "onto_one_way_lift_from_below",
];

#[test]
fn sweep_carries_riders_without_drift() {
    let evals = evaluate_all(
        &[level("platforms")],
        &platbench::sweep::kind::run_default(),
    );
    for name in FOLLOWABLE {
        // The carry bound: carry_drift <= 1e-4 tiles, the float carry's rounding over a ride (the
        // reference is a rigid carry); carry_airborne_frames = 0, on the platform throughout.
        let drift = value(&evals, name, "carry_drift");
        assert!(drift <= 1e-4, "{name}: carry_drift {drift}");
        assert_eq!(value(&evals, name, "carry_airborne_frames"), 0.0, "{name}");
    }
    // Jumping off and back on: the rider is on platform 0 again at the end.
    let back = find(&evals, "jump_off_and_back_on");
    assert_eq!(back.trace.rows.last().unwrap().platform, Some(0));
    assert!(back
        .trace
        .rows
        .iter()
        .any(|r| r.platform.is_none() && r.frame > 0));
}

#[test]
fn a_platform_dropping_faster_than_gravity_leaves_its_rider_behind() {
    // Today's rule (`RiderFollow::Gravity`; the default is Celeste's, which keeps the rider).
    // Platform 2 starts down at 20 tiles/s from rest: a rider can only fall g dt^2 in the first
    // step, so it is left in the air and falls after it: airborne frames and a growing drift are
    // the right outcome, not a defect.
    let evals = evaluate_all(&[level("platforms")], &with_rule(RiderFollow::Gravity));
    assert!(value(&evals, "fast_descent", "carry_airborne_frames") > 0.0);
    let fall = find(&evals, "fast_descent");
    // It really falls (gravity), never through the platform: no crush, no deep overlap.
    assert!(fall.trace.rows.iter().any(|r| r.vy < -5.0));
    assert_eq!(value(&evals, "fast_descent", "crush_count"), 0.0);
}

#[test]
fn sweep_pushes_without_overlap_and_reports_a_crush() {
    let evals = evaluate_all(
        &[level("platforms")],
        &platbench::sweep::kind::run_default(),
    );
    let eps = SweepConfig::default().epsilon as f64;
    for r in some_rows(&evals, "push_penetration") {
        // A push leaves no overlap beyond the sweep's own tolerance: push_penetration <=
        // epsilon; the crush's overlap is left to the crush rule.
        assert!(
            r.value <= eps,
            "{}: push_penetration {}",
            r.scenario,
            r.value
        );
    }
    // Pushed along the floor: it moved with the block.
    let pushed = find(&evals, "pushed_across_the_floor");
    let (first, last) = (pushed.trace.rows[0].x, pushed.trace.rows.last().unwrap().x);
    assert!(last - first > 2.0, "pushed {} tiles", last - first);
    // Crushed against the wall: the trace reports it, so by the crush rule (docs/metrics.md)
    // it is the crush the scenario designs and counts 0, and the character is never left
    // inside the static level (it stays against the wall, overlapping the platform).
    let crushed = find(&evals, "crushed_against_a_wall");
    assert!(crushed.trace.rows.iter().any(|r| r.crushed == 1));
    assert_eq!(value(&evals, "crushed_against_a_wall", "crush_count"), 0.0);
    assert!(value(&evals, "crushed_against_a_wall", "max_penetration") <= eps);
}

#[test]
fn rapier_runs_every_platform_scenario_and_its_carry_is_pinned() {
    for shape in CharacterShape::ALL {
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            let run = platbench::rapier::kind::run(building, shape);
            let evals = evaluate_all(&[level("platforms")], &run);
            assert_eq!(evals.len(), 10, "{}", run.label);
            // The platforms move before the characters (the default): the controller carries
            // by the velocity of the step it moves in. On the horizontal ride the rider trails
            // by one step of the 2 tiles/s platform (0.033 tiles) or two, and by three (0.1)
            // where the controller found no contact with the platform on a few early steps and
            // carried nothing (the round cuboid, measured); it stays grounded.
            let drift = value(&evals, "ride_horizontal", "carry_drift");
            assert!(
                drift <= 0.1 + 1e-4,
                "{}: horizontal drift {drift}",
                run.label
            );
            assert_eq!(
                value(&evals, "ride_horizontal", "carry_airborne_frames"),
                0.0
            );
            // Measured, pinned: on the diagonal path the rider loses the platform (>= 1 airborne
            // frame); and a character that a platform closes on against a wall ends overlapping
            // the platform (0.89 deep), as the sweep's does, with no crush reported (Rapier has
            // no crush event): the squeeze is the crush the scenario designs, counted for no
            // controller, reported or not (docs/metrics.md). Its overlap is the rule's, not
            // push_penetration's: what is left is the contact before it, under ON_PLATFORM
            // (0.05 tiles, the metrics' contact gap; measured 0.009).
            assert!(
                value(&evals, "diagonal", "carry_airborne_frames") > 0.0,
                "{}",
                run.label
            );
            let crushes = value(&evals, "crushed_against_a_wall", "crush_count");
            assert_eq!(crushes, 0.0, "{}", run.label);
            let crush = value(&evals, "crushed_against_a_wall", "push_penetration");
            assert!(crush < 0.05, "{}: {crush}", run.label);
            // A block sliding into a character standing clear of the floor pushes it along
            // without overlap: the controller moves a character hit by a kinematic body at the
            // body's velocity (measured 0 on every shape and building).
            let pushed = value(&evals, "pushed_across_the_floor", "push_penetration");
            assert_eq!(pushed, 0.0, "{}", run.label);
        }
    }
}

/// The sweep with rider-follow rule `rule`, everything else default.
fn with_rule(rule: RiderFollow) -> RunConfig {
    RunConfig::new(
        "default",
        SweepConfig {
            rider_follow: rule,
            ..SweepConfig::default()
        },
    )
}

#[test]
fn rider_follow_both_ways_on_every_platform_scenario() {
    // The rider-follow setting: both rules on every built-in platform scenario. Measured (this
    // test's numbers, which docs/sweep.md quotes): they agree everywhere except where a platform
    // moves down faster than a rider can fall: the turning elevator (today's rule: 18 airborne
    // frames and 0.12 tiles of drift in 6 s; Celeste's: 0 and 4.8e-7) and the fast drop (33 frames
    // and 5.5 tiles; Celeste's: 0 and 1e-6). So Celeste's rule is the default.
    assert_eq!(SweepConfig::default().rider_follow, RiderFollow::Solid);
    let levels = [level("platforms"), level("moving_wall"), level("elevator")];
    let gravity = evaluate_all(&levels, &with_rule(RiderFollow::Gravity));
    let solid = evaluate_all(&levels, &with_rule(RiderFollow::Solid));
    // 10 + 1 + 1 scenarios, all run by both.
    assert_eq!((gravity.len(), solid.len()), (12, 12));
    let dropping_away = ["fast_descent", "ride_turning_elevator"];
    for m in ["carry_drift", "carry_airborne_frames"] {
        for (g, s) in rows(&gravity, m).into_iter().zip(rows(&solid, m)) {
            assert_eq!(g.scenario, s.scenario);
            if m == "carry_airborne_frames" {
                // Celeste's rule never leaves a rider in the air on these rides.
                assert_eq!(s.value, 0.0, "{}: {m} {}", s.scenario, s.value);
            } else {
                // Within the float carry's rounding: 1e-4 tiles (the carry bound; measured at most
                // 2.1e-5, on walk_on_platform).
                assert!(s.value <= 1e-4, "{}: {m} {}", s.scenario, s.value);
            }
            if dropping_away.contains(&g.scenario.as_str()) {
                // Today's rule leaves the rider behind there: 18 frames and 0.12 tiles on the
                // elevator, more on the 20 tiles/s drop.
                assert!(g.value > s.value, "{}: {m} {}", g.scenario, g.value);
            } else {
                // Elsewhere the two rules move the rider identically.
                assert_eq!(g.value, s.value, "{}: {m}", g.scenario);
            }
        }
    }
    assert_eq!(
        value(&gravity, "ride_turning_elevator", "carry_airborne_frames"),
        18.0
    );
}

#[test]
fn a_rider_lifted_into_a_ceiling_is_crushed_on_the_move_that_squeezes_it() {
    // Found by review: a rider carried up into a ceiling was flagged crushed one step after its
    // box first overlapped the platform. A 4-tile lift rises at 2 tiles/s under a ceiling (row 8,
    // bottom y = 8); its 0.8 x 0.9 rider stands on it. On the first row where the rider's feet are
    // below the platform's top (by more than the epsilon, 1e-3 tiles), the trace must say crushed,
    // in float and on the subpixel grid (where the platform is where that mode places it).
    let text = "name = \"lift\"\nmap = \"\"\"\n............\n............\n############\n............\n\
                ............\n............\n............\n............\n............\n............\n\
                ############\n\"\"\"\n[[platform]]\nrect = [3.0, 2.0, 4.0, 0.5]\npath = [[3.0, 2.0], [3.0, 9.0]]\n\
                speed = 2.0\n[[scenario]]\nname = \"squeeze\"\nspawn = [5.0, 2.5]\nduration = 4.0\n";
    let lift = platbench::level::parse_level(text, "lift.toml").expect("level parses");
    for (run, grid) in [
        (platbench::sweep::kind::run_default(), 0),
        (platbench::sweep::kind::run_integer(32), 32),
    ] {
        let e = platbench::metrics::evaluate(&lift, &lift.scenarios[0], &run).expect("runs");
        let p = &lift.platforms[0];
        let dt = lift.scenarios[0].dt as f64;
        let first_inside = e
            .trace
            .rows
            .iter()
            .enumerate()
            .skip(1)
            .find(|(k, r)| r.y < p.placed_aabb(*k as f64 * dt, grid).maxs.y - 1e-3)
            .map(|(_, r)| r)
            .expect("the lift squeezes its rider into the ceiling");
        assert_eq!(first_inside.crushed, 1, "{}: {first_inside:?}", run.label);
    }
}

#[test]
fn the_sweep_in_f64_carries_as_the_float_mode_at_the_origin_and_1e12_tiles_out() {
    use platbench::sweep::kind::{run_default, run_double};
    // Every built-in level with moving platforms (the f64 mode models them: f64 world boxes on
    // their path, docs/stability.md).
    let levels = [level("platforms"), level("moving_wall"), level("elevator")];
    let float = evaluate_all(&levels, &run_default());
    let double = evaluate_all(&levels, &run_double());
    let far: Vec<_> = levels
        .iter()
        .map(|l| {
            let mut l = l.clone();
            l.origin = glam::DVec2::splat(1e12);
            l
        })
        .collect();
    let double_far = evaluate_all(&far, &run_double());
    assert_eq!((float.len(), double.len(), double_far.len()), (12, 12, 12));
    for (f, d) in some_rows(&float, "carry_drift")
        .into_iter()
        .zip(rows(&double, "carry_drift"))
    {
        assert_eq!(f.scenario, d.scenario);
        // At the origin both carry by the platform's own displacement; what drift they show is
        // rounding: the float mode's of its f32 world positions (measured up to 2.1e-5 tiles,
        // walk_on_platform), the f64 mode's only that of the trace's f32 level coordinates
        // (measured up to 4.8e-7). Bounds: the carry bound, 1e-4, on the difference (the float
        // carry's own bound), and for f64 one f32 spacing at the levels' largest coordinate (under
        // 64 tiles: 2^-18).
        assert!(
            (f.value - d.value).abs() <= 1e-4,
            "{}: {} {}",
            f.scenario,
            f.value,
            d.value
        );
        assert!(
            d.value <= 2f64.powi(-18),
            "{}: f64 drift {}",
            d.scenario,
            d.value
        );
    }
    for (d, x) in some_rows(&double, "carry_drift")
        .into_iter()
        .zip(rows(&double_far, "carry_drift"))
    {
        // 1e12 tiles out (f64 spacing 2^-13 there): the platform's corner is placed at the
        // nearest f64 (half a spacing off its path on each axis) and the rider carried with it
        // exactly, so against the exact path it shows at most one spacing per axis, sqrt(2)
        // spacings on a diagonal, plus the trace's f32 rounding (2^-18). Measured up to 1.4e-4.
        let bound = 2f64.sqrt() * 2f64.powi(-13) + 2f64.powi(-18);
        assert!(
            x.value <= bound,
            "{}: drift {} at 1e12",
            x.scenario,
            x.value
        );
        assert_eq!(d.scenario, x.scenario);
    }
    let of = |e, m| rows(e, m).into_iter().map(|r| r.value).collect::<Vec<_>>();
    // Whether a rider stays on, and whether it is crushed, do not change: equal everywhere.
    for m in ["carry_airborne_frames", "crush_count"] {
        assert_eq!(of(&float, m), of(&double, m), "{m}");
        assert_eq!(of(&double, m), of(&double_far, m), "{m}");
    }
    // Nor what the metrics read of its ground: the far trace keeps the origin's grounded and
    // platform flags, and the rider within 6e-5 of the platform's top, so the same counts.
    // (The metric's cast missed a platform 1e-5 to 1e-4 below a box: 26 false_grounded frames
    // on `diagonal` and 24 on `circle` at 1e12, none at the origin.)
    for m in ["false_grounded", "grounded_flicker"] {
        assert_eq!(of(&double, m), of(&double_far, m), "{m}");
    }
    // Frame by frame, the far run's trace follows the origin's: every move there is rounded
    // to 2^-13 tile, and over a scenario those roundings add up to at most 1.9e-4 tiles
    // (measured, walk_on_platform); the bound is the sweep's epsilon (1e-3), its own contact
    // tolerance.
    for (d, x) in double.iter().zip(&double_far) {
        assert_eq!(d.1.trace.rows.len(), x.1.trace.rows.len(), "{}", d.0);
        for (a, b) in d.1.trace.rows.iter().zip(&x.1.trace.rows) {
            let off = (a.x - b.x).abs().max((a.y - b.y).abs());
            assert!(off <= 1e-3, "{} frame {}: {off}", d.0, a.frame);
        }
    }
}

#[test]
fn rapier_f64_stops_its_rider_a_frame_at_the_turn_at_the_origin_and_not_1e12_tiles_out() {
    // docs/stability.md (f64 worlds): Rapier's controller, not the harness. At the origin the capsule
    // rests exactly at the controller's offset above platform 0; just after the platform turns
    // (t = 4 s) a cast along the surface reads the contact normal tilted 2.5e-14 against the
    // move and applies nothing: the rider stays put a frame. 1e12 tiles out it reads (0, 1).
    let run = platbench::rapier::kind::run_with(platbench::rapier::RapierConfig {
        colliders: ColliderBuilding::PerTile,
        shape: CharacterShape::Capsule,
        precision: platbench::rapier::Precision::F64,
        ..Default::default()
    });
    let mut l = level("platforms");
    l.scenarios.retain(|s| s.name == "ride_horizontal");
    let mut far = l.clone();
    far.origin = glam::DVec2::splat(1e12);
    let at_origin = evaluate_all(std::slice::from_ref(&l), &run);
    let out = evaluate_all(std::slice::from_ref(&far), &run);
    // One frame of the platform's 2 tiles/s at dt 1/60 is 1/30 tile; 1e-5: the trace's f32
    // level coordinates (measured 0.03333330).
    let drift = value(&at_origin, "ride_horizontal", "carry_drift");
    assert!((drift - 1.0 / 30.0).abs() < 1e-5, "at the origin: {drift}");
    let rows = &find(&at_origin, "ride_horizontal").trace.rows;
    assert_eq!(rows[242].x, rows[243].x, "the stop, frames 242 and 243");
    // Far out: no stop; what drift is left is the f64 spacing there (2^-13 = 1.2e-4 a
    // coordinate; measured 6.6e-5), under 1e-4, the carry bound (the float carry's rounding over a
    // ride).
    let far_drift = value(&out, "ride_horizontal", "carry_drift");
    assert!(far_drift < 1e-4, "1e12 tiles out: {far_drift}");
    let rows = &find(&out, "ride_horizontal").trace.rows;
    assert!(rows.windows(2).skip(1).all(|w| w[0].x != w[1].x));
}

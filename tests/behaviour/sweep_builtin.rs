//! The sweep controller's own bounds (a flush rest, no overlap beyond its epsilon, no jitter,
//! flicker or tunneling, no progress lost on seams, the exact jump height), asserted from the
//! traces and metrics of the built-in set.

use crate::common;

use common::{builtin_levels, evaluate_all, level, rows, some_rows};
use platbench::config::RunConfig;
use platbench::motion::{discrete_apex, jump_speed, JumpMode, MotionParams};
use platbench::scenario::effective_params;
use platbench::sweep::SweepConfig;

#[test]
fn landing_rest_and_stability_bounds_hold_on_every_scenario() {
    let evals = evaluate_all(&builtin_levels(), &platbench::sweep::kind::run_default());
    let eps = SweepConfig::default().epsilon as f64;

    let gaps = rows(&evals, "rest_gap");
    // Every scenario but the two 10 s walks ends with idle input (see compare/levels).
    assert!(
        gaps.len() >= 20,
        "rest metrics measured on {} scenarios",
        gaps.len()
    );
    // The seed's box stands on a slope by its centre and overhangs the ramp by design
    // (tests/behaviour/geometry.rs measures that overhang): on a slope a rest is inside the ramp by exactly
    // that overlap, anywhere else flush.
    let overlap = |level: &str, scenario: &str| {
        rows(&evals, "slope_overlap")
            .into_iter()
            .find(|r| r.level == level && r.scenario == scenario)
            .map_or(0.0, |r| r.value)
    };
    for r in gaps {
        // The sweep's rest bound: it snaps flush, so rest_gap <= 1e-4 tiles (or, resting on a ramp,
        // inside it by exactly the designed overlap).
        let on_ramp = (r.value + overlap(&r.level, &r.scenario)).abs() <= 1e-4;
        assert!(
            r.value.abs() <= 1e-4 || on_ramp,
            "{}.{}: rest_gap {}",
            r.level,
            r.scenario,
            r.value
        );
    }
    for r in some_rows(&evals, "max_penetration") {
        // The sweep's overlap bound: max_penetration <= the epsilon overlap tolerance, its declared
        // overlap (beyond the ramp's designed overhang on a slope).
        assert!(
            r.value <= overlap(&r.level, &r.scenario) + eps,
            "{}.{}: max_penetration {}",
            r.level,
            r.scenario,
            r.value
        );
    }
    for m in [
        "rest_jitter",
        "grounded_flicker",
        "false_grounded",
        "stuck_frames",
        "tunneled",
    ] {
        let rs = rows(&evals, m);
        assert!(!rs.is_empty());
        for r in rs {
            // Exactly 0, each metric's reference (no jitter, no flicker after landing, no
            // tunneling); the sweep never calls itself grounded in the air and never stops on open
            // ground.
            assert_eq!(r.value, 0.0, "{}.{}: {m} {}", r.level, r.scenario, r.value);
        }
    }
    let lands = rows(&evals, "land_frame_error");
    // The six drops and the fast fall onto the thin floor.
    assert!(
        lands.len() >= 7,
        "landing measured on {} scenarios",
        lands.len()
    );
    for r in lands {
        // The sweep lands on the very frame the discrete integrator predicts.
        assert_eq!(
            r.value, 0.0,
            "{}.{}: land_frame_error {}",
            r.level, r.scenario, r.value
        );
    }
    // No NaN or infinity anywhere in any trace.
    for (name, e) in &evals {
        for row in &e.trace.rows {
            for v in [row.x, row.y, row.vx, row.vy] {
                assert!(
                    v.is_finite(),
                    "{name}: non-finite value at frame {}",
                    row.frame
                );
            }
        }
    }
}

#[test]
fn walking_ten_seconds_over_seams_loses_nothing() {
    let evals = evaluate_all(
        &[level("flat_seams")],
        &platbench::sweep::kind::run_default(),
    );
    for name in ["walk_right_10s", "walk_left_10s"] {
        let r = rows(&evals, "progress_ratio")
            .into_iter()
            .find(|r| r.scenario == name)
            .unwrap_or_else(|| panic!("progress_ratio measured on {name}"));
        // The sweep's progress bound: within 1e-4 of 1 over 10 s on the seamed floor (seams cost a
        // swept box nothing).
        assert!(
            (r.value - 1.0).abs() <= 1e-4,
            "{name}: progress_ratio {}",
            r.value
        );
    }
}

#[test]
fn fast_movers_stop_flush_at_the_thin_wall_and_floor() {
    let evals = evaluate_all(
        &[level("thin_wall")],
        &platbench::sweep::kind::run_default(),
    );
    let eps = SweepConfig::default().epsilon;
    let find = |n: &str| &evals.iter().find(|(k, _)| k.ends_with(n)).unwrap().1;
    // The wall is column 20 (x in [20, 21]); the character is 0.8 wide, so its feet x must stay
    // at or left of 19.6 (+eps) coming from the left, at or right of 21.4 from the right.
    let right = find("fast_right");
    assert!(right.trace.rows.iter().all(|r| r.x <= 19.6 + eps));
    assert!((right.trace.rows.last().unwrap().x - 19.6).abs() < 1e-4);
    let left = find("fast_left");
    assert!(left.trace.rows.iter().all(|r| r.x >= 21.4 - eps));
    // The thin floor is row 6 (y in [6, 7]): the fast fall must rest on its top.
    let down = find("fast_down");
    assert!(down.trace.rows.iter().all(|r| r.y >= 7.0 - eps));
    assert_eq!(down.trace.rows.last().unwrap().y, 7.0);
}

#[test]
fn exact_discrete_jump_reaches_the_requested_height_and_continuous_undershoots() {
    let jumps = level("jumps");
    let exact = evaluate_all(
        std::slice::from_ref(&jumps),
        &platbench::sweep::kind::run_default(),
    );
    let continuous_run = RunConfig {
        params: MotionParams {
            jump_mode: JumpMode::Continuous,
            ..Default::default()
        },
        ..platbench::sweep::kind::run_default()
    };
    let continuous = evaluate_all(std::slice::from_ref(&jumps), &continuous_run);
    let ex = rows(&exact, "apex_error");
    assert_eq!(ex.len(), 7, "six standing jumps and one running jump");
    for r in &ex {
        // The exact jump's bound: apex_error <= 1e-4 tiles in exact-discrete mode (the take-off
        // speed is solved so that the symplectic-Euler apex is the requested height,
        // `motion::jump_speed`: only rounding is left).
        assert!(
            r.value.abs() <= 1e-4,
            "{}: apex_error {}",
            r.scenario,
            r.value
        );
    }
    for r in some_rows(&continuous, "apex_error") {
        let spec = jumps
            .scenarios
            .iter()
            .find(|s| s.name == r.scenario)
            .unwrap();
        let p = effective_params(&continuous_run.params, spec);
        let v = jump_speed(&p, spec.dt);
        let predicted = discrete_apex(p.gravity, v, spec.dt) - p.jump_height as f64;
        // The continuous formula's undershoot is the discrete integrator's, not collision
        // error: the trace must match the analytic discrete apex (f32 noise, 1e-4).
        assert!(
            (r.value - predicted).abs() <= 1e-4,
            "{}: {} vs {predicted}",
            r.scenario,
            r.value
        );
        // And it is a real, visible error: between 0 and one step's rise (v dt) short.
        assert!(
            r.value < -0.01 && r.value > -(v * spec.dt) as f64,
            "{}: {}",
            r.scenario,
            r.value
        );
    }
}

#[test]
fn two_runs_give_bit_identical_traces() {
    let levels = builtin_levels();
    let a = evaluate_all(&levels, &platbench::sweep::kind::run_default());
    let b = evaluate_all(&levels, &platbench::sweep::kind::run_default());
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        let (mut cx, mut cy) = (Vec::new(), Vec::new());
        x.trace.write_csv(&mut cx).unwrap();
        y.trace.write_csv(&mut cy).unwrap();
        assert!(cx == cy, "{name}: traces differ between two runs");
    }
}

//! `idle_drift` (its reference: standing still): a standing character with no input, off ladders
//! and riding nothing, stays put; a wall sliding flush past its side does not carry it.

use crate::common;

use common::{builtin_levels, evaluate_all, level, rows};
use platbench::metrics::{compute, Context};
use platbench::motion::MotionParams;
use platbench::scenario::effective_params;
use platbench::shape::CharacterShape;

#[test]
fn the_sweep_stands_still_wherever_it_stands_idle() {
    let evals = evaluate_all(&builtin_levels(), &platbench::sweep::kind::run_default());
    let drifts = rows(&evals, "idle_drift");
    // Every scenario that ends standing has an idle span (drops, rests, walks that stop).
    assert!(drifts.len() >= 20, "{} scenarios measured", drifts.len());
    for r in drifts {
        // A standing sweep character is not moved; what is left is f32 rounding of positions
        // below 64 tiles (one ulp there is 7.6e-6).
        assert!(
            r.value <= 7.6e-6,
            "{}.{}: idle_drift {}",
            r.level,
            r.scenario,
            r.value
        );
    }
}

#[test]
fn a_character_dragged_by_the_passing_wall_is_seen() {
    let wall = level("moving_wall");
    let evals = evaluate_all(
        std::slice::from_ref(&wall),
        &platbench::sweep::kind::run_default(),
    );
    let (_, e) = &evals[0];
    let spec = &wall.scenarios[0];
    let params = effective_params(&MotionParams::default(), spec);
    let measure = |t: &platbench::trace::Trace| {
        compute(&Context {
            shape: CharacterShape::Cuboid,
            level: &wall,
            spec,
            params: &params,
            trace: t,
            declared: Default::default(),
        })
        .into_iter()
        .find(|r| r.metric == "idle_drift")
        .expect("idle_drift measured")
        .value
    };
    // The sweep's own run: the wall slides past twice and the character does not move.
    assert_eq!(measure(&e.trace), 0.0);
    // The same trace, dragged 0.001 tiles a frame away from the wall from frame 60 on (as a
    // controller that takes a side contact for ground would be): the drift is the drag's sum.
    let mut dragged = e.trace.clone();
    let n = dragged.rows.len();
    for r in dragged.rows.iter_mut().skip(60) {
        r.x -= 0.001 * (r.frame as f32 - 59.0);
    }
    let expected = 0.001 * (n as f64 - 60.0);
    // 1e-4: f32 positions near x = 5.
    assert!(
        (measure(&dragged) - expected).abs() < 1e-4,
        "{} vs {expected}",
        measure(&dragged)
    );
}

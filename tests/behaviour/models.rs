//! A reference is a model's choice: the slope speed against constant horizontal speed and against
//! constant speed along the surface, both reported; the rest gap against touching and against the
//! configuration's own declared contact.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{evaluate_all, level, rows};
use platbench::metrics::{compute, Context, DeclaredContact, MetricRow};
use platbench::motion::MotionParams;
use platbench::scenario::effective_params;
use platbench::shape::CharacterShape;
use platbench::trace::Trace;

#[test]
fn slope_speed_is_shown_against_both_models() {
    // (level, gradient of its ramps)
    for (name, gradient) in [
        ("slope_22_5", 0.41421f64),
        ("slope_26_6", 0.5),
        ("slope_45", 1.0),
    ] {
        let evals = evaluate_all(&[level(name)], &platbench::sweep::kind::run_default());
        let horizontal = rows(&evals, "slope_speed_ratio");
        let along = rows(&evals, "slope_surface_speed_ratio");
        assert!(
            !horizontal.is_empty() && horizontal.len() == along.len(),
            "{name}"
        );
        for (h, a) in horizontal.iter().zip(&along) {
            assert_eq!(h.scenario, a.scenario);
            // The seed keeps its horizontal speed, so along the surface it goes faster: at most
            // sqrt(1 + gradient²) times (on the ramp itself; crest and foot steps bend less).
            // 1e-3: f32 positions.
            let steepest = (1.0 + gradient * gradient).sqrt();
            assert!(
                a.value > h.value,
                "{name}.{}: {} vs {}",
                a.scenario,
                a.value,
                h.value
            );
            assert!(
                a.value <= h.value * steepest + 1e-3,
                "{name}.{}: {}",
                a.scenario,
                a.value
            );
        }
    }
}

fn rest_gaps(t: &Trace, declared: DeclaredContact) -> (f64, f64) {
    let drops = level("drops");
    let spec = drops
        .scenarios
        .iter()
        .find(|s| s.name == "drop_1")
        .expect("drop_1");
    let params = effective_params(&MotionParams::default(), spec);
    let rows = compute(&Context {
        shape: CharacterShape::Cuboid,
        level: &drops,
        spec,
        params: &params,
        trace: t,
        declared,
    });
    let v = |m: &str| -> f64 {
        rows.iter()
            .find(|r: &&MetricRow| r.metric == m)
            .expect("measured")
            .value
    };
    (v("rest_gap"), v("rest_gap_declared"))
}

#[test]
fn a_rest_is_scored_against_the_gap_the_configuration_declares() {
    let evals = evaluate_all(&[level("drops")], &platbench::sweep::kind::run_default());
    let (_, e) = evals
        .iter()
        .find(|(n, _)| n == "drops.drop_1")
        .expect("drop_1 ran");
    // Rapier's default offset: 1% of the 0.9-tile height.
    let offset = DeclaredContact {
        gap: 0.009,
        ..Default::default()
    };
    // The sweep rests flush: touching kept (0), and against a declared offset it is 0.009 too
    // close (a controller that declares a gap and does not keep it is charged).
    let (touch, declared) = rest_gaps(&e.trace, DeclaredContact::default());
    assert!(touch.abs() < 1e-6 && declared.abs() < 1e-6);
    let (_, broken) = rest_gaps(&e.trace, offset);
    assert!((broken + 0.009).abs() < 1e-6, "{broken}");
    // The same rest lifted by the offset: 0.009 from touching, and the declared promise kept.
    let mut lifted = e.trace.clone();
    for r in &mut lifted.rows {
        r.y += 0.009;
    }
    let (touch, kept) = rest_gaps(&lifted, offset);
    // 1e-6: f32 positions near y = 1.
    assert!(
        (touch - 0.009).abs() < 1e-6 && kept.abs() < 1e-6,
        "{touch} {kept}"
    );
}

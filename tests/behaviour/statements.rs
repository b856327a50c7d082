//! The report's statements on a controller that is not built in: a toy that lands a frame late
//! (tests/common's `LateLander`, the sweep with its grounded flag reported a frame late) is told
//! "Lands late", and the sweep it wraps is not.

use crate::common;

use platbench::config::RunConfig;
use platbench::report::rules::{evaluate, RULES};

#[test]
fn a_controller_that_lands_a_frame_late_is_stated_to_land_late() {
    let levels = common::builtin_levels();
    let mut rows = Vec::new();
    for run in [
        platbench::sweep::kind::run_default(),
        RunConfig::new("default", common::LateLander::default()),
    ] {
        for (_, e) in common::evaluate_all(&levels, &run) {
            rows.extend(e.metrics);
        }
    }
    let late: Vec<f64> = rows
        .iter()
        .filter(|r| r.backend == "late_lander" && r.metric == "land_frame_error")
        .map(|r| r.value)
        .collect();
    assert!(!late.is_empty(), "no landing measured");
    // One frame late on every drop: the flag waits for a step that starts grounded.
    assert!(late.iter().all(|&v| v == 1.0), "{late:?}");
    let said = evaluate(RULES, &rows);
    let lands_late: Vec<&String> = said
        .iter()
        .filter(|s| s.starts_with("Lands late"))
        .collect();
    assert_eq!(lands_late.len(), 1, "{said:?}");
    assert!(lands_late[0].contains("late_lander (1)"), "{said:?}");
    // The sweep lands on the integrator's frame (tests/behaviour/sweep_builtin.rs): not named.
    assert!(!lands_late[0].contains("sweep"), "{said:?}");
    assert!(
        !said.iter().any(|s| s.starts_with("Lands early")),
        "{said:?}"
    );
}

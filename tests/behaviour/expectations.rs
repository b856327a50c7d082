//! A level that says what should happen: a character walking into a bottomless pit fails the
//! level's expectations (`expect_*`) and the `left_level` fault, each at the frame its trace
//! shows; a character that walks where the level says passes them.

use crate::common;

use common::evaluate_all;
use platbench::config::RunConfig;
use platbench::level::parse_level;
use platbench::metrics::{Evaluation, MetricRow};

/// A 20 x 4 map: floor (row 0) under x 0..6 and 10..20, a bottomless pit at x 6..10.
/// `walk_into_pit` walks right from x 2.5 for 3 s (180 frames at 1/60 s) and expects to be on
/// the far side (x 15..19) by 3 s, standing, never below 0.5; `walk_past_pit` starts beyond the
/// pit and walks right for 1 s at 8 tiles/s, a region it reaches.
const GAPS: &str = r#"
name = "gaps"
map = """
....................
....................
....................
######....##########
"""

[[scenario]]
name = "walk_into_pit"
spawn = [2.5, 1.0]
duration = 3.0
inputs = [ { t = 0.0, right = true } ]
[scenario.expect]
reach = { x = [15, 19], y = [1, 1.5], by = 3.0 }
grounded_at_end = true
min_y = 0.5
stay_in_map = true

[[scenario]]
name = "walk_past_pit"
spawn = [11.5, 1.0]
duration = 2.0
inputs = [ { t = 0.0, right = true }, { t = 0.5, right = false } ]
[scenario.expect]
reach = { x = [13, 19], y = [1, 1.5], by = 1.5 }
grounded_at_end = true
min_y = 0.5
stay_in_map = true
"#;

/// The configurations the test runs: the sweep, and Rapier's when it is built.
fn configs() -> Vec<RunConfig> {
    #[allow(unused_mut)]
    let mut runs = vec![platbench::sweep::kind::run_default()];
    #[cfg(feature = "rapier")]
    for shape in platbench::rapier::CharacterShape::ALL {
        runs.push(platbench::rapier::kind::run(
            platbench::rapier::ColliderBuilding::Merged,
            shape,
        ));
    }
    runs
}

fn row<'a>(e: &'a Evaluation, metric: &str) -> &'a MetricRow {
    e.metrics
        .iter()
        .find(|r| r.metric == metric)
        .unwrap_or_else(|| panic!("no {metric} row"))
}

#[test]
fn a_character_falling_into_a_pit_fails_where_the_trace_shows_it() {
    let level = parse_level(GAPS, "gaps.toml").unwrap();
    for run in configs() {
        let evals = evaluate_all(std::slice::from_ref(&level), &run);
        let (name, e) = &evals[0];
        assert_eq!(name, "gaps.walk_into_pit");
        let rows = &e.trace.rows;
        let at = |m: &str| (row(e, m).value, row(e, m).frame);
        let label = &run.label;
        // It really fell: the pit is bottomless, so the feet end far below the floor's bottom
        // (y = 0), 3 s of falling from 1.
        let last = rows.last().unwrap();
        assert!(last.y < -5.0, "{label}: ends at y {}", last.y);
        // left_level: the first frame whose feet are below the level's bottom (its lowest tile
        // row, 0) while falling.
        let below = rows.iter().find(|r| r.y < 0.0 && r.vy < 0.0).unwrap();
        assert_eq!(at("left_level"), (1.0, Some(below.frame)), "{label}");
        // It walked off the pit's edge (x = 6) first: no frame before it left the floor.
        assert!(rows[below.frame as usize].x > 5.0, "{label}");
        // min_y = 0.5: the first frame under it.
        let under = rows.iter().find(|r| r.y < 0.5).unwrap();
        assert_eq!(at("expect_min_y"), (1.0, Some(under.frame)), "{label}");
        assert!(under.frame < below.frame, "{label}");
        // reach by 3 s: frame 180 (3 / (1/60)), the deadline, it never got there.
        assert_eq!(at("expect_reach"), (1.0, Some(180)), "{label}");
        // Airborne at the end, on the last frame (180).
        assert_eq!(at("expect_grounded_at_end"), (1.0, Some(180)), "{label}");
        // stay_in_map: the feet leave the map (y < 0) on the first frame below y = 0.
        let out = rows.iter().find(|r| r.y < 0.0).unwrap();
        assert_eq!(at("expect_stay_in_map"), (1.0, Some(out.frame)), "{label}");
    }
}

#[test]
fn a_character_that_reaches_the_region_passes() {
    let level = parse_level(GAPS, "gaps.toml").unwrap();
    for run in configs() {
        let evals = evaluate_all(std::slice::from_ref(&level), &run);
        let (name, e) = &evals[1];
        assert_eq!(name, "gaps.walk_past_pit");
        let label = &run.label;
        let at = |m: &str| (row(e, m).value, row(e, m).frame);
        // The region starts at x = 13: the pass is the first frame the feet are at or past it.
        let inside = e.trace.rows.iter().find(|r| r.x >= 13.0).unwrap();
        assert_eq!(at("expect_reach"), (0.0, Some(inside.frame)), "{label}");
        // Standing on the last frame (120: 2 s at 1/60 s).
        assert_eq!(at("expect_grounded_at_end"), (0.0, Some(120)), "{label}");
        // Never below 0.5, never out of the map, never out of the level: no offending frame.
        for m in ["expect_min_y", "expect_stay_in_map", "left_level"] {
            assert_eq!(at(m), (0.0, None), "{label} {m}");
        }
    }
}

#[test]
fn a_scenario_that_states_nothing_gets_only_the_left_level_fault() {
    // The pit scenario without its expect table: still flagged as leaving the level, with no
    // expect_* row (nothing was stated).
    let text = GAPS.replacen(
        "[scenario.expect]\nreach = { x = [15, 19], y = [1, 1.5], by = 3.0 }\ngrounded_at_end = true\nmin_y = 0.5\nstay_in_map = true\n",
        "",
        1,
    );
    assert_ne!(text, GAPS);
    let level = parse_level(&text, "gaps.toml").unwrap();
    let evals = evaluate_all(
        std::slice::from_ref(&level),
        &platbench::sweep::kind::run_default(),
    );
    let e = &evals[0].1;
    assert_eq!(row(e, "left_level").value, 1.0);
    assert!(e.metrics.iter().all(|r| !r.metric.starts_with("expect_")));
}

//! `left_level` and the `expect_*` rows on hand-made traces: each passes on a trace that keeps
//! the promise and fails, at the frame that broke it, on one that does not.

use super::*;
use crate::level::{parse_level, Deadline, Expectations, Reach, ScenarioSpec};
use crate::metrics::tests::{spec, trace, LEVEL};
use crate::metrics::{DeclaredContact, Measure};
use crate::motion::MotionParams;
use crate::shape::CharacterShape;
use crate::trace::Trace;
use glam::Vec2;

fn run(level: &Level, s: &ScenarioSpec, t: &Trace, f: fn(&Context, Frames) -> Measure) -> Measure {
    let p = MotionParams::default();
    f(
        &Context {
            shape: CharacterShape::Cuboid,
            level,
            spec: s,
            params: &p,
            trace: t,
            declared: DeclaredContact::default(),
        },
        Frames::new(&t.rows),
    )
}

fn run_opt(
    level: &Level,
    s: &ScenarioSpec,
    t: &Trace,
    f: fn(&Context, Frames) -> Option<Measure>,
) -> Option<Measure> {
    let p = MotionParams::default();
    f(
        &Context {
            shape: CharacterShape::Cuboid,
            level,
            spec: s,
            params: &p,
            trace: t,
            declared: DeclaredContact::default(),
        },
        Frames::new(&t.rows),
    )
}

/// LEVEL (tests.rs): 20 x 4 tiles, a floor on row 0 and a wall in column 10.
fn level() -> Level {
    parse_level(LEVEL, "m.toml").unwrap()
}

fn with(expect: Expectations) -> ScenarioSpec {
    let mut s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
    s.expect = expect;
    s
}

/// A trace whose rows fall at `vy` (tiles/s) from their second row on.
fn falling(points: &[(f32, f32, bool)], vy: f32) -> Trace {
    let mut t = trace(points);
    for r in t.rows.iter_mut().skip(1) {
        r.vy = vy;
    }
    t
}

#[test]
fn the_bottom_is_the_lowest_tile_row_or_platform_reach() {
    // LEVEL's floor is row 0: nothing is lower than y = 0.
    assert_eq!(level_bottom(&level()), 0.0);
    // Two empty rows under a floor on row 2: its bottom is y = 2.
    let high = parse_level("map = \"\"\"\n....\n####\n....\n....\n\"\"\"\n", "h.toml").unwrap();
    assert_eq!(level_bottom(&high), 2.0);
    // A lift going down to y = 0.5 (its rect's corner at 3, path to 0.5) catches below row 2.
    let lift = parse_level(
        "map = \"\"\"\n....\n####\n....\n....\n\"\"\"\n[[platform]]\nrect = [0.0, 3.0, 1.0, 0.25]\npath = [[0.0, 3.0], [0.0, 0.5]]\nspeed = 1.0\n",
        "l.toml",
    )
    .unwrap();
    assert_eq!(level_bottom(&lift), 0.5);
    // An empty map: its own bottom.
    let empty = parse_level("map = \"\"\"\n....\n....\n\"\"\"\n", "e.toml").unwrap();
    assert_eq!(level_bottom(&empty), 0.0);
}

#[test]
fn falling_below_the_floor_leaves_the_level_at_the_first_frame_below() {
    let l = level();
    let s = with(Expectations::default());
    // Feet at 1 (on the floor), 0.5 (sunk), then -0.2: below the bottom (0) while falling.
    let t = falling(
        &[(2.5, 1.0, true), (2.5, 0.5, false), (2.5, -0.2, false)],
        -5.0,
    );
    let m = run(&l, &s, &t, left_level);
    assert_eq!((m.value, m.frame), (1.0, Some(2)));
    // The same heights rising (vy > 0) have not left: something may still be caught.
    let t = falling(
        &[(2.5, 1.0, true), (2.5, 0.5, false), (2.5, -0.2, false)],
        5.0,
    );
    assert_eq!(run(&l, &s, &t, left_level).frame, None);
}

#[test]
fn walking_off_the_side_leaves_the_level_once_the_box_is_wholly_beside_the_map() {
    let l = level();
    let s = with(Expectations::default());
    // LEVEL is 20 wide; the box is 0.8 wide: at x = 20.3 it still overlaps the map (left edge
    // 19.9), at 20.5 it is wholly beside it (left edge 20.1). Left side: x = -0.5 (right edge
    // -0.1).
    let t = trace(&[(19.0, 1.0, true), (20.3, 1.0, true), (20.5, 1.0, true)]);
    assert_eq!(run(&l, &s, &t, left_level).frame, Some(2));
    let t = trace(&[(1.0, 1.0, true), (-0.3, 1.0, true), (-0.5, 1.0, true)]);
    assert_eq!(run(&l, &s, &t, left_level).frame, Some(2));
    // High above the map (y = 50 on a 4-tile map) is not leaving it.
    let t = trace(&[(2.5, 1.0, true), (2.5, 50.0, false), (2.5, 1.0, true)]);
    assert_eq!(run(&l, &s, &t, left_level).value, 0.0);
}

#[test]
fn reach_passes_at_the_first_frame_inside_and_fails_at_the_deadline() {
    let l = level();
    let reach = |by| Expectations {
        reach: Some(Reach {
            min: Vec2::new(5.0, 1.0),
            max: Vec2::new(6.0, 2.0),
            by,
        }),
        ..Default::default()
    };
    // Frames 0..4 at x = 2.5, 4, 5 (inside: bounds inclusive), 6.5.
    let t = trace(&[
        (2.5, 1.0, true),
        (4.0, 1.0, true),
        (5.0, 1.0, true),
        (6.5, 1.0, true),
    ]);
    let m = run_opt(&l, &with(reach(Deadline::End)), &t, expect_reach).unwrap();
    assert_eq!((m.value, m.frame), (0.0, Some(2)));
    // By frame 1 (or by 0.15 s at dt 0.1: frame 1) it was not there yet.
    let m = run_opt(&l, &with(reach(Deadline::Frame(1))), &t, expect_reach).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(1)));
    let m = run_opt(&l, &with(reach(Deadline::Seconds(0.15))), &t, expect_reach).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(1)));
    // By 0.2 s: frame 2, the frame at 0.2 s itself.
    let m = run_opt(&l, &with(reach(Deadline::Seconds(0.2))), &t, expect_reach).unwrap();
    assert_eq!((m.value, m.frame), (0.0, Some(2)));
    // No region stated: no row.
    assert!(run_opt(&l, &with(Expectations::default()), &t, expect_reach).is_none());
}

#[test]
fn end_state_and_height_expectations_fail_where_they_break() {
    let l = level();
    let t = trace(&[(2.5, 1.0, true), (2.5, 0.4, false), (2.5, 3.0, false)]);
    let grounded = |g| Expectations {
        grounded_at_end: Some(g),
        ..Default::default()
    };
    // Airborne at the end (frame 2).
    let m = run_opt(&l, &with(grounded(true)), &t, expect_grounded_at_end).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(2)));
    let m = run_opt(&l, &with(grounded(false)), &t, expect_grounded_at_end).unwrap();
    assert_eq!((m.value, m.frame), (0.0, Some(2)));
    // Never below 0.5: broken at frame 1 (0.4); never below 0.4 holds (strictly below fails).
    let min = |y| Expectations {
        min_y: Some(y),
        ..Default::default()
    };
    let m = run_opt(&l, &with(min(0.5)), &t, expect_min_y).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(1)));
    let m = run_opt(&l, &with(min(0.4)), &t, expect_min_y).unwrap();
    assert_eq!((m.value, m.frame), (0.0, None));
    // Stay in the 20 x 4 map: y = 5 at frame 2 leaves it through the top.
    let stay = Expectations {
        stay_in_map: true,
        ..Default::default()
    };
    let t = trace(&[(2.5, 1.0, true), (2.5, 4.0, false), (2.5, 5.0, false)]);
    let m = run_opt(&l, &with(stay), &t, expect_stay_in_map).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(2)));
}

#[test]
fn land_on_needs_the_named_platform_under_the_feet() {
    // A platform at rest-ish (1e-6 tiles/s): its top at y = 2, x from 4 to 6.
    let l = parse_level(
        &format!("{LEVEL}[[platform]]\nrect = [4.0, 1.75, 2.0, 0.25]\npath = [[4.0, 1.75], [4.0, 1.0]]\nspeed = 0.000001\n"),
        "p.toml",
    )
    .unwrap();
    let s = with(Expectations {
        land_on: Some(0),
        ..Default::default()
    });
    // Grounded on the floor beside it, then on its top at frame 2.
    let t = trace(&[(2.5, 1.0, true), (3.0, 1.0, true), (4.5, 2.0, true)]);
    let m = run_opt(&l, &s, &t, expect_land_on).unwrap();
    assert_eq!((m.value, m.frame), (0.0, Some(2)));
    // Over its top but airborne, then beside it: never on it, failed at the last frame.
    let t = trace(&[(2.5, 1.0, true), (4.5, 2.0, false), (7.0, 1.0, true)]);
    let m = run_opt(&l, &s, &t, expect_land_on).unwrap();
    assert_eq!((m.value, m.frame), (1.0, Some(2)));
}

//! Each metric family reports the trace frame its value came from: hand-made traces whose worst
//! frame is known (the deepest overlap on frame 7 reads `Some(7)`, a late landing its landing
//! frame, a count its first offending frame, an end state the last frame).
use super::tests::{spec, trace, LEVEL};
use super::*;
use crate::level::{parse_level, InputEvent};

/// Every metric of `t`, a run of `s` on the level of TOML `level`.
fn measure_on(level: &str, s: &ScenarioSpec, t: &Trace) -> Vec<MetricRow> {
    let level = parse_level(level, "m.toml").unwrap();
    let p = MotionParams::default();
    compute(&Context {
        shape: CharacterShape::Cuboid,
        level: &level,
        spec: s,
        params: &p,
        trace: t,
        declared: DeclaredContact::default(),
    })
}

/// Metric `m`'s frame (the outer `None`: not reported).
fn frame(rows: &[MetricRow], m: &str) -> Option<Option<u32>> {
    rows.iter().find(|r| r.metric == m).map(|r| r.frame)
}

fn hold(right: bool, up: bool, jump: bool) -> Vec<InputEvent> {
    vec![InputEvent {
        t: 0.0,
        right: right.then_some(true),
        up: up.then_some(true),
        jump: jump.then_some(true),
        ..Default::default()
    }]
}

#[test]
fn a_peak_is_the_first_frame_at_the_fold_s_maximum() {
    let mut p = Peak::new(0.0);
    for (f, v) in [(0, -0.5), (1, 0.2), (2, 0.7), (3, 0.1), (4, 0.7)] {
        p.push(f, v);
    }
    assert_eq!((p.value, p.frame), (0.7, Some(2)));
    // Nothing above the start: the first row, and the start's value.
    let mut p = Peak::new(0.0);
    p.push(5, -1.0);
    p.push(6, 0.0);
    assert_eq!((p.value, p.frame), (0.0, Some(5)));
    assert_eq!(Peak::new(0.0).frame, None);
}

#[test]
fn landing_metrics_give_the_deepest_the_widest_and_the_last_frame() {
    // A rest on the floor (top y = 1), sunk 0.02 at frame 3 and 0.05 at frames 7 and 9.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
    let mut pts = vec![(2.5, 1.0, true); 11];
    pts[3].1 = 0.98;
    pts[7].1 = 0.95;
    pts[9].1 = 0.95;
    let rows = measure_on(LEVEL, &s, &trace(&pts));
    assert_eq!(frame(&rows, "max_penetration"), Some(Some(7)));
    assert_eq!(frame(&rows, "penetration_beyond_declared"), Some(Some(7)));
    // The settled rest is rows 6 to 10: its range is reached at the low of frame 7.
    assert_eq!(frame(&rows, "rest_jitter"), Some(Some(7)));
    assert_eq!(frame(&rows, "rest_gap"), Some(Some(10)));
    assert_eq!(frame(&rows, "rest_gap_declared"), Some(Some(10)));
    // The largest drift from where it settled (frame 1) is 0.05, first at frame 7.
    assert_eq!(frame(&rows, "idle_drift"), Some(Some(7)));
    // Nothing offended: the counts and events have no frame.
    for m in [
        "bounce_frames",
        "grounded_flicker",
        "false_grounded",
        "stuck_frames",
        "tunneled",
    ] {
        assert_eq!(frame(&rows, m), Some(None), "{m}");
    }
}

#[test]
fn landing_counts_give_their_first_offending_frame() {
    // Flicker: left the ground with it still under the feet at frames 2 and 4.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 0.5);
    let pts = [
        (2.5, 1.0, true),
        (2.5, 1.0, true),
        (2.5, 1.005, false),
        (2.5, 1.0, true),
        (2.5, 1.005, false),
        (2.5, 1.0, true),
    ];
    let rows = measure_on(LEVEL, &s, &trace(&pts));
    assert_eq!(frame(&rows, "grounded_flicker"), Some(Some(2)));
    // Grounded 2 tiles above the floor at frames 4 and 6; a bounce at frame 8.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
    let mut pts = vec![(2.5, 1.0, true); 11];
    pts[4] = (2.5, 3.0, true);
    pts[6] = (2.5, 3.0, true);
    pts[8] = (2.5, 1.3, false);
    let rows = measure_on(LEVEL, &s, &trace(&pts));
    assert_eq!(frame(&rows, "false_grounded"), Some(Some(4)));
    assert_eq!(frame(&rows, "bounce_frames"), Some(Some(8)));
}

#[test]
fn a_late_landing_gives_its_landing_frame_and_no_landing_the_last() {
    // Predicted to land at frame 2 (see tests.rs); lands at frame 4.
    let drop = spec(Vec2::new(2.5, 1.5), vec![], 2.0);
    let mut pts = vec![(2.5, 1.5, false); 4];
    pts.extend(vec![(2.5, 1.0, true); 17]);
    let rows = measure_on(LEVEL, &drop, &trace(&pts));
    assert_eq!(frame(&rows, "land_frame_error"), Some(Some(4)));
    let rows = measure_on(LEVEL, &drop, &trace(&[(2.5, 1.5, false); 21]));
    assert_eq!(frame(&rows, "land_frame_error"), Some(Some(20)));
}

/// An open floor (top y = 1) with room above for a 3-tile jump.
const TALL: &str = r#"
name = "m"
map = """
....................
....................
....................
....................
....................
....................
....................
....................
####################
"""
"#;

#[test]
fn a_jump_gives_its_apex_frame() {
    let s = spec(Vec2::new(2.5, 1.0), hold(false, false, true), 0.8);
    let ys = [1.0, 1.5, 2.0, 2.2, 2.2, 2.0, 1.5, 1.0, 1.0];
    let pts: Vec<_> = ys.iter().map(|&y| (2.5, y, y == 1.0)).collect();
    let rows = measure_on(TALL, &s, &trace(&pts));
    assert_eq!(frame(&rows, "apex_error"), Some(Some(3)));
}

#[test]
fn a_walk_gives_its_first_stuck_frame_and_its_last_for_progress() {
    // Commanded 0.6 tiles a step: it moves on step 1 and stalls on steps 2 and 3 (frames 2, 3).
    let walk = spec(Vec2::new(1.5, 1.0), hold(true, false, false), 0.5);
    let pts = [
        (1.5, 1.0, true),
        (2.1, 1.0, true),
        (2.1, 1.0, true),
        (2.1, 1.0, true),
        (2.7, 1.0, true),
        (3.3, 1.0, true),
    ];
    let rows = measure_on(LEVEL, &walk, &trace(&pts));
    assert_eq!(frame(&rows, "stuck_frames"), Some(Some(2)));
    assert_eq!(frame(&rows, "progress_ratio"), Some(Some(5)));
}

#[test]
fn a_tunnel_gives_the_frame_past_the_wall() {
    let s = spec(Vec2::new(5.5, 1.0), vec![], 0.3);
    let pts = [
        (5.5, 1.0, true),
        (8.5, 1.0, true),
        (15.5, 1.0, true),
        (15.5, 1.0, true),
    ];
    let rows = measure_on(LEVEL, &s, &trace(&pts));
    assert_eq!(frame(&rows, "tunneled"), Some(Some(2)));
}

/// A 45-degree ramp at column 4, rising to the right from the floor (top y = 1) to y = 2.
const RAMP: &str = r#"
name = "m"
map = """
..........
..........
....a#....
##########
"""
[legend]
"a" = { line = [0.0, 1.0] }
"#;

#[test]
fn slope_metrics_give_the_deepest_and_the_farthest_frame() {
    // Dropped onto the ramp and left there: inside it by the box's overhang on most frames,
    // deepest at frame 6, hovering 0.9 above its surface under the centre at frame 5.
    let s = spec(Vec2::new(4.5, 1.5), vec![], 1.0);
    let mut pts = vec![(4.5, 1.5, true); 11];
    pts[5].1 = 2.4;
    pts[6].1 = 1.3;
    let rows = measure_on(RAMP, &s, &trace(&pts));
    assert_eq!(frame(&rows, "slope_overlap"), Some(Some(6)));
    assert_eq!(frame(&rows, "slope_gap_max"), Some(Some(5)));
}

/// A 45-degree ramp rising right over columns 5 to 7, from the floor (top y = 1) to y = 4.
const HILL: &str = r#"
name = "m"
map = """
..............
.......a......
......a#......
.....a##......
##############
"""
[legend]
"a" = { line = [0.0, 1.0] }
"#;

#[test]
fn slope_speeds_give_the_step_farthest_from_the_run_speed() {
    // Walking up at 3 tiles/s across, but 1 tile/s on the step into frame 5.
    let walk = spec(Vec2::new(5.05, 1.05), hold(true, false, false), 0.7);
    let xs = [5.05, 5.35, 5.65, 5.95, 6.25, 6.35, 6.65, 6.95];
    let rows = measure_on(HILL, &walk, &trace(&xs.map(|x| (x, x - 4.0, true))));
    assert_eq!(frame(&rows, "slope_speed_ratio"), Some(Some(5)));
    assert_eq!(frame(&rows, "slope_surface_speed_ratio"), Some(Some(5)));
}

/// A ramp steeper than the climb limit at column 4, two tiles high.
const STEEP: &str = r#"
name = "m"
map = """
..........
....b.....
....a#....
##########
"""
[legend]
"a" = { line = [0.0, 2.0] }
"b" = { line = [-1.0, 1.0] }
"#;

#[test]
fn a_blocked_climb_gives_its_highest_frame() {
    let walk = spec(Vec2::new(2.5, 1.0), hold(true, false, false), 0.5);
    let pts = [
        (2.5, 1.0, true),
        (3.1, 1.0, true),
        (3.5, 1.0, true),
        (3.6, 1.2, true),
        (3.6, 1.1, true),
        (3.6, 1.0, true),
    ];
    let rows = measure_on(STEEP, &walk, &trace(&pts));
    assert_eq!(
        rows.iter()
            .find(|r| r.metric == "steep_blocked")
            .map(|r| (r.value, r.frame)),
        Some((1.0, Some(3)))
    );
}

/// A ladder at column 4 from the floor (top y = 1) to y = 3, and a one-way platform at y = 3.
const LADDER: &str = r#"
name = "m"
map = """
..........
....H..==.
....H.....
##########
"""
"#;

#[test]
fn a_climb_gives_its_worst_step_and_an_end_state_its_last_frame() {
    let mut s = spec(Vec2::new(4.5, 1.0), hold(false, true, false), 0.5);
    s.expect_y = Some(1.85);
    let ys = [1.0, 1.2, 1.4, 1.45, 1.65, 1.85];
    let mut t = trace(&ys.map(|y| (4.5, y, false)));
    for r in &mut t.rows[1..] {
        r.ladder = 1;
    }
    // At 4 tiles/s, the 0.5 tiles/s step into frame 3 is the worst.
    let rows = measure_on(LADDER, &s, &t);
    assert_eq!(frame(&rows, "ladder_speed_error"), Some(Some(3)));
    assert_eq!(frame(&rows, "ladder_result"), Some(Some(5)));
    assert_eq!(frame(&rows, "oneway_result"), Some(Some(5)));
    // Never on the ladder: the first frame it was told to climb.
    let t = trace(&[(4.5, 1.0, true); 6]);
    let rows = measure_on(LADDER, &s, &t);
    assert_eq!(frame(&rows, "ladder_speed_error"), Some(Some(1)));
}

/// A floor (top y = 1) and a 2 x 0.5 platform at x 4 rising from y 1 at 1 tile/s.
const LIFT: &str = "name = \"m\"\nmap = \"\"\"\n..........\n..........\n..........\n##########\n\"\"\"\n[[platform]]\nrect = [4.0, 1.0, 2.0, 0.5]\npath = [[4.0, 1.0], [4.0, 3.0]]\nspeed = 1.0\n";

#[test]
fn platform_metrics_give_the_deepest_frame_the_first_crush_and_the_ride_s_frames() {
    // Feet at x 3.7 (0.1 into the platform) at frame 2, 4.5 (0.6 deep) at frame 3 and (0.4
    // deep, the platform risen) at frame 5: crushed twice, first at frame 3.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 0.5);
    let xs = [2.5, 2.5, 3.7, 4.5, 2.5, 4.5];
    let rows = measure_on(LIFT, &s, &trace(&xs.map(|x| (x, 1.0, true))));
    assert_eq!(frame(&rows, "push_penetration"), Some(Some(3)));
    assert_eq!(frame(&rows, "crush_count"), Some(Some(3)));
    // Riding its top (y 1.5 + t): shifted 0.2 at frame 4, airborne at frame 6.
    let mut ride = spec(Vec2::new(5.0, 1.5), vec![], 0.8);
    ride.ride = Some(0);
    let mut pts: Vec<_> = (0..9).map(|k| (5.0, 1.5 + k as f32 * 0.1, true)).collect();
    pts[4].0 = 5.2;
    pts[6].2 = false;
    let rows = measure_on(LIFT, &ride, &trace(&pts));
    assert_eq!(frame(&rows, "carry_drift"), Some(Some(4)));
    assert_eq!(frame(&rows, "carry_airborne_frames"), Some(Some(6)));
}

#[test]
fn a_timing_row_has_no_frame() {
    let level = parse_level(LEVEL, "m.toml").unwrap();
    let s = spec(Vec2::new(2.5, 1.0), vec![], 0.1);
    let run = crate::sweep::kind::run_default();
    let t = super::timing::Timing {
        median: 10.0,
        q1: 9.0,
        q3: 12.0,
    };
    let row = timing_row(&level, &s, &run, t);
    assert_eq!(
        (row.frame, row.value, row.q1, row.q3),
        (None, 10.0, Some(9.0), Some(12.0))
    );
}

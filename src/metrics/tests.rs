//! Each metric on hand-made traces of a bad controller, so that a test asserting a bound on
//! a real run is known to be able to fail.
use super::*;
use crate::level::{parse_level, InputEvent};

pub(super) const LEVEL: &str = r#"
name = "m"
map = """
..........#.........
..........#.........
..........#.........
####################
"""
"#;

pub(super) fn spec(spawn: Vec2, inputs: Vec<InputEvent>, duration: f32) -> ScenarioSpec {
    ScenarioSpec {
        name: "s".into(),
        spawn,
        size: Vec2::new(0.8, 0.9),
        velocity: Vec2::ZERO,
        duration,
        dt: 0.1,
        inputs,
        motion: Default::default(),
        expect_y: None,
        ride: None,
        expect: Default::default(),
    }
}

pub(super) fn trace(points: &[(f32, f32, bool)]) -> Trace {
    Trace {
        level: "m".into(),
        scenario: "s".into(),
        backend: "fake".into(),
        config: "default".into(),
        rows: points
            .iter()
            .enumerate()
            .map(|(k, &(x, y, g))| TraceRow {
                frame: k as u32,
                t: k as f32 * 0.1,
                character: 0,
                x,
                y,
                vx: 0.0,
                vy: 0.0,
                grounded: g as u8,
                ground_nx: 0.0,
                ground_ny: 0.0,
                platform: None,
                ladder: 0,
                crushed: 0,
            })
            .collect(),
    }
}

fn measure(s: &ScenarioSpec, t: &Trace) -> Vec<MetricRow> {
    let level = parse_level(LEVEL, "m.toml").unwrap();
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

fn value(rows: &[MetricRow], m: &str) -> Option<f64> {
    rows.iter().find(|r| r.metric == m).map(|r| r.value)
}

#[test]
fn every_computed_metric_is_in_the_registry() {
    // A walk and a rest: the metrics every scenario gets and the rest metrics. A metric
    // computed but not registered would print with no unit, in no table.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
    let rows = measure(&s, &trace(&[(2.5, 1.0, true); 11]));
    // A rest with no input gets the rest metrics and those of every scenario.
    let names: Vec<&str> = rows.iter().map(|r| r.metric).collect();
    assert_eq!(
        names,
        [
            "rest_gap",
            "rest_gap_declared",
            "max_penetration",
            "penetration_beyond_declared",
            "rest_jitter",
            "bounce_frames",
            "grounded_flicker",
            "false_grounded",
            "stuck_frames",
            "tunneled",
            "idle_drift",
            "left_level"
        ]
    );
    for r in &rows {
        assert!(
            registry::get(r.metric).is_some(),
            "{} unregistered",
            r.metric
        );
        assert_eq!(r.unit, registry::unit(r.metric));
    }
}

#[test]
fn tunneling_through_the_wall_is_detected() {
    let s = spec(Vec2::new(5.5, 1.0), vec![], 0.2);
    let through = trace(&[(5.5, 1.0, true), (15.5, 1.0, true), (15.5, 1.0, true)]);
    assert_eq!(value(&measure(&s, &through), "tunneled"), Some(1.0));
    let stopped = trace(&[(5.5, 1.0, true), (9.6, 1.0, true), (9.6, 1.0, true)]);
    assert_eq!(value(&measure(&s, &stopped), "tunneled"), Some(0.0));
    // Dropping through the floor from above.
    let fell = trace(&[(2.5, 2.0, false), (2.5, -1.5, false), (2.5, -2.0, false)]);
    assert_eq!(value(&measure(&s, &fell), "tunneled"), Some(1.0));
}

#[test]
fn penetration_rest_gap_and_jitter_are_measured() {
    let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
    let mut pts = vec![(2.5, 1.0, true); 11];
    pts[4].1 = 0.97; // sank 0.03 into the floor while settling
    pts[8].1 = 0.99; // dips 0.01 in the last half second, at rest
    pts[10].1 = 1.02; // ends 0.02 above it
    let rows = measure(&s, &trace(&pts));
    assert!((value(&rows, "max_penetration").unwrap() - 0.03).abs() < 1e-6);
    assert!((value(&rows, "rest_gap").unwrap() - 0.02).abs() < 1e-6);
    // Jitter counts from the settled rest (the last 0.5 s, rows 6 to 10): 1.02 - 0.99. The
    // settling dip at row 4 is the landing's business, not the rest's.
    assert!((value(&rows, "rest_jitter").unwrap() - 0.03).abs() < 1e-6);
}

#[test]
fn flicker_counts_unexplained_airborne_frames_on_ground() {
    let s = spec(Vec2::new(2.5, 1.0), vec![], 0.5);
    let pts = [
        (2.5, 1.0, true),
        (2.5, 1.0, true),
        (2.5, 1.005, false),
        (2.5, 1.0, true),
        (2.5, 1.005, false),
        (2.5, 1.0, true),
    ];
    assert_eq!(
        value(&measure(&s, &trace(&pts)), "grounded_flicker"),
        Some(2.0)
    );
}

#[test]
fn stuck_frames_count_open_ground_only_and_false_grounded_counts_air() {
    let right = vec![InputEvent {
        t: 0.0,
        right: Some(true),
        ..Default::default()
    }];
    // Commanded 0.6 tiles a step; the character moves on step 1, stalls on steps 2 and 3.
    let walk = spec(Vec2::new(1.5, 1.0), right.clone(), 0.3);
    let pts = [
        (1.5, 1.0, true),
        (2.1, 1.0, true),
        (2.1, 1.0, true),
        (2.1, 1.0, true),
    ];
    assert_eq!(
        value(&measure(&walk, &trace(&pts)), "stuck_frames"),
        Some(2.0)
    );
    // Against the wall at x = 10 (box edge 9.6 + 0.4): blocked, not stuck.
    let wall = spec(Vec2::new(9.6, 1.0), right, 0.2);
    let pts = [(9.6, 1.0, true), (9.6, 1.0, true), (9.6, 1.0, true)];
    assert_eq!(
        value(&measure(&wall, &trace(&pts)), "stuck_frames"),
        Some(0.0)
    );
    // Grounded 2 tiles above the floor: false; grounded 0.05 above or 0.3 sunk: real ground.
    let s = spec(Vec2::new(2.5, 1.0), vec![], 0.3);
    let pts = [
        (2.5, 3.0, true),
        (2.5, 1.05, true),
        (2.5, 0.7, true),
        (2.5, 3.0, false),
    ];
    assert_eq!(
        value(&measure(&s, &trace(&pts)), "false_grounded"),
        Some(1.0)
    );
}

#[test]
fn progress_ratio_and_landing_on_a_stuck_or_late_controller() {
    let walk = spec(
        Vec2::new(1.5, 1.0),
        vec![InputEvent {
            t: 0.0,
            right: Some(true),
            ..Default::default()
        }],
        0.5,
    );
    // Commanded: 0.1 s steps at accel 60 reach 6 t/s in one step: 5 x 0.6 = 3 tiles.
    let stuck = trace(&[(1.5, 1.0, true); 6]);
    assert_eq!(value(&measure(&walk, &stuck), "progress_ratio"), Some(0.0));
    let drop = spec(Vec2::new(2.5, 1.5), vec![], 2.0);
    // From 0.5 tiles at g dt² = 0.3: 0.3 * n(n+1)/2 >= 0.5 at n = 2; landing at frame 4.
    let mut pts = vec![(2.5, 1.5, false); 4];
    pts.extend(vec![(2.5, 1.0, true); 17]);
    assert_eq!(
        value(&measure(&drop, &trace(&pts)), "land_frame_error"),
        Some(2.0)
    );
}

#[test]
fn clipped_scans_equal_the_whole_box() {
    // A character far wider and taller than a small map (60 x 60 tiles over a 6 x 4 map with
    // solids, a slope and a one-way tile), placed so that its box covers the whole map and
    // beyond: the overlaps found walking the map's cells only are those found walking every
    // cell of the box, the walk the metrics did before it was clipped (cells outside the map
    // are empty). 60 tiles keeps the whole-box walk small; the clip is the same at 1000.
    use crate::level::character_box;
    use crate::shape::CharacterShape;
    let level = parse_level(
        "map = \"\"\"\n......\n..=...\n./##..\n######\n\"\"\"\n",
        "c.toml",
    )
    .unwrap();
    let size = Vec2::new(60.0, 60.0);
    for shape in [
        CharacterShape::Cuboid,
        CharacterShape::Capsule,
        CharacterShape::Ball,
    ] {
        let g = ground::Ground::new(&level, shape, size);
        for feet in [
            Vec2::new(3.0, 0.5),
            Vec2::new(-20.0, 1.0),
            Vec2::new(10.0, -3.5),
        ] {
            let mut clipped = Vec::new();
            g.each_overlap(feet, true, true, |t, d| clipped.push((t, d)));
            // Every cell of the box, in the same order (rows, then columns).
            let bb = character_box(feet, size);
            let mut whole = Vec::new();
            for j in bb.mins.y.floor() as i64 - 1..bb.maxs.y.ceil() as i64 + 1 {
                for i in bb.mins.x.floor() as i64 - 1..bb.maxs.x.ceil() as i64 + 1 {
                    let d = g.tile_overlap(feet, i, j);
                    if d > 0.0 {
                        whole.push(((i, j), d));
                    }
                }
            }
            assert_eq!(clipped, whole, "{shape:?} at {feet}");
        }
    }
}

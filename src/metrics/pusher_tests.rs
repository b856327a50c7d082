//! A scenario that shoves or crushes by design, judged by its own rule: hand-made traces where a
//! moving block shoves, lifts or squeezes the character (see [`super::pushers`]).
use super::tests::{spec, trace};
use super::*;
use crate::level::parse_level;

/// A floor (top y = 1), a wall from x = 10 up, and a 1 x 1 block on the floor sliding right at
/// 2 tiles/s (0.2 tiles a 0.1 s step) from x = `from` to the wall and beyond.
fn level(from: f32) -> String {
    format!(
        "name = \"m\"\nmap = \"\"\"\n..........#.........\n..........#.........\n..........#.........\n####################\n\"\"\"\n[[platform]]\nrect = [{from}, 1.0, 1.0, 1.0]\npath = [[{from}, 1.0], [10.5, 1.0]]\nspeed = 2.0\n"
    )
}

fn measure(level_toml: &str, s: &ScenarioSpec, t: &Trace) -> Vec<MetricRow> {
    let level = parse_level(level_toml, "m.toml").unwrap();
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

fn metric(rows: &[MetricRow], m: &str) -> (f64, Option<u32>) {
    let r = rows.iter().find(|r| r.metric == m).unwrap();
    (r.value, r.frame)
}

/// The character (0.8 wide, feet at x 5) stands still until the block (x 2 to 3 at t = 0)
/// reaches its left side at frame 8; from there the block shoves it right, jostling it 0.1 up
/// and off the ground every other frame, to the end (frame 14).
fn shoved() -> (String, ScenarioSpec, Trace) {
    let s = spec(Vec2::new(5.0, 1.0), vec![], 1.4);
    let pts: Vec<(f32, f32, bool)> = (0..15)
        .map(|k| {
            if k < 8 {
                (5.0, 1.0, true)
            } else {
                let up = k % 2 == 1;
                (5.0 + 0.2 * (k - 8) as f32, if up { 1.1 } else { 1.0 }, !up)
            }
        })
        .collect();
    (level(2.0), s, trace(&pts))
}

#[test]
fn a_shove_does_not_feed_the_rest_metrics() {
    let (l, s, t) = shoved();
    let rows = measure(&l, &s, &t);
    // The settled rest is its last 0.5 s (frames 10 to 14), all shoved: the 0.1-tile jostle
    // (which rest_jitter read before) and the three airborne frames (which bounce_frames
    // counted: 11, 13) are the block's doing.
    assert_eq!(metric(&rows, "rest_jitter"), (0.0, None));
    assert_eq!(metric(&rows, "bounce_frames"), (0.0, None));
    // The same jostle with no block is charged: the rule leaves out only the pushed frames.
    let rows = measure(super::tests::LEVEL, &s, &t);
    assert!((metric(&rows, "rest_jitter").0 - 0.1).abs() < 1e-6);
    assert_eq!(metric(&rows, "bounce_frames").0, 3.0);
}

#[test]
fn a_fall_off_a_block_that_slid_away_is_not_a_bounce() {
    // A 1 x 1 block from x 5.5 sliding left at 2 tiles/s runs into the character standing at
    // x 5 (0.8 wide: frames 1 to 3 inside it) and lifts it onto its top (y 2, frames 4 to 9);
    // its right edge passes the character's left side (x 4.6) after frame 9, so the character
    // falls (frames 10 to 12), lands at frame 13 and hops at frame 15. The fall is the block's
    // doing; the hop after landing is a bounce.
    let s = spec(Vec2::new(5.0, 1.0), vec![], 1.8);
    let mut pts = vec![(5.0, 1.0, true); 19];
    for p in &mut pts[4..10] {
        *p = (5.0, 2.0, true);
    }
    pts[10] = (5.0, 1.8, false);
    pts[11] = (5.0, 1.5, false);
    pts[12] = (5.0, 1.1, false);
    pts[15] = (5.0, 1.05, false);
    let l = "name = \"m\"\nmap = \"\"\"\n..........\n..........\n..........\n##########\n\"\"\"\n[[platform]]\nrect = [5.5, 1.0, 1.0, 1.0]\npath = [[5.5, 1.0], [0.5, 1.0]]\nspeed = 2.0\n";
    let rows = measure(l, &s, &trace(&pts));
    // Before the rule: 4 frames, the first at 10 (the fall counted as a bounce).
    assert_eq!(metric(&rows, "bounce_frames"), (1.0, Some(15)));
}

/// The character (feet at x 9.6, flush against the wall at x 10) stays where it is while the
/// block (x 7 to 8 at t = 0) slides into it and squeezes it against the wall: the room left is
/// less than its 0.8 width from frame 7 (face at 9.4), and it is 0.4 deep inside the block at
/// frame 8. `flag`: whether the trace flags the crush (the sweep's `crushed` column).
fn crushed(flag: bool) -> Vec<MetricRow> {
    let s = spec(Vec2::new(9.6, 1.0), vec![], 1.0);
    let mut t = trace(&[(9.6, 1.0, true); 11]);
    if flag {
        for r in &mut t.rows[7..] {
            r.crushed = 1;
        }
    }
    measure(&level(7.0), &s, &t)
}

#[test]
fn a_crush_by_design_that_ends_flagged_is_the_crush_rule_s() {
    let flagged = crushed(true);
    // Squeezed and reported: the crush the scenario designs, not counted; the block's overlap
    // from the squeeze on is the crush, not a push fault (before the squeeze it only touched:
    // 0).
    assert_eq!(metric(&flagged, "crush_count"), (0.0, None));
    assert_eq!(metric(&flagged, "push_penetration").0, 0.0);
    // The same squeeze with no crush reported (a controller with no crush event, as Rapier and
    // Box2D have none) is judged alike: the crush by design, not counted, and its depth not a
    // push fault.
    let silent = crushed(false);
    assert_eq!(metric(&silent, "crush_count"), (0.0, None));
    assert_eq!(metric(&silent, "push_penetration").0, 0.0);
}

#[test]
fn a_platform_that_runs_through_a_character_with_room_counts() {
    // The block slides from x 2 into a character at x 5 that it should push (its face reaches
    // the character's side, x 4.6, at frame 8, with 5 tiles of room before the wall): the
    // trace leaves it in place, the block 0.4 inside at frame 10. Not a squeeze: counted,
    // and its depth is a push fault, whatever the trace flags.
    let s = spec(Vec2::new(5.0, 1.0), vec![], 1.5);
    let mut t = trace(&[(5.0, 1.0, true); 16]);
    for r in &mut t.rows {
        r.crushed = 1;
    }
    let rows = measure(&level(2.0), &s, &t);
    assert_eq!(metric(&rows, "crush_count").0, 1.0);
    assert!(metric(&rows, "push_penetration").0 > platforms::CRUSH_DEPTH as f64);
}

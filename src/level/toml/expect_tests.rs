//! The `expect` table's unit tests: what it reads, and each error at its line and column.

use glam::Vec2;

use super::*;
use crate::level::{Deadline, Expectations, Reach};

/// A 6 x 3 level with one platform and a scenario of 2 s at 1/60 s (120 frames), `expect`
/// (lines from line 14 on) appended after its `[[scenario]]` keys.
fn level(expect: &str) -> Result<Level, LevelError> {
    let text = format!(
        r#"name = "t"
map = """
......
......
######
"""
[[platform]]
rect = [2.0, 1.0, 1.0, 0.25]
sine = {{ amplitude = [0.0, 1.0], period = 2.0 }}
[[scenario]]
name = "s"
spawn = [0.5, 1.0]
duration = 2.0
{expect}
"#
    );
    parse_level(&text, "bad.toml")
}

#[test]
fn reads_every_expectation() {
    let l = level(
        "[scenario.expect]\nreach = { x = [4, 5.5], by = 1.5 }\ngrounded_at_end = true\nmin_y = 0.5\nstay_in_map = true\nland_on = 0\n",
    )
    .unwrap();
    assert_eq!(
        l.scenarios[0].expect,
        Expectations {
            reach: Some(Reach {
                min: Vec2::new(4.0, f32::NEG_INFINITY),
                max: Vec2::new(5.5, f32::INFINITY),
                by: Deadline::Seconds(1.5),
            }),
            grounded_at_end: Some(true),
            min_y: Some(0.5),
            stay_in_map: true,
            land_on: Some(0),
        }
    );
    // Inline, with a frame deadline; no table: nothing expected.
    let l = level("expect = { reach = { y = [2, 3], by_frame = 120 } }").unwrap();
    let r = l.scenarios[0].expect.reach.unwrap();
    assert_eq!((r.min.y, r.max.y, r.by), (2.0, 3.0, Deadline::Frame(120)));
    assert!(level("").unwrap().scenarios[0].expect.is_empty());
}

/// The error of `expect`, with its line and column.
fn err(expect: &str) -> LevelError {
    match level(expect) {
        Err(e) => e,
        Ok(_) => panic!("{expect:?} was accepted"),
    }
}

#[test]
fn an_unknown_key_names_itself_and_the_known_ones() {
    // Line 14 is the first line of `expect`; `grounded` starts at column 1.
    let e = err("[scenario.expect]\ngrounded = true\n");
    assert_eq!((e.line, e.column), (15, 1), "{e}");
    assert!(e.message.contains("unknown field `grounded`"), "{e}");
    assert!(e.message.contains("grounded_at_end"), "{e}");
    // Inside reach: `t` is not `by`.
    let e = err("expect = { reach = { x = [1, 2], t = 1.0 } }");
    assert_eq!(e.line, 14, "{e}");
    assert!(e.message.contains("unknown field `t`"), "{e}");
    assert!(e.message.contains("by_frame"), "{e}");
}

#[test]
fn a_value_of_the_wrong_kind_says_what_was_expected() {
    // `"yes"` starts at column 19 of line 15.
    let e = err("[scenario.expect]\ngrounded_at_end = \"yes\"\n");
    assert_eq!((e.line, e.column), (15, 19), "{e}");
    assert!(e.message.contains("string"), "{e}");
    assert!(e.message.contains("bool"), "{e}");
    // A platform by a name: platforms are numbered.
    let e = err("[scenario.expect]\nland_on = \"lift\"\n");
    assert_eq!((e.line, e.column), (15, 11), "{e}");
    assert!(
        e.message.contains(
            "expect.land_on is string \"lift\"; expected a platform's number, 0 <= land_on < 1"
        ),
        "{e}"
    );
}

#[test]
fn bad_regions_deadlines_and_platforms_are_placed() {
    // `[5, 4]` starts at column 15 of line 15.
    let e = err("[scenario.expect]\nreach = { x = [5, 4] }\n");
    assert_eq!((e.line, e.column), (15, 15), "{e}");
    assert!(
        e.message
            .contains("expect.reach x is [5, 4]; expected [low, high] with low <= high"),
        "{e}"
    );
    let e = err("[scenario.expect]\nreach = { by = 1.0 }\n");
    assert_eq!((e.line, e.column), (15, 9), "{e}");
    assert!(e.message.contains("states no region"), "{e}");
    // The scenario lasts 2 s, 120 frames.
    let e = err("[scenario.expect]\nreach = { x = [1, 2], by = 2.5 }\n");
    assert_eq!((e.line, e.column), (15, 28), "{e}");
    assert!(
        e.message.contains("expected 0 <= by <= duration (2)"),
        "{e}"
    );
    let e = err("[scenario.expect]\nreach = { x = [1, 2], by_frame = 121 }\n");
    assert_eq!((e.line, e.column), (15, 34), "{e}");
    assert!(e.message.contains("expected 0 <= by_frame <= 120"), "{e}");
    let e = err("[scenario.expect]\nreach = { x = [1, 2], by = 1.0, by_frame = 3 }\n");
    assert!(e.message.contains("both `by`"), "{e}");
    // The level has one platform, number 0.
    let e = err("[scenario.expect]\nland_on = 1\n");
    assert_eq!((e.line, e.column), (15, 11), "{e}");
    assert!(
        e.message.contains(
            "land_on = 1 names no platform; expected a platform's number, 0 <= land_on < 1"
        ),
        "{e}"
    );
    let e = err("[scenario.expect]\nmin_y = nan\n");
    assert_eq!((e.line, e.column), (15, 9), "{e}");
    assert!(e.message.contains("expect.min_y is NaN"), "{e}");
}

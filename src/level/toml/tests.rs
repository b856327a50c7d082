//! The format's unit tests: maps, legends, platforms, scenarios and their errors, through
//! [`parse_level`].

use glam::Vec2;

use super::*;
use crate::level::{Slope, Tile, DEFAULT_CHARACTER_SIZE};

const OK: &str = r#"
name = "t"
map = """
....
#..#
####
"""

[[scenario]]
name = "drop"
spawn = [1.5, 2.0]
duration = 1.0
inputs = [ { t = 0.0, right = true }, { t = 0.5, right = false } ]
"#;

#[test]
fn parses_map_bottom_up() {
    let l = parse_level(OK, "t.toml").unwrap();
    assert_eq!((l.width, l.height), (4, 3));
    assert_eq!(l.tile(0, 0), Tile::Solid);
    assert_eq!(l.tile(0, 1), Tile::Solid);
    assert_eq!(l.tile(1, 1), Tile::Empty);
    assert_eq!(l.tile(0, 2), Tile::Empty);
    assert_eq!(l.scenarios.len(), 1);
    assert_eq!(l.scenarios[0].inputs[1].right, Some(false));
    assert_eq!(l.scenarios[0].size, DEFAULT_CHARACTER_SIZE);
}

fn err(text: &str) -> LevelError {
    parse_level(text, "bad.toml").unwrap_err()
}

#[test]
fn unknown_map_character_names_line_and_column() {
    let e = err("map = \"\"\"\n....\n.x..\n\"\"\"\n");
    assert_eq!((e.line, e.column), (3, 2), "{e}");
    assert!(e.message.contains("unknown map character 'x'"), "{e}");
    assert!(e.to_string().starts_with("bad.toml:3:2:"));
}

#[test]
fn a_map_written_with_escapes_parses_and_its_errors_point_into_the_string() {
    // A basic string with `\n` escapes once panicked: positions computed in the value were
    // used to slice the file's text, landing inside the multi-byte 'é' of the name.
    let l = parse_level(
        "name = \"t\"\ndescription = \"é\"\nmap = \"....\\n####\\n\"\n",
        "t.toml",
    )
    .unwrap();
    assert_eq!((l.width, l.height), (4, 2));
    assert_eq!(l.tile(0, 0), Tile::Solid);
    // The 'x' is column 13 of line 1: after `map = "..`, `\n` and `.`.
    let e = err("map = \"..\\n.x\\n\"\n");
    assert_eq!((e.line, e.column), (1, 13), "{e}");
    assert!(e.message.contains("unknown map character 'x'"), "{e}");
    // A short row: at the end of its text, before the `\n` that ends it.
    let e = err("map = \"\\u00e9é\\n.\\n\"\n[legend]\n\"é\" = \"solid\"\n");
    assert_eq!((e.line, e.column), (1, 18), "{e}");
    assert!(e.message.contains("map row 2 has 1 tiles"), "{e}");
    // The case that panicked: the end of row 2 computed in the value fell inside the second
    // 'é' of the text; it is the closing quote.
    let e = err("map = \"\\néé\"\n");
    assert_eq!((e.line, e.column), (1, 12), "{e}");
}

#[test]
fn ragged_rows_are_an_error() {
    let e = err("map = \"\"\"\n....\n...\n\"\"\"\n");
    assert_eq!(e.line, 3, "{e}");
    assert!(e.message.contains("has 3 tiles, expected 4"), "{e}");
}

#[test]
fn toml_syntax_error_has_position() {
    let e = err("name = \"x\"\nmap = [\n");
    assert!(e.line >= 2, "{e}");
}

#[test]
fn unknown_field_is_named() {
    let e = err("map = \"#\"\nmpa = 3\n");
    assert_eq!(e.line, 2, "{e}");
    assert!(e.message.contains("unknown field"), "{e}");
}

#[test]
fn spawn_inside_solid_is_rejected() {
    let e = err("map = \"\"\"\n..\n##\n\"\"\"\n[[scenario]]\nname = \"a\"\nspawn = [0.5, 0.5]\nduration = 1.0\n");
    assert_eq!(e.line, 7, "{e}");
    assert!(e.message.contains("inside the solid tile"), "{e}");
}

#[test]
fn inputs_out_of_order_and_bad_numbers() {
    let base = "map = \"\"\"\n..\n##\n\"\"\"\n[[scenario]]\nname = \"a\"\nspawn = [0.5, 1.0]\n";
    let e = err(&format!("{base}duration = -1.0\n"));
    assert!(e.message.contains("expected a number > 0"), "{e}");
    let e = err(&format!("{base}duration = nan\n"));
    assert!(e.message.contains("finite"), "{e}");
    let e = err(&format!(
        "{base}duration = 2.0\ninputs = [ {{ t = 1.0 }}, {{ t = 0.5 }} ]\n"
    ));
    assert!(e.message.contains("time order"), "{e}");
    assert_eq!(e.line, 9, "{e}");
}

#[test]
fn legend_entries_and_features() {
    let text = "map = \"ab=H#\"\n[legend]\na = { heights = [12, 11, 10, 8, 7, 6, 5, 5, 5, 5, 5, 4, 3, 2, 1, 1] }\nb = { line = [0.0, 0.5] }\n";
    let l = parse_level(text, "f.toml").unwrap();
    assert!(l.features.slopes && l.features.one_way && l.features.ladders);
    assert_eq!(
        l.tile(1, 0),
        Tile::Slope(Slope::Line {
            left: 0.0,
            right: 0.5
        })
    );
    let e = err("map = \"a\"\n[legend]\na = { heights = [1, 2] }\n");
    assert_eq!(e.line, 3, "{e}");
    assert!(e.message.contains("exactly 16"), "{e}");
    let e = err("map = \"a\"\n[legend]\na = { line = [0.0] }\n");
    assert!(e.message.contains("line slope"), "{e}");
    let e = err("map = \"a\"\n[legend]\nab = \"solid\"\n");
    assert!(e.message.contains("single character"), "{e}");
}

#[test]
fn platforms_parse_and_bad_ones_are_named() {
    let ok = "map = \"....\"\n[[platform]]\nrect = [0, 0, 2, 0.5]\npath = [[0, 0], [2, 0]]\nspeed = 1.0\n";
    let l = parse_level(ok, "p.toml").unwrap();
    assert!(l.features.moving_platforms);
    assert_eq!(l.platforms[0].size, Vec2::new(2.0, 0.5));
    let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\n");
    assert!(e.message.contains("exactly one motion"), "{e}");
    assert_eq!(e.line, 2, "{e}");
    // More waypoints than the limit (src/limits.rs MAX_PATH_POINTS): refused before any work.
    let long: Vec<String> = (0..=crate::limits::MAX_PATH_POINTS)
        .map(|i| format!("[{i}, 0]"))
        .collect();
    let e = err(&format!(
        "map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\npath = [{}]\nspeed = 1\n",
        long.join(", ")
    ));
    assert!(
        e.to_string()
            .contains("1001 waypoints; expected at most 1000"),
        "{e}"
    );
    let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\npath = [[0, 0]]\nspeed = 1\n");
    assert!(e.message.contains("at least 2 waypoints"), "{e}");
    let e =
        err("map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\npath = [[1, 0], [2, 0]]\nspeed = 1\n");
    assert!(e.message.contains("first waypoint"), "{e}");
    let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, -1, 1]\nsine = { amplitude = [1, 0], period = 2 }\n");
    assert!(e.message.contains("rect width"), "{e}");
}

#[test]
fn empty_map_is_an_error() {
    let e = err("map = \"\"\n");
    assert!(e.message.contains("empty"), "{e}");
}

#[test]
fn an_origin_is_exact_in_f64_up_to_1e15_tiles_and_an_error_beyond() {
    let with = |o: &str| format!("name = \"t\"\norigin = {o}\nmap = \"\"\"\n....\n####\n\"\"\"\n");
    // 1e12 and 1e15 - 0.125 are not f32s (the nearest are 999,999,995,904 and
    // 999,999,986,991,104): kept exactly, for an f64 backend to place the level there.
    let l = parse_level(&with("[1e12, -999999999999999.875]"), "o.toml").unwrap();
    assert_eq!(l.origin, glam::DVec2::new(1e12, -(1e15 - 0.125)));
    // Within 1e7 the f32 backends' origin is the one they always had (the f32 nearest).
    let l = parse_level(&with("[1234.5, 0.1]"), "o.toml").unwrap();
    assert_eq!(l.origin_f32(), Vec2::new(1234.5, 0.1f32));
    // Beyond limits::MAX_ORIGIN (1e15, the stress matrix's largest offset): located, with
    // the range expected.
    for (o, what) in [
        ("[2e15, 0.0]", "origin x"),
        ("[0.0, -1e16]", "origin y"),
        ("[nan, 0.0]", "origin x"),
        ("[1e308, 0.0]", "origin x"),
    ] {
        let e = parse_level(&with(o), "o.toml").unwrap_err();
        assert_eq!(
            (e.file.as_str(), e.line, e.column),
            ("o.toml", 2, 10),
            "{e}"
        );
        assert!(e.message.starts_with(&format!("{what} is ")), "{e}");
        assert!(
            e.message.contains(&format!(
                "expected -1000000000000000 <= {what} <= 1000000000000000 (tiles)"
            )),
            "{e}"
        );
    }
    // Past 1e16 in exponent form: 1e308 is not printed as its 309 digits.
    let e = parse_level(&with("[1e308, 0.0]"), "o.toml").unwrap_err();
    assert!(e.message.starts_with("origin x is 1e308; expected"), "{e}");
}

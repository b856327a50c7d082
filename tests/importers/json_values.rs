//! Issue 40's unclear errors on a Tiled JSON map: values Tiled never writes where they are (a
//! top level that is no object, a size that is not a positive whole number, a number written
//! as a string, a cell that is not a tile id), once passed to the `tiled` crate or told with no
//! line. Each is now refused by the walk before serde_json reads the file
//! (src/level/tiled/json_values.rs), with exit 2 and `FILE:LINE:COLUMN:`, the layer or object,
//! what was found and what was expected; what Tiled does write (floats for an object's place,
//! strings for property values) is still read. Every map here is written for these tests.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::Path;

use super::common::platbench;

/// A 3 x 2 map, one key or a few a line, with placeholders: `W` the map's width (line 4), `TW`
/// its tile width (line 6), `TSW` the tileset's (line 9), `LW` the floor layer's width (line
/// 12), `CELL` the floor's cell 4 (x = 1, y = 1; line 14), `SX` the spawn's x (line 15).
const MAP: &str = r#"{
"type": "map", "version": "1.10", "orientation": "orthogonal", "infinite": false,
"properties": [{"name": "width", "type": "string", "value": "wide"}],
"width": W,
"height": 2,
"tilewidth": TW,
"tileheight": 16,
"tilesets": [
{"firstgid": 1, "name": "t", "tilewidth": TSW, "tileheight": 16, "tilecount": 16, "columns": 16, "image": "t.png", "imagewidth": 256, "imageheight": 16}],
"layers": [
{"type": "tilelayer", "name": "floor",
"width": LW, "height": 2,
"data": [0, 0, 0,
1, CELL, 1]},
{"type": "objectgroup", "name": "spawns", "objects": [{"id": 1, "name": "spawn", "point": true, "x": SX, "y": 16}]}
]
}
"#;

/// [`MAP`] with `subs` in place of their placeholders and the defaults for the rest.
fn map(subs: &[(&str, &str)]) -> String {
    let mut all: Vec<(&str, &str)> = subs.to_vec();
    for d in [
        ("TSW", "16"),
        ("TW", "16"),
        ("LW", "3"),
        ("W", "3"),
        ("CELL", "1"),
        ("SX", "8.5"),
    ] {
        if !all.iter().any(|s| s.0 == d.0) {
            all.push(d);
        }
    }
    // Longer placeholders first: `TSW` and `TW` hold `W`.
    all.sort_by_key(|s| std::cmp::Reverse(s.0.len()));
    let mut text = MAP.to_string();
    for (k, v) in all {
        text = text.replace(k, v);
    }
    text
}

/// `NAME:LINE:COLUMN` of the first `needle` on 1-based line `line` of `text` (the column
/// 1-based, in bytes: these files are ASCII).
fn at(name: &str, text: &str, line: usize, needle: &str) -> String {
    let l = text.lines().nth(line - 1).unwrap();
    format!("{name}:{line}:{}", l.find(needle).unwrap() + 1)
}

/// The error line of `platbench COMMAND` on `text` written as `DIR/NAME`, asserting exit 2.
fn error(dir: &Path, command: &str, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    let mut cmd = platbench();
    cmd.arg(command).arg(&p);
    if command == "run" {
        cmd.args(["--backend", "sweep", "--out"])
            .arg(dir.join("out"));
    }
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// Asserts that `err` is an error line holding `want` after the file's place `place`
/// (`NAME:LINE:COLUMN`, the path's end).
fn assert_at(err: &str, place: &str, want: &str) {
    assert!(
        err.starts_with("error: ") && err.contains(&format!("/{place}: {want}")),
        "expected {place}: {want:?} in: {err}"
    );
}

#[test]
fn a_top_level_that_is_no_object_is_named_where_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Each once "Document ended before root element <map> was found" from `inspect` (read as
    // XML), and a TOML error from `run`. The value's place: line 2, column 3.
    for (name, text, found) in [
        ("null.tmj", "\n  null\n", "the file's top level is null"),
        ("list.json", "\n  []\n", "the file's top level is an array"),
        ("five.tmj", "\n  5\n", "the file's top level is 5"),
        (
            "text.json",
            "\n  \"map\"\n",
            "the file's top level is the string \"map\"",
        ),
    ] {
        for command in ["inspect", "run"] {
            let err = error(d, command, name, text);
            let want = format!("{found}; expected a JSON object ({{ ... }}) holding a Tiled map");
            assert_at(&err, &format!("{name}:2:3"), &want);
        }
    }
    // Nothing at all: the end of the file.
    let err = error(d, "inspect", "empty.tmj", "");
    assert_at(
        &err,
        "empty.tmj:1:1",
        "the file is empty; expected a JSON object ({ ... }) holding a Tiled map",
    );
}

#[test]
fn sizes_that_are_not_positive_whole_numbers_are_refused_at_their_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Within the limits and as Tiled writes it (an object at x = 8.5, a property whose value
    // is a string, named "width"): read.
    let ok = d.join("ok.tmj");
    std::fs::write(&ok, map(&[])).unwrap();
    let out = platbench().arg("inspect").arg(&ok).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The largest side: src/limits.rs MAX_TILES (no side of a 1,000,000-tile map is longer).
    // The largest tile size: a TMX attribute's u32, as the tiled crate reads it
    // (MAX_TILE_PIXELS in src/level/tiled/json_values.rs).
    let pixels = "a whole number of pixels from 1 to 4294967295, as Tiled writes it";
    let tiles = "a whole number of tiles from 1 to 1000000, as Tiled writes it";
    let huge = "123456789012345678901234567890";
    let cases = [
        // Once "Error parsing attribute 'tilewidth'" with no line.
        ("TW", "-0", 6, "the map: \"tilewidth\" is -0", pixels),
        (
            "TW",
            huge,
            6,
            &*format!("the map: \"tilewidth\" is {huge}"),
            pixels,
        ),
        ("W", "3.0", 4, "the map: \"width\" is 3.0", tiles),
        (
            "W",
            "0",
            4,
            "the map: \"width\" is 0",
            "a positive whole number, as Tiled writes it",
        ),
        // Once "its data holds 6 comma-separated cells; expected exactly 0 cells".
        ("LW", "2.5", 12, "layer \"floor\": \"width\" is 2.5", tiles),
        ("LW", "-3", 12, "layer \"floor\": \"width\" is -3", tiles),
        // A tileset's tile size may be 0 (an image collection), never a fraction.
        (
            "TSW",
            "16.5",
            9,
            "tileset \"t\": \"tilewidth\" is 16.5",
            "a whole number of pixels from 0 to 4294967295, as Tiled writes it",
        ),
    ];
    for (key, value, line, found, expected) in cases {
        let text = map(&[(key, value)]);
        let err = error(d, "inspect", "m.tmj", &text);
        let place = at("m.tmj", &text, line, value);
        assert_at(&err, &place, &format!("{found}; expected {expected}"));
    }
}

#[test]
fn a_string_where_tiled_writes_a_number_is_refused_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let number = "expected a number, as Tiled writes it";
    // Once read as the number it spells.
    for (key, value, line, found) in [
        ("W", "\"3\"", 4, "the map: \"width\" is the string \"3\""),
        (
            "LW",
            "\"3\"",
            12,
            "layer \"floor\": \"width\" is the string \"3\"",
        ),
        (
            "SX",
            "\"8\"",
            15,
            "object 1 \"spawn\": \"x\" is the string \"8\"",
        ),
    ] {
        let text = map(&[(key, value)]);
        let err = error(d, "run", "m.tmj", &text);
        let place = at("m.tmj", &text, line, value);
        assert_at(&err, &place, &format!("{found}; {number}"));
    }
}

#[test]
fn a_cell_that_is_not_a_tile_id_is_named_at_its_line_and_place() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Once "cell 4 is ...; expected a tile id" with no line. A tile id is a u32, as Tiled's
    // gids are (4294967296 is one past). Cell 4 of a 3-wide layer: x = 1,
    // y = 1, on line 14.
    for (value, found) in [
        ("\"x\"", "the string \"x\""),
        ("true", "true"),
        ("-3", "-3"),
        ("1.5", "1.5"),
        ("4294967296", "4294967296"),
    ] {
        let text = map(&[("CELL", value)]);
        let err = error(d, "run", "m.tmj", &text);
        let place = at("m.tmj", &text, 14, value);
        assert_at(&err, &place, &format!("layer \"floor\": cell x = 1, y = 1 (column and row from the map's top-left, as Tiled shows them; cell 4 of its data) is {found}; expected a tile id, a whole number from 0 to 4294967295"));
    }
}

#[test]
fn what_tiled_writes_in_properties_and_older_tilesets_is_not_read_as_the_map_s_structure() {
    // A class property's members named `tiles` or `objects` are the user's data, and an older
    // tileset file has no `type` and, as an image collection, a tile size of 0: an adversary's
    // hand-written files that Tiled writes were refused (`tile first: "x" is the string
    // "left"`; `the map: "tileheight" is 0`). Each now imports, as before the value checks.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let class = r#"[{"name": "spawner", "type": "class", "propertytype": "Spawner", "value": {"tiles": {"first": {"x": "left", "id": true}}, "objects": [{"x": "right"}]}}]"#;
    let text = map(&[]).replacen(
        r#"[{"name": "width", "type": "string", "value": "wide"}]"#,
        class,
        1,
    );
    std::fs::write(
        d.join("old.json"),
        r#"{"columns":0,"margin":0,"name":"empty","spacing":0,"tilecount":0,"tileheight":0,"tilewidth":0,"tiles":[]}"#,
    )
    .unwrap();
    let old = map(&[]).replacen(
        r#""tilesets": ["#,
        r#""tilesets": [{"firstgid": 100, "source": "old.json"},"#,
        1,
    );
    for (name, text) in [("class.tmj", text), ("old_tileset.tmj", old)] {
        let p = d.join(name);
        std::fs::write(&p, &text).unwrap();
        let out = platbench().arg("inspect").arg(&p).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{name}: {err}");
    }
}

#[test]
fn a_value_of_a_type_tiled_never_writes_is_refused_at_its_place() {
    // Each was read by the `tiled` crate as absent, as another value or with its bare words
    // (issue 40: `"infinite": "false"`, `layers` null or an object, a point's flag a string,
    // a bool property "yes" ran with exit 0 or said "Invalid property value" with no place).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = map(&[]);
    let spawn = r#"{"id": 1, "name": "spawn", "point": true, "x": 8.5, "y": 16}"#;
    let tileset = r#"{"firstgid": 1, "name": "t","#;
    let wide = r#""type": "string", "value": "wide""#;
    #[rustfmt::skip]
    let cases: [(&str, &str, usize, &str, &str); 12] = [
        (r#""infinite": false"#, r#""infinite": "false""#, 2, r#""false""#,
         r#"the map: "infinite" is the string "false"; expected true or false, as Tiled writes it"#),
        (r#""layers": ["#, r#""layers": null, "l": ["#, 10, "null",
         r#"the map: "layers" is null; expected an array, as Tiled writes it"#),
        (r#""tilesets": ["#, r#""tilesets": "t.tsx", "t": ["#, 8, r#""t.tsx""#,
         r#"the map: "tilesets" is the string "t.tsx"; expected an array, as Tiled writes it"#),
        (r#""objects": ["#, r#""objects": {}, "o": ["#, 15, "{}",
         r#"layer "spawns": "objects" is an object; expected an array, as Tiled writes it"#),
        (r#""data": ["#, r#""data": {"a": 1}, "d": ["#, 13, "{",
         r#"layer "floor": "data" is an object; expected an array of tile ids or a base64 string, as Tiled writes it"#),
        (r#""point": true"#, r#""point": "true""#, 15, r#""true""#,
         r#"object 1 "spawn": "point" is the string "true"; expected true or false, as Tiled writes it"#),
        (wide, r#""type": "bool", "value": "yes""#, 3, r#""yes""#,
         r#"the map: property "width" of type "bool": "value" is the string "yes"; expected true or false"#),
        (wide, r#""type": "int", "value": 1.5"#, 3, "1.5",
         r#"the map: property "width" of type "int": "value" is 1.5; expected a whole number from -2147483648 to 2147483647"#),
        // A member written twice: serde_json keeps the second, Tiled's reader may not.
        (r#""height": 2,"#, r#""height": 2, "height": 3,"#, 5, r#""height": 3"#,
         r#"the map: "height" is written a second time here; expected each member once, as Tiled writes it (JSON readers differ in which of the two they keep)"#),
        (r#""type": "tilelayer""#, r#""type": "tiles""#, 11, r#""tiles""#,
         r#"layer "floor": "type" is the string "tiles"; expected tilelayer, objectgroup, imagelayer or group, as Tiled writes it"#),
        // Tiled writes zstd too, which the crate does not read: once its words, no place.
        (r#""data": [0, 0, 0,"#, r#""encoding": "base64", "compression": "zstd", "d": [0, 0, 0,"#, 13, r#""zstd""#,
         r#"layer "floor": "compression" is the string "zstd"; expected csv, or base64 with no compression (""), zlib or gzip, which the tiled crate reads"#),
        (tileset, r#"{"name": "t","#, 9, "{",
         r#"tileset "t" has no "firstgid"; expected the gid of its first tile, a whole number from 1 to 4294967295, as Tiled writes it in every tileset of a map or template"#),
    ];
    assert!(base.contains(spawn));
    for (from, to, line, needle, want) in cases {
        assert!(base.contains(from), "{from}");
        let text = base.replacen(from, to, 1);
        let err = error(d, "inspect", "m.tmj", &text);
        assert_at(&err, &at("m.tmj", &text, line, needle), want);
    }
    // What Tiled writes there is read: a bool property that is true, an older map's
    // properties written as an object ({"name": value}, Tiled before 1.2).
    for (from, to) in [
        (wide, r#""type": "bool", "value": true"#),
        (
            r#"[{"name": "width", "type": "string", "value": "wide"}]"#,
            r#"{"description": "old"}"#,
        ),
    ] {
        let p = d.join("fine.tmj");
        std::fs::write(&p, base.replacen(from, to, 1)).unwrap();
        let out = platbench().arg("inspect").arg(&p).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{to}: {err}");
    }
}

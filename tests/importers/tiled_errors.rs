//! Tiled maps: what cannot be read is an error that names the object, tileset, tile, cell or
//! layer, and says what was expected.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use platbench::level::{import_tiled_map, Tile};

use super::tiled::{row0, MapText, SPAWN};

#[test]
fn platform_and_spawn_errors_name_the_object() {
    let platform = |props: &str, path_obj: &str| {
        format!(
            r#"{SPAWN}
<object id="2" name="lift" class="platform" x="0" y="0" width="32" height="8"><properties>{props}</properties></object>
{path_obj}"#
        )
    };
    let poly = r#"<object id="3" name="p" x="0" y="0"><polyline points="0,0 32,0"/></object>"#;
    let path = r#"<property name="path" type="object" value="3"/>"#;
    let speed = r#"<property name="speed" type="float" value="2"/>"#;
    let cases = [
        (platform(path, poly), "object 2 \"lift\"", "\"speed\""),
        (platform(speed, poly), "object 2 \"lift\"", "\"path\""),
        (
            platform(
                &format!(r#"{path}<property name="speed" type="float" value="-1"/>"#),
                poly,
            ),
            "object 2 \"lift\"",
            "expected 0 < speed <= 10000",
        ),
        (
            platform(
                &format!("{path}{speed}"),
                r#"<object id="3" name="p" x="0" y="0" width="8" height="8"><ellipse/></object>"#,
            ),
            "object 2 \"lift\"",
            "which is an ellipse; expected a polyline (the path",
        ),
        (
            platform(
                &format!("{path}{speed}"),
                r#"<object id="3" name="p" x="0" y="0"><polyline points="0,0 0,0"/></object>"#,
            ),
            "object 2 \"lift\"",
            "zero length",
        ),
        (
            r#"<object id="4" name="s" class="spawn" x="0" y="0" width="8" height="8"><ellipse/></object>"#
                .to_string(),
            "object 4 \"s\"",
            "a spawn point is an ellipse",
        ),
        (
            format!(
                r#"{SPAWN}<object id="4" name="s" class="spawn" x="40" y="16"><point/></object>"#
            ),
            "object 4 \"s\"",
            "also the name of object 1",
        ),
        (
            // A path of 1,001 points, one more than the limit (src/limits.rs MAX_PATH_POINTS).
            platform(
                &format!("{path}{speed}"),
                &format!(
                    r#"<object id="3" name="p" x="0" y="0"><polyline points="{}"/></object>"#,
                    (0..1001).map(|i| format!("{i},0")).collect::<Vec<_>>().join(" ")
                ),
            ),
            "object 2 \"lift\"",
            "has 1001 points; expected at most 1000",
        ),
    ];
    for (objects, subject, what) in cases {
        let e = MapText {
            objects: &objects,
            ..MapText::default()
        }
        .error();
        assert!(
            e.contains(subject) && e.contains(what),
            "{subject} / {what}: {e}"
        );
    }
}

#[test]
fn unsupported_tiles_are_errors_naming_tileset_tile_and_cell() {
    let shape = |obj: &str| {
        format!(r#"<tile id="0"><objectgroup draworder="index">{obj}</objectgroup></tile>"#)
    };
    let props = |p: &str| format!(r#"<tile id="0"><properties>{p}</properties></tile>"#);
    let cases = [
        (
            // Partial and compound shapes are approximated (tests/importers/shapes.rs); a
            // rotated one is not.
            shape(r#"<object id="1" x="0" y="0" width="16" height="16" rotation="30"/>"#),
            "rotated by 30 degrees",
        ),
        (
            props(r#"<property name="slope_left" type="float" value="0.5"/>"#),
            "only one of slope_left and slope_right",
        ),
        (
            props(r#"<property name="collision" value="lava"/>"#),
            "collision = \"lava\"",
        ),
        (
            props(r#"<property name="heights" value="1,2,3"/>"#),
            "has 3 entries",
        ),
        (
            props(
                r#"<property name="collision" value="solid"/><property name="slope_left" type="float" value="0"/><property name="slope_right" type="float" value="1"/>"#,
            ),
            "expected one of them",
        ),
    ];
    for (tiles, what) in cases {
        // Tile 0 (gid 1) at column 1 of the bottom row, row 1 from the top as Tiled counts.
        let e = MapText {
            tiles: &tiles,
            rows: &["0,0,0", "0,1,0"],
            ..MapText::default()
        }
        .error();
        assert!(
            e.contains("tileset \"t\" tile 0 (at cell x = 1, y = 1, column and row from the map's top-left): ") && e.contains(what),
            "{what}: {e}"
        );
    }
    // A slope drawn flipped vertically (gid 1 | 0x40000000) would be a ceiling: at column 2,
    // row 1 from the top.
    let e = MapText {
        tiles: &props(
            r#"<property name="slope_left" type="float" value="0"/><property name="slope_right" type="float" value="1"/>"#,
        ),
        rows: &["0,0,0", "0,0,1073741825"],
        ..MapText::default()
    }
    .error();
    assert!(
        e.contains("tile 0 (at cell x = 2, y = 1, column and row from the map's top-left): ")
            && e.contains("flipped vertically"),
        "{e}"
    );
    // A tile id past the tileset's end: the map's line (10: the row "0,0,17"), the layer, the
    // cell as Tiled shows it (column 2, row 1 from the top), the gid and the gids the map's
    // tileset holds (its 16 tiles from firstgid 1).
    let e = MapText {
        rows: &["0,0,0", "0,0,17"],
        ..MapText::default()
    }
    .error();
    let want = "m.tmx:10: layer \"collision\": cell x = 2, y = 1 (column and row from the map's top-left, as Tiled shows them) holds gid 17 (tile 16 of tileset \"t\"), which names no tile; expected 0 (no tile) or a gid of the map's tilesets: 1 to 16 (\"t\")";
    assert!(e.contains(want), "{e}");
}

#[test]
fn unsupported_maps_and_layers_are_errors() {
    let iso = MapText {
        map_attrs: r#"orientation="isometric" infinite="0""#,
        ..MapText::default()
    }
    .error();
    assert!(
        iso.contains("orientation is isometric") && iso.contains("orthogonal"),
        "{iso}"
    );
    // Tile art larger than the map's cells is one cell each, with a note.
    let big = MapText {
        tileset_size: 32,
        ..MapText::default()
    }
    .import()
    .unwrap();
    assert_eq!(row0(&big.level), vec![Tile::Solid; 3]);
    assert!(
        big.warnings
            .iter()
            .any(|w| w.subject == "tileset \"t\"" && w.message.contains("32 x 32")),
        "{:?}",
        big.warnings
    );
    // A second tile layer that puts a ladder where the first has a solid.
    let dir = tempfile::tempdir().unwrap();
    let text = MapText {
        tiles: r#"<tile id="1"><properties><property name="collision" value="ladder"/></properties></tile>"#,
        ..MapText::default()
    }
    .text()
    .replace(
        " <objectgroup",
        " <layer id=\"3\" name=\"more walls\" width=\"3\" height=\"2\"><data encoding=\"csv\">0,0,0,2,0,0</data></layer>\n <objectgroup",
    );
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    // The solid stops from more sides than the ladder: it is kept, and the meeting warned at the
    // first cell where they meet, column 0 of row 1 from the top (the second layer's cell 3).
    let met = import_tiled_map(&path).unwrap();
    assert_eq!(met.level.tile(0, 0), Tile::Solid);
    assert!(
        met.warnings.iter().any(|w| w.subject == "layer \"more walls\""
            && w.message.starts_with("1 cell(s) (the first at x = 0, y = 1, column and row from the map's top-left) where its ladder tiles meet layer \"collision\"'s solid tiles")),
        "{:?}",
        met.warnings
    );
    // Layer data shorter than the layer (4 cells of 6, base64): an error, not a panic.
    let short = MapText::default().text().replace(
        "<data encoding=\"csv\">\n0,0,0,\n1,1,1\n</data>",
        "<data encoding=\"base64\">AQAAAAEAAAABAAAAAQAAAA==</data>",
    );
    std::fs::write(&path, short).unwrap();
    let e = import_tiled_map(&path).unwrap_err().to_string();
    assert!(
        e.contains("layer \"collision\"")
            && e.contains("4 cells of 4 bytes")
            && e.contains("expected exactly 6 cells"),
        "{e}"
    );
}

#[test]
fn collision_objects_that_meet_in_a_cell_name_it_as_tiled_shows_it() {
    // An up ramp and a down ramp drawn over the same cell, column 1 of the top row, in a
    // collision object layer: two different slopes in one cell, which neither stops more.
    let text = MapText::default().text().replace(
        " <objectgroup id=\"2\" name=\"objects\">\n",
        " <objectgroup id=\"2\" name=\"walls\">\n<object id=\"11\" name=\"up\" x=\"16\" y=\"0\"><polygon points=\"0,16 16,16 16,0\"/></object>\n<object id=\"12\" name=\"down\" x=\"16\" y=\"0\"><polygon points=\"0,16 16,16 0,0\"/></object>\n",
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    let e = import_tiled_map(&path).unwrap_err().to_string();
    assert!(
        e.contains("object 12 \"down\": at cell x = 1, y = 0 (column and row from the map's top-left): it is a line slope (1, 0) but the cell already holds a line slope (0, 1) from object 11 \"up\" in layer \"walls\""),
        "{e}"
    );
}

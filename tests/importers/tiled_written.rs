//! Issue 40: maps as Tiled writes them are read, not refused (an infinite JSON map's empty
//! layer, an infinite map in the old XML cell format), and a map's bad numbers, gids and chunk
//! sizes are named at their line (and the attribute's column) instead of the `tiled` crate's
//! bare "Error parsing attribute 'width'" or a silently dropped tile.
#![cfg(feature = "tiled")]

use std::path::Path;

use platbench::level::{import_tiled_map, Tile};

/// A tileset of one 16 px tile (gid 1), embedded; written for these tests.
const TILESET: &str = r#"<tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"><image source="t.png" width="16" height="16"/></tileset>"#;

/// A 4 x 2 map: `tileset` on line 3, `layer` from line 4, `objects` after it.
fn tmx(map_attrs: &str, tileset: &str, layer: &str, objects: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" {map_attrs} tilewidth=\"16\" tileheight=\"16\">\n{tileset}\n{layer}\n<objectgroup id=\"5\" name=\"objects\">\n{objects}\n</objectgroup>\n</map>\n"
    )
}

const FLOOR: &str = r#"<layer id="1" name="ground" width="4" height="2"><data encoding="csv">0,0,0,0,1,1,1,1</data></layer>"#;
const START: &str = r#"<object id="1" name="start" x="24" y="16"><point/></object>"#;

fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The import's error as the CLI shows it.
fn error(name: &str, text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), name, text);
    let Err(e) = import_tiled_map(&p) else {
        panic!("the map should be refused");
    };
    let shown = e.to_string();
    // Every error names the file first.
    let file = p.display().to_string();
    assert!(shown.starts_with(&file), "{shown}");
    shown[file.len()..].to_string()
}

#[test]
fn an_infinite_json_maps_empty_layer_is_read() {
    // Tiled 1.11 writes a layer with nothing drawn as 0 x 0 with no chunks.
    let chunk = format!("[{}]", ["1"; 256].join(","));
    let text = format!(
        r#"{{"type":"map","version":"1.10","orientation":"orthogonal","renderorder":"right-down","infinite":true,"width":3,"height":2,"tilewidth":16,"tileheight":16,"nextlayerid":3,"nextobjectid":1,
"layers":[{{"id":1,"name":"collision","type":"tilelayer","width":16,"height":16,"startx":0,"starty":0,"x":0,"y":0,"opacity":1,"visible":true,"chunks":[{{"x":0,"y":0,"width":16,"height":16,"data":{chunk}}}]}},
{{"id":2,"name":"empty","type":"tilelayer","chunks":[],"width":0,"height":0,"startx":0,"starty":0,"x":0,"y":0,"opacity":1,"visible":true}}],
"tilesets":[{{"firstgid":1,"name":"t","tilewidth":16,"tileheight":16,"tilecount":1,"columns":1,"image":"t.png","imagewidth":16,"imageheight":16,"margin":0,"spacing":0}}]}}"#
    );
    let dir = tempfile::tempdir().unwrap();
    let r = import_tiled_map(&write(dir.path(), "m.tmj", &text));
    assert!(r.is_ok(), "{}", r.err().unwrap());
}

#[test]
fn an_infinite_map_in_the_old_xml_cell_format_is_read_chunk_by_chunk() {
    // Two 2 x 2 chunks of <tile> elements, as Tiled writes a layer with no encoding.
    let tiles = |gid: &str| format!("<tile gid=\"{gid}\"/>\n").repeat(4);
    let layer = format!(
        "<layer id=\"1\" name=\"ground\" width=\"4\" height=\"2\"><data>\n<chunk x=\"0\" y=\"0\" width=\"2\" height=\"2\">\n{}</chunk>\n<chunk x=\"2\" y=\"0\" width=\"2\" height=\"2\">\n{}</chunk>\n</data></layer>",
        tiles("1"),
        tiles("1")
    );
    let text = tmx(
        "width=\"4\" height=\"2\" infinite=\"1\"",
        TILESET,
        &layer,
        START,
    );
    let dir = tempfile::tempdir().unwrap();
    let r = import_tiled_map(&write(dir.path(), "m.tmx", &text));
    let i = r.unwrap_or_else(|e| panic!("{e}"));
    // 4 x 2 solid cells from the two chunks (the walls added at the open sides aside).
    let l = &i.level;
    let solid = (0..l.width as i64)
        .flat_map(|x| (0..l.height as i64).map(move |y| (x, y)))
        .filter(|&(x, y)| l.tile(x, y) == Tile::Solid)
        .count();
    // 8 from the chunks, plus the walls added at the open sides (as tall as the map).
    assert_eq!(solid, 8 + 2 * l.height as usize, "{solid} solid cells");
    // A short chunk is still refused, at the chunk's line (5).
    let short = text.replacen("<tile gid=\"1\"/>\n", "", 1);
    let e = error("m.tmx", &short);
    assert!(
        e.starts_with(":5: ") && e.contains("chunk at x = 0, y = 0: its data holds 3"),
        "{e}"
    );
    // A bad gid in the old format is its tile element's, at line and column.
    let bad = text.replacen("<tile gid=\"1\"/>", "<tile gid=\"x\"/>", 1);
    let e = error("m.tmx", &bad);
    assert!(
        e.starts_with(":6:7: ") && e.contains("<tile>: attribute \"gid\" is \"x\""),
        "{e}"
    );
}

#[test]
fn bad_numbers_are_named_at_their_attribute() {
    let map = "width=\"4\" height=\"2\"";
    // (what the file holds, where the error points, what it says): the columns are those of
    // the attribute in the lines `tmx` writes.
    let cases = [
        (tmx("width=\"4O\" height=\"2\"", TILESET, FLOOR, START), ":2:71: ", "<map>: attribute \"width\" is \"4O\"; expected a whole number"),
        (tmx("width=\"\" height=\"2\"", TILESET, FLOOR, START), ":2:71: ", "attribute \"width\" is \"\""),
        (tmx(map, &TILESET.replace("firstgid=\"1\"", "firstgid=\"\""), FLOOR, START), ":3:10: ", "tileset \"t\": attribute \"firstgid\" is \"\""),
        (tmx(map, TILESET, FLOOR, &START.replace("id=\"1\"", "id=\"x\"")), ":6:9: ", "attribute \"id\" is \"x\""),
        (tmx(map, TILESET, FLOOR, &START.replace("x=\"24\"", "x=\"2a4\"")), ":6:29: ", "object 1 \"start\": attribute \"x\" is \"2a4\"; expected a number"),
        (tmx(map, TILESET, FLOOR, r#"<object id="2" x="0" y="0"><polygon points="0,0 1,a 2,2"/></object>"#), ":6:37: ", "attribute \"points\" has point 2 \"1,a\""),
        (tmx(map, TILESET, FLOOR, r#"<properties><property name="n" type="int" value="zz"/></properties>"#), ":6:43: ", "property \"n\": attribute \"value\" is \"zz\"; expected a whole number from -2147483648"),
        (tmx(map, TILESET, &FLOOR.replace("height=\"2\"", "height=\"-2\""), START), ":4:39: ", "layer \"ground\": attribute \"height\" is \"-2\""),
    ];
    for (text, at, says) in cases {
        let e = error("m.tmx", &text);
        assert!(e.starts_with(at) && e.contains(says), "{at} {says}: {e}");
    }
}

#[test]
fn a_chunk_without_cells_says_its_size() {
    let layer = r#"<layer id="1" name="ground" width="4" height="2"><data encoding="csv">
<chunk x="0" y="0" width="0" height="16"></chunk></data></layer>"#;
    let e = error(
        "m.tmx",
        &tmx(
            "width=\"4\" height=\"2\" infinite=\"1\"",
            TILESET,
            layer,
            START,
        ),
    );
    // Line 5, column 20: the chunk's `width` attribute.
    assert!(
        e.starts_with(":5:20: ")
            && e.contains("the chunk is 0 x 16 tiles; expected a width and height of at least 1"),
        "{e}"
    );
    // A height of 0 is named at `height` (column 31).
    let flat = layer.replace("width=\"0\" height=\"16\"", "width=\"16\" height=\"0\"");
    let map = tmx(
        "width=\"4\" height=\"2\" infinite=\"1\"",
        TILESET,
        &flat,
        START,
    );
    let e = error("m.tmx", &map);
    assert!(
        e.starts_with(":5:31: ") && e.contains("16 x 0 tiles"),
        "{e}"
    );
    let neg = layer.replace("width=\"0\"", "width=\"-1\"");
    let e = error(
        "m.tmx",
        &tmx(
            "width=\"4\" height=\"2\" infinite=\"1\"",
            TILESET,
            &neg,
            START,
        ),
    );
    assert!(e.contains("<chunk>: attribute \"width\" is \"-1\""), "{e}");
}

#[test]
fn tiles_in_no_tileset_are_refused_not_dropped() {
    // Cells of gid 1 with no tileset: the crate would drop them without a word.
    let e = error("m.tmx", &tmx("width=\"4\" height=\"2\"", "", FLOOR, START));
    assert!(
        e.starts_with(":4: ")
            && e.contains("cell 5 (x = 0, y = 1) of its data is gid 1, but the map has no tileset"),
        "{e}"
    );
    // The same cells in base64, plain and zlib-compressed (encoded with Python's base64 and
    // zlib from the little-endian gids 0,0,0,0,1,1,1,1): the same cell named.
    for (attrs, data, what) in [
        (
            r#"encoding="base64""#,
            "AAAAAAAAAAAAAAAAAAAAAAEAAAABAAAAAQAAAAEAAAA=",
            "its base64 data",
        ),
        (
            r#"encoding="base64" compression="zlib""#,
            "eNpjYEAFjGgYAABIAAU=",
            "its zlib-compressed base64 data",
        ),
    ] {
        let layer = format!(
            r#"<layer id="1" name="ground" width="4" height="2"><data {attrs}>{data}</data></layer>"#
        );
        let e = error("m.tmx", &tmx("width=\"4\" height=\"2\"", "", &layer, START));
        assert!(
            e.starts_with(":4: ")
                && e.contains(&format!(
                    "cell 5 (x = 0, y = 1) of {what} is gid 1, but the map has no tileset"
                )),
            "{e}"
        );
    }
    // Below the first tileset's firstgid (here 5): in none either.
    let e = error(
        "m.tmx",
        &tmx(
            "width=\"4\" height=\"2\"",
            &TILESET.replace("firstgid=\"1\"", "firstgid=\"5\""),
            FLOOR,
            START,
        ),
    );
    assert!(
        e.contains("gid 1, below the first tileset's firstgid 5"),
        "{e}"
    );
    // A tile object whose gid is past its tileset's one tile.
    let obj = r#"<object id="1" name="start" gid="99" x="24" y="32" width="16" height="16"/>"#;
    let e = error(
        "m.tmx",
        &tmx("width=\"4\" height=\"2\"", TILESET, FLOOR, obj),
    );
    assert!(
        e.starts_with(":6: ") && e.contains("object 1 \"start\": its tile is gid 99 (tile 98 of tileset \"t\"), which names no tile; expected a gid of the map's tilesets: 1 to 1 (\"t\")"),
        "{e}"
    );
}

#[test]
fn an_object_error_gives_the_objects_line() {
    // A spawn rotated: refused, at its object's line (7: the second object).
    let objs = format!("{START}\n<object id=\"2\" name=\"spawn\" x=\"24\" y=\"16\" rotation=\"45\"><point/></object>");
    let e = error(
        "m.tmx",
        &tmx("width=\"4\" height=\"2\"", TILESET, FLOOR, &objs),
    );
    assert!(
        e.starts_with(":7: ") && e.contains("object 2 \"spawn\""),
        "{e}"
    );
}

#[test]
fn a_json_template_that_refers_to_itself_is_named_at_its_template_key() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "self.tj",
        "{\"type\": \"template\",\n \"object\": {\"name\": \"o\", \"width\": 16, \"height\": 16,\n  \"template\": \"self.tj\"}}",
    );
    let objs = format!("{START}\n<object id=\"2\" template=\"self.tj\" x=\"8\" y=\"8\"/>");
    let p = write(
        dir.path(),
        "m.tmx",
        &tmx("width=\"4\" height=\"2\"", TILESET, FLOOR, &objs),
    );
    let e = import_tiled_map(&p).err().unwrap().to_string();
    // Line 3 of self.tj holds its "template" key (its XML twin's line 2 was named before).
    let at = format!(
        "{}:3: object template \"self.tj\" refers back",
        dir.path().join("self.tj").display()
    );
    assert!(e.starts_with(&at), "{e}");
}

#[test]
fn a_tileset_files_faults_are_named_at_its_own_line() {
    let dir = tempfile::tempdir().unwrap();
    let map = write(
        dir.path(),
        "m.tmx",
        &tmx(
            "width=\"4\" height=\"2\"",
            r#"<tileset firstgid="1" source="t.tsx"/>"#,
            FLOOR,
            START,
        ),
    );
    let tsx = |attrs: &str, tiles: &str| {
        format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<tileset version=\"1.10\" name=\"t\" {attrs} tilecount=\"1\" columns=\"1\">\n<image source=\"t.png\" width=\"16\" height=\"16\"/>\n{tiles}</tileset>\n")
    };
    let shown = |tileset: &str| {
        write(dir.path(), "t.tsx", tileset);
        let Err(e) = import_tiled_map(&map) else {
            panic!("the map should be refused");
        };
        e.to_string()
    };
    // A tile width that is not a number: at its attribute, line 2 column 34, in t.tsx.
    let e = shown(&tsx("tilewidth=\"1x6\" tileheight=\"16\"", ""));
    assert!(
        e.contains("t.tsx:2:34: ")
            && e.contains("attribute \"tilewidth\" is \"1x6\"; expected a whole number")
            && e.contains("(the map ")
            && e.contains("m.tmx refers to it)"),
        "{e}"
    );
    // More elements than a Tiled JSON map may hold objects (limits::MAX_JSON_OBJECTS,
    // 500,000): the tileset element, its image and 499,998 tiles fill it; the next tile (on
    // line 500,002: tile k is on line 3 + k) is one too many.
    let tiles = "<tile id=\"0\"/>\n".repeat(500_000);
    let e = shown(&tsx("tilewidth=\"16\" tileheight=\"16\"", &tiles));
    assert!(
        e.contains("t.tsx:500002: ") && e.contains("<tile> is element 500001 of the tileset file"),
        "{e}"
    );
}

#[test]
fn corrupt_compressed_data_is_called_corrupt() {
    // Issue 40: a zlib stream that is not deflate read as "holds 0 bytes … was the file cut
    // short". The data: a zlib header (78 9C) and four 0xFF bytes, in base64.
    let layer = r#"<layer id="1" name="ground" width="4" height="2"><data encoding="base64" compression="zlib">eJz/////</data></layer>"#;
    let e = error(
        "m.tmx",
        &tmx("width=\"4\" height=\"2\"", TILESET, layer, START),
    );
    assert!(
        e.starts_with(":4: ")
            && e.contains("layer \"ground\": its zlib-compressed data is corrupt: it inflates to 0 bytes, then")
            && e.contains("expected zlib data that inflates to 8 cells of 4 bytes"),
        "{e}"
    );
}

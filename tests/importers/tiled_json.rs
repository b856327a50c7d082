//! Tiled JSON maps (`.tmj`, `.json`): read as their TMX twins, so they import to the same level
//! with the same rules, and fail with errors that name the JSON layer; a file's format is told
//! by its content, and every error names the format it was read as.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::Path;

use platbench::level::{detect_format, import_tiled_map, LevelFormat, TiledImport};

use super::common::platbench;
use super::tiled::shipped;

/// The level of an import, with the fields that name the file or its layers' paths cleared:
/// what a game would play.
fn played(mut r: TiledImport) -> (platbench::level::Level, Vec<String>) {
    r.level.source.clear();
    let spawns = r
        .spawns
        .iter()
        .map(|s| format!("{} {:?}", s.name, s.position))
        .collect();
    (r.level, spawns)
}

#[test]
fn a_json_map_imports_as_its_tmx_twin() {
    // tests/maps/showcase.tmj is showcase.tmx saved as JSON, its tile layers in a group.
    let tmx = played(import_tiled_map(&shipped("showcase.tmx")).unwrap());
    let json = import_tiled_map(&shipped("showcase.tmj")).unwrap();
    let roles: Vec<_> = json.layers.iter().map(|l| l.name.clone()).collect();
    assert!(roles.contains(&"level/ground".to_string()), "{roles:?}");
    assert!(
        json.warnings.is_empty(),
        "a JSON map is a format, not a warning: {:?}",
        json.warnings
    );
    assert_eq!(played(json), tmx);
    // An infinite map with a zlib-compressed base64 chunk and an embedded tileset.
    let tmx = played(import_tiled_map(&shipped("infinite.tmx")).unwrap());
    assert_eq!(
        played(import_tiled_map(&shipped("infinite.json")).unwrap()),
        tmx
    );
}

#[test]
fn the_format_is_told_by_the_content() {
    let dir = tempfile::tempdir().unwrap();
    let copy = |from: &str, to: &str| {
        let p = dir.path().join(to);
        std::fs::copy(shipped(from), &p).unwrap();
        p
    };
    assert_eq!(
        detect_format(&copy("showcase.tmj", "a.json")).unwrap(),
        LevelFormat::TiledJson
    );
    assert_eq!(
        detect_format(&copy("linear_old.ldtk", "b.json")).unwrap(),
        LevelFormat::Ldtk
    );
    assert_eq!(
        detect_format(&copy("showcase.tmx", "c.map")).unwrap(),
        LevelFormat::Tmx
    );
    // A map renamed by a build step runs as the map it is.
    copy("terrain.tsx", "terrain.tsx");
    let renamed = copy("showcase.tmj", "level1.json");
    let out = platbench()
        .args(["inspect"])
        .arg(&renamed)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let ldtk = copy("linear_old.ldtk", "old.json");
    let out = platbench().args(["inspect"]).arg(&ldtk).output().unwrap();
    assert!(out.status.success(), "{out:?}");
    // Even saved as `.toml`: its side file would be itself, so it has none.
    let as_toml = copy("showcase.tmj", "saved.toml");
    for command in ["inspect", "run"] {
        let out = platbench()
            .args([command])
            .arg(&as_toml)
            .args(["--backend", "sweep"][..if command == "run" { 2 } else { 0 }].iter())
            .output()
            .unwrap();
        assert!(out.status.success(), "{command}: {out:?}");
    }
}

/// `platbench run FILE`'s stderr, which must fail with exit 2.
fn run_error(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    let out = platbench().arg("run").arg(&p).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn errors_name_the_json_layer_and_the_format() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // JSON syntax: the line and column.
    let e = run_error(d, "broken.tmj", "{\n \"layers\": [,]\n}");
    assert!(
        e.contains("broken.tmj:2:") && e.contains("not Tiled JSON"),
        "{e}"
    );
    // A cell that is not a tile id: the layer and the cell.
    let e = run_error(
        d,
        "cell.tmj",
        r#"{"type":"map","width":2,"height":1,"tilewidth":16,"tileheight":16,"orientation":"orthogonal",
            "layers":[{"type":"tilelayer","name":"floor","width":2,"height":1,"data":[1,"x"]}]}"#,
    );
    assert!(
        e.contains("cell.tmj:2:89: layer \"floor\": cell x = 1, y = 0 (column and row from the map's top-left, as Tiled shows them; cell 1 of its data) is the string \"x\""),
        "{e}"
    );
    // A tileset given where a map is expected.
    let e = run_error(
        d,
        "ts.json",
        r#"{"type":"tileset","name":"t","tilewidth":16}"#,
    );
    assert!(e.contains("it is a Tiled tileset"), "{e}");
    // A layer larger than a level may be: refused by the walk before the JSON is read into a
    // tree, at the line and column where the layer starts (line 2: 12 spaces, `"layers":[`).
    let e = run_error(
        d,
        "big.tmj",
        r#"{"type":"map","width":2,"height":1,"tilewidth":16,"tileheight":16,"orientation":"orthogonal",
            "layers":[{"type":"tilelayer","name":"wide","width":100000,"height":100000,"data":[0]}]}"#,
    );
    assert!(
        e.contains(
            "big.tmj:2:23: layer \"wide\" is 100000 x 100000 tiles; expected at most 1000000 tiles"
        ),
        "{e}"
    );
    // A check of the TMX twin (data shorter than its layer) is shown at the JSON line where the
    // layer starts, not a line of a file the user never saw, and names the layer once.
    let e = run_error(
        d,
        "short.tmj",
        r#"{"type":"map","width":2,"height":1,"tilewidth":16,"tileheight":16,"orientation":"orthogonal",
            "layers":[
            {"type":"tilelayer","name":"floor","width":2,"height":1,"data":[1]}]}"#,
    );
    assert!(
        e.contains("short.tmj:3: layer \"floor\": its data holds 1 comma-separated cells; expected exactly 2 cells"),
        "{e}"
    );
    // A file that is neither: read as a level, and said so.
    let e = run_error(d, "level1.tmj", "hello world\n");
    assert!(e.contains("read as a platbench level (TOML)"), "{e}");
}

#[test]
fn a_tile_id_of_no_tile_names_the_layer_once_the_cell_from_the_top_and_its_json_line() {
    // Tileset "t" holds gids 1 to 16 (an image of 16 tiles); gid 17 names none. One cell a line
    // in the layer's data, as Tiled writes it: the cell at column 2, row 1 from the top is on
    // line 14 (the layer starts on line 7, its data on line 8).
    let map = |data: &str| {
        format!(
            r#"{{"type":"map","version":"1.10","orientation":"orthogonal","width":3,"height":2,
"tilewidth":16,"tileheight":16,"infinite":false,
"tilesets":[{{"firstgid":1,"name":"t","tilewidth":16,"tileheight":16,"tilecount":16,"columns":16,"image":"t.png","imagewidth":256,"imageheight":16}}],
"layers":[
{{"type":"objectgroup","name":"objects","objects":[]}},
{{"type":"group","name":"world","layers":[
 {{"type":"tilelayer","name":"ground","width":3,"height":2,
{data}}}]}}]}}
"#
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmj");
    std::fs::write(&path, map("\"data\":[\n0,\n0,\n0,\n1,\n1,\n17]")).unwrap();
    let e = import_tiled_map(&path).unwrap_err().to_string();
    let want = "m.tmj:14: layer \"world/ground\": cell x = 2, y = 1 (column and row from the map's top-left, as Tiled shows them) holds gid 17 (tile 16 of tileset \"t\"), which names no tile; expected 0 (no tile) or a gid of the map's tilesets: 1 to 16 (\"t\")";
    assert!(e.ends_with(want), "{e}");
    // Base64 data (cells 1, 1, 1, 1, 1, 17) has no line a cell: the line where the layer starts.
    let b64 = "\"encoding\":\"base64\",\"data\":\"AQAAAAEAAAABAAAAAQAAAAEAAAARAAAA\"";
    std::fs::write(&path, map(b64)).unwrap();
    let e = import_tiled_map(&path).unwrap_err().to_string();
    assert!(
        e.contains("m.tmj:7: layer \"world/ground\": cell x = 2, y = 1 "),
        "{e}"
    );
}

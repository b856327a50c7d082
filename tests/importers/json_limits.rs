//! Issue 40's limits on a Tiled JSON map, tileset or template, checked by a walk over the text
//! before serde_json reads it into a tree (src/level/tiled/json_walk.rs): the same limits as a
//! TMX map's, and the JSON's own (objects, values, nesting), each refused with the file, the
//! line and column where the count passes (or where the layer starts), the layer or object, what
//! was found and what was expected. Every file here is written for these tests.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::{Path, PathBuf};

use platbench::level::import_tiled_map;

use super::common::platbench;

/// `MAX_POLYGON_POINTS` in src/limits.rs.
const MAX_POLYGON_POINTS: usize = 10_000;
/// `MAX_TILES` in src/limits.rs.
const MAX_TILES: usize = 1_000_000;
/// `MAX_LAYER_CELLS` in src/limits.rs: 16 layers of `MAX_TILES`.
const MAX_LAYER_CELLS: usize = 16 * MAX_TILES;
/// `MAX_JSON_OBJECTS` in src/limits.rs.
const MAX_JSON_OBJECTS: usize = 500_000;
/// `MAX_JSON_VALUES` in src/limits.rs.
const MAX_JSON_VALUES: usize = 5_000_000;

/// An embedded tileset of 16 tiles (gids 1 to 16).
const TILESET: &str = r#"{"firstgid":1,"name":"t","tilewidth":16,"tileheight":16,"tilecount":16,"columns":16,"image":"t.png","imagewidth":256,"imageheight":16}"#;
/// A 3 x 2 floor: the bottom row solid.
const FLOOR: &str =
    r#"{"type":"tilelayer","name":"floor","width":3,"height":2,"data":[0,0,0,1,1,1]}"#;
/// A spawn point on the floor.
const SPAWN: &str = r#"{"type":"objectgroup","name":"spawns","objects":[{"id":1,"name":"spawn","point":true,"x":8,"y":16}]}"#;

/// A 3 x 2 JSON map of 16 px tiles with `tilesets` whose layers are `layers`, one a line from
/// line 4.
fn map_with(tilesets: &str, layers: &[String]) -> String {
    format!(
        "{{\"type\":\"map\",\"version\":\"1.10\",\"orientation\":\"orthogonal\",\"width\":3,\"height\":2,\"tilewidth\":16,\"tileheight\":16,\"infinite\":false,\n\"tilesets\":[{tilesets}],\n\"layers\":[\n{}]}}\n",
        layers.join(",\n")
    )
}

/// The map of [`map_with`] with the embedded tileset and the floor, the spawns and `more` as its
/// layers (the floor on line 4, `more` from line 6).
fn map(more: &[String]) -> String {
    let mut layers = vec![FLOOR.to_string(), SPAWN.to_string()];
    layers.extend(more.iter().cloned());
    map_with(TILESET, &layers)
}

/// Writes `text` as `DIR/NAME`.
fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The import error of `text` written as `DIR/m.tmj`.
fn error(dir: &Path, text: &str) -> String {
    match import_tiled_map(&write(dir, "m.tmj", text)) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

/// `n` points, all `{"x":0,"y":0}`: 14 characters each with its comma.
fn points(n: usize) -> String {
    vec![r#"{"x":0,"y":0}"#; n].join(",")
}

/// The 1-based column of the first point of `line` past the limit (14 characters a point).
fn column_past_limit(line: &str) -> usize {
    line.find(r#"{"x""#).unwrap() + 1 + 14 * MAX_POLYGON_POINTS
}

#[test]
fn a_polygon_past_the_limit_is_refused_where_it_passes_in_a_map_tileset_or_template() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let layer = |n| {
        format!(
            r#"{{"type":"objectgroup","name":"collision","objects":[{{"id":7,"name":"ramp","x":0,"y":0,"polygon":[{}]}}]}}"#,
            points(n)
        )
    };
    // At the limit: read (a polygon that is no ramp, a warning).
    assert!(import_tiled_map(&write(d, "m.tmj", &map(&[layer(MAX_POLYGON_POINTS)]))).is_ok());
    // One more: refused at that point, line 6 (the third layer), before the tree is built.
    let over = layer(MAX_POLYGON_POINTS + 1);
    let want = format!(
        "m.tmj:6:{}: object 7 \"ramp\": its polygon has more than 10000 points (this is point 10001); expected at most 10000",
        column_past_limit(&over)
    );
    let p = write(d, "m.tmj", &map(&[over]));
    let out = platbench().arg("inspect").arg(&p).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(&want), "{stderr}");
    // A JSON tileset's tile with a collision polyline past the limit: the tileset, its line and
    // column, the object and the tile.
    let tsj = format!(
        r#"{{"type":"tileset","name":"ts","tilewidth":16,"tileheight":16,"tilecount":1,"columns":1,"image":"t.png","imagewidth":16,"imageheight":16,"tiles":[{{"id":0,"objectgroup":{{"objects":[{{"id":1,"name":"slope","x":0,"y":0,"polyline":[{}]}}]}}}}]}}"#,
        points(MAX_POLYGON_POINTS + 1)
    );
    write(d, "t.tsj", &tsj);
    let e = error(
        d,
        &map_with(
            r#"{"firstgid":1,"source":"t.tsj"}"#,
            &[FLOOR.into(), SPAWN.into()],
        ),
    );
    let want = format!(
        "line 1, column {}: object 1 \"slope\" (a collision shape of tile 0): its polyline has more than 10000 points",
        column_past_limit(&tsj)
    );
    assert!(e.contains("t.tsj") && e.contains(&want), "{e}");
    // A JSON template's object.
    let tj = format!(
        r#"{{"type":"template","object":{{"name":"rail","x":0,"y":0,"polyline":[{}]}}}}"#,
        points(MAX_POLYGON_POINTS + 1)
    );
    write(d, "r.tj", &tj);
    let rail = r#"{"type":"objectgroup","name":"rails","objects":[{"id":3,"template":"r.tj","x":0,"y":0}]}"#;
    let e = error(d, &map(&[rail.into()]));
    let want = format!(
        "line 1, column {}: object  \"rail\": its polyline has more than 10000 points",
        column_past_limit(&tj)
    );
    assert!(e.contains("r.tj") && e.contains(&want), "{e}");
}

#[test]
fn tile_layers_past_the_cell_limits_are_refused_at_the_layer_before_the_tree_is_built() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Layers of 1000 x 1000 cells (their base64 data left empty: the walk counts what they
    // declare): as many as MAX_LAYER_CELLS holds pass the walk (refused later, for their data).
    let layer = |k: usize| {
        format!(
            r#"{{"type":"tilelayer","name":"l{k}","width":1000,"height":1000,"encoding":"base64","data":""}}"#
        )
    };
    let n = MAX_LAYER_CELLS / MAX_TILES;
    let layers: Vec<String> = (0..=n).map(layer).collect();
    let e = error(d, &map_with(TILESET, &layers[..n]));
    assert!(!e.contains("together"), "{e}");
    // One more: refused at the line where it starts.
    let e = error(d, &map_with(TILESET, &layers));
    assert!(
        e.contains(&format!("m.tmj:{}:1: layer \"l16\" (1000 x 1000 tiles) brings the map's tile layers to 17000000 cells together; expected at most 16000000", 4 + n)),
        "{e}"
    );
    // Data of more cells than a layer may hold.
    let long = format!(
        r#"{{"type":"tilelayer","name":"long","width":3,"height":2,"data":[{}]}}"#,
        vec!["0"; MAX_TILES + 1].join(",")
    );
    let e = error(d, &map(&[long]));
    assert!(
        e.contains(
            "m.tmj:6:1: layer \"long\": its data holds 1000001 cells; expected at most 1000000"
        ),
        "{e}"
    );
}

#[test]
fn json_objects_values_and_nesting_past_their_limits_are_refused_where_they_pass() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // As many empty objects as the limit, besides the map's others: past it on line 6.
    let junk = format!(
        r#"{{"type":"objectgroup","name":"junk","objects":[{}]}}"#,
        vec!["{}"; MAX_JSON_OBJECTS].join(",")
    );
    let e = error(d, &map(&[junk]));
    assert!(
        e.contains("m.tmj:6:") && e.contains("more than 500000 JSON objects"),
        "{e}"
    );
    // As many numbers as the limit outside the tile layers' data.
    let numbers = format!(
        r#"{{"type":"objectgroup","name":"junk","objects":[],"properties":{{"n":[{}]}}}}"#,
        vec!["0"; MAX_JSON_VALUES].join(",")
    );
    let e = error(d, &map(&[numbers]));
    assert!(
        e.contains("m.tmj:6:")
            && e.contains("more than 5000000 JSON values besides the cells of its tile layers"),
        "{e}"
    );
    // Groups around the floor: 61 are read; at 62 its data array is the 128th array or object
    // inside another (the map, its layers, each group and its layers, the floor), past
    // serde_json's 127.
    let nest = |n: usize| {
        format!(
            "{}{FLOOR}{}",
            r#"{"type":"group","name":"g","layers":["#.repeat(n),
            "]}".repeat(n)
        )
    };
    let ok = map_with(TILESET, &[nest(61), SPAWN.into()]);
    assert!(import_tiled_map(&write(d, "m.tmj", &ok)).is_ok());
    let deep = nest(62);
    let e = error(d, &map_with(TILESET, &[deep.clone(), SPAWN.into()]));
    let column = deep.find("[0,0,0").unwrap() + 1;
    assert!(
        e.contains(&format!("m.tmj:4:{column}: arrays and objects nest more than 127 deep here; expected at most 127")),
        "{e}"
    );
}

#[test]
fn compressed_json_layer_data_is_inflated_no_further_than_its_cells() {
    let dir = tempfile::tempdir().unwrap();
    // zlib data (1.4 kB) that inflates to 1 MiB (tests/robustness/crashes.rs's bomb), as a 3 x 2
    // layer's: read no further than its 6 cells of 4 bytes, and refused at the layer's line.
    let bomb = format!("eNrtwTEBAAAAwqD1T20IX6{}D4DAPAAAQ==", "A".repeat(1355));
    let floor = format!(
        r#"{{"type":"tilelayer","name":"floor","width":3,"height":2,"encoding":"base64","compression":"zlib","data":"{bomb}"}}"#
    );
    let e = error(dir.path(), &map_with(TILESET, &[floor, SPAWN.into()]));
    assert!(
        e.contains("m.tmj:4: layer \"floor\": its data holds more than 24 bytes (6 cells); expected exactly 6 cells"),
        "{e}"
    );
}

//! Issue 40's limits on what one map or level may hold, each checked before the work it bounds
//! and refused with the file, the line, the object or layer, what was found and what was
//! expected: points of a Tiled polygon, spawn points, tile ids (gids), and a TOML level's size,
//! items and input events. Every file here is written for these tests.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use platbench::level::{load_tiled_map, parse_level, Slope, Tile};

use super::tiled::{row0, MapText};

/// `MAX_POLYGON_POINTS` in src/limits.rs.
const MAX_POLYGON_POINTS: usize = 10_000;
/// `MAX_SPAWNS` in src/limits.rs.
const MAX_SPAWNS: usize = 1_000;
/// `MAX_TOML_ITEMS` in src/limits.rs.
const MAX_TOML_ITEMS: usize = 500_000;
/// `MAX_INPUT_EVENTS` in src/limits.rs.
const MAX_INPUT_EVENTS: usize = 50_000;
/// `MAX_TOML_BYTES` in src/limits.rs (32 MiB).
const MAX_TOML_BYTES: usize = 32 * 1024 * 1024;

/// A ramp of a 16 px tile drawn with `n` points (tile pixels, y down): its bottom corners and
/// its top-right corner (16, 8), then its top-left corner (0, 0) `n - 3` times over (points
/// spread along its top would be within a pixel of each other, and take its corner with them).
fn ramp_points(n: usize) -> String {
    let mut p = vec!["0,16", "16,16", "16,8"];
    p.extend(std::iter::repeat_n("0,0", n - 3));
    p.join(" ")
}

/// The 1-based line of `text` holding `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

#[test]
fn a_polygon_of_more_points_than_the_limit_is_refused_naming_its_object_and_line() {
    let tile = |n| {
        format!(
            r#"<tile id="0"><objectgroup><object id="1" name="slope" x="0" y="0"><polygon points="{}"/></object></objectgroup></tile>"#,
            ramp_points(n)
        )
    };
    // At the limit: read, and still the ramp once the points on its top line are dropped.
    let at_limit = tile(MAX_POLYGON_POINTS);
    let map = MapText {
        tiles: &at_limit,
        rows: &["0,0,0", "0,1,0"],
        ..MapText::default()
    };
    let slope = Tile::Slope(Slope::Line {
        left: 1.0,
        right: 0.5,
    });
    assert_eq!(row0(&map.import().unwrap().level)[1], slope);
    // One more: refused before it is read, at the tileset tile's line in the map.
    let over = tile(MAX_POLYGON_POINTS + 1);
    let map = MapText {
        tiles: &over,
        rows: &["0,0,0", "0,1,0"],
        ..MapText::default()
    };
    let line = line_of(&map.text(), "name=\"slope\"");
    let e = map.error();
    let want = format!("m.tmx:{line}: object 1 \"slope\" (a collision shape of tile 0): its polygon has 10001 points; expected at most 10000");
    assert!(e.contains(&want), "{e}");
    // A polyline of the map's own object layer, after the tileset's tiles: no tile named.
    let rail = format!(
        r#"<object id="7" name="rail" x="0" y="0"><polyline points="{}"/></object>"#,
        ramp_points(MAX_POLYGON_POINTS + 1)
    );
    let map = MapText {
        tiles: r#"<tile id="1"><properties><property name="collision" value="solid"/></properties></tile>"#,
        objects: &rail,
        ..MapText::default()
    };
    let line = line_of(&map.text(), "name=\"rail\"");
    let e = map.error();
    let want = format!(
        "m.tmx:{line}: object 7 \"rail\": its polyline has 10001 points; expected at most 10000"
    );
    assert!(e.contains(&want), "{e}");
}

/// `n` spawn points on the floor of the default 3 x 2 map.
fn spawns(n: usize) -> String {
    (1..=n)
        .map(|k| format!(r#"<object id="{k}" class="spawn" x="24" y="16"><point/></object>"#))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn more_spawn_points_than_the_limit_are_refused_before_their_probes_are_made() {
    let dir = tempfile::tempdir().unwrap();
    // At the limit: every spawn read, each with its probes (a drop at least).
    let at_limit = spawns(MAX_SPAWNS);
    let path = MapText {
        objects: &at_limit,
        ..MapText::default()
    }
    .write(dir.path());
    let (level, _) = load_tiled_map(&path).unwrap();
    assert!(
        level.scenarios.len() >= MAX_SPAWNS,
        "{}",
        level.scenarios.len()
    );
    // One more: the spawn past the limit is named.
    let over = spawns(MAX_SPAWNS + 1);
    let e = MapText {
        objects: &over,
        ..MapText::default()
    }
    .error();
    assert!(
        e.contains(": object 1001 \"\": it is spawn point 1001 of the map; expected at most 1000")
            && e.split("m.tmx:")
                .nth(1)
                .is_some_and(|l| l.starts_with(|c: char| c.is_ascii_digit())),
        "{e}"
    );
}

#[test]
fn a_tile_id_of_no_tile_names_the_layer_the_cell_from_the_top_and_the_line() {
    // Tileset "props" holds gids 11 and 12; gid 14 is its tile 3, which it does not have.
    let text = r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="4" height="3" tilewidth="16" tileheight="16" infinite="0" nextlayerid="5" nextobjectid="2">
 <tileset firstgid="1" name="tiles" tilewidth="16" tileheight="16" tilecount="4" columns="4"><image source="t.png" width="64" height="16"/></tileset>
 <tileset firstgid="11" name="props" tilewidth="16" tileheight="16" tilecount="2" columns="2"><image source="p.png" width="32" height="16"/></tileset>
 <group id="1" name="world">
  <layer id="2" name="ground" width="4" height="3">
   <data encoding="csv">
0,0,0,0,
0,0,0,14,
1,1,1,1
</data>
  </layer>
 </group>
 <objectgroup id="3" name="objects"><object id="1" class="spawn" x="8" y="32"><point/></object></objectgroup>
</map>
"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    let e = load_tiled_map(&path).unwrap_err().to_string();
    // Line 9 holds the row "0,0,0,14"; Tiled shows the cell as x = 3, y = 1.
    let want = "m.tmx:9: layer \"world/ground\": cell x = 3, y = 1 (column and row from the map's top-left, as Tiled shows them) holds gid 14 (tile 3 of tileset \"props\"), which names no tile; expected 0 (no tile) or a gid of the map's tilesets: 1 to 4 (\"tiles\"), 11 to 12 (\"props\")";
    assert!(e.contains(want), "{e}");
}

/// A TOML level whose one scenario has `events` input events `{t=0.0}` (4 items each: `{`, `=`,
/// the point and `,`), all
/// on line 10.
fn level_with_events(events: usize) -> String {
    format!(
        "name = \"ev\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 1.0\ninputs = [{}]\n",
        "{t=0.0},".repeat(events)
    )
}

#[test]
fn a_toml_level_is_refused_past_its_bytes_items_or_input_events_before_it_costs_memory() {
    // At the event limit: read.
    let l = parse_level(&level_with_events(MAX_INPUT_EVENTS), "ev.toml").unwrap();
    assert_eq!(l.scenarios[0].inputs.len(), MAX_INPUT_EVENTS);
    // One more event: the event past the limit, line 10 (its column: 10 for `inputs = [`,
    // then 8 characters an event).
    let e = parse_level(&level_with_events(MAX_INPUT_EVENTS + 1), "ev.toml").unwrap_err();
    assert_eq!((e.line, e.column), (10, 11 + 8 * MAX_INPUT_EVENTS), "{e}");
    assert!(
        e.message.contains(
            "scenario \"s\" has 50001 input events (this is event 50001); expected at most 50000"
        ),
        "{e}"
    );
    // Past the item limit (4 items an event, so MAX / 3 events are past it): refused before the
    // `toml` crate reads it.
    let e = parse_level(&level_with_events(MAX_TOML_ITEMS / 3), "ev.toml").unwrap_err();
    assert_eq!(e.line, 10, "{e}");
    assert!(
        e.message
            .contains("the file holds more than 500000 TOML items")
            && e.message.contains("expected at most 500000"),
        "{e}"
    );
    // Past the byte limit, whatever it holds.
    let big = format!("# {}\n", "x".repeat(MAX_TOML_BYTES));
    let e = parse_level(&big, "big.toml").unwrap_err();
    assert_eq!((e.file.as_str(), e.line), ("big.toml", 1), "{e}");
    assert!(
        e.message.contains(&format!(
            "the file is {} bytes; expected at most 33554432",
            big.len()
        )),
        "{e}"
    );
}

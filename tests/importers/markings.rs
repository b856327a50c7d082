//! The ways games mark one-way platforms and hazards in Tiled maps (docs/formats.md, "Tile
//! properties"): a string property `class = one_way`, the bools `unisolid` and `semisolid`,
//! hazard bools that make a tile or a collision rectangle not solid, `isOneWay` on a collision
//! rectangle, the solid bools `collide` and `estSolide`, collision polylines, the class
//! `platform` without a path (one-way) and a platform path naming a point. Each map is written
//! for its rule.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use glam::Vec2;
use platbench::level::{import_tiled_map_with, PlatformMotion, Tile};

use super::tiled::{open_edges, row0, MapText};

fn prop(name: &str, ty: &str, value: &str) -> String {
    format!(r#"<property name="{name}" type="{ty}" value="{value}"/>"#)
}

#[test]
fn tile_properties_mark_one_way_platforms_and_hazards() {
    let tile = |id: u32, props: &[String]| {
        format!(
            r#"<tile id="{id}"><properties>{}</properties></tile>"#,
            props.concat()
        )
    };
    let tiles = [
        tile(0, &[prop("class", "string", "one_way")]),
        tile(1, &[prop("unisolid", "bool", "true")]),
        tile(2, &[prop("hazard", "bool", "true")]),
        // A hazard that the game also makes solid stays solid.
        tile(
            3,
            &[
                prop("hazard", "bool", "true"),
                prop("collides", "bool", "true"),
            ],
        ),
        tile(4, &[prop("collide", "bool", "true")]),
        tile(5, &[prop("estSolide", "bool", "true")]),
        // A `type` string that is no tile kind says nothing: the tileset marks with bools,
        // so the tile is empty.
        tile(6, &[prop("type", "string", "grass")]),
        tile(7, &[prop("semisolid", "bool", "true")]),
    ]
    .concat();
    let r = MapText {
        tiles: &tiles,
        rows: &["0,0,0,0,0,0,0,0", "1,2,3,4,5,6,7,8"],
        ..MapText::default()
    }
    .import()
    .unwrap();
    assert_eq!(
        row0(&r.level),
        [
            Tile::OneWay,
            Tile::OneWay,
            Tile::Empty,
            Tile::Solid,
            Tile::Solid,
            Tile::Solid,
            Tile::Empty,
            Tile::OneWay
        ]
    );
}

#[test]
fn collision_rectangles_carry_their_own_marks() {
    // A collision object layer of three rectangles on the bottom row of a 3 x 2 map of 16 px
    // tiles: a plain one, one with isOneWay = true, one with hazard = true.
    let rect = |id: u32, x: u32, props: &str| {
        format!(
            r#"<object id="{id}" x="{x}" y="16" width="16" height="16"><properties>{props}</properties></object>"#
        )
    };
    let text = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="3" height="2" tilewidth="16" tileheight="16" infinite="0" nextlayerid="2" nextobjectid="4">
 <objectgroup id="1" name="collision">
  {}
  {}
  {}
 </objectgroup>
 <objectgroup id="2" name="spawns"><object id="9" name="spawn" x="8" y="8"><point/></object></objectgroup>
</map>
"#,
        rect(1, 0, ""),
        rect(2, 16, &prop("isOneWay", "bool", "true")),
        rect(3, 32, &prop("hazard", "bool", "true")),
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    let r = import_tiled_map_with(&path, &open_edges()).unwrap();
    assert_eq!(row0(&r.level), [Tile::Solid, Tile::OneWay, Tile::Empty]);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.subject == "object 3 \"\"" && w.message.contains("\"hazard\"")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn collision_polylines_are_runs_of_cells_and_untravelling_platforms_one_way() {
    // A 4 x 3 map of 16 px tiles whose collision layer holds, as melonJS's platformer draws
    // them: a level polyline of class `platform` across x = 16..48 px at y = 16 px (the top of
    // Tiled row 1, so the cells under it, level row 1, i = 1 and 2, one-way); an upright
    // polyline at x = 64 px, the map's right side (the column left of it, i = 3, solid); a
    // floor rectangle on the bottom row; and a slanted polyline (a warning, no cell).
    let text = r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="4" height="3" tilewidth="16" tileheight="16" infinite="0" nextlayerid="3" nextobjectid="9">
 <objectgroup id="1" name="Collision">
  <object id="1" type="platform" x="16" y="16"><polyline points="0,0 32,0"/></object>
  <object id="2" x="64" y="0"><polyline points="0,0 0,48"/></object>
  <object id="3" x="0" y="32" width="64" height="16"/>
  <object id="4" x="0" y="0"><polyline points="0,0 16,16"/></object>
 </objectgroup>
 <objectgroup id="2" name="spawns"><object id="9" name="spawn" x="8" y="32"><point/></object></objectgroup>
</map>
"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    let r = import_tiled_map_with(&path, &open_edges()).unwrap();
    let row = |j: i64| -> Vec<Tile> { (0..4).map(|i| r.level.tile(i, j)).collect() };
    assert_eq!(row(0), [Tile::Solid; 4]);
    assert_eq!(
        row(1),
        [Tile::Empty, Tile::OneWay, Tile::OneWay, Tile::Solid]
    );
    assert_eq!(row(2), [Tile::Empty, Tile::Empty, Tile::Empty, Tile::Solid]);
    let said = |subject: &str, text: &str| {
        r.warnings
            .iter()
            .any(|w| w.subject == subject && w.message.contains(text))
    };
    assert!(
        said(
            "layer \"Collision\"",
            "1 collision shape(s) of class \"platform\" with no \"path\": read as one-way"
        ),
        "{:?}",
        r.warnings
    );
    assert!(
        said("object 4 \"\"", "1 slanted leg(s)"),
        "{:?}",
        r.warnings
    );
}

#[test]
fn a_platform_path_naming_a_point_goes_there_and_back() {
    // A 32 x 16 px platform at (16, 16) px on a 6 x 4 map of 16 px tiles, whose path names a
    // point at (48, 0) px: its top-left corner goes 2 tiles right and 1 up, and back.
    let objects = r#"<object id="1" name="s" class="spawn" x="8" y="64"><point/></object>
<object id="2" name="lift" x="16" y="16" width="32" height="16"><properties><property name="path" type="object" value="3"/><property name="speed" type="float" value="2"/></properties></object>
<object id="3" x="48" y="0"><point/></object>"#;
    let rows = ["0,0,0,0,0,0", "0,0,0,0,0,0", "0,0,0,0,0,0", "1,1,1,1,1,1"];
    let dir = tempfile::tempdir().unwrap();
    let path = MapText {
        rows: &rows,
        objects,
        ..MapText::default()
    }
    .write(dir.path());
    let r = import_tiled_map_with(&path, &open_edges()).unwrap();
    assert_eq!(r.level.platforms.len(), 1);
    let p = &r.level.platforms[0];
    // Bottom-left at (1, 2) tiles in the level (y up: the rectangle's bottom is 32 px down a
    // 64 px map).
    assert_eq!(p.start, Vec2::new(1.0, 2.0));
    assert_eq!(
        p.motion,
        PlatformMotion::Waypoints {
            points: vec![Vec2::new(1.0, 2.0), Vec2::new(3.0, 3.0)],
            speed: 2.0
        }
    );
    // The point is used as a path, so no warning calls it ignored.
    assert!(
        r.warnings.iter().all(|w| w.subject != "object 3 \"\""),
        "{:?}",
        r.warnings
    );
}

#[test]
fn a_one_way_bool_on_some_tiles_leaves_the_unmarked_tiles_solid() {
    // Tile 1 carries `unisolid = true`; tile 0, the floor, carries nothing. Only a tileset that
    // marks its solid tiles with a bool leaves its unmarked tiles empty; a one-way (or ladder)
    // bool marks its own tiles only.
    let tiles = format!(
        r#"<tile id="1"><properties>{}</properties></tile>"#,
        prop("unisolid", "bool", "true")
    );
    let dir = tempfile::tempdir().unwrap();
    let path = MapText {
        tiles: &tiles,
        rows: &["0,2,0", "1,1,1"],
        ..MapText::default()
    }
    .write(dir.path());
    let r = import_tiled_map_with(&path, &open_edges()).unwrap();
    assert_eq!(row0(&r.level), [Tile::Solid; 3]);
    assert_eq!(r.level.tile(1, 1), Tile::OneWay);
}

//! The ways games mark one-way platforms and hazards in Tiled maps (docs/formats.md, "Tile
//! properties"): a string property `class = one_way`, the bools `unisolid` and `semisolid`,
//! hazard bools that make a tile or a collision rectangle not solid, `isOneWay` on a collision
//! rectangle, and the solid bools `collide` and `estSolide`. Each map is written for its rule.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use platbench::level::{import_tiled_map_with, Tile};

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

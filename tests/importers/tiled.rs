//! Tiled maps (`.tmx`, docs/formats.md): each mapping rule, each unsupported construct's message,
//! the probes, the side file, and the showcase map run end to end on both backends.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::{Path, PathBuf};

use glam::Vec2;
use platbench::level::{
    import_tiled_map, import_tiled_map_with, load_tiled_map, load_tiled_map_with, Edges,
    ImportOptions, LayerRole, PlatformMotion, Slope, Tile, TiledError, TiledImport,
};

/// The default rules with the map's sides left open, for the tests of other rules
/// (tests/importers/edges.rs tests the walls).
pub(super) fn open_edges() -> ImportOptions {
    ImportOptions {
        edges: Some(Edges::Open),
        ..ImportOptions::default()
    }
}

pub(super) fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/maps")
        .join(name)
}

/// A map of 16 px tiles with one inline tileset named "t" (`tiles`: its `<tile>` elements), one
/// CSV tile layer (`rows`, top row first) and one object layer (`objects`), written as
/// `DIR/NAME.tmx`. `map_attrs` replaces the orientation and infinite attributes.
pub(super) struct MapText<'a> {
    pub(super) tiles: &'a str,
    pub(super) rows: &'a [&'a str],
    pub(super) objects: &'a str,
    pub(super) map_attrs: &'a str,
    pub(super) tileset_size: u32,
}

impl Default for MapText<'_> {
    fn default() -> Self {
        MapText {
            tiles: "",
            rows: &["0,0,0", "1,1,1"],
            objects: "",
            map_attrs: r#"orientation="orthogonal" infinite="0""#,
            tileset_size: 16,
        }
    }
}

impl MapText<'_> {
    pub(super) fn text(&self) -> String {
        let w = self.rows[0].split(',').count();
        let h = self.rows.len();
        let s = self.tileset_size;
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" {attrs} renderorder="right-down" width="{w}" height="{h}" tilewidth="16" tileheight="16" nextlayerid="3" nextobjectid="20">
 <tileset firstgid="1" name="t" tilewidth="{s}" tileheight="{s}" tilecount="16" columns="16">
  <image source="t.png" width="{iw}" height="{s}"/>
{tiles}
 </tileset>
 <layer id="1" name="collision" width="{w}" height="{h}">
  <data encoding="csv">
{rows}
</data>
 </layer>
 <objectgroup id="2" name="objects">
{objects}
 </objectgroup>
</map>
"#,
            attrs = self.map_attrs,
            iw = 16 * s,
            tiles = self.tiles,
            rows = self.rows.join(",\n"),
            objects = self.objects,
        )
    }

    pub(super) fn write(&self, dir: &Path) -> PathBuf {
        let path = dir.join("m.tmx");
        std::fs::write(&path, self.text()).unwrap();
        path
    }

    /// The map imported with its sides open, as the rule tests read it.
    pub(super) fn import(&self) -> Result<TiledImport, TiledError> {
        let dir = tempfile::tempdir().unwrap();
        import_tiled_map_with(&self.write(dir.path()), &open_edges()).map_err(|f| f.error)
    }

    pub(super) fn error(&self) -> String {
        match self.import() {
            Ok(_) => panic!("expected an error for\n{}", self.text()),
            Err(e) => e.to_string(),
        }
    }
}

pub(super) fn row0(l: &platbench::level::Level) -> Vec<Tile> {
    (0..l.width as i64).map(|i| l.tile(i, 0)).collect()
}

#[test]
fn every_tile_rule_maps_to_its_tile() {
    // tests/maps/rules.tmx: the bottom row holds tile ids 0..=10 in order, then tile 8 and tile
    // 5 flipped horizontally; the top row is empty except the excluded decoration layer.
    let r = import_tiled_map_with(&shipped("rules.tmx"), &open_edges()).unwrap();
    let line = |left, right| Tile::Slope(Slope::Line { left, right });
    let heights: [u8; 16] = std::array::from_fn(|k| 16 - k as u8);
    assert_eq!(
        row0(&r.level),
        vec![
            Tile::Solid,                          // 0: no properties, no shape: solid by default
            Tile::Solid,                          // 1: collision = solid
            Tile::OneWay,                         // 2: collision = one_way
            Tile::Ladder,                         // 3: collision = ladder
            Tile::Empty,                          // 4: collision = empty
            line(0.0, 0.5),                       // 5: slope_left = 0, slope_right = 0.5
            Tile::Slope(Slope::Heights(heights)), // 6: heights = "16,15,...,1"
            Tile::Solid,                          // 7: collision editor, full-tile rectangle
            line(0.0, 1.0),                       // 8: collision editor ramp, up to the right
            line(0.75, 0.25), // 9: collision editor trapezoid, down (y 4..8 px of 16)
            Tile::Solid,      // 10: collision = solid plus an unknown property
            line(1.0, 0.0),   // 8 flipped: the mirrored ramp
            line(0.5, 0.0),   // 5 flipped: the mirrored line slope
        ]
    );
    // The decoration layer (collision = false) puts tile 0 at the top-left: left out.
    assert_eq!(r.level.tile(0, 1), Tile::Empty);
    let f = r.level.features;
    assert!(f.slopes && f.one_way && f.ladders && !f.moving_platforms);
    // The unknown property is named with its tile, once; the map marks no spawn, so the
    // fallback spawn is said aloud.
    assert_eq!(r.warnings.len(), 2, "{:?}", r.warnings);
    let w = r.warnings[0].to_string();
    assert!(
        w.contains("tileset \"rules\" tile 10") && w.contains("\"damage\""),
        "{w}"
    );
    assert!(r.warnings[1].message.starts_with("no spawn point found"));
    assert_eq!(r.level.name, "rules");
    assert!(r.level.source.ends_with("rules.tmx"));
}

#[test]
fn base64_zlib_layers_read_like_csv() {
    let csv = import_tiled_map_with(&shipped("rules.tmx"), &open_edges()).unwrap();
    let b64 = import_tiled_map_with(&shipped("rules_base64.tmx"), &open_edges()).unwrap();
    assert_eq!(row0(&b64.level), row0(&csv.level));
    assert_eq!(b64.level.tile(0, 1), Tile::Empty);
}

#[test]
fn the_showcase_map_imports_its_geometry_platform_and_spawns() {
    let r = import_tiled_map(&shipped("showcase.tmx")).unwrap();
    let l = &r.level;
    assert_eq!((l.name.as_str(), l.width, l.height), ("showcase", 24, 12));
    assert!(l.description.starts_with("Tiled showcase"));
    // Tiled's bottom row is j = 0: the floor.
    assert!((0..24).all(|i| l.tile(i, 0) == Tile::Solid));
    // The ramp from the external tileset's collision editor, then its mirror.
    assert_eq!(
        l.tile(8, 1),
        Tile::Slope(Slope::Line {
            left: 0.0,
            right: 1.0
        })
    );
    assert_eq!(
        l.tile(13, 1),
        Tile::Slope(Slope::Line {
            left: 1.0,
            right: 0.0
        })
    );
    assert_eq!(l.tile(10, 1), Tile::Solid);
    assert_eq!(l.tile(3, 2), Tile::OneWay);
    assert_eq!(l.tile(19, 4), Tile::Ladder);
    // The decoration layer's solids across the walk (row 1, i = 6..12) are left out.
    assert_eq!(l.tile(6, 1), Tile::Empty);
    // The platform: 48 x 8 px at (224, 88) px on a 12-row map of 16 px = (14, 6) tiles, 3 x 0.5;
    // its path is a 64 px polyline to the right: 4 tiles, from the platform's start.
    assert_eq!(l.platforms.len(), 1);
    let p = &l.platforms[0];
    assert_eq!(
        (p.start, p.size),
        (Vec2::new(14.0, 6.0), Vec2::new(3.0, 0.5))
    );
    assert_eq!(
        p.motion,
        PlatformMotion::Waypoints {
            points: vec![Vec2::new(14.0, 6.0), Vec2::new(18.0, 6.0)],
            speed: 2.0
        }
    );
    assert!(l.features.moving_platforms);
    // A point spawn named "start" at (56, 176) px, and an unnamed 16 px rectangle (object 4) at
    // (160, 144) px whose bottom centre is the feet.
    let spawns: Vec<(&str, Vec2)> = r
        .spawns
        .iter()
        .map(|s| (s.name.as_str(), s.position))
        .collect();
    assert_eq!(
        spawns,
        [
            ("start", Vec2::new(3.5, 1.0)),
            ("spawn4", Vec2::new(10.5, 2.0))
        ]
    );
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}

#[test]
fn probes_run_at_each_spawn_and_the_ride_starts_on_the_platform() {
    let (l, _) = load_tiled_map(&shipped("showcase.tmx")).unwrap();
    let names: Vec<&str> = l.scenarios.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "start-drop",
            "start-walk_left",
            "start-walk_right",
            "start-jump",
            "start-ride",
            "spawn4-drop",
            "spawn4-walk_left",
            "spawn4-walk_right",
            "spawn4-jump",
            "spawn4-ride"
        ]
    );
    let ride = &l.scenarios[4];
    // On the middle of the platform's top: (14 + 3/2, 6 + 0.5); one round trip of 2 x 4 tiles
    // at 2 tiles/s.
    assert_eq!(
        (ride.spawn, ride.ride, ride.duration),
        (Vec2::new(15.5, 6.5), Some(0), 4.0)
    );
}

#[test]
fn a_side_file_replaces_the_probes() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["showcase.tmx", "terrain.tsx"] {
        std::fs::copy(shipped(f), dir.path().join(f)).unwrap();
    }
    let map = dir.path().join("showcase.tmx");
    std::fs::write(
        dir.path().join("showcase.toml"),
        "[[scenario]]\nname = \"climb\"\nspawn = [19.5, 1.0]\nduration = 2.0\ninputs = [ { t = 0.0, up = true } ]\nexpect_y = 5.0\n\n[[scenario]]\nname = \"lift\"\nspawn = [15.5, 6.5]\nduration = 3.0\nride = 0\n",
    )
    .unwrap();
    let (l, warnings) = load_tiled_map(&map).unwrap();
    let names: Vec<&str> = l.scenarios.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["climb", "lift"]);
    assert_eq!(l.scenarios[0].expect_y, Some(5.0));
    assert!(
        warnings
            .iter()
            .any(|w| w.message.contains("replaces the probes")),
        "{warnings:?}"
    );
    // Errors in the side file keep its line and column: `ride = 3` on line 5, column 8.
    std::fs::write(
        dir.path().join("showcase.toml"),
        "[[scenario]]\nname = \"lift\"\nspawn = [15.5, 6.5]\nduration = 3.0\nride = 3\n",
    )
    .unwrap();
    let e = load_tiled_map(&map).unwrap_err().to_string();
    assert!(
        e.contains("showcase.toml:5:8:") && e.contains("names no platform"),
        "{e}"
    );
    // Anything but scenarios is refused, with its line.
    std::fs::write(dir.path().join("showcase.toml"), "map = \"#\"\n").unwrap();
    let e = load_tiled_map(&map).unwrap_err().to_string();
    assert!(
        e.contains("showcase.toml:1:1:") && e.contains("unknown field"),
        "{e}"
    );
}

#[test]
fn a_map_without_spawns_starts_at_a_standable_cell_or_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    // A floor of 3 tiles: the leftmost standable cell is (0, 1), feet at (0.5, 1).
    let path = MapText::default().write(dir.path());
    let (l, warnings) = load_tiled_map_with(&path, &open_edges()).unwrap();
    assert_eq!(l.scenarios[0].name, "auto-drop");
    assert_eq!(l.scenarios[0].spawn, Vec2::new(0.5, 1.0));
    assert!(
        warnings
            .iter()
            .any(|w| w.message.contains("no spawn point found")
                && w.message.contains("class \"spawn\"")
                && w.message.contains("--spawn")),
        "{warnings:?}"
    );
    // Nothing to stand on: an error that says what to add, and the warnings so far.
    let path = MapText {
        rows: &["0,0,0", "0,0,0"],
        ..MapText::default()
    }
    .write(dir.path());
    let f = load_tiled_map_with(&path, &ImportOptions::default()).unwrap_err();
    let e = f.error.to_string();
    assert!(e.contains("no spawn points") && e.contains("m.toml"), "{e}");
    assert!(
        f.warnings.iter().any(|w| w.message.contains("no solids")),
        "{:?}",
        f.warnings
    );
}

pub(super) const SPAWN: &str =
    r#"<object id="1" name="s" class="spawn" x="8" y="16"><point/></object>"#;

#[test]
fn objects_that_are_neither_spawns_nor_platforms_are_warned_about_by_id_and_name() {
    let objects = format!(
        r#"{SPAWN}
<object id="5" name="cloud" x="0" y="0" width="16" height="16"><ellipse/></object>
<object id="6" name="sign" x="0" y="0" width="32" height="16"><text>hi</text></object>
<object id="7" name="bush" gid="1" x="0" y="16" width="16" height="16"/>
<object id="8" name="stray" x="0" y="0"><polyline points="0,0 16,0"/></object>
<object id="9" name="trigger" class="door" x="0" y="0" width="16" height="16"/>"#
    );
    let r = MapText {
        objects: &objects,
        ..MapText::default()
    }
    .import()
    .unwrap();
    assert_eq!(r.spawns.len(), 1);
    let text: Vec<String> = r.warnings.iter().map(|w| w.to_string()).collect();
    for (id, name, what) in [
        (5, "cloud", "an ellipse"),
        (6, "sign", "a text"),
        (7, "bush", "tile object"),
        (8, "stray", "no platform"),
        (9, "trigger", "class \"door\""),
    ] {
        let subject = format!("object {id} \"{name}\"");
        assert!(
            text.iter()
                .any(|w| w.contains(&subject) && w.contains(what)),
            "{subject} / {what}: {text:#?}"
        );
    }
}

/// The level's tiles as the level format writes them, top row first.
fn grid(l: &platbench::level::Level) -> String {
    platbench::level::import::ascii_map(l).0
}

fn spawns_of(r: &TiledImport) -> Vec<(&str, Vec2)> {
    r.spawns
        .iter()
        .map(|s| (s.name.as_str(), s.position))
        .collect()
}

#[test]
fn collision_rectangles_in_named_object_layers_make_the_grid() {
    // tests/maps/object_collision.tmx: a floor and a wall as rectangles in
    // "Platform-Colliders", a 4 px one-way rectangle at the top of row 2 in "OneWay", a coin
    // in "Coins", one rectangle in "PlayerSpawn"; the tile layers are art.
    let r = import_tiled_map_with(&shipped("object_collision.tmx"), &open_edges()).unwrap();
    assert_eq!(
        grid(&r.level),
        "..........\n..........\n...==....#\n.........#\n##########\n"
    );
    // The spawn layer's rectangle at (16, 48) px, 16 x 16: feet at its bottom centre.
    assert_eq!(spawns_of(&r), [("spawn5", Vec2::new(1.5, 1.0))]);
    let role = |name: &str| r.layers.iter().find(|l| l.name == name).unwrap().role;
    assert_eq!(role("Background"), LayerRole::Decoration);
    assert_eq!(role("Tile Layer 1"), LayerRole::Decoration);
    assert_eq!(role("Platform-Colliders"), LayerRole::Collision);
    assert_eq!(role("OneWay"), LayerRole::OneWay);
    assert_eq!(role("Coins"), LayerRole::Decoration);
    let why = &r
        .layers
        .iter()
        .find(|l| l.name == "Tile Layer 1")
        .unwrap()
        .why;
    assert!(why.contains("Platform-Colliders"), "{why}");
    // Overridden on the command line (names in any case): the unmarked tile layer is read
    // again, and the one-way layer left out (its rectangle would meet the tile layer's solids).
    let opts = ImportOptions {
        layer_roles: vec![
            ("tile layer 1".into(), LayerRole::Collision),
            ("oneway".into(), LayerRole::Decoration),
        ],
        ..open_edges()
    };
    let r = import_tiled_map_with(&shipped("object_collision.tmx"), &opts).unwrap();
    assert_eq!(
        (r.level.tile(0, 4), r.level.tile(3, 2)),
        (Tile::Solid, Tile::Solid)
    );
    // Without the second override the two layers meet in a cell: the solid tile is kept (it
    // stops from more sides) and a warning names both layers.
    let opts = ImportOptions {
        layer_roles: vec![("Tile Layer 1".into(), LayerRole::Collision)],
        ..ImportOptions::default()
    };
    let r = import_tiled_map_with(&shipped("object_collision.tmx"), &opts).unwrap();
    assert!(
        r.warnings.iter().any(|w| w
            .message
            .contains("one-way tiles meet layer \"Tile Layer 1\"'s solid tiles")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn tile_layers_are_picked_by_name_and_bool_properties_mark_tiles() {
    // tests/maps/named_tiles.tmx: "Ground" is read; "bg", "Water" and the unmarked
    // "Tile Layer 3" are not. Tiles marked collidable or isSolid are solid, oneway one-way, and
    // the unmarked tile 1 in a tileset that marks with bools is empty.
    let r = import_tiled_map_with(&shipped("named_tiles.tmx"), &open_edges()).unwrap();
    assert_eq!(grid(&r.level), "........\n....==.#\n.......#\n###..###\n");
    // The object named "Player" (no class) is the spawn; the enemy is warned about.
    assert_eq!(spawns_of(&r), [("Player", Vec2::new(1.5, 1.0))]);
    assert!(r.warnings.iter().any(|w| w.subject == "object 2 \"enemy\""));
    // With --tile-layers collision, the unmarked layer's tile appears at the top-left.
    let opts = ImportOptions {
        tile_layers: Some(LayerRole::Collision),
        ..ImportOptions::default()
    };
    let r = import_tiled_map_with(&shipped("named_tiles.tmx"), &opts).unwrap();
    assert_eq!(r.level.tile(0, 3), Tile::Solid);
}

#[test]
fn the_loader_is_tolerant_where_tiled_is() {
    // tests/maps/tolerant.tmx: tileset "old" has no tilecount (2 computed from its 32 x 16
    // image), "ground" is in the XML cell encoding, tolerant.tsj is a JSON tileset (tile 0
    // solid = true, tile 1 a ramp drawn in the collision editor), the 32 x 48 crate of an image
    // collection is one cell, "platforms" is offset by (16, -16) px: one tile right and one up.
    let r = import_tiled_map_with(&shipped("tolerant.tmx"), &open_edges()).unwrap();
    assert_eq!(grid(&r.level), "......\n.==...\n.....#\n###/##\n");
    // The tile object of class "spawn" at (32, 48) px, 16 wide: feet at (40, 48) px.
    assert_eq!(spawns_of(&r), [("spawn1", Vec2::new(2.5, 1.0))]);
    let text: Vec<String> = r.warnings.iter().map(|w| w.to_string()).collect();
    for what in [
        "no tilecount",
        "XML cell encoding",
        "JSON tileset",
        "offset by (16, -16)",
        "32 x 48",
    ] {
        assert!(text.iter().any(|w| w.contains(what)), "{what}: {text:#?}");
    }
}

#[test]
fn an_infinite_map_is_cropped_to_its_chunks() {
    // tests/maps/infinite.tmx: one 16 x 16 chunk at Tiled cell (-16, -16); the floor on its
    // bottom row, a post at each end of the row above; the spawn at (-200, -16) px.
    let r = import_tiled_map_with(&shipped("infinite.tmx"), &open_edges()).unwrap();
    assert_eq!((r.level.width, r.level.height), (16, 16));
    assert!((0..16).all(|i| r.level.tile(i, 0) == Tile::Solid));
    assert_eq!(r.level.tile(0, 1), Tile::Solid);
    assert_eq!(r.level.tile(15, 1), Tile::Solid);
    assert_eq!(r.level.tile(1, 1), Tile::Empty);
    assert_eq!(spawns_of(&r), [("start", Vec2::new(3.5, 1.0))]);
}

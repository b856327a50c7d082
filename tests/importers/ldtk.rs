//! LDtk projects (`.ldtk`, docs/formats.md): IntGrid collision by value names, a separate platforms
//! layer, external levels, a GridVania world as one level, a linear world's levels one at a time,
//! spawns by entity name and pivot, the overrides, and `platbench inspect`.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use std::path::{Path, PathBuf};

use glam::Vec2;
use platbench::level::import::ascii_map;
use platbench::level::ldtk::{import_ldtk_with, load_ldtk_with};
use platbench::level::{ImportOptions, Tile};

/// Options that wall the sides the map leaves open (LDtk's default leaves them open).
fn walled() -> ImportOptions {
    ImportOptions {
        edges: Some(platbench::level::Edges::Walls),
        ..ImportOptions::default()
    }
}

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/maps")
        .join(name)
}

#[test]
fn a_gridvania_world_is_one_level_in_world_coordinates() {
    // tests/maps/world.ldtk (LDtk 1.5.3): Level_0 at world x 0, Level_1 at 64 px (4 cells of
    // 16 px) in world/Level_1.ldtkl. Level_0's IntGrid: Wall (1) under it except a Water (3)
    // cell, Platform (2) cells one-way, a Ladder (4); Level_1: a floor of walls and, in the
    // separate IntGrid layer "Platforms", two one-way cells.
    let r = import_ldtk_with(&shipped("world.ldtk"), &walled()).unwrap();
    // The world's sides are open: a wall outside each (src/level/import/edges.rs), the map
    // one tile right.
    assert_eq!(
        ascii_map(&r.level).0,
        "#........#\n#.==H.==.#\n###.######\n"
    );
    // PlayerSpawn: pivot (0.5, 1) at (8, 32) px, 16 x 16: feet at (8, 32) px, (0.5, 1) tiles of
    // the map, (1.5, 1) of the level with its left wall.
    let spawns: Vec<(&str, Vec2)> = r
        .spawns
        .iter()
        .map(|s| (s.name.as_str(), s.position))
        .collect();
    assert_eq!(spawns, [("PlayerSpawn", Vec2::new(1.5, 1.0))]);
    let text: Vec<String> = r.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        text.iter().any(|w| w.contains("\"Water\": a hazard")),
        "{text:#?}"
    );
    // By default an LDtk project's sides stay open, as the LDtk games of the corpus leave
    // them (docs/maps.md): the same world with no walls.
    let r = import_ldtk_with(&shipped("world.ldtk"), &ImportOptions::default()).unwrap();
    assert_eq!(
        ascii_map(&r.level).0,
        "........
.==H.==.
##.#####
"
    );
    // One level picked with --level: Level_1 alone, 4 x 3, from its own corner.
    let opts = ImportOptions {
        level: Some("level_1".into()),
        ..walled()
    };
    let r = import_ldtk_with(&shipped("world.ldtk"), &opts).unwrap();
    assert_eq!(ascii_map(&r.level).0, "#....#\n#.==.#\n######\n");
    // No spawn entity there: the fallback spawn, said aloud.
    assert_eq!(r.spawns[0].name, "auto");
    assert!(r
        .warnings
        .iter()
        .any(|w| w.message.starts_with("no spawn point found")));
}

#[test]
fn a_linear_world_imports_one_level_and_the_mapping_is_overridable() {
    // tests/maps/linear_old.ldtk (LDtk 0.9.3, 8 px cells): level "Start" has Collider (1) and
    // spikes (2) on its bottom row; "Second" a floor of two cells.
    let (l, warnings) = load_ldtk_with(&shipped("linear_old.ldtk"), &walled()).unwrap();
    assert_eq!(ascii_map(&l).0, "#...#\n##.##\n");
    assert!(
        warnings.iter().any(|w| w.message.contains("--level")),
        "{warnings:?}"
    );
    // Start_Point: pivot (0, 0) at (16, 0) px, 8 x 8: feet at (20, 8) px = (2.5, 1) tiles of the
    // map, (3.5, 1) of the level with its left wall.
    assert_eq!(l.scenarios[0].name, "Start_Point-drop");
    assert_eq!(l.scenarios[0].spawn, Vec2::new(3.5, 1.0));
    let opts = ImportOptions {
        intgrid: vec![("spikes".into(), Tile::Solid)],
        ..walled()
    };
    let r = import_ldtk_with(&shipped("linear_old.ldtk"), &opts).unwrap();
    assert_eq!(ascii_map(&r.level).0, "#...#\n#####\n");
    let opts = ImportOptions {
        level: Some("Second".into()),
        ..walled()
    };
    let r = import_ldtk_with(&shipped("linear_old.ldtk"), &opts).unwrap();
    assert_eq!(ascii_map(&r.level).0, "#..#\n####\n");
    let opts = ImportOptions {
        level: Some("Third".into()),
        ..walled()
    };
    let e = import_ldtk_with(&shipped("linear_old.ldtk"), &opts)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--level Third") && e.contains("Start, Second"),
        "{e}"
    );
}

#[test]
fn broken_projects_are_errors_with_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.ldtk");
    std::fs::write(&p, "{\n  \"levels\": [ 1,\n").unwrap();
    let e = import_ldtk_with(&p, &walled()).unwrap_err().to_string();
    assert!(
        e.contains("bad.ldtk:2:") && e.contains("not an LDtk project"),
        "{e}"
    );
    // A world larger than the tile cap is refused before anything is allocated.
    std::fs::write(
        &p,
        r#"{"worldLayout":"Free","levels":[{"identifier":"a","worldX":0,"worldY":0,"pxWid":16,"pxHei":16,"layerInstances":[{"__identifier":"g","__type":"IntGrid","__cWid":1,"__cHei":1,"__gridSize":16,"intGridCsv":[1]}]},{"identifier":"b","worldX":1600000000,"worldY":1600000000,"pxWid":16,"pxHei":16,"layerInstances":[]}]}"#,
    )
    .unwrap();
    let e = import_ldtk_with(&p, &walled()).unwrap_err().to_string();
    // The tile cap, crate::limits::MAX_TILES.
    assert!(e.contains("expected 1 to 1000000 cells"), "{e}");
    // A level at worldX = i64::MAX: its right edge (worldX + pxWid + grid - 1) overflowed an
    // i64 (wrapping in release); now refused where it stands, past 10^15 pixels.
    std::fs::write(
        &p,
        "{\"worldLayout\":\"Free\",\"levels\":[\n{\"identifier\":\"a\",\"worldX\":0,\"worldY\":0,\"pxWid\":16,\"pxHei\":16,\"layerInstances\":[{\"__identifier\":\"g\",\"__type\":\"IntGrid\",\"__cWid\":1,\"__cHei\":1,\"__gridSize\":16,\"intGridCsv\":[1]}]},\n{\"identifier\":\"b\",\"worldX\":9223372036854775807,\"worldY\":0,\"pxWid\":16,\"pxHei\":16,\"layerInstances\":[]}]}",
    )
    .unwrap();
    let e = import_ldtk_with(&p, &walled()).unwrap_err().to_string();
    assert!(
        e.contains("bad.ldtk:3:") && e.contains("size of 9223372036854775807; expected"),
        "{e}"
    );
}

#[test]
fn inspect_prints_layers_spawns_and_the_grid() {
    let out = common::platbench()
        .arg("inspect")
        .arg(shipped("object_collision.tmx"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for what in [
        "\"Tile Layer 1\" (tiles): decoration",
        "\"OneWay\" (objects): one_way",
        // The map's sides are open: walls outside them, the map one tile right.
        "spawn5 at (2.5, 1)",
        "#...==....##\n#.........##\n############",
        "the map's left and right sides are open",
    ] {
        assert!(stdout.contains(what), "{what}:\n{stdout}");
    }
    let out = common::platbench()
        .args(["inspect", "--edges", "walls", "--level", "Level_1"])
        .arg(shipped("world.ldtk"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("#....#\n#.==.#\n######"), "{stdout}");
    // A run of an LDtk world on the sweep: the probes at its spawn.
    let dir = tempfile::tempdir().unwrap();
    let out = common::platbench()
        .args(["run", "--backend", "sweep", "--out"])
        .arg(dir.path().join("o"))
        .arg(shipped("world.ldtk"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir
        .path()
        .join("o/traces/world.PlayerSpawn-drop.sweep.csv")
        .exists());
}

#[test]
fn a_side_file_without_scenarios_runs_the_standard_probes_as_for_a_tiled_map() {
    // A copy of world.ldtk (and its external level) beside a side file with an [import] table
    // and no [[scenario]] (what `inspect` suggests writing): it says how to read the project,
    // and the standard probes run, the same as without the file.
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(shipped("world.ldtk"), dir.path().join("world.ldtk")).unwrap();
    std::fs::create_dir(dir.path().join("world")).unwrap();
    std::fs::copy(
        shipped("world/Level_1.ldtkl"),
        dir.path().join("world/Level_1.ldtkl"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("world.toml"),
        "[import]\nedges = \"walls\"\n",
    )
    .unwrap();
    let path = dir.path().join("world.ldtk");
    let (with_side, _) = load_ldtk_with(&path, &walled()).unwrap_or_else(|e| panic!("{}", e.error));
    std::fs::remove_file(dir.path().join("world.toml")).unwrap();
    let (without, _) = load_ldtk_with(&path, &walled()).unwrap_or_else(|e| panic!("{}", e.error));
    assert!(!without.scenarios.is_empty());
    let names = |l: &platbench::level::Level| {
        l.scenarios
            .iter()
            .map(|s| s.name.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(names(&with_side), names(&without));
}

#[test]
fn an_intgrid_layer_named_for_collision_leaves_the_unnamed_ones_out() {
    // Two IntGrid layers of one 2 x 1 level: "Collisions" (1, 0) and "Pipes" (0, 1), written
    // for this test: the game collides with the named one only.
    let layer = |name: &str, csv: &str| {
        format!(
            r#"{{"__identifier":"{name}","__type":"IntGrid","__cWid":2,"__cHei":1,"__gridSize":16,"intGridCsv":[{csv}]}}"#
        )
    };
    let text = format!(
        r#"{{"worldLayout":"Free","levels":[{{"identifier":"a","worldX":0,"worldY":0,"pxWid":32,"pxHei":16,"layerInstances":[{},{}]}}]}}"#,
        layer("Collisions", "1,0"),
        layer("Pipes", "0,1")
    );
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("two.ldtk");
    std::fs::write(&p, text).unwrap();
    let open = ImportOptions {
        edges: Some(platbench::level::Edges::Open),
        ..walled()
    };
    let r = import_ldtk_with(&p, &open).unwrap();
    let pipes = r.layers.iter().find(|l| l.name == "Pipes").unwrap();
    assert_eq!(
        pipes.role,
        platbench::level::LayerRole::Decoration,
        "{}",
        pipes.why
    );
    assert!(
        pipes.why.contains("\"Collisions\" is named for collision"),
        "{}",
        pipes.why
    );
    assert_eq!(
        (r.level.tile(0, 0), r.level.tile(1, 0)),
        (Tile::Solid, Tile::Empty)
    );
}

#[test]
fn one_level_of_a_spatial_world_stays_open_where_it_joins_a_neighbour() {
    // world.ldtk with the neighbours LDtk 1.x writes (`__neighbours`, dir "e"/"w"): Level_1 sits
    // right of Level_0. Picked alone, Level_1's left side is where the game goes on into
    // Level_0, so it gets no wall; its right side, with no neighbour, still does.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shipped("world.ldtk")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let levels = json["levels"].as_array_mut().unwrap();
    levels[0]["__neighbours"] = serde_json::json!([{ "levelIid": "b", "dir": "e" }]);
    levels[1]["__neighbours"] = serde_json::json!([{ "levelIid": "a", "dir": "w" }]);
    std::fs::write(dir.path().join("world.ldtk"), json.to_string()).unwrap();
    std::fs::create_dir(dir.path().join("world")).unwrap();
    std::fs::copy(
        shipped("world/Level_1.ldtkl"),
        dir.path().join("world/Level_1.ldtkl"),
    )
    .unwrap();
    let opts = ImportOptions {
        level: Some("level_1".into()),
        ..walled()
    };
    let r = import_ldtk_with(&dir.path().join("world.ldtk"), &opts).unwrap();
    // Level_1 is 4 x 3 with a floor of walls (the test above): a wall on the right only.
    assert_eq!(ascii_map(&r.level).0, "....#\n.==.#\n#####\n");
    assert!(
        r.warnings
            .iter()
            .any(|w| w.message.contains("left side joins another level")),
        "{:#?}",
        r.warnings
    );
    // The whole world, read together, is walled on both outer sides as before.
    let r = import_ldtk_with(&dir.path().join("world.ldtk"), &walled()).unwrap();
    assert_eq!(
        ascii_map(&r.level).0,
        "#........#\n#.==H.==.#\n###.######\n"
    );
}

#[test]
fn entities_named_for_collision_are_solid_boxes_and_the_intgrid_beside_them_art() {
    // A 4 x 2 level of 16 px cells: an IntGrid "TileLayer" paints the floor (drawn art in
    // games that collide with entity boxes), and the entity layer "PhysicsEntities" holds one
    // "SolidBlock" 32 x 16 px at (16, 16) (pivot 0, 0): the two middle cells of the bottom row.
    let dir = tempfile::tempdir().unwrap();
    let text = r#"{"worldLayout":"Free","levels":[{"identifier":"a","worldX":0,"worldY":0,"pxWid":64,"pxHei":32,"layerInstances":[
{"__identifier":"PhysicsEntities","__type":"Entities","__cWid":4,"__cHei":2,"__gridSize":16,"entityInstances":[{"__identifier":"SolidBlock","__pivot":[0,0],"px":[16,16],"width":32,"height":16}]},
{"__identifier":"TileLayer","__type":"IntGrid","__cWid":4,"__cHei":2,"__gridSize":16,"intGridCsv":[0,0,0,0,1,1,1,1]}]}]}"#;
    let p = dir.path().join("blocks.ldtk");
    std::fs::write(&p, text).unwrap();
    let open = ImportOptions {
        edges: Some(platbench::level::Edges::Open),
        ..walled()
    };
    let r = import_ldtk_with(&p, &open).unwrap();
    assert_eq!(ascii_map(&r.level).0, "....\n.##.\n");
    let role = |n: &str| r.layers.iter().find(|l| l.name == n).unwrap().clone();
    assert_eq!(
        role("PhysicsEntities").role,
        platbench::level::LayerRole::Collision
    );
    let tiles = role("TileLayer");
    assert_eq!(
        tiles.role,
        platbench::level::LayerRole::Decoration,
        "{}",
        tiles.why
    );
    assert!(tiles.why.contains("\"PhysicsEntities\""), "{}", tiles.why);
    // Named for collision by the user, the IntGrid layer collides too.
    let given = ImportOptions {
        layer_roles: vec![("TileLayer".into(), platbench::level::LayerRole::Collision)],
        ..open
    };
    let r = import_ldtk_with(&p, &given).unwrap();
    assert_eq!(ascii_map(&r.level).0, "....\n####\n");
}

#[test]
fn the_collision_layer_with_the_largest_painted_area_sets_the_grid_and_coarser_cells_are_split() {
    // A 96 x 32 px level whose three IntGrid layers are all named for collision:
    // "SpikeCollisions" of 8 px cells paints one cell (64 px²), "GroundCollisions" of 16 px
    // cells the whole bottom row (6 cells, 1536 px², the largest: the grid is 16 px),
    // "BlockCollisions" of 32 px cells its right-hand cell (1024 px², 2 x 2 of the grid's
    // cells). The 8 px layer, finer than the grid, is left out with a warning.
    let dir = tempfile::tempdir().unwrap();
    let spikes = format!("{}1{}", "0,".repeat(36), ",0".repeat(11));
    let text = format!(
        r#"{{"worldLayout":"Free","levels":[{{"identifier":"a","worldX":0,"worldY":0,"pxWid":96,"pxHei":32,"layerInstances":[
{{"__identifier":"SpikeCollisions","__type":"IntGrid","__cWid":12,"__cHei":4,"__gridSize":8,"intGridCsv":[{spikes}]}},
{{"__identifier":"GroundCollisions","__type":"IntGrid","__cWid":6,"__cHei":2,"__gridSize":16,"intGridCsv":[0,0,0,0,0,0,1,1,1,1,1,1]}},
{{"__identifier":"BlockCollisions","__type":"IntGrid","__cWid":3,"__cHei":1,"__gridSize":32,"intGridCsv":[0,0,1]}}]}}]}}"#
    );
    let p = dir.path().join("grids.ldtk");
    std::fs::write(&p, text).unwrap();
    let r = import_ldtk_with(&p, &ImportOptions::default()).unwrap();
    assert_eq!(ascii_map(&r.level).0, "....##\n######\n");
    let spikes = r
        .layers
        .iter()
        .find(|l| l.name == "SpikeCollisions")
        .unwrap();
    assert_eq!(spikes.role, platbench::level::LayerRole::Decoration);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.subject == "layer \"SpikeCollisions\""
                && w.message.contains("not a whole multiple")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn a_coarse_layer_s_far_cell_does_not_wrap_onto_the_level() {
    // A 4 x 2 px level of 1 px cells ("Base", the floor, given as collision) and a layer
    // "Walls" of 2^49 px cells whose one painted cell is column 32768: 2^64 cells of the grid
    // to the right, far outside the level. Multiplied in i64 the position wrapped to 0 and painted
    // the whole level solid.
    let dir = tempfile::tempdir().unwrap();
    let walls = format!("{}1", "0,".repeat(32768));
    let text = format!(
        r#"{{"worldLayout":"Free","levels":[{{"identifier":"a","worldX":0,"worldY":0,"pxWid":4,"pxHei":2,"layerInstances":[
{{"__identifier":"Base","__type":"IntGrid","__cWid":4,"__cHei":2,"__gridSize":1,"intGridCsv":[0,0,0,0,1,1,1,1]}},
{{"__identifier":"Walls","__type":"IntGrid","__cWid":32769,"__cHei":1,"__gridSize":562949953421312,"intGridCsv":[{walls}]}}]}}]}}"#
    );
    let p = dir.path().join("far.ldtk");
    std::fs::write(&p, text).unwrap();
    let opts = ImportOptions {
        layer_roles: vec![("Base".into(), platbench::level::LayerRole::Collision)],
        ..ImportOptions::default()
    };
    let r = import_ldtk_with(&p, &opts).unwrap_or_else(|e| panic!("{}", e.error));
    assert_eq!(ascii_map(&r.level).0, "....\n####\n");
}

#[test]
fn more_spawn_entities_than_the_limit_are_refused_naming_the_level_layer_and_entity() {
    // MAX_SPAWNS (src/limits.rs) is 1,000: 1,001 "Player" entities on the floor of a 4 x 2
    // level. The error named only the file before; it names the one past the limit.
    let dir = tempfile::tempdir().unwrap();
    let player =
        r#"{"__identifier":"Player","__pivot":[0.5,1],"px":[24,16],"width":16,"height":16}"#;
    let text = format!(
        r#"{{"worldLayout":"Free","levels":[{{"identifier":"a","worldX":0,"worldY":0,"pxWid":64,"pxHei":32,"layerInstances":[
{{"__identifier":"Entities","__type":"Entities","__cWid":4,"__cHei":2,"__gridSize":16,"entityInstances":[{}]}},
{{"__identifier":"Collision","__type":"IntGrid","__cWid":4,"__cHei":2,"__gridSize":16,"intGridCsv":[0,0,0,0,1,1,1,1]}}]}}]}}"#,
        vec![player; 1001].join(",")
    );
    let p = dir.path().join("crowd.ldtk");
    std::fs::write(&p, text).unwrap();
    let e = import_ldtk_with(&p, &walled()).unwrap_err().to_string();
    assert!(
        e.contains("level \"a\", layer \"Entities\": entity \"Player\" at px (24, 16) is spawn point 1001 of the project; expected at most 1000"),
        "{e}"
    );
}

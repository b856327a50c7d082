//! The map's sides (src/level/import/edges.rs): walls outside the sides a map leaves open, as
//! games stop their player at the world's bounds, so the `walk_left` probe meets a wall instead
//! of walking into the void; `--edges open` keeps the map as drawn.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use glam::Vec2;
use platbench::level::{load_tiled_map_with, Edges, ImportOptions, Tile};
use platbench::metrics::evaluate;

use super::common::platbench;
use super::tiled::MapText;

/// A floor of 6 tiles under 3 empty rows, a spawn at map cell (1, 2): written for this test.
fn open_sided() -> MapText<'static> {
    MapText {
        rows: &["0,0,0,0,0,0", "0,0,0,0,0,0", "0,0,0,0,0,0", "1,1,1,1,1,1"],
        objects: r#"<object id="1" name="spawn" x="24" y="48"><point/></object>"#,
        ..MapText::default()
    }
}

/// The `left_level` value of the scenario ending in `probe`, run on the sweep.
fn left_level(level: &platbench::level::Level, probe: &str) -> f64 {
    let spec = level
        .scenarios
        .iter()
        .find(|s| s.name.ends_with(probe))
        .unwrap();
    let e = evaluate(level, spec, &platbench::sweep::kind::run_default()).unwrap();
    e.metrics
        .iter()
        .find(|m| m.metric == "left_level")
        .map(|m| m.value)
        .unwrap()
}

#[test]
fn open_sides_get_walls_and_the_walk_left_probe_stays_in() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, open_sided().text()).unwrap();
    let (l, warnings) = load_tiled_map_with(&path, &ImportOptions::default()).unwrap();
    // One wall column each side, as tall as the map; the bottom stays open.
    assert_eq!((l.width, l.height), (8, 4));
    for j in 0..4 {
        assert_eq!((l.tile(0, j), l.tile(7, j)), (Tile::Solid, Tile::Solid));
    }
    assert_eq!(l.tile(1, 1), Tile::Empty);
    // The map moved one tile right: the spawn at map x 1.5 is at 2.5.
    assert_eq!(l.scenarios[0].spawn, Vec2::new(2.5, 1.0));
    assert!(
        warnings
            .iter()
            .any(|w| w.message.contains("left and right sides are open")),
        "{warnings:?}"
    );
    // walk_left runs into the wall (3 s at run speed is farther than the 2.5 tiles to the edge).
    assert_eq!(left_level(&l, "walk_left"), 0.0);
    // Left open, the map stays as drawn.
    let open = ImportOptions {
        edges: Some(Edges::Open),
        ..ImportOptions::default()
    };
    let (l, warnings) = load_tiled_map_with(&path, &open).unwrap();
    assert_eq!((l.width, l.scenarios[0].spawn), (6, Vec2::new(1.5, 1.0)));
    assert!(!warnings
        .iter()
        .any(|w| w.message.contains("sides are open")));
    // Left open, the walk left reaches the map's side 1.5 tiles away on flat ground: the map's
    // problem, said and not run (tests/importers/map_problems.rs).
    assert!(!l.scenarios.iter().any(|s| s.name.ends_with("walk_left")));
    assert!(
        warnings
            .iter()
            .any(|w| w.message.contains("walk_left is not run")
                && w.message.contains("open left side")),
        "{warnings:?}"
    );
}

#[test]
fn the_edges_option_is_checked_and_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, open_sided().text()).unwrap();
    let out = platbench()
        .args(["inspect", "--edges", "open"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("6 x 4 tiles"), "{text}");
    let out = platbench()
        .args(["inspect", "--edges", "sideways"])
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("--edges sideways: expected walls or open"),
        "{e}"
    );
}

#[test]
fn a_boundary_drawn_outside_the_map_is_said_and_the_side_walled() {
    // A collision rectangle one tile outside the map's left side, as tall as the map, beside a
    // floor of rectangles: written for this test.
    let text = r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="4" height="3" tilewidth="16" tileheight="16" infinite="0" nextlayerid="3" nextobjectid="4">
 <objectgroup id="1" name="collision">
  <object id="1" x="-16" y="0" width="16" height="48"/>
  <object id="2" x="0" y="32" width="64" height="16"/>
 </objectgroup>
 <objectgroup id="2" name="spawns"><object id="3" name="spawn" x="24" y="32"><point/></object></objectgroup>
</map>
"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.tmx");
    std::fs::write(&path, text).unwrap();
    let (l, warnings) = load_tiled_map_with(&path, &ImportOptions::default()).unwrap();
    // The 3 cells of the boundary are dropped, and said.
    assert!(
        warnings.iter().any(|w| w.subject == "layer \"collision\""
            && w.message.starts_with(
                "3 cell(s) of its collision rectangles and polylines lie outside the map"
            )),
        "{warnings:?}"
    );
    // The default walls stand for it: column 0 is solid from bottom to top.
    assert!((0..3).all(|j| l.tile(0, j) == Tile::Solid));
    // With --edges open the drawn boundary is kept all the same (the game has it), and the
    // right side, which the map leaves open, stays open.
    let open = ImportOptions {
        edges: Some(platbench::level::Edges::Open),
        ..ImportOptions::default()
    };
    let (l, warnings) = load_tiled_map_with(&path, &open).unwrap();
    assert!((0..3).all(|j| l.tile(0, j) == Tile::Solid));
    assert_eq!(l.width, 5);
    assert!((1..3).all(|j| l.tile(4, j) == Tile::Empty));
    assert!(
        warnings.iter().any(|w| w.subject == "map"
            && w.message
                .starts_with("the map draws collision just outside its left side")),
        "{warnings:?}"
    );
}

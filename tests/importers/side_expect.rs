//! A Tiled or LDtk map's side file carries `expect` tables like a level file: read into the
//! scenarios, checked on the trace, and refused at the side file's line and column when wrong.
// These tests read a map importer: they run with the default features.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::{Path, PathBuf};

use platbench::level::ldtk::load_ldtk_with;
use platbench::level::tiled::load_tiled_map;
use platbench::level::{ImportOptions, Level};
use platbench::metrics::evaluate;

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/maps")
        .join(name)
}

/// A side file of one scenario standing at `spawn` for 1 s (60 frames), with `expect` as its
/// `[scenario.expect]` table (its keys from line 6 on).
fn side(spawn: &str, expect: &str) -> String {
    format!(
        "[[scenario]]\nname = \"stand\"\nspawn = {spawn}\nduration = 1.0\n[scenario.expect]\n{expect}\n"
    )
}

/// A copy of the shipped Tiled map rules.tmx beside `side`, loaded.
fn tiled(dir: &Path, side_text: &str) -> Result<Level, String> {
    std::fs::copy(shipped("rules.tmx"), dir.join("rules.tmx")).unwrap();
    std::fs::write(dir.join("rules.toml"), side_text).unwrap();
    load_tiled_map(&dir.join("rules.tmx"))
        .map(|(l, _)| l)
        .map_err(|e| e.to_string())
}

/// A copy of the shipped LDtk project world.ldtk (and its external level) beside `side`, loaded.
fn ldtk(dir: &Path, side_text: &str) -> Result<Level, String> {
    std::fs::copy(shipped("world.ldtk"), dir.join("world.ldtk")).unwrap();
    std::fs::create_dir_all(dir.join("world")).unwrap();
    std::fs::copy(
        shipped("world/Level_1.ldtkl"),
        dir.join("world/Level_1.ldtkl"),
    )
    .unwrap();
    std::fs::write(dir.join("world.toml"), side_text).unwrap();
    load_ldtk_with(&dir.join("world.ldtk"), &ImportOptions::default())
        .map(|(l, _)| l)
        .map_err(|e| e.error.to_string())
}

#[test]
fn side_files_carry_expectations_to_the_metrics() {
    // rules.tmx's side file (tests/maps/rules.toml) stands its character on the solid tile at
    // (1.5, 1) (the map's first column, one tile right of the wall the import adds).
    let dir = tempfile::tempdir().unwrap();
    let stand = side("[1.5, 1.0]", "min_y = 2.0\ngrounded_at_end = true");
    let t = tiled(dir.path(), &stand).unwrap();
    assert_eq!(t.scenarios[0].expect.min_y, Some(2.0));
    // Standing at y = 1 all along: below min_y = 2 from frame 0, grounded at the end (60).
    let e = evaluate(&t, &t.scenarios[0], &platbench::sweep::kind::run_default()).unwrap();
    let at = |m: &str| {
        let r = e.metrics.iter().find(|r| r.metric == m).unwrap();
        (r.value, r.frame)
    };
    assert_eq!(at("expect_min_y"), (1.0, Some(0)));
    assert_eq!(at("expect_grounded_at_end"), (0.0, Some(60)));
    // An unknown key in the side file: refused at its line (7) and column (1).
    let bad = side("[1.5, 1.0]", "min_y = 2.0\nfloor = 1");
    let err = tiled(dir.path(), &bad).unwrap_err();
    assert!(
        err.contains("rules.toml:7:1: unknown field `floor`"),
        "{err}"
    );
}

#[test]
fn ldtk_side_files_take_the_same_expect_tables() {
    let dir = tempfile::tempdir().unwrap();
    // The first standard probe's spawn of this world, where the side file's scenario starts.
    let bare = {
        let d = tempfile::tempdir().unwrap();
        std::fs::copy(shipped("world.ldtk"), d.path().join("world.ldtk")).unwrap();
        std::fs::create_dir_all(d.path().join("world")).unwrap();
        std::fs::copy(
            shipped("world/Level_1.ldtkl"),
            d.path().join("world/Level_1.ldtkl"),
        )
        .unwrap();
        load_ldtk_with(&d.path().join("world.ldtk"), &ImportOptions::default())
            .unwrap_or_else(|e| panic!("{}", e.error))
            .0
    };
    let s = bare.scenarios[0].spawn;
    let spawn = format!("[{}, {}]", s.x, s.y);
    let l = ldtk(
        dir.path(),
        &side(&spawn, "reach = { y = [-1000, 1000], by_frame = 0 }"),
    )
    .unwrap();
    let e = evaluate(&l, &l.scenarios[0], &platbench::sweep::kind::run_default()).unwrap();
    let r = e
        .metrics
        .iter()
        .find(|r| r.metric == "expect_reach")
        .unwrap();
    // Frame 0 is the spawn, inside a region spanning every height: kept at frame 0.
    assert_eq!((r.value, r.frame), (0.0, Some(0)));
    // A reversed box: refused at the side file's line 6, column 15 (the `[`).
    let err = ldtk(dir.path(), &side(&spawn, "reach = { y = [3, 1] }")).unwrap_err();
    assert!(
        err.contains("world.toml:6:15: expect.reach y is [3, 1]"),
        "{err}"
    );
}

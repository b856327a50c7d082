//! Probes the map makes impossible (src/level/probes/map_problems.rs, src/level/import/spawns.rs):
//! a spawn deep inside a solid, a drop over a bottomless pit, a walk into one on flat ground are
//! said as the map's problem and not run; a spawn drawn a little into the floor is lifted onto it.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use platbench::level::{load_tiled_map_with, ImportOptions, Level, TiledWarning};

/// A loaded map: the level with its probes, and the import's warnings and notes.
type Loaded = (Level, Vec<TiledWarning>);

use super::common::platbench;
use super::tiled::MapText;

/// A floor with a two-tile pit (map columns 3 and 4) under three empty rows; written for this
/// test. The sides are walled (the default), so only the pit is bottomless.
const PIT: &[&str] = &[
    "0,0,0,0,0,0,0,0",
    "0,0,0,0,0,0,0,0",
    "0,0,0,0,0,0,0,0",
    "1,1,1,0,0,1,1,1",
];

fn import(rows: &'static [&'static str], objects: &str) -> Loaded {
    let dir = tempfile::tempdir().unwrap();
    let map = MapText {
        rows,
        objects,
        ..MapText::default()
    };
    load_tiled_map_with(&map.write(dir.path()), &ImportOptions::default())
        .map_err(|f| f.error)
        .unwrap()
}

fn names(i: &Loaded) -> Vec<&str> {
    i.0.scenarios.iter().map(|s| s.name.as_str()).collect()
}

fn said<'a>(i: &'a Loaded, what: &str) -> Vec<&'a str> {
    i.1.iter()
        .map(|w| w.message.as_str())
        .filter(|m| m.contains(what))
        .collect()
}

#[test]
fn a_walk_into_a_bottomless_pit_on_flat_ground_is_the_maps_problem() {
    // Feet at map (1.5, 1) tiles: 1.5 tiles from the pit's edge, well within the 9 tiles
    // every controller walks in the probe's 3 s (ProbeConfig::certain_reach).
    let i = import(
        PIT,
        r#"<object id="1" name="s" class="spawn" x="24" y="48"><point/></object>"#,
    );
    assert_eq!(names(&i), ["s-drop", "s-walk_left", "s-jump"]);
    let notes = said(&i, "s-walk_right is not run");
    assert_eq!(notes.len(), 1, "{:?}", i.1);
    // Level column 4 is map column 3: the left wall added by the default edges shifts the map.
    assert!(notes[0].starts_with("map problem:"), "{}", notes[0]);
    assert!(notes[0].contains("column 4"), "{}", notes[0]);
    assert!(
        notes[0].contains("nothing is under that column"),
        "{}",
        notes[0]
    );
}

#[test]
fn a_drop_over_a_bottomless_pit_runs_no_probe_from_that_spawn() {
    // Spawn `p` over the pit (map x 3.5); spawn `s` on the floor still runs its probes.
    let i = import(
        PIT,
        r#"<object id="1" name="s" class="spawn" x="104" y="48"><point/></object>
<object id="2" name="p" class="spawn" x="56" y="16"><point/></object>"#,
    );
    assert!(
        names(&i).iter().all(|n| n.starts_with("s-")),
        "{:?}",
        names(&i)
    );
    assert!(names(&i).contains(&"s-drop"));
    let notes = said(
        &i,
        "p-drop (and every other probe from this spawn) is not run",
    );
    assert_eq!(notes.len(), 1, "{:?}", i.1);
    assert!(notes[0].contains("falls out of the map"), "{}", notes[0]);
}

#[test]
fn a_spawn_a_little_in_the_floor_is_lifted_and_one_deep_inside_is_not_run() {
    let rows: &[&str] = &["0,0,0,0", "0,0,0,0", "1,1,1,1"];
    // Feet 3 px (0.19 tile) into the floor's top at y = 32 px: lifted onto it.
    let i = import(
        rows,
        r#"<object id="1" name="s" class="spawn" x="24" y="35"><point/></object>"#,
    );
    assert_eq!(i.0.scenarios[0].spawn.y, 1.0);
    assert_eq!(said(&i, "lifted onto its top").len(), 1, "{:?}", i.1);
    // Feet 8 px (half a tile) into the floor: deeper than the 0.25 tile a drawing can be off
    // (SINK_TOLERANCE); the spawn is the map's problem and the fallback spawn runs instead.
    let i = import(
        rows,
        r#"<object id="1" name="s" class="spawn" x="24" y="40"><point/></object>"#,
    );
    let notes = said(&i, "inside the solid tile");
    assert_eq!(notes.len(), 1, "{:?}", i.1);
    assert!(notes[0].starts_with("map problem:"), "{}", notes[0]);
    assert!(
        !names(&i).iter().any(|n| n.starts_with("s-")),
        "{:?}",
        names(&i)
    );
    assert!(!names(&i).is_empty());
}

#[test]
fn inspect_and_run_say_the_map_problem() {
    let dir = tempfile::tempdir().unwrap();
    let map = MapText {
        rows: PIT,
        objects: r#"<object id="1" name="s" class="spawn" x="24" y="48"><point/></object>"#,
        ..MapText::default()
    };
    let path = map.write(dir.path());
    let out = platbench().arg("inspect").arg(&path).output().unwrap();
    assert!(out.status.success(), "{out:?}");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        text.contains("map problem: probe s-walk_right is not run"),
        "{text}"
    );
    assert!(text.contains("  s: drop, walk_left, jump\n"), "{text}");
    // `run` says it on stderr, and runs the probes the map allows.
    let out = platbench()
        .arg("run")
        .arg(&path)
        .arg("--out")
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("spawn \"s\": map problem: probe s-walk_right is not run"),
        "{err}"
    );
    assert!(err.contains("3 scenarios"), "{err}");
}

#[test]
fn a_map_whose_every_probe_is_a_map_problem_says_how_to_give_it_one() {
    let dir = tempfile::tempdir().unwrap();
    // The only spawn hangs over the pit.
    let map = MapText {
        rows: PIT,
        objects: r#"<object id="1" name="p" class="spawn" x="56" y="16"><point/></object>"#,
        ..MapText::default()
    };
    let path = map.write(dir.path());
    let out = platbench()
        .current_dir(dir.path())
        .arg("run")
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("p-drop (and every other probe"), "{err}");
    assert!(err.contains("every probe is a map problem"), "{err}");
    assert!(err.contains("--spawn X,Y"), "{err}");
}

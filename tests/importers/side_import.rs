//! A map's side file says what the game means where no rule fits (docs/formats.md, "Side
//! file"): its `[import]` table names layer roles, IntGrid values and tile properties with
//! their kind, spawns and the map's sides; the command line's flags win over it; `inspect`
//! says which roles were guessed and the line that makes them certain.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::{Path, PathBuf};

use platbench::level::ldtk::import_ldtk_with;
use platbench::level::{import_tiled_map_with, ImportOptions, Tile};

use super::common::platbench;
use super::tiled::{row0, shipped, MapText};

/// A 3 x 2 map of 16 px tiles with two unmarked tile layers, "Tile Layer 1" (the floor) and
/// "Bushes Layer" (one tile in the middle of the top row, which an unmarked layer makes solid), written as
/// DIR/m.tmx with `side` as DIR/m.toml.
fn two_layers(dir: &Path, side: &str) -> PathBuf {
    let text = MapText::default()
        .text()
        .replace("name=\"collision\"", "name=\"Tile Layer 1\"")
        .replace(
            " <objectgroup id=\"2\" name=\"objects\">",
            " <layer id=\"3\" name=\"Bushes Layer\" width=\"3\" height=\"2\"><data encoding=\"csv\">\n0,1,0,\n0,0,0\n</data></layer>\n <objectgroup id=\"2\" name=\"objects\">",
        );
    std::fs::write(dir.join("m.tmx"), text).unwrap();
    if !side.is_empty() {
        std::fs::write(dir.join("m.toml"), side).unwrap();
    }
    dir.join("m.tmx")
}

#[test]
fn the_side_file_names_roles_and_sides_and_the_command_line_wins() {
    let dir = tempfile::tempdir().unwrap();
    // Without a side file, both unmarked tile layers are collision: the bush is solid, and the
    // open sides get walls.
    let map = two_layers(dir.path(), "");
    let r = import_tiled_map_with(&map, &ImportOptions::default()).unwrap();
    assert_eq!((r.level.width, r.level.tile(2, 1)), (5, Tile::Solid));
    // The side file says the bushes are decoration and the sides open.
    let side = "[import]\nlayers = { \"Bushes Layer\" = \"decoration\" }\nedges = \"open\"\n";
    let map = two_layers(dir.path(), side);
    let r = import_tiled_map_with(&map, &ImportOptions::default()).unwrap();
    assert_eq!((r.level.width, r.level.tile(1, 1)), (3, Tile::Empty));
    assert!(
        r.warnings.is_empty()
            || r.warnings
                .iter()
                .all(|w| !w.message.contains("no layer of that name"))
    );
    // A misspelt name matches no layer: said, with the map's layer names.
    let typo = "[import]\nlayers = { \"Bush Layer\" = \"decoration\" }\n";
    let m = two_layers(dir.path(), typo);
    let t = import_tiled_map_with(&m, &ImportOptions::default()).unwrap();
    assert!(
        t.warnings
            .iter()
            .any(|w| w.subject == "layer \"Bush Layer\""
                && w.message.contains("no layer of that name")
                && w.message.contains("Bushes Layer")),
        "{:?}",
        t.warnings
    );
    let map = two_layers(dir.path(), side);
    let r = import_tiled_map_with(&map, &ImportOptions::default()).unwrap();
    let bushes = r.layers.iter().find(|l| l.name == "Bushes Layer").unwrap();
    assert!(
        bushes.why.starts_with("given:") && !bushes.is_guess(),
        "{bushes:?}"
    );
    // The command line wins: --edges walls.
    let out = platbench()
        .args(["inspect", "--edges", "walls"])
        .arg(&map)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("5 x 2 tiles"), "{text}");
    // inspect lists the guessed layer (the floor, by default) with the line to make it certain,
    // and not the given one.
    assert!(
        text.contains("guessed: 2 layer(s)")
            && text.contains(
                "layers = { \"Tile Layer 1\" = \"collision\", \"objects\" = \"objects\" }"
            ),
        "{text}"
    );
}

#[test]
fn values_and_properties_get_their_kind_from_the_side_file() {
    let dir = tempfile::tempdir().unwrap();
    // LDtk: linear_old.ldtk's spikes value (2) is a hazard, not solid, by its name; the side
    // file makes it solid.
    let ldtk = dir.path().join("old.ldtk");
    std::fs::copy(shipped("linear_old.ldtk"), &ldtk).unwrap();
    std::fs::write(
        dir.path().join("old.toml"),
        "[import]\nintgrid = { spikes = \"solid\" }\nedges = \"open\"\n",
    )
    .unwrap();
    let r = import_ldtk_with(&ldtk, &ImportOptions::default()).unwrap();
    assert_eq!(
        platbench::level::import::ascii_map(&r.level).0,
        "...\n###\n"
    );
    // Tiled: a tile with the int property damage = 3 (not a mark platbench knows) is solid by
    // default; the side file's tile_properties make it empty.
    let tiles = r#"<tile id="0"><properties><property name="damage" type="int" value="3"/></properties></tile>"#;
    let map = MapText {
        tiles,
        rows: &["0,0,0", "2,1,2"],
        ..MapText::default()
    }
    .write(dir.path());
    let side = "[import]\ntile_properties = { damage = \"empty\" }\nedges = \"open\"\n";
    std::fs::write(map.with_extension("toml"), side).unwrap();
    let r = import_tiled_map_with(&map, &ImportOptions::default()).unwrap();
    assert_eq!(row0(&r.level), [Tile::Solid, Tile::Empty, Tile::Solid]);
}

#[test]
fn a_wrong_side_file_is_located() {
    let dir = tempfile::tempdir().unwrap();
    let map = two_layers(
        dir.path(),
        "[import]\nlayers = { \"Bushes Layer\" = \"shrubbery\" }\n",
    );
    let out = platbench().arg("run").arg(&map).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("m.toml:2:29") && e.contains("\"shrubbery\" is no role"),
        "{e}"
    );
}

#[test]
fn the_side_file_inspect_suggests_changes_nothing_and_the_probes_still_run() {
    // tests/maps/object_collision.tmx guesses its layers (a spawn layer among them); the block
    // `inspect` prints, written beside a copy of the map as the side file, makes the guesses
    // certain: the same layers, the same spawn, the same probe scenarios.
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.tmx");
    std::fs::copy(shipped("object_collision.tmx"), &map).unwrap();
    let inspect = |path: &Path| {
        let out = platbench().arg("inspect").arg(path).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let before = inspect(&map);
    let block: String = before
        .lines()
        .skip_while(|l| l.trim() != "[import]")
        .take_while(|l| !l.trim().is_empty())
        .map(|l| format!("{}\n", l.trim()))
        .collect();
    assert!(block.contains("layers = {"), "{before}");
    std::fs::write(dir.path().join("m.toml"), &block).unwrap();
    let after = inspect(&map);
    let section = |text: &str, head: &str| -> String {
        text.lines()
            .skip_while(|l| !l.starts_with(head))
            .take_while(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(section(&after, "spawns"), section(&before, "spawns"));
    assert_eq!(section(&after, "probes"), section(&before, "probes"));
    let run = platbench().arg("run").arg(&map).output().unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

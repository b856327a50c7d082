//! Issue 40, LDtk: values LDtk never writes, once read as something else with exit 0 or told
//! without the level: an entity's `px` of one or three numbers (the first two read), a place of
//! 1e39 pixels (warned as `(inf, -inf)`), a negative IntGrid value or one its layer does not
//! define, a `layerDefUid` naming no definition (the level read differently), a negative level
//! size (said as "0 x 3 cells"), a huge second level (said as "the world"), an external level
//! that is the project itself (said as "no IntGrid layer"), and an `--intgrid` value the project
//! never defines. Each project here is written for these tests.

#![cfg(feature = "ldtk")]

use std::path::Path;

use crate::common::platbench;

use super::hostile::assert_error;

/// A one-level project, 4 x 3 cells of 16 pixels, with placeholders: `PX` the spawn's `px`,
/// `CSV` the IntGrid cells, `UID` the IntGrid layer's `layerDefUid` (its definition's is 1),
/// `PXWID` the level's width, `EXT` the level's `externalRelPath`.
const PROJECT: &str = r#"{
"defs": {"layers": [
{"identifier": "Collisions", "type": "IntGrid", "uid": 1, "gridSize": 16,
"intGridValues": [{"value": 1, "identifier": "Wall"}, {"value": 2, "identifier": "Platform"}]}]},
"levels": [{"identifier": "Only", "worldX": 0, "worldY": 0,
"pxWid": PXWID, "pxHei": 48, "externalRelPath": EXT,
"layerInstances": [
{"__identifier": "Entities", "__type": "Entities", "__cWid": 4, "__cHei": 3, "__gridSize": 16,
"entityInstances": [{"__identifier": "PlayerSpawn", "__pivot": [0.5, 1],
"px": PX, "width": 16, "height": 16}]},
{"__identifier": "Collisions", "__type": "IntGrid", "__cWid": 4, "__cHei": 3, "__gridSize": 16,
"layerDefUid": UID,
"intGridCsv": CSV}
]}]}
"#;

fn project(subs: &[(&str, &str)]) -> String {
    let mut text = PROJECT.to_string();
    for (k, v) in [
        ("PXWID", "64"),
        ("EXT", "null"),
        ("PX", "[24, 32]"),
        ("UID", "1"),
        ("CSV", "[0,0,0,0, 0,0,0,0, 1,1,1,1]"),
    ] {
        let v = subs.iter().find(|s| s.0 == k).map_or(v, |s| s.1);
        text = text.replace(k, v);
    }
    text
}

fn inspect(path: &Path, extra: &[&str]) -> std::process::Output {
    platbench()
        .arg("inspect")
        .args(extra)
        .arg(path)
        .output()
        .unwrap()
}

#[test]
fn values_ldtk_never_writes_are_refused_naming_the_level_layer_or_place() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = d.join("p.ldtk");
    std::fs::write(&p, project(&[])).unwrap();
    let out = inspect(&p, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // (placeholder, value, the error after the file's name). Lines: PXWID 6, PX 10, CSV 13;
    // serde_json places a value's error at its last character.
    #[rustfmt::skip]
    let cases = [
        ("PX", "[24]", ":10:10: an entity's px holds 1 number; expected exactly 2 (x, y), as LDtk writes it"),
        ("PX", "[24, 32, 5]", ":10:17: an entity's px holds 3 numbers; expected exactly 2 (x, y)"),
        // 1e39 is past f32, as every place is read; the limit: json.rs MAX_PIXELS (10^15).
        ("PX", "[1e39, 32]", ":10:16: an entity place of 1e39 pixels; expected -10^15 to 10^15 pixels"),
        ("PXWID", "-64", ":6:12: a level size of -64 pixels; expected 0 to 10^15 pixels, as LDtk writes it"),
        ("CSV", "[0,0,0,0, 0,0,0,0, 1,-5,1,1]", ":13:43: intGridCsv's cell 9 holds -5; expected 0 (empty)"),
        ("CSV", "[0,0,0,0, 0,0,0,0, 1,1,7,1]", ": layer \"Collisions\": cell x = 2, y = 2 holds IntGrid value 7, which the layer's definition does not list; expected 0 (empty) or one of 1 \"Wall\", 2 \"Platform\""),
        ("UID", "9999", ": layer \"Collisions\": its layerDefUid 9999 names no layer definition; expected the uid of one of the project's (defs.layers: 1)"),
        // 1,000,064 pixels of 16 across, 3 high: 62,504 x 3 = 187,512 cells fits; 64,000,000
        // does not (src/limits.rs MAX_TILES, 1,000,000 cells).
        ("PXWID", "64000000", ": level \"Only\" is 4000000 x 3 cells of 16 pixels (pxWid 64000000, pxHei 48); expected at most 1000000 cells"),
        ("EXT", "\"p.ldtk\"", ": level \"Only\": externalRelPath \"p.ldtk\" is the project itself; expected the level's own file (.ldtkl)"),
    ];
    for (key, value, want) in cases {
        let mut text = project(&[(key, value)]);
        if key == "EXT" {
            // An external level has no layers in the project.
            let at = text.find("\"layerInstances\"").unwrap();
            let end = text.rfind("]}]}").unwrap();
            text = format!(
                "{}\"layerInstances\": null{}",
                &text[..at],
                &text[end + 1..]
            );
        }
        std::fs::write(&p, &text).unwrap();
        assert_error(&inspect(&p, &[]), &format!("{}{want}", p.display()));
    }
}

#[test]
fn an_intgrid_option_the_project_never_defines_is_warned_of() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.ldtk");
    std::fs::write(&p, project(&[])).unwrap();
    // Once accepted without a word: value 99999999999 and the name "Lava" are in no
    // definition; value 2 and the name "wall" are (a name matches as --layer's do).
    let out = inspect(
        &p,
        &[
            "--intgrid",
            "99999999999=solid",
            "--intgrid",
            "Lava=empty",
            "--intgrid",
            "2=solid",
            "--intgrid",
            "wall=one_way",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    // `inspect` lists the import's warnings with its report.
    let err = String::from_utf8_lossy(&out.stdout);
    for key in ["99999999999", "Lava"] {
        let want = format!("  project: --intgrid {key}: no IntGrid value of the project is {key} or named so; it changes nothing (the values: 1 \"Wall\", 2 \"Platform\")");
        assert!(err.contains(&want), "{want:?} in: {err}");
    }
    assert_eq!(err.matches("--intgrid").count(), 2, "{err}");
}

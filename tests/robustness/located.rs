//! Issue 40's unclear errors, part four: `inspect` given a file that is no map (once "Document
//! ended before root element <map> was found"), and input that is not UTF-8 (once "invalid
//! utf-8 sequence of 1 bytes from index N", a byte index) in every input format: each now exits
//! 2 naming the file, the line and column, what was found and what was expected. Every file
//! here is written for these tests.

#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::Path;

use crate::common::platbench;

use super::hostile::assert_error;

/// A 3 x 2 TMX map whose bottom row is solid, using tileset `t.tsx`.
const TMX: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"3\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" nextlayerid=\"2\" nextobjectid=\"1\">\n <tileset firstgid=\"1\" source=\"t.tsx\"/>\n <layer id=\"1\" name=\"floor\" width=\"3\" height=\"2\">\n  <data encoding=\"csv\">\n0,0,0,\n1,1,1\n</data>\n </layer>\n</map>\n";

/// `platbench COMMAND FILE` (with an output folder in `dir` for `run`).
fn on(command: &str, file: &Path, dir: &Path) -> std::process::Output {
    let mut cmd = platbench();
    cmd.arg(command).arg(file);
    if command == "run" {
        cmd.args(["--backend", "sweep", "--out"])
            .arg(dir.join("out"));
    }
    cmd.output().unwrap()
}

#[test]
fn inspect_given_a_level_or_other_text_says_what_it_reads() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A platbench level, whatever its name: the content decides, as for every command.
    for name in ["level.toml", "level.txt", "level.tmx"] {
        let p = d.join(name);
        std::fs::write(&p, "\n  name = \"a\"\nmap = \"\"\"\n#\n\"\"\"\n").unwrap();
        let out = on("inspect", &p, d);
        // The first thing in the file, on line 2 at column 3.
        assert_error(
            &out,
            &format!(
                "{}:2:3: found \"name = \\\"a\\\"\", which is no map",
                p.display()
            ),
        );
        assert_error(&out, "platbench inspect expects a Tiled map (.tmx, .tmj or .json) or an LDtk project (.ldtk)");
    }
}

#[test]
fn text_that_is_not_utf8_is_named_by_line_and_column_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let write = |name: &str, bytes: &[u8]| {
        let p = d.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    let not_utf8 = "found byte(s) 0xFF, not UTF-8; expected UTF-8 text";
    // Line 2, after `name = "é` (the 'é' two bytes, one column): column 10.
    let level = write("level8.toml", b"# a level\nname = \"\xc3\xa9\xff\"\n");
    assert_error(
        &on("run", &level, d),
        &format!("{}:2:10: {not_utf8}", level.display()),
    );
    // A Tiled map, TMX or JSON: line 2, column 12 (after `<map name="`, `"name": "ab`).
    for (name, text) in [
        (
            "bad.tmx",
            &b"<?xml version=\"1.0\"?>\n<map name=\"\xff\">\n"[..],
        ),
        (
            "bad.tmj",
            &b"{\"type\": \"map\",\n\"name\": \"ab\xff\"}\n"[..],
        ),
    ] {
        let map = write(name, text);
        for command in ["inspect", "run"] {
            assert_error(
                &on(command, &map, d),
                &format!(
                    "{}:2:12: cannot load the Tiled map: {not_utf8}",
                    map.display()
                ),
            );
        }
    }
    // An LDtk project: line 2, column 9 (after `"name": `).
    let ldtk = write(
        "bad.ldtk",
        b"{\"__header__\": {}, \"jsonVersion\": \"1.5.3\",\n\"name\": \xff}\n",
    );
    assert_error(
        &on("inspect", &ldtk, d),
        &format!("{}:2:9: {not_utf8}", ldtk.display()),
    );
    // A map's side file: line 2, column 11 (after `edges = "o`).
    let side_map = write("side.tmx", TMX.as_bytes());
    write("side.toml", b"[import]\nedges = \"o\xffpen\"\n");
    assert_error(
        &on("run", &side_map, d),
        &format!("{}:2:11: {not_utf8}", d.join("side.toml").display()),
    );
    // A tileset the map uses: line 2, column 32 (after `<tileset version="1.10" name="t`).
    let map = write("uses.tmx", TMX.as_bytes());
    write(
        "t.tsx",
        b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<tileset version=\"1.10\" name=\"t\xff\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\">\n</tileset>\n",
    );
    assert_error(
        &on("inspect", &map, d),
        &format!("t.tsx: cannot load the Tiled map: line 2, column 32: {not_utf8}"),
    );
}

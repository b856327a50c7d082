//! Hostile input, part three (issue 40): nothing crashes and nothing hangs. One small file
//! written for each class: a TOML map whose positions once panicked.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::platbench;

use super::hostile::assert_error;

// ---- a panic: positions in an escaped map string ------------------------------------------

#[test]
fn a_map_written_with_escapes_is_read_and_its_errors_are_located() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("escaped.toml");
    // A basic string with `\n` escapes and a non-ASCII row: the end of row 2, computed in the
    // unescaped value and added to the string's start, fell inside the 'é' of the text.
    std::fs::write(&level, "name = \"e\"\nmap = \"\\n\u{e9}\u{e9}\"\n").unwrap();
    let out = platbench()
        .arg("run")
        .arg(&level)
        .arg("--out")
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    // Guards the panic (exit 101): a clean error at the closing quote of line 2, in the file.
    assert_error(&out, "escaped.toml:2:12: map row 2 has 2 tiles, expected 0");
    // Guards the other half of the fix: a well-formed escaped map runs like a multi-line one.
    std::fs::write(
        &level,
        "name = \"e\"\nmap = \"....\\n####\\n\"\n[[scenario]]\nname = \"s\"\nspawn = [1.5, 1.0]\nduration = 0.5\n",
    )
    .unwrap();
    let out = platbench()
        .arg("run")
        .arg(&level)
        .args(["--backend", "sweep", "--out"])
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    common::assert_success(&out);
}

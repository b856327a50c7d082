//! Issue 40's unclear errors, part five: a cause said twice (an I/O error quoted in the message
//! and chained again), raw TOML parser words (`duplicate key` without the key, a NUL reported
//! as the token the parser wanted), an LDtk limit called "not an LDtk project" with its place
//! given twice, an empty or `null` project at column 0, a side file's bad bytes blamed on the
//! project, and 1,001 spawns of a side file blamed on the map. Each now exits 2 naming the
//! file, the line and column, what was found and what was expected, once. Every file here is
//! written for these tests.

#![cfg(all(feature = "tiled", feature = "ldtk"))]

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::platbench;

use super::hostile::{assert_error, stderr};

fn cmd(args: &[&std::ffi::OsStr]) -> Output {
    platbench().args(args).output().unwrap()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Fails unless the error names `file` and says `cause` exactly once.
fn assert_once(out: &Output, file: &Path, cause: &str) {
    assert_error(out, &file.display().to_string());
    let err = stderr(out);
    assert_eq!(err.matches(cause).count(), 1, "{cause:?} once in: {err}");
}

#[test]
fn a_file_that_cannot_be_read_is_named_with_its_cause_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let missing = d.join("missing.toml");
    let out_dir = d.join("out");
    let missing_dir = d.join("nowhere");
    let enoent = "No such file or directory";
    let runs: [Vec<&std::ffi::OsStr>; 5] = [
        vec!["run".as_ref(), missing.as_os_str()],
        vec!["inspect".as_ref(), missing.as_os_str()],
        vec![
            "report".as_ref(),
            "--tradeoff".as_ref(),
            missing.as_os_str(),
            "--out".as_ref(),
            out_dir.as_os_str(),
        ],
        vec![
            "diff".as_ref(),
            missing_dir.as_os_str(),
            missing_dir.as_os_str(),
        ],
        vec![
            "check".as_ref(),
            "--baseline".as_ref(),
            missing_dir.as_os_str(),
        ],
    ];
    for args in &runs {
        let out = cmd(args);
        let named = if args[0] == "diff" || args[0] == "check" {
            &missing_dir
        } else {
            &missing
        };
        assert_once(&out, named, enoent);
    }
    // A directory where a file is expected: said once, with what was expected.
    for command in ["run", "inspect"] {
        let out = cmd(&[command.as_ref(), d.as_os_str()]);
        assert_once(&out, d, "it is a directory; expected a regular file");
    }
    // An unreadable file (permission denied). Root reads it anyway, so as root (CI) platbench
    // runs as user 65534 (`setpriv`, util-linux), from a copy in a folder that user may enter.
    use std::os::unix::fs::PermissionsExt;
    let open = std::fs::Permissions::from_mode(0o755);
    std::fs::set_permissions(d, open).unwrap();
    let locked = write(d, "locked.toml", b"name = \"a\"\n");
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o000)).unwrap();
    let root = std::fs::read(&locked).is_ok();
    let bin = d.join("platbench");
    if root {
        std::fs::copy(env!("CARGO_BIN_EXE_platbench"), &bin).unwrap();
    }
    for command in ["run", "inspect"] {
        let mut c = if root {
            let mut c = std::process::Command::new("setpriv");
            c.args(["--reuid=65534", "--regid=65534", "--clear-groups"])
                .arg(&bin);
            c
        } else {
            platbench()
        };
        let out = c.arg(command).arg(&locked).output().unwrap();
        assert_once(&out, &locked, "Permission denied");
    }
}

#[test]
fn toml_errors_name_the_key_and_the_character_found() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let level = "name = \"ok\"\nmap = \"\"\"\n..\n##\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [0.5, 1.0]\nduration = 1.0\nduration = 2.0\n";
    let dup = write(d, "dup.toml", level.as_bytes());
    // `duration` is set on line 9 and again on line 10, column 1.
    assert_error(
        &cmd(&["run".as_ref(), dup.as_os_str()]),
        &format!(
            "{}:10:1: duplicate key `duration`, first set at line 9; expected each key once in a table",
            dup.display()
        ),
    );
    // A NUL on line 3, column 3 of a multi-line string.
    let nul = write(
        d,
        "nul.toml",
        b"name = \"ok\"\nmap = \"\"\"\n..\0.\n##\n\"\"\"\n",
    );
    let out = cmd(&["run".as_ref(), nul.as_os_str()]);
    assert_error(
        &out,
        &format!("{}:3:3: found the control character U+0000", nul.display()),
    );
    assert!(stderr(&out).contains("expected text"), "{}", stderr(&out));
    // Issue 40: a file cut inside its map's `"""` said only "invalid multi-line basic
    // string, expected `\"`" at the file's end; now at the quotes that open it, line 2, col 7.
    let cut = write(d, "cut.toml", b"name = \"ok\"\nmap = \"\"\"\n..\n#");
    assert_error(
        &cmd(&["run".as_ref(), cut.as_os_str()]),
        &format!("{}:2:7: the multi-line string opened here (\"\"\") is never closed: the file ends inside it", cut.display()),
    );
}

#[test]
fn ldtk_errors_say_what_is_wrong_once_at_one_place() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A layer one cell wider than src/limits.rs MAX_TILES (1,000,000): over a limit, not "not an
    // LDtk project", its place said once (line 1, just after the number).
    let text = r#"{"levels":[{"identifier":"a","worldX":0,"worldY":0,"pxWid":16,"pxHei":16,"layerInstances":[{"__identifier":"g","__type":"IntGrid","__cWid":1000001,"__cHei":1,"__gridSize":16,"intGridCsv":[1]}]}]}"#;
    let column = text.find("1000001").unwrap() + "1000001".len();
    let wide = write(d, "wide.ldtk", text.as_bytes());
    let out = cmd(&["inspect".as_ref(), wide.as_os_str()]);
    assert_error(
        &out,
        &format!(
            "{}:1:{column}: a layer of 1000001 cells across; expected 0 to 1000000",
            wide.display()
        ),
    );
    let err = stderr(&out);
    assert!(
        !err.contains("not an LDtk project") && !err.contains(" at line "),
        "{err}"
    );
    // An empty file, and one whose top level is null.
    let empty = write(d, "empty.ldtk", b"");
    assert_error(
        &cmd(&["inspect".as_ref(), empty.as_os_str()]),
        &format!(
            "{}:1:1: found an empty file; expected an LDtk project (a JSON object",
            empty.display()
        ),
    );
    let null = write(d, "null.ldtk", b"\n null\n");
    assert_error(
        &cmd(&["run".as_ref(), null.as_os_str()]),
        &format!(
            "{}:2:2: found \"null\" at the top level; expected an LDtk project (a JSON object",
            null.display()
        ),
    );
    // A project's side file that is not UTF-8: the side file at its line and column (line 2,
    // column 11, after `edges = "o`), not "cannot read the LDtk file".
    let maps = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps");
    let project = d.join("world.ldtk");
    std::fs::copy(maps.join("world.ldtk"), &project).unwrap();
    let side = write(d, "world.toml", b"[import]\nedges = \"o\xffpen\"\n");
    let out = cmd(&["inspect".as_ref(), project.as_os_str()]);
    assert_error(
        &out,
        &format!(
            "{}:2:11: found byte(s) 0xFF, not UTF-8; expected UTF-8 text",
            side.display()
        ),
    );
    assert!(!stderr(&out).contains("LDtk file"), "{}", stderr(&out));
}

#[test]
fn a_side_file_with_too_many_spawns_is_named_at_the_one_too_many() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let maps = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps");
    let map = d.join("showcase.tmx");
    std::fs::copy(maps.join("showcase.tmx"), &map).unwrap();
    std::fs::copy(maps.join("terrain.tsx"), d.join("terrain.tsx")).unwrap();
    // One spawn a line from line 3: spawn 1,001 (one past src/limits.rs MAX_SPAWNS) is on line
    // 1,003, at column 3.
    let spawns: String = (0..1001).map(|_| "  [3.5, 2.0],\n").collect();
    let side = write(
        d,
        "showcase.toml",
        format!("[import]\nspawns = [\n{spawns}]\n").as_bytes(),
    );
    for command in ["inspect", "run"] {
        assert_error(
            &cmd(&[command.as_ref(), map.as_os_str()]),
            &format!(
                "{}:1003:3: spawns: this is spawn point 1001 of the side file; expected at most 1000",
                side.display()
            ),
        );
    }
}

#[test]
fn a_long_name_is_refused_and_quoted_short() {
    // Issue 40: a 20 MB level name was copied into every run (3.7 GB, then an abort) and a
    // 300-byte scenario name failed only when its trace file was written. Names are at most
    // 64 bytes (limits::MAX_NAME_BYTES); the error quotes 40 characters of a long one.
    let dir = tempfile::tempdir().unwrap();
    let long = "n".repeat(100_000);
    let level = format!("name = \"{long}\"\nmap = \"\"\"\n......\n######\n\"\"\"\n");
    let p = write(dir.path(), "long.toml", level.as_bytes());
    let out = cmd(&["run".as_ref(), p.as_os_str()]);
    assert_error(&out, "long.toml:");
    let err = stderr(&out);
    assert!(
        err.contains("(100000 bytes) must be 1 to 64 ASCII letters") && err.len() < 1_000,
        "{err}"
    );
    let scenario = format!(
        "name = \"e\"\nmap = \"\"\"\n......\n######\n\"\"\"\n\n[[scenario]]\nname = \"{}\"\nspawn = [1.5, 1.0]\nduration = 1.0\n",
        "w".repeat(300)
    );
    let p = write(dir.path(), "scen.toml", scenario.as_bytes());
    let out = cmd(&["run".as_ref(), p.as_os_str()]);
    // Line 8, column 8: the scenario's name value.
    assert_error(&out, "scen.toml:8:8: scenario name");
    assert!(stderr(&out).contains("(300 bytes)"), "{}", stderr(&out));
}

#[test]
fn a_number_array_of_the_wrong_length_is_refused_at_its_value() {
    // Issue 40: `spawn = [1.5, 1.0, 2.0]` ran with the third number dropped (serde reads the
    // first two of a longer array); a platform's five-number rect likewise.
    let dir = tempfile::tempdir().unwrap();
    let level = |scenario_line: &str, platform: &str| {
        format!("name = \"e\"\nmap = \"\"\"\n......\n######\n\"\"\"\n{platform}\n[[scenario]]\nname = \"w\"\n{scenario_line}\nduration = 1.0\n")
    };
    for (name, text, at, found) in [
        (
            "spawn3.toml",
            level("spawn = [1.5, 1.0, 2.0]", ""),
            "spawn3.toml:9:9: ",
            "3 numbers; expected exactly 2",
        ),
        (
            "spawn1.toml",
            level("spawn = [1.5]", ""),
            "spawn1.toml:9:9: ",
            "1 number; expected exactly 2",
        ),
        (
            "rect5.toml",
            level(
                "spawn = [1.5, 1.0]",
                "[[platform]]\nrect = [0, 0, 1, 1, 9]\n",
            ),
            "rect5.toml:7:8: ",
            "5 numbers; expected exactly 4",
        ),
    ] {
        let p = write(dir.path(), name, text.as_bytes());
        let out = cmd(&[
            "run".as_ref(),
            "--backend".as_ref(),
            "sweep".as_ref(),
            p.as_os_str(),
        ]);
        assert_error(&out, at);
        assert!(stderr(&out).contains(found), "{name}: {}", stderr(&out));
    }
}

#[test]
fn a_json_map_or_project_with_a_byte_order_mark_is_told_so() {
    // Issue 40: serde_json said "expected value" at 1:1 and nothing of the BOM.
    let dir = tempfile::tempdir().unwrap();
    for name in ["m.tmj", "p.ldtk"] {
        let p = write(dir.path(), name, "\u{feff}{\"type\": \"map\"}".as_bytes());
        let out = cmd(&["inspect".as_ref(), p.as_os_str()]);
        assert_error(
            &out,
            &format!("{name}:1:1: found a byte order mark (U+FEFF) before the JSON"),
        );
    }
}

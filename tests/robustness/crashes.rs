//! Hostile input, part three (issue 40): nothing crashes and nothing hangs. One small file
//! written for each class: a TOML map whose positions once panicked, Tiled templates, tilesets
//! and groups that recursed until the stack overflowed, tile data the `tiled` crate refused with
//! no layer or line, and inputs that are not regular files.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::platbench;

use super::hostile::{assert_error, output_within, stderr};

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

// ---- recursion in a TOML level: keys of many parts, values nested deep ------------------

#[test]
fn a_toml_key_or_value_nested_past_the_limit_is_refused_where_it_passes() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("deep.toml");
    let run = |text: &str| {
        std::fs::write(&level, text).unwrap();
        platbench()
            .arg("run")
            .arg(&level)
            .arg("--out")
            .arg(dir.path().join("o"))
            .output()
            .unwrap()
    };
    // MAX_TOML_DEPTH (src/limits.rs) is 32. A key of 100 parts got the `toml` crate's bare
    // "recursion limit" at 1:1. The count passes 32 at the 33rd dot, just after part k32: its
    // column is the length of the first 33 parts, each with its dot.
    let key: Vec<String> = (0..100).map(|i| format!("k{i}")).collect();
    let out = run(&format!("name = \"d\"\n{} = 1\n", key.join(".")));
    let dot_33 = key[..33].iter().map(|k| k.len() + 1).sum::<usize>();
    assert_error(
        &out,
        &format!("deep.toml:2:{dot_33}: nesting passes 32 levels here"),
    );
    // Arrays nested 100 deep: the 33rd `[` (column 5 + 32) is named, not the crate's
    // "cannot recurse further".
    let out = run(&format!("a = {}{}\n", "[".repeat(100), "]".repeat(100)));
    assert_error(&out, "deep.toml:1:37: nesting passes 32 levels here");
}

// ---- stack overflows: Tiled references that loop back, groups nested without end ----------

/// A 4 x 2 map's opening and its one empty tile layer; the case's elements go after it.
const MAP_HEAD: &str = "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"4\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n <layer id=\"1\" name=\"ground\" width=\"4\" height=\"2\"><data encoding=\"csv\">0,0,0,0,0,0,0,0</data></layer>\n";

/// A template whose object uses the template `next`.
fn template(next: &str) -> String {
    format!("<?xml version=\"1.0\"?>\n<template>\n <object name=\"x\" template=\"{next}\" width=\"16\" height=\"16\"/>\n</template>\n")
}

/// A map with one object that uses the template `first`.
fn map_using(first: &str) -> String {
    format!("{MAP_HEAD} <objectgroup id=\"2\" name=\"o\">\n  <object id=\"1\" template=\"{first}\" x=\"8\" y=\"8\"/>\n </objectgroup>\n</map>\n")
}

/// `platbench COMMAND MAP --out DIR/o`, ended within 60 s (a refusal takes milliseconds; the
/// guard only turns a hang into a failure).
fn on_map(command: &str, map: &std::path::Path) -> std::process::Output {
    let mut cmd = platbench();
    cmd.arg(command).arg(map);
    if command != "inspect" {
        cmd.arg("--out")
            .arg(map.with_file_name(format!("out-{command}")));
    }
    output_within(cmd, 60)
}

#[test]
fn tiled_recursion_is_an_error_naming_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A template that uses itself.
    std::fs::write(d.join("self.tx"), template("self.tx")).unwrap();
    std::fs::write(d.join("self.tmx"), map_using("self.tx")).unwrap();
    for command in ["run", "inspect", "report", "sweep"] {
        // Guards the stack overflow (exit 134) in every command that reads a map: the loop
        // is named where it closes, self.tx line 3, with the chain it went round.
        assert_error(&on_map(command, &d.join("self.tmx")), "self.tx:3:19: object template \"self.tx\" refers back to self.tx, which is already being read (self.tx -> self.tx)");
    }
    // Two templates that use each other.
    std::fs::write(d.join("a.tx"), template("b.tx")).unwrap();
    std::fs::write(d.join("b.tx"), template("a.tx")).unwrap();
    std::fs::write(d.join("pair.tmx"), map_using("a.tx")).unwrap();
    // Guards the overflow through a second file: closed in b.tx, both files in the chain.
    assert_error(
        &on_map("run", &d.join("pair.tmx")),
        "b.tx:3:19: object template \"a.tx\" refers back to a.tx, which is already being read (a.tx -> b.tx -> a.tx)",
    );
    // A tileset whose tile's collision object uses a template of that tileset's tile.
    std::fs::write(
        d.join("t.tsx"),
        "<?xml version=\"1.0\"?>\n<tileset version=\"1.10\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\">\n <tile id=\"0\">\n  <objectgroup id=\"2\">\n   <object id=\"1\" template=\"t.tx\"/>\n  </objectgroup>\n </tile>\n</tileset>\n",
    )
    .unwrap();
    std::fs::write(
        d.join("t.tx"),
        "<?xml version=\"1.0\"?>\n<template>\n <tileset firstgid=\"1\" source=\"t.tsx\"/>\n <object gid=\"1\" width=\"16\" height=\"16\"/>\n</template>\n",
    )
    .unwrap();
    std::fs::write(
        d.join("ts.tmx"),
        format!("{MAP_HEAD} <tileset firstgid=\"1\" source=\"t.tsx\"/>\n</map>\n"),
    )
    .unwrap();
    // Guards the overflow through a tileset: the template's reference back to it, at its line.
    assert_error(
        &on_map("run", &d.join("ts.tmx")),
        "t.tx:3:24: tileset \"t.tsx\" refers back to t.tsx, which is already being read (t.tsx -> t.tx -> t.tsx)",
    );
    // Group layers nested 100,000 deep (1.7 MB).
    let n = 100_000;
    let groups = format!(
        "{MAP_HEAD}{}{}</map>\n",
        "<group name=\"g\">\n".repeat(n),
        "</group>\n".repeat(n)
    );
    std::fs::write(d.join("groups.tmx"), groups).unwrap();
    // Guards the overflow of nested groups: refused at the 65th group (line 68: two lines of
    // head, the layer, 64 groups), with the limit.
    assert_error(
        &on_map("run", &d.join("groups.tmx")),
        "groups.tmx:68: group layer \"g\" is nested 65 groups deep; expected group layers nested at most 64 deep",
    );
}

// ---- unclear errors: what the tiled crate reported with no layer or line ------------------

#[test]
fn bad_tile_data_is_named_with_its_layer_and_line() {
    let dir = tempfile::tempdir().unwrap();
    // The map has no tileset, so its cells are 0 (a gid would be in no tileset, refused first).
    let head = "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"4\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"{inf}\">\n <layer id=\"1\" name=\"walls\" width=\"4\" height=\"2\">\n  <data encoding=\"{enc}\">\n";
    let cases = [
        // Once "Invalid symbol 64, offset 0.": the layer, the line and the character.
        (
            "0",
            "base64",
            "@AAAAAEAAAABAAAAAQAAAAEAAAABAAAAAQAAAAEAAAA=",
            "b64.tmx:5: layer \"walls\": its base64 data holds '@' at character 1",
        ),
        // Once "invalid digit found in string": the layer, the line and the cell.
        (
            "0",
            "csv",
            "0,0,0,0,\n0,x,0,0",
            "csv.tmx:6: layer \"walls\": cell 6 (x = 1, y = 1) of its CSV data is \"x\"",
        ),
        // Once "number too large to fit in target type".
        (
            "0",
            "csv",
            "0,0,0,0,\n0,0,0,4294967296",
            "big.tmx:6: layer \"walls\": cell 8 (x = 3, y = 1) of its CSV data is 4294967296, more than 4294967295",
        ),
        // Once "Invalid tile found in map being parsed": the chunk, short of its cells.
        (
            "1",
            "csv",
            "<chunk x=\"0\" y=\"0\" width=\"2\" height=\"2\">0,0,0</chunk>",
            "chunk.tmx:5: layer \"walls\", chunk at x = 0, y = 0: its data holds 3 comma-separated cells; expected exactly 4 cells",
        ),
    ];
    // A chunk whose zlib data (1.4 kB) inflates to 1 MiB: inflated no further than its 256
    // cells (a 1 GiB bomb once peaked at 6 GB before any check).
    let bomb = format!("eNrtwTEBAAAAwqD1T20IX6{}D4DAPAAAQ==", "A".repeat(1355));
    let bomb = format!("<chunk x=\"0\" y=\"0\" width=\"16\" height=\"16\">{bomb}</chunk>");
    let cases = cases.into_iter().chain([(
        "1",
        "base64\" compression=\"zlib",
        bomb.as_str(),
        "bomb.tmx:5: layer \"walls\", chunk at x = 0, y = 0: its data holds more than 1024 bytes (256 cells)",
    )]);
    for (infinite, encoding, data, needle) in cases {
        let name = needle.split(':').next().unwrap();
        let map = dir.path().join(name);
        let text = head.replace("{inf}", infinite).replace("{enc}", encoding);
        std::fs::write(
            &map,
            format!("{text}{data}\n  </data>\n </layer>\n</map>\n"),
        )
        .unwrap();
        let out = platbench()
            .arg("run")
            .arg(&map)
            .arg("--out")
            .arg(dir.path().join("o"))
            .output()
            .unwrap();
        // Guards the crate's bare message: the file, its line and the layer, what was found and
        // what was expected.
        assert_error(&out, needle);
        assert!(stderr(&out).contains("expected"), "{}", stderr(&out));
    }
}

// ---- hangs and endless reads: inputs that are not regular files ---------------------------

/// Makes a named pipe at `path` that no one writes to: opening it to read would block.
fn fifo(path: &std::path::Path) {
    let made = std::process::Command::new("mkfifo").arg(path).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", path.display());
}

#[cfg(unix)]
#[test]
fn inputs_that_are_not_regular_files_are_refused_before_they_are_read() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let pipe = d.join("pipe.toml");
    fifo(&pipe);
    let mut cmd = platbench();
    cmd.arg("run").arg(&pipe).arg("--out").arg(d.join("o"));
    // Guards the hang of a FIFO given as a level: refused, named, said what it is.
    assert_error(
        &output_within(cmd, 60),
        "pipe.toml: it is a named pipe (FIFO); expected a regular file",
    );
    // A run to compare against, then copies whose metrics file or trace is a pipe or a device.
    let level = super::hostile::quick_level(d);
    let base = d.join("base");
    common::assert_success(&super::hostile::run_quick(&level, &base, &[]));
    let copy = |name: &str, file: &str| {
        let new = d.join(name);
        std::fs::create_dir_all(new.join("traces")).unwrap();
        for f in ["metrics.csv", "traces/quick.stand.sweep.csv"] {
            if f != file {
                std::fs::copy(base.join(f), new.join(f)).unwrap();
            }
        }
        new.join(file)
    };
    let piped = copy("piped", "metrics.csv");
    fifo(&piped);
    let zero_metrics = copy("zero_metrics", "metrics.csv");
    symlink("/dev/zero", &zero_metrics).unwrap();
    let zero_trace = copy("zero_trace", "traces/quick.stand.sweep.csv");
    symlink("/dev/zero", &zero_trace).unwrap();
    for (file, kind) in [
        // Guards the hang of `diff` on a FIFO as NEW's metrics file.
        (&piped, "a named pipe (FIFO)"),
        // Guards the 4 GiB allocation of one endless CSV record, as metrics and as a trace.
        (&zero_metrics, "a character device"),
        (&zero_trace, "a character device"),
    ] {
        let new = file.ancestors().find(|a| a.parent() == Some(d)).unwrap();
        let mut cmd = platbench();
        cmd.arg("diff").arg(&base).arg(new);
        assert_error(
            &output_within(cmd, 60),
            &format!("{}: it is {kind}; expected a regular file", file.display()),
        );
    }
    // `report --tradeoff` given a pipe and a device.
    let trade_pipe = d.join("tradeoff.csv");
    fifo(&trade_pipe);
    let trade_zero = d.join("zero.csv");
    symlink("/dev/zero", &trade_zero).unwrap();
    for (file, kind) in [
        // Guards the hang of `report --tradeoff` on a FIFO.
        (&trade_pipe, "a named pipe (FIFO)"),
        // Guards the endless read of a device as a trade-off CSV.
        (&trade_zero, "a character device"),
    ] {
        let mut cmd = platbench();
        cmd.arg("report")
            .arg(&level)
            .arg("--tradeoff")
            .arg(file)
            .args(["--backend", "sweep", "--out"])
            .arg(d.join("r"));
        assert_error(
            &output_within(cmd, 60),
            &format!("{}: it is {kind}; expected a regular file", file.display()),
        );
    }
}

#[test]
fn an_out_path_through_a_missing_folder_and_back_is_refused_and_nothing_is_deleted() {
    // `ghost/../victim` was checked while `ghost` was missing (nothing there), then named
    // `victim` once the output's folders were created, and `victim` was replaced as a whole.
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim");
    std::fs::create_dir(&victim).unwrap();
    std::fs::write(victim.join("data.txt"), "precious").unwrap();
    for command in [
        &["hunt", "--cases", "8", "--backend", "sweep"][..],
        &["run", "--backend", "sweep"],
    ] {
        let out = platbench()
            .current_dir(dir.path())
            .args(command)
            .args(["--out", "ghost/../victim"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command:?}: {err}");
        assert!(
            err.contains("ghost/../victim") && err.contains("`..`"),
            "{err}"
        );
        assert_eq!(
            std::fs::read_to_string(victim.join("data.txt")).unwrap(),
            "precious"
        );
        assert!(
            !dir.path().join("ghost").exists(),
            "{command:?} created ghost/"
        );
    }
}

#[test]
fn a_negative_world_size_and_a_number_beyond_f32_say_what_is_wrong() {
    // `--world-size -1` read as an unknown option "-1"; now the value is judged.
    let out = platbench()
        .args(["stress", "--world-size", "-1", "--backend", "sweep"])
        .output()
        .unwrap();
    assert_error(&out, "-1");
    assert!(
        !stderr(&out).contains("unexpected argument"),
        "{}",
        stderr(&out)
    );
    // 1e308 is finite: the message says it is beyond what the level's f32 holds.
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("far.toml");
    std::fs::write(
        &level,
        "map = \"\"\"\n...\n###\n\"\"\"\n[[scenario]]\nname = \"s\"\nspawn = [1e308, 1.0]\nduration = 1.0\n",
    )
    .unwrap();
    let out = platbench().arg("run").arg(&level).output().unwrap();
    assert_error(&out, "f32 can hold");
    assert!(
        !stderr(&out).contains("expected a finite number"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_spawn_option_outside_the_level_or_negative_is_judged_by_its_value() {
    // tests/maps/showcase.tmx is 22 x 12 tiles, 24 wide with its side walls. A negative value
    // read as an unknown option, 1e308 was called not finite, and feet outside the level ran
    // probes in the void with exit 0.
    let map = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps/showcase.tmx");
    for (spawn, said) in [
        ("-1,2", "--spawn -1,2: the feet are outside the level"),
        (
            "1e308,1",
            "--spawn 1e308,1: expected X,Y, two numbers of tiles from -1e7 to 1e7",
        ),
        (
            "5,1000000",
            "--spawn 5,1000000: the feet are outside the level",
        ),
    ] {
        for command in [&["inspect"][..], &["run", "--backend", "sweep"]] {
            let out = platbench()
                .args(command)
                .arg(&map)
                .args(["--spawn", spawn])
                .output()
                .unwrap();
            assert_error(&out, said);
        }
    }
}

#[test]
fn tile_layers_read_as_objects_is_refused() {
    // `objects` is an object layer's role; `--tile-layers objects` was accepted and did nothing.
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.tmx");
    std::fs::write(
        &map,
        r#"<?xml version="1.0" encoding="UTF-8"?>
<map version="1.10" orientation="orthogonal" renderorder="right-down" width="2" height="1" tilewidth="16" tileheight="16" infinite="0" nextlayerid="2" nextobjectid="1">
 <tileset firstgid="1" name="t" tilewidth="16" tileheight="16" tilecount="1" columns="1"><image source="t.png" width="16" height="16"/></tileset>
 <layer id="1" name="art" width="2" height="1"><data encoding="csv">1,1</data></layer>
</map>"#,
    )
    .unwrap();
    let out = platbench()
        .arg("inspect")
        .arg(&map)
        .args(["--tile-layers", "objects"])
        .output()
        .unwrap();
    assert_error(&out, "--tile-layers objects");
}

#[test]
fn diff_fails_on_a_repeated_key_a_nan_reference_and_a_third_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let head = "level,scenario,backend,config,metric,value,unit,reference,error,frame,q1,q3\n";
    let write = |name: &str, rows: &str| {
        let d = dir.path().join(name);
        std::fs::create_dir_all(d.join("traces")).unwrap();
        std::fs::write(d.join("metrics.csv"), format!("{head}{rows}")).unwrap();
        d
    };
    let good = "l,s,sweep,default,rest_gap,0.0,tiles,0.0,0.0,,,\n";
    let base = write("base", good);
    // NEW got worse, then repeats the original row: one of the two went uncompared (exit 0).
    let repeated = write(
        "repeated",
        "l,s,sweep,default,rest_gap,0.5,tiles,0.0,0.5,,,\nl,s,sweep,default,rest_gap,0.0,tiles,0.0,0.0,,,\n",
    );
    let diff = |a: &std::path::Path, b: &std::path::Path, extra: &[&str]| {
        platbench()
            .arg("diff")
            .arg(a)
            .arg(b)
            .args(extra)
            .output()
            .unwrap()
    };
    let out = diff(&base, &repeated, &[]);
    assert_error(&out, ":3: the row repeats line 2");
    // BASE's reference is NaN and NEW's value moved far: a difference, exit 1 (it was 0).
    let nan_base = write(
        "nan_base",
        "l,s,sweep,default,rest_gap,0.0,tiles,NaN,NaN,,,\n",
    );
    let moved = write("moved", "l,s,sweep,default,rest_gap,5.0,tiles,NaN,NaN,,,\n");
    let out = diff(&nan_base, &moved, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    // A third number in --tol was ignored; now refused before any work.
    let out = diff(&base, &base, &["--tol", "rest_gap=1,2,3"]);
    assert_error(&out, "--tol rest_gap=1,2,3");
    // A trace in BASE whose name is not UTF-8 was skipped, so its absence from NEW passed.
    {
        use std::os::unix::ffi::OsStringExt;
        let odd = write("odd", good);
        let name = std::ffi::OsString::from_vec(b"l.s.sweep.\xff.csv".to_vec());
        std::fs::write(odd.join("traces").join(name), "frame,t\n").unwrap();
        let out = diff(&odd, &base, &[]);
        assert_error(&out, "the trace's file name is not UTF-8");
    }
}

#[test]
fn a_chunk_beyond_tiled_s_cell_coordinates_is_named_not_called_missing() {
    // tests/maps/infinite.tmx with its chunk moved to x = 2147483632: it ends past i32::MAX,
    // the `tiled` reader dropped it, and the map was said to "hold no chunk".
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps/infinite.tmx"),
    )
    .unwrap()
    .replacen("<chunk x=\"-16\"", "<chunk x=\"2147483632\"", 1);
    let map = dir.path().join("far.tmx");
    std::fs::write(&map, text).unwrap();
    let out = platbench().arg("inspect").arg(&map).output().unwrap();
    assert_error(&out, "chunk at x = 2147483632");
    assert!(!stderr(&out).contains("no chunk"), "{}", stderr(&out));
}

#[cfg(unix)]
#[test]
fn a_side_file_that_is_not_a_regular_file_is_refused_not_ignored() {
    // A pipe, a device, a directory or a dangling link at `MAP.toml` was skipped as "no side
    // file", so `inspect` and `run` went on with exit 0 and without the user's settings.
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps/infinite.tmx"),
    )
    .unwrap();
    type Make = fn(&std::path::Path);
    let cases: [(&str, &str, Make); 4] = [
        ("pipe", "a named pipe (FIFO)", |p| fifo(p)),
        ("zero", "a character device", |p| {
            symlink("/dev/zero", p).unwrap()
        }),
        ("folder", "a directory", |p| std::fs::create_dir(p).unwrap()),
        ("dangling", "No such file", |p| {
            symlink("nowhere.toml", p).unwrap()
        }),
    ];
    for (name, kind, make) in cases {
        let map = d.join(format!("{name}.tmx"));
        std::fs::write(&map, &text).unwrap();
        let side = d.join(format!("{name}.toml"));
        make(&side);
        for command in ["inspect", "run"] {
            let mut cmd = platbench();
            cmd.arg(command).arg(&map);
            if command == "run" {
                cmd.args(["--backend", "sweep", "--out"]).arg(d.join("o"));
            }
            let out = output_within(cmd, 60);
            assert_error(&out, &format!("{name}.toml"));
            assert!(stderr(&out).contains(kind), "{}", stderr(&out));
        }
    }
}

//! Work in proportion to the input (issue 40): `report --stability` judges any number of rows
//! in one pass (a file of thousands of configurations once took minutes) and refuses, at its
//! line, a file whose combination grids would hold more cells than src/limits.rs allows; every
//! command that builds worlds of the user's levels on several threads takes fewer on a large
//! level, and says so. Each file is written by the test, a few thousand rows at most.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::Path;
use std::process::Output;

use crate::common::{assert_success, platbench};

use super::hostile::{assert_error, quick_level, stderr};

const STABILITY: &str =
    "backend,config,dimension,value,dimension2,value2,invariant,holds,measured,tolerance\n";

/// `platbench report LEVEL --backend sweep --stability FILE --out DIR/r`, FILE holding `rows`
/// after the header.
fn report_with_stability(dir: &Path, rows: &str) -> Output {
    let file = dir.join("stability.csv");
    std::fs::write(&file, format!("{STABILITY}{rows}")).unwrap();
    platbench()
        .arg("report")
        .arg(quick_level(dir))
        .args(["--backend", "sweep", "--stability"])
        .arg(&file)
        .arg("--out")
        .arg(dir.join("r"))
        .output()
        .unwrap()
}

#[test]
fn a_stability_file_of_thousands_of_configurations_gets_a_verdict_each() {
    let dir = tempfile::tempdir().unwrap();
    // 3,000 configurations of one offset row each: a verdict searched every row for each
    // configuration (5,000 such rows took 3.3 s, 20,000 over a minute).
    let rows: String = (0..3000)
        .map(|k| format!("sweep,c{k},offset,0.0,,,finite,{},0.0,0.0\n", k % 3 != 0))
        .collect();
    let out = report_with_stability(dir.path(), &rows);
    assert_success(&out);
    let md = std::fs::read_to_string(dir.path().join("r/report.md")).unwrap();
    let verdicts = md.lines().filter(|l| l.starts_with("| sweep c")).count();
    // One verdict row and one reach row per configuration.
    assert_eq!(verdicts, 2 * 3000, "{}", stderr(&out));
    assert!(md.contains("| sweep c3 | offset | breaks at the base case 0 (finite) |"));
    assert!(md.contains("| sweep c1 | offset | holds at 0 | - |"));
    // The same rows with a damaged last one: refused at its line, the file read to its end.
    let bad = format!("{rows}sweep,c,offset,zero,,,finite,true,0.0,0.0\n");
    let out = report_with_stability(dir.path(), &bad);
    // Line 3,002: the header, then 3,000 good rows.
    assert_error(
        &out,
        "stability.csv:3002: field 4 (value): found \"zero\"; expected a number",
    );
    // One row past src/limits.rs MAX_STABILITY_ROWS (100,000) is refused at its line: 2.8
    // million such rows reached 3.5 GB.
    let rows: String = (0..=100_000)
        .map(|k| format!("sweep,c{k},offset,0.0,,,finite,true,0.0,0.0\n"))
        .collect();
    let out = report_with_stability(dir.path(), &rows);
    assert_error(&out, "stability.csv:100002: more than 100000 rows");
}

#[test]
fn combination_grids_past_the_cell_cap_are_refused_at_the_row_that_passes_it() {
    let dir = tempfile::tempdir().unwrap();
    // Each row a new first and second value: after k rows the grid is k x k cells. 317^2 =
    // 100,489 is the first square past src/limits.rs MAX_STABILITY_GRID_CELLS (100,000), at
    // the 317th row, line 318.
    let rows: String = (0..400)
        .map(|k| format!("sweep,default,offset,{k}.0,dt,{k}.0,finite,true,0.0,0.0\n"))
        .collect();
    let out = report_with_stability(dir.path(), &rows);
    assert_error(
        &out,
        "stability.csv:318: the combination grids would hold 100489 cells (offset x dt: 317 rows of configuration and value x 317 values); expected at most 100000",
    );
    // 300 such rows (90,000 cells) are drawn: a row per value, a column per value.
    let rows: String = rows.lines().take(300).map(|l| format!("{l}\n")).collect();
    let out = report_with_stability(dir.path(), &rows);
    assert_success(&out);
    let md = std::fs::read_to_string(dir.path().join("r/report.md")).unwrap();
    let grid: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("| sweep default |"))
        .collect();
    assert_eq!(grid.len(), 300);
    // The configuration, the first value, then one cell per second value.
    assert_eq!(grid[0].matches(" | ").count() + 1, 2 + 300);
}

/// A 1000 x 1000 level (src/limits.rs MAX_TILES) of open air over a floor, with one scenario
/// of a single frame.
fn large_level(dir: &Path) -> std::path::PathBuf {
    let mut map = String::new();
    for _ in 0..999 {
        map.push_str(&".".repeat(1000));
        map.push('\n');
    }
    map.push_str(&"#".repeat(1000));
    let path = dir.join("large.toml");
    std::fs::write(
        &path,
        format!("name = \"large\"\nmap = \"\"\"\n{map}\n\"\"\"\n[[scenario]]\nname = \"tick\"\nspawn = [1.5, 1.0]\nduration = 0.02\n"),
    )
    .unwrap();
    path
}

#[test]
fn every_command_building_worlds_of_a_large_level_takes_fewer_threads_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let level = large_level(dir.path());
    let d = |name: &str| dir.path().join(name).display().to_string();
    // A thread's world of a million tiles is up to 1.4 GB (src/limits.rs
    // THREAD_BYTES_PER_TILE), so one thread keeps within RUN_MEMORY (2 GiB), not the 4 asked.
    let note = "platbench: 1 thread rather than 4: a thread running a level of 1000000 tiles";
    let level = level.display().to_string();
    for args in [
        vec!["report", &level, "--out", &d("report")],
        vec!["sweep", &level, "--out", &d("sweep")],
        vec!["baseline", &level, "--baseline", &d("baseline")],
        vec!["check", "--baseline", &d("baseline"), "--out", &d("check")],
    ] {
        let out = platbench()
            .args(&args)
            .args(["--jobs", "4"])
            .args(if args[0] == "check" {
                &[][..]
            } else {
                &["--backend", "sweep"][..]
            })
            .output()
            .unwrap();
        assert_success(&out);
        assert!(stderr(&out).contains(note), "{}: {}", args[0], stderr(&out));
    }
}

/// A finite 10 x 5 Tiled map with a one-tile tileset, a spawn, and `body` as its tile layers.
fn small_tmx(body: &str, infinite: bool) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"10\" height=\"5\" tilewidth=\"16\" tileheight=\"16\" infinite=\"{}\"><tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\"><image source=\"t.png\" width=\"16\" height=\"16\"/></tileset>{body}<objectgroup id=\"9\" name=\"objects\"><object id=\"1\" name=\"start\" x=\"40\" y=\"48\"><point/></object></objectgroup></map>\n",
        u8::from(infinite)
    )
}

#[test]
fn a_map_of_many_layers_or_chunks_is_scanned_in_one_pass() {
    // The map's pre-pass counted each layer's and chunk's line from the file's start, so its
    // time grew with their square: 40,000 layers of 10 x 5 (a 7.7 MB file) and 160,000 one-cell
    // chunks ran past 120 s. Both are within every limit (src/limits.rs) and now take seconds;
    // the 60 s timeout guards the hang, it does not time the work.
    let dir = tempfile::tempdir().unwrap();
    let cells = [["0"; 40].join(","), ["1"; 10].join(",")].join(",");
    let layers: String = (0..40_000)
        .map(|k| format!("<layer id=\"{}\" name=\"ground{k}\" width=\"10\" height=\"5\"><data encoding=\"csv\">{cells}</data></layer>\n", k + 10))
        .collect();
    let chunks: String = (0..400)
        .map(|y| {
            let row: String = (0..400)
                .map(|x| format!("<chunk x=\"{x}\" y=\"{y}\" width=\"1\" height=\"1\">0</chunk>"))
                .collect();
            row + "\n"
        })
        .collect();
    let chunked = format!(
        "<layer id=\"2\" name=\"ground\" width=\"10\" height=\"5\"><data encoding=\"csv\"><chunk x=\"0\" y=\"4\" width=\"10\" height=\"1\">{}</chunk>{chunks}</data></layer>",
        ["1"; 10].join(",")
    );
    for (name, text) in [
        ("layers.tmx", small_tmx(&layers, false)),
        ("chunks.tmx", small_tmx(&chunked, true)),
    ] {
        let map = dir.path().join(name);
        std::fs::write(&map, text).unwrap();
        let mut cmd = platbench();
        cmd.arg("inspect").arg(&map);
        assert_success(&super::hostile::output_within(cmd, 60));
    }
}

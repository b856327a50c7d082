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
    assert_error(&out, "stability.csv: not the CSV this option expects");
    assert!(stderr(&out).contains("line: 3002"), "{}", stderr(&out));
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

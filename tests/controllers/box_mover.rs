//! The documented plug-in example (`examples/box_mover.rs`) as a user's crate runs it: registered
//! with one line beside the built-in controllers, run on every built-in level, skipped by the
//! harness on the levels whose features it does not model, and scored like any controller.

#[path = "../../examples/box_mover.rs"]
#[allow(dead_code)]
mod example;

use std::process::ExitCode;

use platbench::cli::{run_cli, Harness};
use platbench::level::Features;
use platbench::registry::Registry;

#[test]
fn the_readme_box_mover_runs_beside_the_builtin_controllers() {
    let dir = tempfile::tempdir().unwrap();
    let h = Harness {
        registry: Registry::builtin().with::<example::BoxMover>(),
        baseline: dir.path().join("baseline"),
    };
    let out = dir.path().join("run");
    let code = run_cli(
        &h,
        [
            "platbench",
            "run",
            "--backend",
            "boxmover",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(code, ExitCode::SUCCESS);
    let metrics = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    let levels = platbench::suite::builtin_levels().unwrap();
    for level in &levels {
        let ran = metrics
            .lines()
            .any(|l| l.starts_with(&format!("{},", level.name)));
        // It models solid tiles only: exactly the levels with no other feature ran.
        assert_eq!(ran, level.features == Features::NONE, "{}", level.name);
    }
    // It stops flush: no penetration beyond its SLOP (1e-4 tiles, the overlap its x-then-y
    // moves tolerate) on any scenario it ran.
    let penetration: Vec<f64> = metrics
        .lines()
        .filter(|l| l.contains(",boxmover,default,max_penetration,"))
        .map(|l| l.split(',').nth(5).unwrap().parse().unwrap())
        .collect();
    assert!(!penetration.is_empty());
    assert!(penetration.iter().all(|&p| p <= 1e-4), "{penetration:?}");
}

#[test]
fn the_documented_plug_in_code_is_the_box_mover_example_verbatim() {
    // docs/own-controller.md "A whole controller" (README links there): the code block after
    // "and its `src/main.rs`" is examples/box_mover.rs, which CI builds (cargo clippy
    // --all-targets) and runs (the test above), so the documented code compiles as written.
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/own-controller.md"),
    )
    .expect("docs/own-controller.md");
    let after = text
        .split_once("and its `src/main.rs`")
        .expect("the plug-in section")
        .1;
    let block = after
        .split_once("```rust\n")
        .expect("a rust code block")
        .1
        .split_once("\n```\n")
        .expect("the block's end")
        .0;
    let example = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/box_mover.rs"),
    )
    .expect("examples/box_mover.rs");
    assert_eq!(format!("{block}\n"), example);
}

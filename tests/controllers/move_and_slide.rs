//! The collide-and-slide example (`examples/move_and_slide/`) as the harness runs it: every
//! built-in scenario it models, on every configuration it contributes, with its metrics in the
//! CSV files and its rows in the report; the levels it does not model are skipped.

#[path = "../../examples/move_and_slide/main.rs"]
#[allow(dead_code)]
mod example;

use std::process::ExitCode;

use platbench::cli::{run_cli, Harness};
use platbench::metrics::registry::METRICS;

#[test]
fn the_example_runs_every_builtin_scenario_it_models_and_reports_them() {
    let dir = tempfile::tempdir().unwrap();
    let h = Harness {
        registry: example::registry(),
        baseline: dir.path().join("baseline"),
    };
    let out = dir.path().join("run");
    let out_s = out.to_str().unwrap();
    let code = run_cli(
        &h,
        [
            "platbench",
            "run",
            "--backend",
            "move_and_slide",
            "--out",
            out_s,
        ],
    );
    assert_eq!(code, ExitCode::SUCCESS);
    let levels = platbench::suite::builtin_levels().unwrap();
    let kind = h.registry.get(example::NAME).expect("registered");
    let configs = kind.builtin_configs();
    assert!(configs.len() >= 2);
    let metrics = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    let mut modelled = 0;
    for level in &levels {
        let supported = configs[0].backend.supports(level);
        assert_eq!(
            supported, !level.features.moving_platforms,
            "{}: it models every feature but moving platforms",
            level.name
        );
        for spec in &level.scenarios {
            for run in &configs {
                let prefix = format!(
                    "{},{},{},{},",
                    level.name,
                    spec.name,
                    example::NAME,
                    run.label
                );
                let rows = metrics.lines().filter(|l| l.starts_with(&prefix)).count();
                if supported {
                    assert!(rows > 0, "no metrics for {prefix}");
                    // Every row names a metric of the catalog.
                    for l in metrics.lines().filter(|l| l.starts_with(&prefix)) {
                        let m = l.split(',').nth(4).unwrap();
                        assert!(METRICS.iter().any(|d| d.name == m), "{l}");
                    }
                } else {
                    assert_eq!(rows, 0, "{prefix} ran on a level it does not model");
                }
            }
            modelled += supported as usize;
        }
    }
    let traces = std::fs::read_dir(out.join("traces")).unwrap().count();
    assert_eq!(traces, modelled * configs.len());
    // docs/move-and-slide.md counts the built-in scenarios it runs, out of all of them.
    let total: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/move-and-slide.md"),
    )
    .unwrap()
    .replace('\n', " ");
    let count = format!("{modelled} of the {total} built-in scenarios");
    assert!(
        doc.contains(&count),
        "docs/move-and-slide.md lacks {count:?}"
    );
    // A few of its figures, as docs/move-and-slide.md quotes them: it keeps its margin at rest, never
    // tunnels, and its default (Godot's 1 px snap) loses a 45-degree ramp walked down at run
    // speed, which a 0.25-tile snap keeps.
    let value = |scenario: &str, config: &str, metric: &str| -> f64 {
        let prefix = format!("{scenario},{},{config},{metric},", example::NAME);
        let line = metrics
            .lines()
            .find(|l| l.starts_with(&prefix))
            .unwrap_or_else(|| panic!("no {prefix}"));
        line.split(',').nth(5).unwrap().parse().unwrap()
    };
    assert!((value("drops,drop_1", "cuboid", "rest_gap") - 0.005).abs() < 1e-3);
    assert_eq!(value("thin_wall,fast_right", "cuboid", "tunneled"), 0.0);
    assert!(value("slope_45,walk_right", "cuboid", "slope_airborne_frames") > 0.0);
    assert_eq!(
        value(
            "slope_45,walk_right",
            "cuboid snap=0.25",
            "slope_airborne_frames"
        ),
        0.0
    );

    let report = dir.path().join("report");
    let code = run_cli(
        &h,
        [
            "platbench",
            "report",
            "--backend",
            "move_and_slide,sweep",
            "--out",
            report.to_str().unwrap(),
        ],
    );
    assert_eq!(code, ExitCode::SUCCESS);
    let md = std::fs::read_to_string(report.join("report.md")).unwrap();
    for run in &configs {
        assert!(
            md.contains(&format!("{} {}", example::NAME, run.label)),
            "report lacks {}",
            run.label
        );
    }
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    assert!(html.contains("move_and_slide cuboid"));
}

/// The example's configurations on the two levels with surfaces steeper than its 45-degree
/// `floor_max_angle`, with their metric rows.
fn steep_rows(configs: Vec<platbench::config::RunConfig>) -> Vec<platbench::metrics::MetricRow> {
    let levels: Vec<_> = platbench::suite::builtin_levels()
        .unwrap()
        .into_iter()
        .filter(|l| l.name == "slope_63_4" || l.name == "seed_tile")
        .collect();
    assert_eq!(levels.len(), 2);
    platbench::suite::run_suite(&levels, &configs)
        .unwrap()
        .metrics
}

fn value(
    rows: &[platbench::metrics::MetricRow],
    scenario: &str,
    config: &str,
    metric: &str,
) -> f64 {
    rows.iter()
        .find(|r| {
            format!("{}.{}", r.level, r.scenario) == scenario
                && r.config == config
                && r.metric == metric
        })
        .unwrap_or_else(|| panic!("no {scenario} {config} {metric}"))
        .value
}

#[test]
fn godots_floor_block_on_wall_keeps_the_mover_off_steep_slopes() {
    use example::MoveAndSlideConfig;
    use platbench::prelude::{CharacterShape, Controller};
    // Godot's defaults, floor_block_on_wall on (character_body_2d.cpp,
    // CharacterBody2D::_move_and_slide_grounded): walking into a 63.4-degree ramp (a wall
    // under the 45-degree floor_max_angle) no longer slides up it. Before the rule was modelled
    // (commit 0693ae0) every configuration climbed it, fell back and climbed again: 7 grounded
    // changes for the box, 8 for the capsule, each way; and the capsule climbed the seed's steep
    // height-array tile (seed_tile.walk_up steep_blocked 0). Measured with the rule: 0 changes
    // and blocked for every configuration.
    let rows = steep_rows(<MoveAndSlideConfig as Controller>::configs());
    for config in [
        "cuboid",
        "capsule",
        "cuboid constant_speed=true",
        "cuboid snap=0.25",
    ] {
        for scenario in [
            "slope_63_4.walk_into_steep",
            "slope_63_4.walk_into_steep_leftward",
        ] {
            assert_eq!(
                value(&rows, scenario, config, "grounded_flicker"),
                0.0,
                "{scenario} {config}"
            );
            assert_eq!(
                value(&rows, scenario, config, "steep_blocked"),
                1.0,
                "{scenario} {config}"
            );
        }
        assert_eq!(
            value(&rows, "seed_tile.walk_up", config, "steep_blocked"),
            1.0,
            "{config}"
        );
    }
    // The rule is the cause: turned off (the other slide rules kept), the climb and its flicker
    // come back (8 changes for the box each way, the capsule up the seed's steep tile).
    let off: Vec<_> = [CharacterShape::Cuboid, CharacterShape::Capsule]
        .into_iter()
        .map(|shape| {
            let c = MoveAndSlideConfig {
                shape,
                floor_block_on_wall: false,
                ..Default::default()
            };
            platbench::config::RunConfig::new(c.label(), c)
        })
        .collect();
    let rows = steep_rows(off);
    assert!(
        value(
            &rows,
            "slope_63_4.walk_into_steep",
            "cuboid block_on_wall=false",
            "grounded_flicker"
        ) >= 7.0
    );
    assert_eq!(
        value(
            &rows,
            "seed_tile.walk_up",
            "capsule block_on_wall=false",
            "steep_blocked"
        ),
        0.0
    );
}

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

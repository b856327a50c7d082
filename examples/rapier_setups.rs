//! Rapier set-ups side by side over the built-in set: the documented remedies for a stuck
//! character (a larger absolute offset, no vertical move while grounded, a larger normal nudge),
//! the feed of Rapier's 2D testbed, the advised feed that combines the bevy_rapier example's
//! and the testbed's, and the platform order, on every shape and collider building. This is the command behind the
//! docs/rapier.md's choice of the "Rapier as its docs advise for a stuck character" configurations.
//!
//! `cargo run --release --example rapier_setups [SHAPE ...]` prints one row per set-up:
//! progress over the flat walks (median and worst), stuck frames (sum), the worst creep at
//! rest, slopes, platform carry and penetration.

#[path = "../compare/builtin.rs"]
mod builtin;

use platbench::config::RunConfig;
use platbench::level::parse_level;
use platbench::metrics::{evaluate_with, MetricRow};
use platbench::rapier::{
    CharacterShape, ColliderBuilding, GroundedMove, Length, PlatformOrder, RapierConfig,
};
use platbench::scenario::Runner;

/// The set-ups compared, each a change from Rapier's defaults.
fn setups() -> Vec<(&'static str, RapierConfig)> {
    let d = RapierConfig::default;
    vec![
        ("default", d()),
        (
            "grounded=none",
            RapierConfig {
                grounded_move: GroundedMove::None,
                ..d()
            },
        ),
        (
            "grounded=none-but-platforms",
            RapierConfig {
                grounded_move: GroundedMove::NoneExceptOnPlatforms,
                ..d()
            },
        ),
        (
            "grounded=testbed",
            RapierConfig {
                grounded_move: GroundedMove::Testbed,
                ..d()
            },
        ),
        (
            "grounded=none-but-testbed-on-platforms",
            RapierConfig {
                grounded_move: GroundedMove::NoneExceptTestbedOnPlatforms,
                ..d()
            },
        ),
        (
            "offset=0.02",
            RapierConfig {
                offset: Length::Absolute(0.02),
                ..d()
            },
        ),
        (
            "offset=0.05",
            RapierConfig {
                offset: Length::Absolute(0.05),
                ..d()
            },
        ),
        (
            "offset=0.1",
            RapierConfig {
                offset: Length::Absolute(0.1),
                ..d()
            },
        ),
        (
            "nudge=1e-3",
            RapierConfig {
                normal_nudge_factor: 1e-3,
                ..d()
            },
        ),
        (
            "offset=0.05 grounded=none-but-platforms",
            RapierConfig {
                offset: Length::Absolute(0.05),
                grounded_move: GroundedMove::NoneExceptOnPlatforms,
                ..d()
            },
        ),
        (
            "autostep=0.3,0.5",
            RapierConfig {
                autostep: Some((Length::Relative(0.3), Length::Relative(0.5))),
                ..d()
            },
        ),
        (
            "platforms=after",
            RapierConfig {
                platform_order: PlatformOrder::AfterCharacters,
                ..d()
            },
        ),
    ]
}

fn main() {
    let shapes: Vec<String> = std::env::args().skip(1).collect();
    let levels: Vec<_> = builtin::LEVELS
        .iter()
        .map(|(f, t)| parse_level(t, f).expect("built-in level parses"))
        .collect();
    println!(
        "| set-up | progress median | progress worst | stuck frames | rest jitter worst | slope speed worst | steep wrong | carry drift worst | carry airborne worst | penetration worst |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for shape in CharacterShape::ALL {
        if !shapes.is_empty() && !shapes.iter().any(|s| *s == shape.label()) {
            continue;
        }
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            for (name, setup) in setups() {
                let config = RapierConfig {
                    colliders: building,
                    shape,
                    ..setup
                };
                let run = RunConfig {
                    label: format!("{} {} {name}", building.label(), shape.label()),
                    backend: std::sync::Arc::new(config),
                    ..platbench::sweep::kind::run_default()
                };
                let mut rows: Vec<MetricRow> = Vec::new();
                for level in &levels {
                    let mut runner = Runner::new(level);
                    for spec in &level.scenarios {
                        let e = evaluate_with(&mut runner, spec, &run).expect("scenario runs");
                        rows.extend(e.metrics);
                    }
                }
                print_row(&run.label, &rows);
                if let Ok(m) = std::env::var("DETAIL") {
                    for r in rows.iter().filter(|r| r.metric == m && r.value != 0.0) {
                        println!("    {}.{} {}", r.level, r.scenario, r.value);
                    }
                }
            }
        }
    }
}

fn values(rows: &[MetricRow], metric: &str) -> Vec<f64> {
    rows.iter()
        .filter(|r| r.metric == metric)
        .map(|r| r.value)
        .collect()
}

fn print_row(label: &str, rows: &[MetricRow]) {
    let mut progress = values(rows, "progress_ratio");
    progress.sort_by(f64::total_cmp);
    let median = progress
        .get(progress.len() / 2)
        .copied()
        .unwrap_or(f64::NAN);
    let worst_progress = progress.first().copied().unwrap_or(f64::NAN);
    let stuck: f64 = values(rows, "stuck_frames").iter().sum();
    let max = |m: &str| values(rows, m).into_iter().fold(0.0f64, f64::max);
    let slope_speed = rows
        .iter()
        .filter(|r| r.metric == "slope_speed_ratio")
        .map(|r| r.error.abs())
        .fold(0.0f64, f64::max);
    let steep_wrong = rows
        .iter()
        .filter(|r| r.metric == "steep_blocked" && r.error != 0.0)
        .count();
    println!(
        "| {label} | {median:.3} | {worst_progress:.3} | {stuck} | {:.4} | {slope_speed:.3} | {steep_wrong} | {:.3} | {} | {:.4} |",
        max("rest_jitter"),
        max("carry_drift"),
        max("carry_airborne_frames"),
        max("max_penetration"),
    );
}

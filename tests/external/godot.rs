//! Godot 3's `KinematicBody2D` over the step protocol (`controllers/godot3/client.gd`, run by
//! `godot3-server`, Godot 3.2): the handshake, determinism, every built-in scenario it models,
//! and documented Godot behaviour read from the traces: the rest gap within `safe_margin`, a
//! slope held with `stop_on_slope`, a moving platform's velocity carried. Every test needs
//! `godot3-server` (`PLATBENCH_GODOT3` names another): without it each says loudly that it
//! skipped, unless `PLATBENCH_REQUIRE_PROGRAMS=1`.

use std::path::PathBuf;

use platbench::config::RunConfig;
use platbench::scenario::run_scenario;
use platbench::trace::Trace;

use crate::common;
use crate::root;

/// Pixels per tile and `safe_margin` (px) as the client sets them (client.gd).
const PIXELS_PER_TILE: f32 = 32.0;
const SAFE_MARGIN_PX: f32 = 0.08;

fn godot(test: &str) -> Option<PathBuf> {
    common::outside_program(
        test,
        "godot3-server",
        "PLATBENCH_GODOT3",
        "apt-get install -y godot3-server",
    )
}

/// The built-in client's configurations, run by `program`.
fn configs(program: &std::path::Path) -> Vec<RunConfig> {
    platbench::external::godot3::load_with(program)
        .unwrap_or_else(|e| panic!("{e}"))
        .builtin_configs()
}

fn config<'a>(runs: &'a [RunConfig], label: &str) -> &'a RunConfig {
    runs.iter().find(|r| r.label == label).expect(label)
}

/// Runs `level.scenario` on `run`.
fn trace(level: &str, scenario: &str, run: &RunConfig) -> Trace {
    let level = common::level(level);
    let spec = level
        .scenarios
        .iter()
        .find(|s| s.name == scenario)
        .unwrap_or_else(|| panic!("{scenario}"));
    run_scenario(&level, spec, run).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_godot_client_answers_the_handshake_and_refuses_ladders() {
    let Some(godot) = godot("tests/external/godot.rs (handshake)") else {
        return;
    };
    let start = std::time::Instant::now();
    let kind = platbench::external::godot3::load_with(&godot).unwrap();
    // The client quits on `end`: the handshake never waits out its 5 s grace before a kill
    // (Godot starts in well under a second here; 4 s leaves room for a loaded machine).
    assert!(
        start.elapsed() < std::time::Duration::from_secs(4),
        "the handshake took {:?}",
        start.elapsed()
    );
    assert_eq!(kind.name(), "godot3");
    // The version Godot reports of itself, in the description its rows carry.
    assert!(
        kind.description().contains("Godot 3."),
        "{}",
        kind.description()
    );
    let runs = kind.builtin_configs();
    let labels: Vec<&str> = runs.iter().map(|r| r.label.as_str()).collect();
    assert_eq!(labels, ["slide", "snap", "snap-merged"]);
    // It models slopes, one-way platforms and moving platforms, not ladders (Godot has none).
    let f = runs[0].backend.features();
    assert!(
        f.slopes && f.one_way && f.moving_platforms && !f.ladders,
        "{f:?}"
    );
    // The contact it declares: Godot's safe_margin as its gap, in tiles.
    let c = runs[0]
        .backend
        .declared_contact(glam::Vec2::new(0.8, 0.9), 0.785);
    assert!(
        (c.gap - SAFE_MARGIN_PX / PIXELS_PER_TILE).abs() < 1e-9,
        "{c:?}"
    );
    let level = common::level("ladders");
    let e = run_scenario(&level, &level.scenarios[0], &runs[0]).unwrap_err();
    assert!(e.is_unsupported(), "{e}");
}

#[test]
fn a_godot_body_rests_within_safe_margin_of_the_floor() {
    let Some(godot) = godot("tests/external/godot.rs (rest gap)") else {
        return;
    };
    // Godot 3's motion recovery keeps a body within `safe_margin` of what it touches (class
    // reference, KinematicBody2D collision/safe_margin): after a drop onto the floor (top at
    // y = 1), every configuration rests grounded at a gap between 0 and safe_margin.
    let margin = SAFE_MARGIN_PX / PIXELS_PER_TILE;
    for run in &configs(&godot) {
        let t = trace("drops", "drop_0_5", run);
        let last = t.rows.last().unwrap();
        assert_eq!(last.grounded, 1, "{}", run.label);
        let gap = last.y - 1.0;
        assert!(
            (0.0..=margin).contains(&gap),
            "{}: rests {gap} tiles above the floor; safe_margin is {margin}",
            run.label
        );
    }
}

#[test]
fn stop_on_slope_holds_a_body_on_a_walkable_slope() {
    let Some(godot) = godot("tests/external/godot.rs (stop_on_slope)") else {
        return;
    };
    // "If stop_on_slope is true, body will not slide on slopes when you include gravity in
    // linear_velocity and the body is standing still" (class reference, move_and_slide). The
    // demo's call (snap) passes it off a platform; the tutorial's call (slide) leaves it false.
    let runs = configs(&godot);
    let drift = |label: &str| {
        let t = trace("slope_22_5", "rest_on_slope", config(&runs, label));
        let (first, last) = (t.rows.first().unwrap(), t.rows.last().unwrap());
        (last.x - first.x).abs()
    };
    // Held: under a thousandth of a tile (0.03 px) over the 1.5 s rest.
    assert!(drift("snap") < 1e-3, "snap drifted {}", drift("snap"));
    // Without it the body slides down the 22.5-degree ramp: more than a tenth of a tile.
    assert!(drift("slide") > 0.1, "slide drifted {}", drift("slide"));
}

#[test]
fn a_moving_platform_carries_its_rider_at_its_own_velocity() {
    let Some(godot) = godot("tests/external/godot.rs (platform carry)") else {
        return;
    };
    // move_and_slide adds the floor's velocity (a KinematicBody2D moved with sync_to_physics)
    // to the body's: over the ride's middle, the rider moves as the platform does. Godot moves
    // the platform in its physics step, after the scripts, so the rider follows one step late:
    // the comparison is of displacements over the same span of steps.
    let Some(run) = configs(&godot).into_iter().find(|r| r.label == "snap") else {
        panic!("snap")
    };
    let level = common::level("platforms");
    let t = trace("platforms", "ride_horizontal", &run);
    let platform = &level.platforms[0];
    let (a, b) = (120, 180);
    let moved = |k: usize| t.rows[k].x;
    let rider = moved(b) - moved(a);
    let at = |k: usize| platform.position(t.rows[k].t as f64).x;
    let platform_moved = at(b - 1) - at(a - 1);
    // Equal to a thousandth of a tile (the f32 positions' rounding over 60 steps is far less).
    assert!(
        (rider - platform_moved).abs() < 1e-3,
        "rider moved {rider}, platform {platform_moved}"
    );
    assert!(
        platform_moved.abs() > 0.5,
        "the platform moves: {platform_moved}"
    );
    assert!(t.rows[a..=b].iter().all(|r| r.grounded == 1));
}

#[test]
fn the_godot_client_gives_the_same_trace_twice() {
    let Some(godot) = godot("tests/external/godot.rs (determinism)") else {
        return;
    };
    let runs = configs(&godot);
    for (level, scenario) in [("platforms", "ride_horizontal"), ("jumps", "jump_3")] {
        let a = trace(level, scenario, config(&runs, "snap"));
        let b = trace(level, scenario, config(&runs, "snap"));
        assert!(a == b, "{level}.{scenario} differs between two runs");
    }
}

#[test]
fn the_godot_client_runs_every_built_in_scenario_it_models() {
    let Some(godot) = godot("tests/external/godot.rs (every built-in scenario)") else {
        return;
    };
    let runs = configs(&godot);
    let run = config(&runs, "snap");
    let (mut ran, mut refused, mut on_ladders) = (0, 0, 0);
    let levels = common::builtin_levels();
    for level in &levels {
        if level.features.ladders {
            on_ladders += level.scenarios.len();
        }
    }
    for level in levels {
        for spec in &level.scenarios {
            match run_scenario(&level, spec, run) {
                Ok(t) => {
                    assert!(
                        t.rows.iter().all(|r| r.x.is_finite() && r.y.is_finite()),
                        "{}.{}",
                        level.name,
                        spec.name
                    );
                    ran += 1;
                }
                // Only ladder levels are refused.
                Err(e) if e.is_unsupported() => {
                    assert!(level.features.ladders, "{}: {e}", level.name);
                    refused += 1;
                }
                Err(e) => panic!("{}.{}: {e}", level.name, spec.name),
            }
        }
    }
    // Every scenario of a level with ladders refused, every other one run (60 of the 64 today).
    assert_eq!(refused, on_ladders, "refused {refused}");
    assert!(on_ladders > 0, "the built-in set has a ladder level");
    assert_eq!(
        ran + refused,
        common::builtin_levels()
            .iter()
            .map(|l| l.scenarios.len())
            .sum::<usize>()
    );
}

#[test]
fn the_repository_controller_file_runs_godot() {
    if godot("tests/external/godot.rs (controllers/godot3/controller.toml)").is_none() {
        return;
    }
    if std::env::var_os("PLATBENCH_GODOT3").is_some() {
        // The committed file runs `godot3-server` from the PATH.
        return;
    }
    let kind = platbench::external::load(&root().join("controllers/godot3/controller.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(kind.builtin_configs().len(), 3);
}

#[test]
fn godot_overhead() {
    let Some(godot) = godot("tests/external/godot.rs (the TCP transport's overhead)") else {
        return;
    };
    crate::print_overhead(config(&configs(&godot), "snap"), "the Godot client's own");
}

#[cfg(target_os = "linux")]
#[test]
fn godot_exits_when_platbench_is_killed() {
    if godot("tests/external/godot.rs (platbench killed mid-run)").is_none() {
        return;
    }
    // platbench killed with SIGKILL while Godot runs a scenario: no Godot outlives it (the
    // kernel's parent-death signal, and the client's own quit when its connection closes).
    let dir = tempfile::tempdir().unwrap();
    let mut command = common::platbench();
    command
        .args(["run", "--controller", "godot3", "--backend", "godot3"])
        .args(["--scenario", "long_floor", "--out"])
        .arg(dir.path().join("run"));
    crate::misbehaving::kill_mid_run(command, "godot3");
}

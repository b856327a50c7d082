//! The harness with a backend it does not ship: a toy controller defined here, registered
//! beside nothing else, run through `run`, `diff` and `report` as a user's crate would; and the
//! committed baseline reproduced by the registry of built-in backends.

use std::path::Path;
use std::process::ExitCode;
use std::rc::Rc;

use glam::Vec2;

use platbench::backend::{BackendError, CharacterId, CharacterState, DeclaredContact};
use platbench::cli::{run_cli, Harness};
use platbench::config::RunConfig;
use platbench::controller::{Controller, Setup};
use platbench::level::Features;
use platbench::motion::{Contacts, Input, MotionParams, MotionState};
use platbench::registry::Registry;

/// A toy controller: the shared motion, and a floor at the highest solid top of the level
/// (nothing else collides).
#[derive(Clone, Debug, Default, PartialEq)]
struct Toy {
    /// Height the toy floats above its floor, in tiles.
    hover: f32,
}

struct ToyMover {
    floor: Rc<f32>,
    params: MotionParams,
    chars: Vec<(Vec2, MotionState)>,
}

impl Controller for Toy {
    type Mover = ToyMover;
    const NAME: &'static str = "toy";

    fn features(&self) -> Features {
        Features::NONE
    }

    fn build(&self, setup: Setup<'_>) -> Result<ToyMover, BackendError> {
        let level = setup.level;
        let floor = setup.shared.get_or_build("toy:floor", || {
            level
                .solid_boxes()
                .map(|b| b.maxs.y)
                .fold(f32::MIN, f32::max)
        });
        Ok(ToyMover {
            floor,
            params: setup.params.clone(),
            chars: setup
                .characters
                .iter()
                .map(|c| (c.spawn, MotionState::with_velocity(c.velocity)))
                .collect(),
        })
    }

    fn step(&self, m: &mut ToyMover, inputs: &[Input], dt: f32) {
        for (k, (pos, motion)) in m.chars.iter_mut().enumerate() {
            let input = inputs.get(k).copied().unwrap_or_default();
            *pos += motion.integrate(&m.params, &input, dt);
            let floor = *m.floor + self.hover;
            let ground = pos.y <= floor;
            if ground {
                pos.y = floor;
            }
            motion.apply_contacts(
                &m.params,
                &input,
                Contacts {
                    ground,
                    ..Default::default()
                },
            );
        }
    }

    fn state(&self, m: &ToyMover, id: CharacterId) -> CharacterState {
        let (pos, motion) = &m.chars[id];
        CharacterState {
            pos: *pos,
            vel: motion.vel,
            grounded: motion.grounded,
            ground_normal: if motion.grounded { Vec2::Y } else { Vec2::ZERO },
            ..Default::default()
        }
    }

    fn configs() -> Vec<RunConfig> {
        vec![
            RunConfig::new("flush", Toy { hover: 0.0 }),
            RunConfig::new("hover", Toy { hover: 0.01 }),
        ]
    }

    fn drawn() -> Vec<(&'static str, &'static str)> {
        vec![("flush", "#000000")]
    }

    fn declared_contact(&self, _size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        DeclaredContact {
            gap: self.hover,
            ..Default::default()
        }
    }
}

const LEVEL: &str = "name = \"plain\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"drop\"\nspawn = [2.5, 2.5]\nduration = 1.0\n[[scenario]]\nname = \"walk\"\nspawn = [1.5, 1.0]\nduration = 1.0\ninputs = [ { t = 0.0, right = true } ]\n";

fn cli(h: &Harness, args: &[&str]) -> ExitCode {
    let mut all = vec!["platbench"];
    all.extend_from_slice(args);
    run_cli(h, all)
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

#[test]
fn a_toy_backend_runs_through_run_diff_and_report() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("plain.toml");
    std::fs::write(&level, LEVEL).unwrap();
    let h = Harness {
        registry: Registry::new().with::<Toy>(),
        baseline: dir.path().join("baseline"),
    };
    let (a, b, r) = (
        dir.path().join("a"),
        dir.path().join("b"),
        dir.path().join("r"),
    );
    for out in [&a, &b] {
        assert_eq!(
            cli(&h, &["run", path(&level), "--out", path(out)]),
            ExitCode::SUCCESS
        );
    }
    // Both configurations ran both scenarios: traces and metric rows named after the toy.
    let metrics = std::fs::read_to_string(a.join("metrics.csv")).unwrap();
    for config in ["flush", "hover"] {
        assert!(
            metrics.contains(&format!("plain,drop,toy,{config},land_frame_error")),
            "{metrics}"
        );
        assert!(metrics.contains(&format!("plain,walk,toy,{config},progress_ratio")));
    }
    assert!(a.join("traces/plain.walk.toy.hover.csv").exists());
    // The toy's declared gap is scored as its design: the hovering toy's rest gap is its hover.
    let gap = metrics
        .lines()
        .find(|l| l.starts_with("plain,drop,toy,hover,rest_gap,"))
        .expect("rest_gap row");
    assert!(gap.contains(",0.01"), "{gap}");
    // A run against itself is clean.
    assert_eq!(cli(&h, &["diff", path(&a), path(&b)]), ExitCode::SUCCESS);
    // A backend the registry lacks is refused like any bad option.
    assert_eq!(
        cli(&h, &["run", "--backend", "sweep", "--out", path(&b)]),
        ExitCode::from(2)
    );
    assert_eq!(
        cli(&h, &["report", path(&level), "--out", path(&r)]),
        ExitCode::SUCCESS
    );
    let md = std::fs::read_to_string(r.join("report.md")).unwrap();
    assert!(md.contains("toy flush"), "{md}");
    assert!(md.contains("toy hover"), "{md}");
}

#[test]
fn the_suite_runs_from_code_and_skips_what_a_backend_does_not_model() {
    let levels = platbench::suite::builtin_levels().unwrap();
    let configs = Registry::new().with::<Toy>().builtin_configs();
    let run = platbench::suite::run_suite(&levels, &configs).unwrap();
    let modelled: usize = levels
        .iter()
        .filter(|l| configs[0].backend.supports(l))
        .map(|l| l.scenarios.len())
        .sum();
    assert!(modelled > 0);
    assert_eq!(run.traces.len(), 2 * modelled);
    assert!(!run.skipped.is_empty());
    assert!(run.metrics.iter().all(|m| m.backend == "toy"));
}

#[test]
fn the_harness_skips_a_level_a_controller_does_not_model_before_building_it() {
    // The toy models solid tiles only (`Features::NONE`) and its build refuses nothing: the
    // harness alone must keep it off the built-in levels with slopes, one-way platforms,
    // ladders or moving platforms, and count only what ran.
    let dir = tempfile::tempdir().unwrap();
    let h = Harness {
        registry: Registry::new().with::<Toy>(),
        baseline: dir.path().join("baseline"),
    };
    let out = dir.path().join("out");
    assert_eq!(cli(&h, &["run", "--out", path(&out)]), ExitCode::SUCCESS);
    let levels = platbench::suite::builtin_levels().unwrap();
    let plain: Vec<&platbench::level::Level> = levels
        .iter()
        .filter(|l| l.features == Features::NONE)
        .collect();
    let modelled: usize = plain.iter().map(|l| l.scenarios.len()).sum();
    // Both sides non-empty, or the test proves nothing.
    assert!(modelled > 0 && plain.len() < levels.len());
    let traces = std::fs::read_dir(out.join("traces")).unwrap().count();
    assert_eq!(
        traces,
        2 * modelled,
        "one trace per configuration and modelled scenario"
    );
    let metrics = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    for l in levels.iter().filter(|l| l.features != Features::NONE) {
        assert!(
            !metrics.contains(&format!("\n{},", l.name)),
            "{} has {:?} and was run",
            l.name,
            l.features
        );
    }
}

#[test]
#[cfg(all(feature = "rapier", feature = "box2d"))]
fn the_builtin_registry_is_the_builtin_set() {
    let names = Registry::builtin().names();
    // `Registry::builtin`'s kinds, in its order.
    assert_eq!(names, ["sweep", "rapier", "box2d"]);
    // The committed baseline's configurations, in its order.
    let labels: Vec<String> = platbench::registry::Registry::builtin()
        .builtin_configs()
        .iter()
        .map(|c| format!("{} {}", c.backend.backend(), c.label))
        .collect();
    // 3 sweep, 16 Rapier (4 shapes on 2 buildings fed gravity every step, then the same fed
    // as Rapier's examples feed it), 4 Box2D (the sample's capsule on per-tile and merged
    // colliders, the advised set-up and the carry with the trade-off grid's stiffest spring,
    // docs/box2d.md): the 23 configurations of compare/baseline/metrics.csv.
    assert_eq!(labels.len(), 23);
    assert_eq!(labels[0], "sweep default");
    assert_eq!(labels[3], "rapier per-tile capsule");
    assert_eq!(
        labels[11],
        "rapier per-tile capsule grounded=none-but-testbed-on-platforms"
    );
    assert_eq!(
        labels[18],
        "rapier merged round-cuboid grounded=none-but-testbed-on-platforms"
    );
    let box2d = &labels[labels.len() - 4..];
    assert_eq!(box2d[0], "box2d per-tile capsule");
    assert_eq!(box2d[1], "box2d merged capsule");
}

#[test]
#[cfg(all(feature = "rapier", feature = "box2d"))]
fn the_sweep_grid_is_the_committed_tradeoff_csv() {
    // compare/tradeoff/tradeoff.csv was written by `platbench sweep` before the registry: the
    // registry's grid has the same settings, in the same order, with the same backends.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/compare/tradeoff/tradeoff.csv"
    ))
    .unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let committed: Vec<(String, String)> = r
        .deserialize::<platbench::tradeoff::TradeoffRow>()
        .map(|row| row.unwrap())
        .filter(|row| row.scope == platbench::tradeoff::ALL)
        .map(|row| (row.backend, row.setting))
        .collect();
    let grid: Vec<(String, String)> = Registry::builtin()
        .tradeoff_settings()
        .into_iter()
        .map(|s| (s.run.backend.backend().to_string(), s.label))
        .collect();
    assert_eq!(grid, committed);
}

//! The harness with a backend it does not ship: a toy controller defined here, registered
//! beside nothing else, run through `run`, `diff` and `report` as a user's crate would; and the
//! committed baseline reproduced by the registry of built-in backends.

use std::path::Path;
use std::process::ExitCode;
use std::rc::Rc;

use glam::Vec2;

use platbench::backend::{
    require_supported, same_settings, Backend, BackendError, BackendKind, BackendSettings,
    CharacterId, CharacterSpec, CharacterState, DeclaredContact, SharedGeometry,
};
use platbench::cli::{run_cli, Harness};
use platbench::level::{Features, Level};
use platbench::motion::{Contacts, Input, MotionParams, MotionState};
use platbench::registry::Registry;
use platbench::scenario::RunConfig;
use platbench::shape::CharacterShape;

/// A toy controller: the shared motion, and a floor at the lowest solid top under the spawn
/// column (nothing else collides).
#[derive(Clone, Debug, PartialEq)]
struct ToyConfig {
    /// Height the toy floats above its floor, in tiles.
    hover: f32,
}

struct Toy {
    floor: Rc<f32>,
    params: MotionParams,
    hover: f32,
    chars: Vec<(Vec2, Vec2, MotionState)>,
}

impl Backend for Toy {
    fn name(&self) -> &'static str {
        "toy"
    }
    fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        self.chars.push((
            spec.spawn,
            spec.size,
            MotionState::with_velocity(spec.velocity),
        ));
        Ok(self.chars.len() - 1)
    }
    fn step(&mut self, inputs: &[Input], dt: f32) {
        for (k, (pos, _, m)) in self.chars.iter_mut().enumerate() {
            let input = inputs.get(k).copied().unwrap_or_default();
            let d = m.integrate(&self.params, &input, dt);
            *pos += d;
            let floor = *self.floor + self.hover;
            let ground = pos.y <= floor;
            if ground {
                pos.y = floor;
            }
            m.apply_contacts(
                &self.params,
                &input,
                Contacts {
                    ground,
                    ..Default::default()
                },
            );
        }
    }
    fn state(&self, id: CharacterId) -> CharacterState {
        let (pos, _, m) = &self.chars[id];
        CharacterState {
            pos: *pos,
            vel: m.vel,
            grounded: m.grounded,
            ground_normal: if m.grounded { Vec2::Y } else { Vec2::ZERO },
            ..Default::default()
        }
    }
}

const FEATURES: Features = Features {
    slopes: false,
    one_way: false,
    ladders: false,
    moving_platforms: false,
};

impl BackendSettings for ToyConfig {
    fn backend(&self) -> &'static str {
        "toy"
    }
    fn shape(&self) -> CharacterShape {
        CharacterShape::Cuboid
    }
    fn supports(&self, level: &Level) -> bool {
        require_supported("toy", "", level.features, FEATURES).is_ok()
    }
    fn declared_contact(&self, _size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        DeclaredContact {
            gap: self.hover,
            ..Default::default()
        }
    }
    fn contact_tolerance(&self, _size: Vec2) -> f64 {
        0.0
    }
    fn build(
        &self,
        level: &Level,
        params: &MotionParams,
        shared: &mut SharedGeometry,
    ) -> Result<Box<dyn Backend>, BackendError> {
        require_supported("toy", &level.name, level.features, FEATURES)?;
        let floor = shared.get_or_build("toy:floor", || {
            level
                .solid_boxes()
                .map(|b| b.maxs.y)
                .fold(f32::MIN, f32::max)
        });
        Ok(Box::new(Toy {
            floor,
            params: params.clone(),
            hover: self.hover,
            chars: Vec::new(),
        }))
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn same_as(&self, other: &dyn BackendSettings) -> bool {
        same_settings(self, other)
    }
}

struct ToyKind;

impl BackendKind for ToyKind {
    fn name(&self) -> &'static str {
        "toy"
    }
    fn shapes(&self) -> Vec<CharacterShape> {
        vec![CharacterShape::Cuboid]
    }
    fn features(&self) -> Features {
        FEATURES
    }
    fn builtin_configs(&self) -> Vec<RunConfig> {
        vec![
            RunConfig::new("flush", ToyConfig { hover: 0.0 }),
            RunConfig::new("hover", ToyConfig { hover: 0.01 }),
        ]
    }
    fn drawn(&self) -> Vec<(&'static str, &'static str)> {
        vec![("flush", "#000000")]
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
        registry: Registry::new().with(ToyKind),
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
    let configs = Registry::new().with(ToyKind).builtin_configs();
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
fn the_builtin_registry_is_the_builtin_set() {
    let names = Registry::builtin().names();
    // `Registry::builtin`'s kinds, in its order.
    assert_eq!(names, ["sweep", "rapier", "box2d"]);
    // The committed baseline's configurations, in its order.
    let labels: Vec<String> = RunConfig::builtin_set()
        .iter()
        .map(|c| format!("{} {}", c.backend.backend(), c.label))
        .collect();
    // 3 sweep, 12 Rapier (4 shapes on 2 buildings and 4 remedies), 2 Box2D (the capsule on
    // per-tile and merged colliders): the 17 configurations of compare/baseline/metrics.csv.
    assert_eq!(labels.len(), 17);
    assert_eq!(labels[0], "sweep default");
    assert_eq!(labels[3], "rapier per-tile capsule");
    assert_eq!(labels[15], "box2d per-tile capsule");
    assert_eq!(labels[16], "box2d merged capsule");
}

#[test]
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

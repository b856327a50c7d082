//! A toy controller in two versions under one name: `Toy<false>` as first written, and
//! `Toy<true>`, "changed", which floats a character spawned right of x = 2 a little higher (the
//! `drop` scenario of [`LEVEL`]; `walk` is untouched).

use std::path::Path;
use std::process::ExitCode;

use glam::Vec2;

use platbench::backend::{BackendError, CharacterId, CharacterState};
use platbench::cli::{run_cli, Harness};
use platbench::config::RunConfig;
use platbench::controller::{Controller, Setup};
use platbench::level::Features;
use platbench::motion::{Contacts, Input, MotionParams, MotionState};
use platbench::registry::Registry;

/// The toy: the shared motion over a floor at the highest solid top, `hover` above it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Toy<const CHANGED: bool> {
    hover: f32,
}

pub struct ToyMover {
    floor: f32,
    params: MotionParams,
    chars: Vec<(Vec2, MotionState, f32)>,
}

impl<const CHANGED: bool> Controller for Toy<CHANGED> {
    type Mover = ToyMover;
    const NAME: &'static str = "toy";

    fn features(&self) -> Features {
        Features::NONE
    }

    fn build(&self, setup: Setup<'_>) -> Result<ToyMover, BackendError> {
        let floor = setup
            .level
            .solid_boxes()
            .map(|b| b.maxs.y)
            .fold(f32::MIN, f32::max);
        Ok(ToyMover {
            floor,
            params: setup.params.clone(),
            chars: setup
                .characters
                .iter()
                .map(|c| {
                    let extra = if CHANGED && c.spawn.x > 2.0 {
                        0.05
                    } else {
                        0.0
                    };
                    (c.spawn, MotionState::with_velocity(c.velocity), extra)
                })
                .collect(),
        })
    }

    fn step(&self, m: &mut ToyMover, inputs: &[Input], dt: f32) {
        for (k, (pos, motion, extra)) in m.chars.iter_mut().enumerate() {
            let input = inputs.get(k).copied().unwrap_or_default();
            *pos += motion.integrate(&m.params, &input, dt);
            let floor = m.floor + self.hover + *extra;
            let ground = pos.y <= floor;
            if ground {
                pos.y = floor;
            }
            let contacts = Contacts {
                ground,
                ..Default::default()
            };
            motion.apply_contacts(&m.params, &input, contacts);
        }
    }

    fn state(&self, m: &ToyMover, id: CharacterId) -> CharacterState {
        let (pos, motion, _) = &m.chars[id];
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
            RunConfig::new("flush", Self { hover: 0.0 }),
            RunConfig::new("hover", Self { hover: 0.01 }),
        ]
    }
}

/// A level of two scenarios: `drop` (spawned at x = 2.5) and `walk` (at x = 1.5).
pub const LEVEL: &str = "name = \"plain\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"drop\"\nspawn = [2.5, 2.5]\nduration = 1.0\n[[scenario]]\nname = \"walk\"\nspawn = [1.5, 1.0]\nduration = 1.0\ninputs = [ { t = 0.0, right = true } ]\n";

/// A harness over the toy as first written (`changed` false) or changed, with `baseline`.
pub fn harness(changed: bool, baseline: &Path) -> Harness {
    let registry = if changed {
        Registry::new().with::<Toy<true>>()
    } else {
        Registry::new().with::<Toy<false>>()
    };
    Harness {
        registry,
        baseline: baseline.to_path_buf(),
    }
}

/// Runs the command line `args` on `h`.
pub fn cli(h: &Harness, args: &[&str]) -> ExitCode {
    let mut all = vec!["platbench"];
    all.extend_from_slice(args);
    run_cli(h, all)
}

/// `p` as a string.
pub fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// The rows of `DIR/check.csv` as (`level.scenario`, `backend config`, status).
pub fn statuses(dir: &Path) -> Vec<(String, String, String)> {
    let text = std::fs::read_to_string(dir.join("check.csv")).expect("check.csv");
    let mut r = csv::Reader::from_reader(text.as_bytes());
    r.records()
        .map(|rec| {
            let rec = rec.expect("a check.csv row");
            (
                format!("{}.{}", &rec[0], &rec[1]),
                format!("{} {}", &rec[2], &rec[3]),
                rec[4].to_string(),
            )
        })
        .collect()
}

/// A temporary directory holding the level file; returns (dir, level path).
pub fn setup() -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let level = dir.path().join("plain.toml");
    std::fs::write(&level, LEVEL).expect("level file");
    (dir, level)
}

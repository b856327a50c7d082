//! A controller of your own beside platbench's: a box that moves x then y against the level's
//! solid tiles and stops flush. This file is the README's "Compare your own controller" code,
//! word for word (a test keeps them equal). In your crate it is `src/main.rs`, with these lines
//! in Cargo.toml (platbench cloned beside your crate; glam at platbench's version, as its vectors
//! are in the API):
//!
//! ```toml
//! [dependencies]
//! platbench = { path = "../platbench" }
//! glam = "0.33"
//! ```
//!
//! `cargo run --release` then prints the built-in comparison with a `boxmover` row, and every
//! platbench command takes it: `cargo run --release -- run --backend boxmover,sweep`.

use glam::Vec2;
use platbench::prelude::*;

/// The mover's settings: your own struct, with a `Default` (none here).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BoxMover {}

/// What it keeps while it runs over a level.
pub struct Running {
    params: MotionParams,
    origin: Vec2,
    /// The solid tiles' boxes, (min, max) corners in world coordinates (tiles).
    solids: Vec<(Vec2, Vec2)>,
    /// Per character: feet (bottom centre, world), size, motion.
    chars: Vec<(Vec2, Vec2, MotionState)>,
}

/// How far a box may already overlap a solid and still be stopped by it (tiles).
const SLOP: f32 = 1e-4;

impl Controller for BoxMover {
    type Mover = Running;
    const NAME: &'static str = "boxmover";

    /// Solid tiles only: levels with slopes, one-way platforms, ladders or moving platforms are
    /// skipped for it.
    fn features(&self) -> Features {
        Features::NONE
    }

    fn build(&self, setup: Setup<'_>) -> Result<Running, BackendError> {
        let origin = setup.level.origin_f32();
        let solids = setup.level.solid_boxes();
        let chars = setup.characters.iter();
        Ok(Running {
            params: setup.params.clone(),
            origin,
            solids: solids.map(|b| (b.mins + origin, b.maxs + origin)).collect(),
            chars: chars
                .map(|c| {
                    (
                        c.spawn + origin,
                        c.size,
                        MotionState::with_velocity(c.velocity),
                    )
                })
                .collect(),
        })
    }

    fn step(&self, m: &mut Running, inputs: &[Input], dt: f32) {
        for (k, (feet, size, motion)) in m.chars.iter_mut().enumerate() {
            let input = inputs.get(k).copied().unwrap_or_default();
            let wanted = motion.integrate(&m.params, &input, dt);
            let mut blocked = [false; 2];
            for axis in [0, 1] {
                let other = 1 - axis;
                let lo = *feet - Vec2::new(size.x / 2.0, 0.0);
                let hi = lo + *size;
                let mut to = lo[axis] + wanted[axis];
                for (min, max) in &m.solids {
                    if hi[other] <= min[other] + SLOP || lo[other] >= max[other] - SLOP {
                        continue; // not in this move's way
                    }
                    if wanted[axis] > 0.0 && hi[axis] <= min[axis] + SLOP {
                        let flush = min[axis] - size[axis];
                        blocked[axis] |= to > flush;
                        to = to.min(flush);
                    } else if wanted[axis] < 0.0 && lo[axis] >= max[axis] - SLOP {
                        blocked[axis] |= to < max[axis];
                        to = to.max(max[axis]);
                    }
                }
                feet[axis] = to + if axis == 0 { size.x / 2.0 } else { 0.0 };
            }
            let contacts = Contacts {
                wall: blocked[0],
                ground: blocked[1] && wanted.y < 0.0,
                ceiling: blocked[1] && wanted.y > 0.0,
                one_way: false,
            };
            motion.apply_contacts(&m.params, &input, contacts);
        }
    }

    fn state(&self, m: &Running, id: CharacterId) -> CharacterState {
        let (feet, _, motion) = &m.chars[id];
        CharacterState {
            pos: *feet - m.origin,
            vel: motion.vel,
            grounded: motion.grounded,
            ground_normal: if motion.grounded { Vec2::Y } else { Vec2::ZERO },
            ..Default::default()
        }
    }
}

fn main() -> std::process::ExitCode {
    platbench::cli::main_with(Registry::builtin().with::<BoxMover>())
}

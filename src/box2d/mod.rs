//! The Box2D backend: Box2D v3's character mover (`b2World_CastMover`, `b2World_CollideMover`,
//! `b2SolvePlanes`, `b2ClipVector`, through the `boxdd` bindings) driven as Box2D's own `Mover`
//! sample (`samples/sample_character.cpp` at the Box2D revision boxdd 0.6 pins, 56edae79)
//! drives it.
//!
//! Box2D's docs: "The mover is assumed to be a capsule", so the character is a vertical capsule
//! that floats above the ground on a "pogo stick": each step a short shape cast down from the
//! capsule's lower centre finds the ground, and a spring-damper on its length gives a vertical
//! velocity that holds the capsule at the pogo's rest length ("so it can move up steps"). The
//! shared motion gives the velocity; the target `pos + v dt + pogo_velocity dt` then goes
//! through the sample's loop: collide the capsule with the world for collision planes, solve
//! the planes for a translation, cast the capsule along it, move by the free fraction, and stop
//! once a move is shorter than the tolerance; finally the velocity is clipped against the
//! planes. The character's box is the capsule and its pogo leg: the feet are where the pogo
//! rests.
//!
//! The settings are [`Box2dConfig`]; the bounds Box2D is kept within are [`check_extent`] and
//! [`check_radius`]; the level's shapes are built in [`world`]; one step of the mover is
//! `mover`'s; [`kind`] registers the backend.

mod bounds;
mod config;
pub mod kind;
mod mover;
mod presets;
pub mod world;

use glam::Vec2;

use boxdd::{CollisionPlane, MoverQueryBuffer, RayQueryBuffer};

use crate::backend::{require_supported, BackendError, CharacterId, CharacterSpec, CharacterState};
use crate::level::{Features, Level};
use crate::motion::{Input, MotionParams, MotionState};
pub use crate::shape::CharacterShape;
pub use bounds::{check_extent, check_radius, LINEAR_SLOP, MAX_LEVEL_EXTENT};
pub use config::{
    Box2dConfig, GroundCarry, PogoShape, SAMPLE_CAPSULE_RADIUS, SAMPLE_CAPSULE_SEGMENT,
    SAMPLE_HEIGHT,
};
pub use mover::ONE_WAY_TOLERANCE;
pub use presets::{advised_pogo_hertz, STIFF_POGO_HERTZ};
pub use world::ColliderBuilding;
pub(crate) use world::{LevelWorld, ShapeTag, ONE_WAY, PLATFORM, SOLID};

struct Character {
    /// Feet position (bottom centre of the box, where the pogo rests), world.
    pos: Vec2,
    size: Vec2,
    /// Capsule radius and centres above the feet.
    radius: f32,
    c1: f32,
    c2: f32,
    /// The pogo spring's velocity, tiles/s (the sample's `m_pogoVelocity`).
    pogo_velocity: f32,
    motion: MotionState,
    ground_normal: Vec2,
    riding: Option<u32>,
    one_way_ground: Option<f32>,
    /// Top of the one-way platform being dropped through, until the character is below it.
    drop_top: Option<f32>,
    /// Why Box2D could not move this character (see [`Box2dBackend::failure`]); it stops there.
    failed: Option<String>,
}

/// The Box2D backend over one level.
pub struct Box2dBackend {
    world: LevelWorld,
    frame: u64,
    /// The platforms' time (s): where they stand while the characters move.
    time: f64,
    ladders: Option<Level>,
    origin: Vec2,
    params: MotionParams,
    config: Box2dConfig,
    characters: Vec<Character>,
    planes: Vec<CollisionPlane>,
    mover_hits: MoverQueryBuffer,
    pogo_hits: RayQueryBuffer,
    /// Sum over every step of the plane solver's iterations, for the tests.
    pub solver_iterations: u64,
}

impl Box2dBackend {
    /// What this backend models.
    pub const SUPPORTED: Features = Features::ALL;

    /// Builds the world for `level`; refuses a character shape the mover does not support.
    pub fn new(
        level: &Level,
        params: MotionParams,
        config: Box2dConfig,
    ) -> Result<Self, BackendError> {
        require_supported(kind::NAME, &level.name, level.features, Self::SUPPORTED)?;
        if config.shape != CharacterShape::Capsule {
            return Err(BackendError::Unsupported {
                backend: kind::NAME,
                feature: format!(
                    "the {} character shape (Box2D's mover is a capsule)",
                    config.shape.label()
                ),
                level: level.name.clone(),
                beyond_bound: false,
            });
        }
        params.validate()?;
        config.validate()?;
        check_extent(level)?;
        Ok(Box2dBackend {
            // Should Box2D refuse a valid level's geometry (a polygon or chain it finds
            // degenerate), it cannot model it: Unsupported, naming what Box2D said.
            world: LevelWorld::new(level, config.colliders).map_err(|e| match e {
                BackendError::InvalidParameter { name, value, .. } => BackendError::Unsupported {
                    backend: kind::NAME,
                    feature: format!(
                        "this level's geometry, which Box2D refuses ({name}: {value})"
                    ),
                    level: level.name.clone(),
                    beyond_bound: false,
                },
                e => e,
            })?,
            frame: 0,
            time: 0.0,
            ladders: level.features.ladders.then(|| level.geometry()),
            origin: level.origin_f32(),
            params,
            config,
            characters: Vec::new(),
            planes: Vec::with_capacity(8),
            mover_hits: MoverQueryBuffer::new(),
            pogo_hits: RayQueryBuffer::new(),
            solver_iterations: 0,
        })
    }

    /// The settings this backend runs with.
    pub fn config(&self) -> &Box2dConfig {
        &self.config
    }

    /// Number of static shapes (boxes, polygons, chains) built for the level.
    pub fn static_shape_count(&self) -> usize {
        self.world.static_shapes
    }

    /// Why Box2D could not move character `id`, if it could not: boxdd refused a query's
    /// output (a hit with no normal, say). The character then stops and its state is
    /// non-finite, so that no metric reads a position Box2D did not compute. The one such
    /// output seen, an f32 shape cast ending at a distance of exactly 0 far from the origin,
    /// is kept from happening ([`MAX_LEVEL_EXTENT`], [`LevelWorld`]): Box2D asserts on it
    /// (`b2ShapeCast` in distance.c), and a dependent's build compiles the assert in.
    pub fn failure(&self, id: CharacterId) -> Option<&str> {
        self.characters.get(id).and_then(|c| c.failed.as_deref())
    }
}

impl Box2dBackend {
    /// Adds a character and returns its id; refuses a non-finite spawn or velocity, or a size
    /// that is not positive.
    pub fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        check_radius(&self.config, spec.size)?;
        let (radius, c1, c2) = self.config.capsule(spec.size);
        self.characters.push(Character {
            pos: spec.spawn + self.origin,
            size: spec.size,
            radius,
            c1,
            c2,
            pogo_velocity: 0.0,
            motion: MotionState::with_velocity(spec.velocity),
            ground_normal: Vec2::ZERO,
            riding: None,
            one_way_ground: None,
            drop_top: None,
            failed: None,
        });
        Ok(self.characters.len() - 1)
    }

    /// Platforms first, as the sample steps its world (moving the elevator) before the mover.
    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    pub fn step(&mut self, inputs: &[Input], dt: f32) {
        let t1 = (self.frame + 1) as f64 * dt as f64;
        if let Err(e) = self.world.step_platforms(t1, dt) {
            panic!("box2d platform step on validated geometry failed: {e}");
        }
        self.time = t1;
        for id in 0..self.characters.len() {
            if self.characters[id].failed.is_some() {
                continue;
            }
            let input = inputs.get(id).copied().unwrap_or_default();
            if let Err(e) = self.step_character(id, &input, dt) {
                self.characters[id].failed = Some(e.to_string());
            }
        }
        self.frame += 1;
    }

    /// The state of character `id` after the last step, in level coordinates.
    pub fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        // A character Box2D could not move has no position to report.
        let (pos, vel) = match c.failed {
            Some(_) => (Vec2::NAN, Vec2::NAN),
            None => (c.pos - self.origin, c.motion.vel),
        };
        CharacterState {
            pos,
            vel,
            grounded: c.motion.grounded,
            ground_normal: c.ground_normal,
            platform: c.riding,
            ladder: c.motion.on_ladder,
            crushed: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::parse_level;

    fn flat() -> Level {
        parse_level(
            "map = \"\"\"\n..........\n..........\n..........\n##########\n\"\"\"\n",
            "flat.toml",
        )
        .unwrap()
    }

    #[test]
    fn other_shapes_are_refused() {
        let config = Box2dConfig {
            shape: CharacterShape::Cuboid,
            ..Default::default()
        };
        let err = Box2dBackend::new(&flat(), MotionParams::default(), config).err();
        assert!(
            matches!(err, Some(BackendError::Unsupported { .. })),
            "{err:?}"
        );
    }

    #[test]
    fn stands_on_flat_ground_on_both_buildings() {
        for colliders in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            let config = Box2dConfig {
                colliders,
                ..Default::default()
            };
            let mut b = Box2dBackend::new(&flat(), MotionParams::default(), config).unwrap();
            let id = b
                .add_character(CharacterSpec {
                    spawn: Vec2::new(5.0, 2.0),
                    size: Vec2::new(0.8, 0.9),
                    velocity: Vec2::ZERO,
                })
                .unwrap();
            for _ in 0..180 {
                b.step(&[Input::default()], 1.0 / 60.0);
            }
            let s = b.state(id);
            assert!(s.grounded, "{colliders:?}: {s:?}");
            // The pogo holds the feet near the ground's top (y = 1) after 3 s: the spring's sag
            // under gravity is 0.029 tiles (derived in tests/controllers/box2d.rs); a tenth of a tile
            // bounds it loosely.
            assert!(
                (s.pos.y - 1.0).abs() < ONE_WAY_TOLERANCE,
                "{colliders:?}: {s:?}"
            );
            assert!((s.pos.x - 5.0).abs() < 1e-4, "{colliders:?}: {s:?}");
        }
    }
}

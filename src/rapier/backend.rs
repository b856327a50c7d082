//! The Rapier backend proper: the character, its step through `move_shape`, the one-way filter,
//! the spawn lift. Compiled once per precision against `super::precision`: the engine crate
//! (`engine`), its scalar (`Real`) and vector (`Vect`), and the conversions `v`, `s` and `back`
//! from and to the harness's f32 level coordinates, which are identities in the f32 build, so
//! that build runs the arithmetic it always ran.

use std::rc::Rc;

use glam::Vec2;

use super::precision::{back, engine, level_origin, s, v, Real, Vect};
use super::precision::{ladder_enter, ladder_leave, NAME};
use super::{
    one_way_top, CharacterShape, GroundedMove, Length, PlatformCarry, PlatformOrder, Platforms,
    RapierConfig, StaticWorld, CLIMB_LIMIT_MARGIN, GROUND_PREDICTION, ONE_WAY_TOLERANCE,
};
use crate::backend::{require_supported, BackendError, CharacterId, CharacterSpec, CharacterState};
use crate::level::{Features, Level};
use crate::motion::{Contacts, Input, MotionParams, MotionState};
use crate::oneway::{drop_over, drop_start, OneWayCheck};
use crate::shape::ShapeParams;
use engine::control::{CharacterAutostep, CharacterLength, KinematicCharacterController};
use engine::parry::math::Pose;
use engine::parry::query::DefaultQueryDispatcher;
use engine::prelude::{QueryFilter, SharedShape};

impl From<Length> for CharacterLength {
    fn from(l: Length) -> Self {
        match l {
            Length::Absolute(x) => CharacterLength::Absolute(s(x)),
            Length::Relative(x) => CharacterLength::Relative(s(x)),
        }
    }
}

/// The controller `config` describes, for motion parameters `p`, on this build's engine.
pub fn controller(config: &RapierConfig, p: &MotionParams) -> KinematicCharacterController {
    KinematicCharacterController {
        up: Vect::Y,
        offset: config.offset.into(),
        slide: config.slide,
        autostep: config.autostep.map(|(h, w)| CharacterAutostep {
            max_height: h.into(),
            min_width: w.into(),
            include_dynamic_bodies: false,
        }),
        max_slope_climb_angle: s(config
            .max_slope_climb_angle
            .unwrap_or(p.max_climb_angle + CLIMB_LIMIT_MARGIN)),
        min_slope_slide_angle: s(config
            .min_slope_slide_angle
            .unwrap_or(p.max_climb_angle + CLIMB_LIMIT_MARGIN)),
        snap_to_ground: config.snap_to_ground.map(Into::into),
        normal_nudge_factor: s(config.normal_nudge_factor),
    }
}

/// The engine's shape for `shape` fitted to a character of outer `size` (tiles), with the
/// dimensions [`CharacterShape::params`] gives every engine.
pub fn build_shape(shape: CharacterShape, size: Vec2) -> SharedShape {
    match shape.params(size) {
        ShapeParams::Cuboid { half } => SharedShape::cuboid(s(half.x), s(half.y)),
        ShapeParams::Capsule {
            half_segment,
            radius,
        } => SharedShape::capsule_y(s(half_segment), s(radius)),
        ShapeParams::Ball { radius } => SharedShape::ball(s(radius)),
        ShapeParams::RoundCuboid { half, border } => {
            SharedShape::round_cuboid(s(half.x), s(half.y), s(border))
        }
    }
}

/// The pose of the shape's centre for a character of outer `size` whose feet (bottom centre)
/// are at `feet` (world), as [`CharacterShape::pose`] in this build's precision.
pub fn pose(feet: Vect, size: Vec2) -> Pose {
    Pose::from_translation(feet + Vect::new(0.0, s(size.y * 0.5)))
}

/// What one call of the controller did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Move {
    /// Translation applied, in tiles.
    pub translation: Vect,
    /// Whether the controller reports the character grounded after the move.
    pub grounded: bool,
    /// The contacts seen in the controller's collision events.
    pub contacts: Contacts,
    /// Normal of the ground hit, if any.
    pub ground_normal: Option<Vect>,
    /// Top of the one-way platform hit as ground, if any.
    pub one_way_top: Option<Real>,
    /// The rigid body (a moving platform) of the ground hit, if it has one.
    pub ground_body: Option<engine::prelude::RigidBodyHandle>,
}

struct Character {
    /// Feet position (bottom centre), in Rapier's world coordinates.
    pos: Vect,
    /// The moving platform it stood on after its last move.
    riding: Option<u32>,
    /// Top of the one-way platform being dropped through, until the character is below it.
    drop_top: Option<Real>,
    /// Top of the one-way platform stood on, if any.
    one_way_ground: Option<Real>,
    size: Vec2,
    shape: SharedShape,
    motion: MotionState,
    ground_normal: Vect,
}

/// The Rapier backend over one level.
pub struct RapierBackend {
    world: Rc<StaticWorld>,
    /// Moving platforms (kinematic bodies in this backend's own copy of the world), if any.
    platforms: Option<Platforms>,
    /// Steps taken, for the platforms' time.
    frame: u64,
    /// The level's grid, kept only when it has ladders (for the shared ladder rules).
    ladders: Option<Level>,
    /// The level's corner in Rapier's world.
    origin: Vect,
    dispatcher: DefaultQueryDispatcher,
    controller: KinematicCharacterController,
    params: MotionParams,
    config: RapierConfig,
    characters: Vec<Character>,
}

impl RapierBackend {
    /// What this backend models today.
    pub const SUPPORTED: Features = Features::ALL;

    /// Builds the colliders for `level`; refuses levels with features it does not model.
    pub fn new(
        level: &Level,
        params: MotionParams,
        config: RapierConfig,
    ) -> Result<Self, BackendError> {
        let world = Rc::new(StaticWorld::new(level, config.colliders));
        Self::with_world(level, world, params, config)
    }

    /// Runs over colliders already built for `level` with `config.colliders` (see
    /// [`StaticWorld::new`]), so that several configurations share one level build.
    pub fn with_world(
        level: &Level,
        world: Rc<StaticWorld>,
        params: MotionParams,
        config: RapierConfig,
    ) -> Result<Self, BackendError> {
        require_supported(NAME, &level.name, level.features, Self::SUPPORTED)?;
        params.validate()?;
        let controller = controller(&config, &params);
        let mut world = world;
        let platforms =
            (!level.platforms.is_empty()).then(|| Platforms::new(level, Rc::make_mut(&mut world)));
        Ok(RapierBackend {
            world,
            platforms,
            frame: 0,
            ladders: level.features.ladders.then(|| level.geometry()),
            origin: level_origin(level),
            dispatcher: DefaultQueryDispatcher,
            controller,
            params,
            config,
            characters: Vec::new(),
        })
    }

    /// The settings this backend runs with.
    pub fn config(&self) -> &RapierConfig {
        &self.config
    }

    /// Number of static colliders built for the level.
    pub fn collider_count(&self) -> usize {
        self.world.colliders.len()
    }

    /// Adds a static collider (in Rapier's world coordinates) beside the level's tiles and
    /// updates the broad phase so queries see it: for scenes that tiles cannot express, such
    /// as the rotated-cuboid slopes of Rapier's own tests.
    pub fn insert_static_collider(&mut self, collider: engine::prelude::Collider) {
        Rc::make_mut(&mut self.world).insert(collider);
    }

    /// Moves character `id` by `desired` through the controller, bypassing the shared motion:
    /// the raw `move_shape` call, for reproducing Rapier's own tests.
    pub fn move_raw(&mut self, id: CharacterId, desired: Vect, dt: f32) -> Move {
        let m = self.move_shape(id, desired, dt);
        self.characters[id].pos += m.translation;
        m
    }

    /// The level's colliders as Rapier's query pipeline sees them, unfiltered.
    fn queries(&self) -> engine::prelude::QueryPipeline<'_> {
        let w = &self.world;
        w.broad_phase.as_query_pipeline(
            &self.dispatcher,
            &w.bodies,
            &w.colliders,
            QueryFilter::default(),
        )
    }

    fn move_shape(&self, id: CharacterId, desired: Vect, dt: f32) -> Move {
        let c = &self.characters[id];
        let w = &self.world;
        let queries = self.queries();
        let start = pose(c.pos, c.size);
        // One-way platforms, as Rapier users write them: a filter predicate that keeps a one-way
        // collider only for a character entirely above its top at the start of the move, and
        // never for one dropping through it.
        let one_way = OneWayCheck {
            feet: c.pos.y,
            tolerance: s(ONE_WAY_TOLERANCE),
            passes_all: c.motion.on_ladder,
            dropping_through: c.drop_top,
        };
        let one_way_rule = move |_: engine::prelude::ColliderHandle,
                                 co: &engine::prelude::Collider| {
            one_way_top(co).is_none_or(|top| one_way.blocks(top))
        };
        let queries = queries.with_filter(QueryFilter::default().predicate(&one_way_rule));
        let mut contacts = Contacts::default();
        let mut ground_normal: Option<Vect> = None;
        let mut ground_one_way: Option<Real> = None;
        let mut ground_body: Option<engine::prelude::RigidBodyHandle> = None;
        let mvt = self
            .controller
            .move_shape(s(dt), &queries, &*c.shape, &start, desired, |hit| {
                // The obstacle's surface normal, as Rapier's controller itself reads it
                // (`is_ceiling = up.dot(normal1) < 0` in its source).
                let n = hit.hit.normal1;
                if n.y > 0.5 {
                    ground_normal = Some(n);
                    let co = w.colliders.get(hit.handle);
                    ground_one_way = co.and_then(one_way_top);
                    ground_body = co.and_then(|co| co.parent());
                } else if n.y < -0.5 {
                    contacts.ceiling = true;
                } else if n.x * desired.x < 0.0 {
                    contacts.wall = true;
                }
            });
        // Rapier reports grounded from contacts within its prediction distance, but names the
        // ground only through a cast that hit it. A step that asked for no vertical move (see
        // `GroundedMove`) casts nothing down, so what it stands on (a one-way top, a platform,
        // the slope's normal) is found by a read-only cast down over that distance, through
        // the same filter. It changes no position.
        if mvt.grounded && ground_normal.is_none() {
            let reach = s(self.config.offset.eval(c.size.y) + GROUND_PREDICTION);
            let after = pose(c.pos + mvt.translation, c.size);
            let options = engine::parry::query::ShapeCastOptions {
                max_time_of_impact: reach,
                target_distance: 0.0,
                stop_at_penetration: false,
                compute_impact_geometry_on_penetration: true,
            };
            if let Some((handle, hit)) = queries.cast_shape(&after, -Vect::Y, &*c.shape, options) {
                if hit.normal1.y > 0.5 {
                    ground_normal = Some(hit.normal1);
                    let co = w.colliders.get(handle);
                    ground_one_way = co.and_then(one_way_top);
                    ground_body = co.and_then(|co| co.parent());
                }
            }
        }
        contacts.ground = mvt.grounded;
        contacts.one_way = ground_one_way.is_some();
        Move {
            one_way_top: ground_one_way,
            ground_body,
            translation: mvt.translation,
            grounded: mvt.grounded,
            contacts,
            ground_normal,
        }
    }

    /// Moves the platforms to their place at the end of this step.
    fn step_platforms(&mut self, dt: f32) {
        if let Some(p) = &mut self.platforms {
            let t1 = (self.frame + 1) as f64 * dt as f64;
            p.step_to(Rc::make_mut(&mut self.world), t1, dt);
        }
    }

    /// How far a character of `shape` at feet `pos` must rise to stand at least the offset
    /// above what is below it: a character spawned flush on the ground starts inside the
    /// offset band, where Rapier's casts report it touching and its depenetration (which runs
    /// only for overlaps) never lifts it. A cast down from `offset` above the spawn finds the
    /// ground within twice the offset.
    fn spawn_lift(&self, pos: Vect, size: Vec2, shape: &SharedShape) -> Real {
        let offset = s(self.config.offset.eval(size.y));
        let queries = self.queries();
        let from = pose(pos + Vect::new(0.0, offset), size);
        let options = engine::parry::query::ShapeCastOptions {
            max_time_of_impact: 2.0 * offset,
            target_distance: 0.0,
            stop_at_penetration: true,
            compute_impact_geometry_on_penetration: false,
        };
        match queries.cast_shape(&from, -Vect::Y, &**shape, options) {
            Some((_, hit)) => (2.0 * offset - hit.time_of_impact).max(0.0),
            None => 0.0,
        }
    }

    fn step_character(&mut self, id: CharacterId, input: &Input, dt: f32) {
        let c = &mut self.characters[id];
        if let Some(level) = &self.ladders {
            ladder_enter(level, self.origin, &mut c.motion, &mut c.pos, c.size, input);
        }
        let was_grounded = c.motion.grounded;
        let mut desired = v(c.motion.integrate(&self.params, input, dt));
        // A grounded step that does not jump, climb or drop through: the vertical move is fed
        // as `grounded_move` says.
        if was_grounded && desired.y <= 0.0 && !c.motion.on_ladder && !c.motion.drop_through {
            match self.config.grounded_move {
                GroundedMove::Gravity => {}
                GroundedMove::None => desired.y = 0.0,
                GroundedMove::NoneExceptOnPlatforms if c.riding.is_none() => desired.y = 0.0,
                GroundedMove::NoneExceptOnPlatforms => {}
                GroundedMove::Constant(speed) => desired.y = s(-speed * dt),
                GroundedMove::Testbed => desired.y = s(-self.params.run_speed * dt),
                GroundedMove::NoneExceptTestbedOnPlatforms if c.riding.is_none() => desired.y = 0.0,
                GroundedMove::NoneExceptTestbedOnPlatforms => {
                    desired.y = s(-self.params.run_speed * dt)
                }
            }
        }
        // The carry Rapier users add: the platform's coming displacement, when grounded on it.
        if let (Some(i), Some(p), PlatformCarry::ControllerPlusDisplacement) =
            (c.riding, &self.platforms, self.config.platform_carry)
        {
            let t0 = self.frame as f64 * dt as f64;
            desired += p.displacement(i as usize, t0, t0 + dt as f64);
        }
        c.drop_top = drop_start(c.drop_top, c.motion.drop_through, c.one_way_ground);
        let m = self.move_shape(id, desired, dt);
        let c = &mut self.characters[id];
        c.pos += m.translation;
        let mut contacts = m.contacts;
        // A rising character that the controller still calls grounded (the take-off frame)
        // keeps its jump: only a downward or level move lands.
        contacts.ground = m.grounded && desired.y <= 0.0;
        // A wall or ceiling counts only if it blocked the move toward it.
        contacts.wall &= m.translation.x.abs() < desired.x.abs() - 1e-6;
        contacts.ceiling &= desired.y > 0.0 && m.translation.y < desired.y;
        c.motion.apply_contacts(&self.params, input, contacts);
        if let Some(level) = &self.ladders {
            ladder_leave(level, self.origin, &mut c.motion, c.pos, c.size, input);
        }
        c.one_way_ground = if contacts.ground { m.one_way_top } else { None };
        c.riding = match (&self.platforms, m.ground_body) {
            (Some(p), Some(body)) if contacts.ground => {
                p.bodies.iter().position(|b| *b == body).map(|i| i as u32)
            }
            _ => None,
        };
        // The drop ends once the character is wholly below the platform it left.
        c.drop_top = drop_over(c.drop_top, c.pos.y + s(c.size.y));
        c.ground_normal = if contacts.ground {
            m.ground_normal.unwrap_or(Vect::Y)
        } else {
            Vect::ZERO
        };
    }
}

impl RapierBackend {
    /// Adds a character and returns its id; refuses a non-finite spawn or velocity, or a size
    /// that is not positive.
    pub fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        let shape = build_shape(self.config.shape, spec.size);
        let pos = v(spec.spawn) + self.origin;
        let lift = if self.config.lift_spawn {
            self.spawn_lift(pos, spec.size, &shape)
        } else {
            0.0
        };
        let pos = pos + Vect::new(0.0, lift);
        self.characters.push(Character {
            pos,
            riding: None,
            drop_top: None,
            one_way_ground: None,
            size: spec.size,
            shape,
            motion: MotionState::with_velocity(spec.velocity),
            ground_normal: Vect::ZERO,
        });
        Ok(self.characters.len() - 1)
    }

    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    pub fn step(&mut self, inputs: &[Input], dt: f32) {
        let order = self.config.platform_order;
        if order == PlatformOrder::BeforeCharacters {
            self.step_platforms(dt);
        }
        for id in 0..self.characters.len() {
            let input = inputs.get(id).copied().unwrap_or_default();
            self.step_character(id, &input, dt);
        }
        if order == PlatformOrder::AfterCharacters {
            self.step_platforms(dt);
        }
        self.frame += 1;
    }

    /// The state of character `id` after the last step, in level coordinates.
    pub fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        CharacterState {
            pos: back(c.pos - self.origin),
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            ground_normal: back(c.ground_normal),
            platform: c.riding,
            ladder: c.motion.on_ladder,
            crushed: false,
        }
    }
}

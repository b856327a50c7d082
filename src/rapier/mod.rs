//! The rapier2d backend: `KinematicCharacterController::move_shape` over the level's colliders,
//! set up the way Rapier's docs and examples do it.
//!
//! Each frame, per character: the shared motion integrates the velocity (gravity accumulates
//! while airborne), the desired translation `v * dt` goes to `move_shape` through the broad
//! phase's `QueryPipeline`, the returned translation is added to the position, and the result is
//! fed back as Rapier's examples do: when grounded the vertical velocity is reset. A ceiling hit
//! that blocked a rising move also resets it (as any platformer must, or the character sticks
//! under the ceiling until gravity wins). A wall that blocked the horizontal move goes through
//! the same shared rule as the sweep's: it stops a coasting character, while held input keeps
//! driving one steered into it. That rule matters for Rapier: its controller reports the
//! internal edges of a per-tile floor as wall contacts, and a walker that lost its speed on each
//! of them would pay our acceleration ramp on top of Rapier's snag. No rigid-body simulation
//! runs: the level has only static colliders.

pub mod colliders;
pub mod kind;
pub mod platforms;

use std::rc::Rc;

use glam::Vec2;
use rapier2d::control::{CharacterAutostep, CharacterLength, KinematicCharacterController};
use rapier2d::parry::query::DefaultQueryDispatcher;
use rapier2d::prelude::{QueryFilter, SharedShape};

use crate::backend::{
    require_supported, Backend, BackendError, CharacterId, CharacterSpec, CharacterState,
};
use crate::level::{Features, Level};
use crate::motion::{Contacts, Input, MotionParams, MotionState};
pub use crate::shape::CharacterShape;
pub use colliders::{one_way_top, ColliderBuilding, StaticWorld};
pub use platforms::{PlatformCarry, Platforms};

/// Added to [`MotionParams::max_climb_angle`] for Rapier's climb and slide angles, in radians.
/// Rapier calls a slope at exactly its limit a wall (`angle >= max_slope_climb_angle`) and
/// slides on one past it, while the shared limit is the steepest walkable, non-slipping slope.
/// Rapier's own climb test puts 0.001 rad around its limit, on exact rotated cuboids; on a
/// merged polyline the contact normals of a 45-degree ramp scatter by about 0.003 rad, so with
/// 0.001 rad the ramp tips past the slide limit on some steps and a resting character creeps
/// down it. 0.01 rad (0.57 degrees) clears that scatter.
pub const CLIMB_LIMIT_MARGIN: f32 = 1e-2;

/// How far beyond its offset Rapier's controller looks for ground, in tiles: its
/// `predict_ground` adds this absolute 0.05 to the offset (rapier2d 0.36.1).
pub const GROUND_PREDICTION: f32 = 0.05;

/// How far below a one-way platform's top the feet may start a move and still land on it, in
/// tiles: rounding only (Rapier keeps its offset above the top when standing on it).
pub const ONE_WAY_TOLERANCE: f32 = 1e-3;

/// A length that is either absolute (tiles) or relative to the character's height, as Rapier's
/// `CharacterLength`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// In tiles.
    Absolute(f32),
    /// As a fraction of the character's height.
    Relative(f32),
}

impl Length {
    /// The length in tiles for a character `height` tiles tall (Rapier evaluates relative
    /// lengths against the height of the shape's bounding box, which is the box's here).
    pub fn eval(self, height: f32) -> f32 {
        match self {
            Length::Absolute(v) => v,
            Length::Relative(v) => v * height,
        }
    }
}

impl From<Length> for CharacterLength {
    fn from(l: Length) -> Self {
        match l {
            Length::Absolute(v) => CharacterLength::Absolute(v),
            Length::Relative(v) => CharacterLength::Relative(v),
        }
    }
}

/// How a grounded step's vertical move is fed to the controller. Rapier leaves this to its
/// users, and its own examples differ; the choice decides whether a box sticks on a long merged
/// floor (rapier #613: a cast at a glancing angle can miss the offset band).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GroundedMove {
    /// Gravity every step: the shared motion's vertical velocity, reset to 0 when grounded, so
    /// each grounded step asks to move down by `g * dt²`. What a game that integrates its own
    /// gravity and hands the controller `v * dt` does (Rapier's docs leave the vertical move to
    /// the user); the set-up `shared/reference/rapier-kcc-0.36.1.md` measured.
    Gravity,
    /// No vertical move while grounded (a jump still rises): the official bevy_rapier character
    /// example (`bevy_rapier3d/examples/character_controller3.rs`) zeroes its vertical movement
    /// when the controller reports grounded and only then adds gravity for the next frame.
    /// Snap-to-ground follows the ground down slopes. The controller's own carry on a moving
    /// platform stops with it: Rapier carries a rider only after a cast hit.
    None,
    /// As [`GroundedMove::None`], except on a moving platform (a kinematic body), where
    /// gravity is fed so that the controller's cast hits the platform and its carry runs.
    NoneExceptOnPlatforms,
    /// A constant push down while grounded, in tiles/s (the step asks for `speed * dt`): Rapier's
    /// own 2D testbed example (`examples2d/utils/character.rs`) subtracts its walking speed from
    /// the vertical move every step, its "artificial gravity".
    Constant(f32),
}

impl GroundedMove {
    /// Short label for configuration names.
    pub fn label(self) -> String {
        match self {
            GroundedMove::Gravity => "gravity".into(),
            GroundedMove::None => "none".into(),
            GroundedMove::NoneExceptOnPlatforms => "none-but-platforms".into(),
            GroundedMove::Constant(v) => format!("push{v}"),
        }
    }
}

/// When moving platforms move within a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlatformOrder {
    /// After every character has moved: the seed's order, the sweep's.
    AfterCharacters,
    /// Before the characters move: the platform's velocity the controller carries with is then
    /// the one of this step's displacement, not the step before's.
    BeforeCharacters,
}

/// Settings of the Rapier backend: every option of Rapier's `KinematicCharacterController`,
/// with Rapier's own defaults, plus how the level and the character are built.
#[derive(Clone, Debug, PartialEq)]
pub struct RapierConfig {
    /// How solid tiles become colliders.
    pub colliders: ColliderBuilding,
    /// The character's collision shape, fitted to its box. Default: a capsule, the shape of
    /// Rapier's own 2D character-controller example (`examples2d/character_controller2.rs`).
    pub shape: CharacterShape,
    /// Gap the controller keeps between the character and obstacles. Rapier's default, 1% of
    /// the character's height; Rapier's docs advise a small non-zero value for numerical
    /// stability, so `rest_gap` is about this value by design.
    pub offset: Length,
    /// Whether the character slides along what it hits (Rapier's default: on).
    pub slide: bool,
    /// Automatic stepping over small obstacles (Rapier's default: off, "computationally
    /// expensive"): maximum step height and minimum free width on top.
    pub autostep: Option<(Length, Length)>,
    /// Steepest slope the character can climb, in radians; `None` takes
    /// [`MotionParams::max_climb_angle`] plus [`CLIMB_LIMIT_MARGIN`] (Rapier's default is 45
    /// degrees, as is ours).
    pub max_slope_climb_angle: Option<f32>,
    /// Slope angle from which the character slides down, in radians; `None` takes
    /// [`MotionParams::max_climb_angle`] plus [`CLIMB_LIMIT_MARGIN`] (Rapier's default is 45
    /// degrees).
    pub min_slope_slide_angle: Option<f32>,
    /// Snap to the ground when it is closer than this below the feet (Rapier's default: 20% of
    /// the character's height); `None` disables snapping.
    pub snap_to_ground: Option<Length>,
    /// Nudge along contact normals that keeps shape casts from sticking while sliding, in
    /// tiles (Rapier's default: 1e-4).
    pub normal_nudge_factor: f32,
    /// How a rider is carried by a moving platform. Default: the controller's own carry, which
    /// the reference measured exact horizontally; adding the displacement too over-carries.
    pub platform_carry: PlatformCarry,
    /// How a grounded step's vertical move is fed (default: gravity every step).
    pub grounded_move: GroundedMove,
    /// Whether a character spawned closer than the offset above the ground is raised to the
    /// offset (default: on). Spawned flush, it would start inside the offset band, where
    /// Rapier's casts see it touching and its depenetration (which runs only for overlaps)
    /// never lifts it; a Rapier user places the character clear of the ground. Off only to
    /// reproduce a scene placed exactly, such as Rapier's own tests.
    pub lift_spawn: bool,
    /// When moving platforms move within a step. Default: before the characters, which
    /// `examples/rapier_setups.rs` measured to carry better than the seed's order (the
    /// controller carries with the platform velocity of the step it moves in, not the step
    /// before's).
    pub platform_order: PlatformOrder,
}

impl Default for RapierConfig {
    fn default() -> Self {
        let kcc = KinematicCharacterController::default();
        RapierConfig {
            colliders: ColliderBuilding::PerTile,
            shape: CharacterShape::Capsule,
            offset: Length::Relative(0.01),
            slide: kcc.slide,
            autostep: None,
            max_slope_climb_angle: None,
            min_slope_slide_angle: None,
            snap_to_ground: Some(Length::Relative(0.2)),
            normal_nudge_factor: kcc.normal_nudge_factor,
            platform_carry: PlatformCarry::Controller,
            grounded_move: GroundedMove::Gravity,
            lift_spawn: true,
            platform_order: PlatformOrder::BeforeCharacters,
        }
    }
}

impl RapierConfig {
    /// The controller these settings describe, for motion parameters `p`.
    pub fn controller(&self, p: &MotionParams) -> KinematicCharacterController {
        KinematicCharacterController {
            up: Vec2::Y,
            offset: self.offset.into(),
            slide: self.slide,
            autostep: self.autostep.map(|(h, w)| CharacterAutostep {
                max_height: h.into(),
                min_width: w.into(),
                include_dynamic_bodies: false,
            }),
            max_slope_climb_angle: self
                .max_slope_climb_angle
                .unwrap_or(p.max_climb_angle + CLIMB_LIMIT_MARGIN),
            min_slope_slide_angle: self
                .min_slope_slide_angle
                .unwrap_or(p.max_climb_angle + CLIMB_LIMIT_MARGIN),
            snap_to_ground: self.snap_to_ground.map(Into::into),
            normal_nudge_factor: self.normal_nudge_factor,
        }
    }

    /// Short label for tables and file names: the collider building and the shape, then how
    /// a grounded step is fed when that is not gravity.
    pub fn label(&self) -> String {
        let mut label = format!("{} {}", self.colliders.label(), self.shape.label());
        if self.grounded_move != GroundedMove::Gravity {
            label += " grounded=";
            label += &self.grounded_move.label();
        }
        label
    }
}

/// What one call of the controller did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Move {
    /// Translation applied, in tiles.
    pub translation: Vec2,
    /// Whether the controller reports the character grounded after the move.
    pub grounded: bool,
    /// The contacts seen in the controller's collision events.
    pub contacts: Contacts,
    /// Normal of the ground hit, if any.
    pub ground_normal: Option<Vec2>,
    /// Top of the one-way platform hit as ground, if any.
    pub one_way_top: Option<f32>,
    /// The rigid body (a moving platform) of the ground hit, if it has one.
    pub ground_body: Option<rapier2d::prelude::RigidBodyHandle>,
}

struct Character {
    /// Feet position (bottom centre), in Rapier's world coordinates.
    pos: Vec2,
    /// The moving platform it stood on after its last move.
    riding: Option<u32>,
    /// Top of the one-way platform being dropped through, until the character is below it.
    drop_top: Option<f32>,
    /// Top of the one-way platform stood on, if any.
    one_way_ground: Option<f32>,
    size: Vec2,
    shape: SharedShape,
    motion: MotionState,
    ground_normal: Vec2,
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
    origin: Vec2,
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
        require_supported("rapier", &level.name, level.features, Self::SUPPORTED)?;
        params.validate()?;
        let controller = config.controller(&params);
        let mut world = world;
        let platforms =
            (!level.platforms.is_empty()).then(|| Platforms::new(level, Rc::make_mut(&mut world)));
        Ok(RapierBackend {
            world,
            platforms,
            frame: 0,
            ladders: level.features.ladders.then(|| level.geometry()),
            origin: level.origin,
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
    pub fn insert_static_collider(&mut self, collider: rapier2d::prelude::Collider) {
        Rc::make_mut(&mut self.world).insert(collider);
    }

    /// Moves character `id` by `desired` through the controller, bypassing the shared motion:
    /// the raw `move_shape` call, for reproducing Rapier's own tests.
    pub fn move_raw(&mut self, id: CharacterId, desired: Vec2, dt: f32) -> Move {
        let m = self.move_shape(id, desired, dt);
        self.characters[id].pos += m.translation;
        m
    }

    /// The level's colliders as Rapier's query pipeline sees them, unfiltered.
    fn queries(&self) -> rapier2d::prelude::QueryPipeline<'_> {
        let w = &self.world;
        w.broad_phase.as_query_pipeline(
            &self.dispatcher,
            &w.bodies,
            &w.colliders,
            QueryFilter::default(),
        )
    }

    fn move_shape(&self, id: CharacterId, desired: Vec2, dt: f32) -> Move {
        let c = &self.characters[id];
        let w = &self.world;
        let queries = self.queries();
        let pose = CharacterShape::pose(c.pos, c.size);
        // One-way platforms, as Rapier users write them: a filter predicate that keeps a one-way
        // collider only for a character entirely above its top at the start of the move, and
        // never for one dropping through it.
        let feet = c.pos.y;
        let drop_top = c.drop_top;
        let on_ladder = c.motion.on_ladder;
        let one_way_rule = move |_: rapier2d::prelude::ColliderHandle,
                                 co: &rapier2d::prelude::Collider| {
            match one_way_top(co) {
                None => true,
                Some(top) => !on_ladder && feet >= top - ONE_WAY_TOLERANCE && drop_top != Some(top),
            }
        };
        let queries = queries.with_filter(QueryFilter::default().predicate(&one_way_rule));
        let mut contacts = Contacts::default();
        let mut ground_normal: Option<Vec2> = None;
        let mut ground_one_way: Option<f32> = None;
        let mut ground_body: Option<rapier2d::prelude::RigidBodyHandle> = None;
        let mvt = self
            .controller
            .move_shape(dt, &queries, &*c.shape, &pose, desired, |hit| {
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
            let reach = self.config.offset.eval(c.size.y) + GROUND_PREDICTION;
            let after = CharacterShape::pose(c.pos + mvt.translation, c.size);
            let options = rapier2d::parry::query::ShapeCastOptions {
                max_time_of_impact: reach,
                target_distance: 0.0,
                stop_at_penetration: false,
                compute_impact_geometry_on_penetration: true,
            };
            if let Some((handle, hit)) = queries.cast_shape(&after, -Vec2::Y, &*c.shape, options) {
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
    fn spawn_lift(&self, pos: Vec2, size: Vec2, shape: &SharedShape) -> f32 {
        let offset = self.config.offset.eval(size.y);
        let queries = self.queries();
        let from = CharacterShape::pose(pos + Vec2::new(0.0, offset), size);
        let options = rapier2d::parry::query::ShapeCastOptions {
            max_time_of_impact: 2.0 * offset,
            target_distance: 0.0,
            stop_at_penetration: true,
            compute_impact_geometry_on_penetration: false,
        };
        match queries.cast_shape(&from, -Vec2::Y, &**shape, options) {
            Some((_, hit)) => (2.0 * offset - hit.time_of_impact).max(0.0),
            None => 0.0,
        }
    }

    fn step_character(&mut self, id: CharacterId, input: &Input, dt: f32) {
        let c = &mut self.characters[id];
        if let Some(level) = &self.ladders {
            crate::ladder::enter(level, self.origin, &mut c.motion, &mut c.pos, c.size, input);
        }
        let was_grounded = c.motion.grounded;
        let mut desired = c.motion.integrate(&self.params, input, dt);
        // A grounded step that does not jump, climb or drop through: the vertical move is fed
        // as `grounded_move` says.
        if was_grounded && desired.y <= 0.0 && !c.motion.on_ladder && !c.motion.drop_through {
            match self.config.grounded_move {
                GroundedMove::Gravity => {}
                GroundedMove::None => desired.y = 0.0,
                GroundedMove::NoneExceptOnPlatforms if c.riding.is_none() => desired.y = 0.0,
                GroundedMove::NoneExceptOnPlatforms => {}
                GroundedMove::Constant(v) => desired.y = -v * dt,
            }
        }
        // The carry Rapier users add: the platform's coming displacement, when grounded on it.
        if let (Some(i), Some(p), PlatformCarry::ControllerPlusDisplacement) =
            (c.riding, &self.platforms, self.config.platform_carry)
        {
            let t0 = self.frame as f64 * dt as f64;
            desired += p.displacement(i as usize, t0, t0 + dt as f64);
        }
        if c.motion.drop_through {
            c.drop_top = c.one_way_ground;
        }
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
            crate::ladder::leave(level, self.origin, &mut c.motion, c.pos, c.size, input);
        }
        c.one_way_ground = if contacts.ground { m.one_way_top } else { None };
        c.riding = match (&self.platforms, m.ground_body) {
            (Some(p), Some(body)) if contacts.ground => {
                p.bodies.iter().position(|b| *b == body).map(|i| i as u32)
            }
            _ => None,
        };
        // The drop ends once the character is wholly below the platform it left.
        if c.drop_top.is_some_and(|top| c.pos.y + c.size.y < top) {
            c.drop_top = None;
        }
        c.ground_normal = if contacts.ground {
            m.ground_normal.unwrap_or(Vec2::Y)
        } else {
            Vec2::ZERO
        };
    }
}

impl Backend for RapierBackend {
    fn name(&self) -> &'static str {
        "rapier"
    }

    fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        let shape = self.config.shape.build(spec.size);
        let pos = spec.spawn + self.origin;
        let lift = if self.config.lift_spawn {
            self.spawn_lift(pos, spec.size, &shape)
        } else {
            0.0
        };
        let pos = pos + Vec2::new(0.0, lift);
        self.characters.push(Character {
            pos,
            riding: None,
            drop_top: None,
            one_way_ground: None,
            size: spec.size,
            shape,
            motion: MotionState::with_velocity(spec.velocity),
            ground_normal: Vec2::ZERO,
        });
        Ok(self.characters.len() - 1)
    }

    fn step(&mut self, inputs: &[Input], dt: f32) {
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

    fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        CharacterState {
            pos: c.pos - self.origin,
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            ground_normal: c.ground_normal,
            platform: c.riding,
            ladder: c.motion.on_ladder,
            crushed: false,
        }
    }
}

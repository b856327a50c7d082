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

pub mod kind;
pub mod world;

use glam::Vec2;

use boxdd::{
    clip_vector, solve_planes, CollisionPlane, MoverQueryBuffer, Position, QueryFilter,
    RayQueryBuffer, ShapeProxy,
};

use crate::backend::{
    invalid, require_supported, BackendError, CharacterId, CharacterSpec, CharacterState,
};
use crate::level::{Features, Level};
use crate::motion::{Contacts, Input, MotionParams, MotionState};
pub use crate::shape::CharacterShape;
pub use world::{b2, ColliderBuilding, LevelWorld, ShapeTag, ONE_WAY, PLATFORM, SOLID};

/// Box2D's linear slop at one length unit per metre (`B2_LINEAR_SLOP`, 0.005 m; one tile is one
/// metre here): `b2SolvePlanes` keeps the capsule this far off every plane ("add slop to
/// prevent jitter").
pub const LINEAR_SLOP: f32 = 0.005;

/// The largest width or height of a level Box2D runs, in tiles (2^14). Its static shapes are
/// kept in the level's own coordinates ([`LevelWorld`]), and Box2D's f32 shape casts run in
/// those coordinates: within 2^14 tiles of the level's corner the f32 spacing is at most 2^-10
/// tile, a fifth of the linear slop the pogo's cast stops short by; Box2D's `constants.h`: "Positions
/// greater than about 16km will have precision problems in single precision" (one tile is one
/// metre here). Farther out the cast can end at a distance of exactly 0, which Box2D asserts
/// against (`b2ShapeCast`, distance.c line 668, `distanceOutput.distance > 0.0f`), killing the
/// process unless its C code is built with `NDEBUG`: a pogo cast 6e4 tiles along a flat floor
/// did (2e4 and 4e4 ran). A larger level is refused as `Unsupported`, a bound kept by design.
/// The level's origin is not bounded by this: placing it moves the ground body, not the
/// arithmetic.
pub const MAX_LEVEL_EXTENT: u32 = 1 << 14;

/// Refuses a character whose capsule radius is not over twice Box2D's linear slop, where Box2D
/// asserts (a bound kept by design).
pub fn check_radius(config: &Box2dConfig, size: Vec2) -> Result<(), BackendError> {
    let (radius, _, _) = config.capsule(size);
    if radius <= 2.0 * LINEAR_SLOP {
        return Err(BackendError::Unsupported {
            backend: kind::NAME,
            feature: format!(
                "a character of size {size} (Box2D's mover needs a capsule radius, half the width or half the height above the pogo leg, over 0.01 tiles, twice its linear slop)"
            ),
            level: String::new(),
            beyond_bound: true,
        });
    }
    Ok(())
}

/// Refuses a level wider or taller than [`MAX_LEVEL_EXTENT`] tiles, as a bound kept by design.
pub fn check_extent(level: &Level) -> Result<(), BackendError> {
    if level.width.max(level.height) > MAX_LEVEL_EXTENT {
        return Err(BackendError::Unsupported {
            backend: kind::NAME,
            feature: format!(
                "a level of {} x {} tiles (Box2D's f32 shape casts run in the level's own \
                 coordinates and keep its linear slop only within {MAX_LEVEL_EXTENT} tiles \
                 of the level's corner; beyond, a cast can end at a distance of exactly 0, \
                 where Box2D asserts and aborts the process)",
                level.width, level.height
            ),
            level: level.name.clone(),
            beyond_bound: true,
        });
    }
    Ok(())
}

/// How far below a one-way platform's top the feet may be and still land on it, and how far
/// from a ladder's top they may be and still stand on it (the shared ladder rules'
/// `enter_within`), in tiles: the pogo holds the feet with a spring, which rests them below the
/// surface by its sag under gravity (0.029 tiles at 60 Hz, `tests/box2d.rs`) and dips further on
/// a landing. A tenth of a tile is a chosen margin over that sag, not a measured bound on the
/// dip.
pub const ONE_WAY_TOLERANCE: f32 = 0.1;

/// The shape the pogo casts down, as the sample offers them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PogoShape {
    /// A ray from the capsule's lower centre.
    Point,
    /// A circle of half the capsule's radius.
    Circle,
    /// A horizontal segment 1.5 capsule radii wide: the sample's default.
    Segment,
}

/// Settings of the Box2D backend: the sample's mover, with the sample's values as defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct Box2dConfig {
    /// How solid tiles become shapes: one box per tile, or merged rectangles as chain loops
    /// (Box2D's docs: chain shapes "provide an efficient way to connect many line segments
    /// together to construct your static game worlds").
    pub colliders: ColliderBuilding,
    /// The character's shape; only [`CharacterShape::Capsule`] (Box2D's docs: "The mover is
    /// assumed to be a capsule"); any other is refused with `Unsupported`.
    pub shape: CharacterShape,
    /// Fraction of the character's height under the capsule, spanned by the pogo leg
    /// (dimensionless). Default 3/11: the sample's capsule (radius 0.3, segment 1.0) rests
    /// 0.6 above the ground on a pogo of rest length 3 radii, 0.6 of its 2.2 total height.
    pub leg_fraction: f32,
    /// The pogo spring's frequency, in Hz (the sample's `m_pogoHertz`, 5).
    pub pogo_hertz: f32,
    /// The pogo spring's damping ratio (dimensionless; the sample's `m_pogoDampingRatio`, 0.8).
    pub pogo_damping_ratio: f32,
    /// The shape the pogo casts (the sample's default: a segment).
    pub pogo_shape: PogoShape,
    /// Vertical speed (tiles/s) at or below which an airborne character whose pogo touches
    /// ground lands: the sample's "avoid snapping to ground if still going up", 0.01.
    pub land_speed: f32,
    /// Most collide-solve-cast rounds per step (the sample's loop: 5).
    pub max_iterations: u32,
    /// A round that moves less than this ends the loop, in tiles (the sample's `tolerance`,
    /// 0.01).
    pub tolerance: f32,
    /// How far a moving platform's collision plane may push the capsule per solve, in tiles:
    /// the sample's elevator `maxPush`, 0.1 ("an elevator that could otherwise push the mover
    /// through the floor", Box2D's docs). Level tiles are rigid (`f32::MAX`).
    pub platform_push_limit: f32,
}

impl Default for Box2dConfig {
    fn default() -> Self {
        Box2dConfig {
            colliders: ColliderBuilding::PerTile,
            shape: CharacterShape::Capsule,
            leg_fraction: 3.0 / 11.0,
            pogo_hertz: 5.0,
            pogo_damping_ratio: 0.8,
            pogo_shape: PogoShape::Segment,
            land_speed: 0.01,
            max_iterations: 5,
            tolerance: 0.01,
            platform_push_limit: 0.1,
        }
    }
}

impl Box2dConfig {
    /// Short label for tables and file names: the collider building and the shape.
    pub fn label(&self) -> String {
        format!("{} {}", self.colliders.label(), self.shape.label())
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<(), BackendError> {
        if !(self.leg_fraction >= 0.0 && self.leg_fraction < 1.0) {
            return Err(invalid("leg_fraction", self.leg_fraction, "0 <= f < 1"));
        }
        if !(self.pogo_hertz.is_finite() && self.pogo_hertz >= 0.0) {
            return Err(invalid("pogo_hertz", self.pogo_hertz, "finite, >= 0 (Hz)"));
        }
        if !(self.pogo_damping_ratio.is_finite() && self.pogo_damping_ratio >= 0.0) {
            return Err(invalid(
                "pogo_damping_ratio",
                self.pogo_damping_ratio,
                "finite, >= 0",
            ));
        }
        if !self.land_speed.is_finite() {
            return Err(invalid("land_speed", self.land_speed, "finite (tiles/s)"));
        }
        if self.max_iterations == 0 {
            return Err(invalid("max_iterations", self.max_iterations, ">= 1"));
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(invalid("tolerance", self.tolerance, "finite, >= 0 (tiles)"));
        }
        if self.platform_push_limit.is_nan() || self.platform_push_limit < 0.0 {
            return Err(invalid(
                "platform_push_limit",
                self.platform_push_limit,
                ">= 0 (tiles)",
            ));
        }
        Ok(())
    }

    /// The capsule for a character of outer `size`: `(radius, lower centre height, upper
    /// centre height)` above the feet, in tiles. The capsule fills the box above the leg, as
    /// wide as the box where its height allows (else a circle as wide as it is tall).
    pub fn capsule(&self, size: Vec2) -> (f32, f32, f32) {
        let leg = self.leg_fraction * size.y;
        let body = size.y - leg;
        let r = (0.5 * size.x).min(0.5 * body);
        (r, leg + r, size.y - r)
    }
}

/// Box2D's implicit spring-damper (`b2SpringDamper`): the new velocity of a spring of
/// `hertz` and `damping_ratio` stretched by `offset` moving at `velocity`, after `dt`.
fn spring_damper(hertz: f32, damping_ratio: f32, offset: f32, velocity: f32, dt: f32) -> f32 {
    let omega = 2.0 * std::f32::consts::PI * hertz;
    let h = omega * dt;
    (velocity - omega * h * offset) / (1.0 + 2.0 * damping_ratio * h + h * h)
}

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

/// What the pogo found.
#[derive(Clone, Copy, Debug)]
struct PogoHit {
    fraction: f32,
    normal: Vec2,
    tag: Option<ShapeTag>,
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

fn to_b2(v: Vec2) -> boxdd::Vec2 {
    boxdd::Vec2::new(v.x, v.y)
}

fn pos_b2(v: Vec2) -> Position {
    Position::from([v.x, v.y])
}

/// A Box2D query on inputs the backend validated; an error here is a bug in the backend.
fn q<T>(r: boxdd::Result<T>) -> T {
    r.unwrap_or_else(|e| panic!("box2d query on validated inputs failed: {e}"))
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

    /// Whether a one-way shape of `tag` takes part for a character with feet at `feet`: never
    /// on a ladder or while dropping through it, and only when the feet are not below its top.
    fn one_way_counts(
        &self,
        tag: &ShapeTag,
        feet: f32,
        drop_top: Option<f32>,
        ladder: bool,
    ) -> bool {
        if ladder {
            return false;
        }
        let top = match (tag.one_way_top, tag.platform) {
            (Some(t), _) => t,
            (None, Some(i)) => self.world.platform_top(i as usize, self.time),
            (None, None) => return true,
        };
        drop_top != Some(top) && feet >= top - ONE_WAY_TOLERANCE
    }

    /// The pogo: a cast down from the capsule's lower centre over the rest length plus a
    /// radius, through the query filter; the closest hit that counts.
    fn pogo(&mut self, id: CharacterId, mask: u64) -> boxdd::Result<(f32, Option<PogoHit>)> {
        let c = &self.characters[id];
        let r = c.radius;
        let rest = c.c1;
        let ray = rest + r;
        let origin = c.pos + Vec2::new(0.0, c.c1);
        let (proxy, translation) = match self.config.pogo_shape {
            PogoShape::Point => (q(ShapeProxy::new([[0.0f32, 0.0]], 0.0)), ray),
            PogoShape::Circle => (q(ShapeProxy::new([[0.0f32, 0.0]], 0.5 * r)), ray - 0.5 * r),
            PogoShape::Segment => (
                q(ShapeProxy::new([[-0.75 * r, 0.0], [0.75 * r, 0.0]], 0.0)),
                ray,
            ),
        };
        let filter = QueryFilter::new().mask(mask);
        {
            let query = self.world.world.query()?;
            query.cast_shape_into(
                pos_b2(origin),
                proxy,
                to_b2(Vec2::new(0.0, -translation)),
                filter,
                &mut self.pogo_hits,
            )?;
        }
        let feet = c.pos.y;
        let (drop_top, ladder) = (c.drop_top, c.motion.on_ladder);
        let mut best: Option<PogoHit> = None;
        for h in self.pogo_hits.iter() {
            let tag = self.world.tags.get(&h.shape_id).copied();
            if let Some(t) = &tag {
                if t.one_way && !self.one_way_counts(t, feet, drop_top, ladder) {
                    continue;
                }
            }
            if best.is_none_or(|b| h.fraction < b.fraction) {
                best = Some(PogoHit {
                    fraction: h.fraction,
                    normal: Vec2::new(h.normal.x, h.normal.y),
                    tag,
                });
            }
        }
        // The pogo's length is the cast's, `ray` (a circle's cast is shorter by its radius and
        // its length is measured the sample's way, `fraction * ray`).
        Ok((ray, best))
    }

    /// One step of one character; an error is a Box2D query whose output boxdd refused.
    fn step_character(&mut self, id: CharacterId, input: &Input, dt: f32) -> boxdd::Result<()> {
        let c = &mut self.characters[id];
        if let Some(level) = &self.ladders {
            // The pogo holds the feet below a ladder's top by its sag, as below a one-way top.
            crate::ladder::enter_within(
                level,
                self.origin,
                &mut c.motion,
                &mut c.pos,
                c.size,
                input,
                ONE_WAY_TOLERANCE,
            );
        }
        let mut desired = c.motion.integrate(&self.params, input, dt);
        if c.motion.drop_through {
            c.drop_top = c.one_way_ground;
        }
        let on_ladder = c.motion.on_ladder;
        let may_land_one_way = !on_ladder && !c.motion.drop_through;
        let mut mask = SOLID | PLATFORM;
        if may_land_one_way {
            mask |= ONE_WAY;
        }
        let was_grounded = c.motion.grounded;
        let vel_y = c.motion.vel.y;
        let (on_ground, hit) = if on_ladder {
            // On a ladder there is no gravity for the spring to hold against, and the capsule
            // floats a leg above the feet: the pogo only senses the ground, and a climb down
            // stops with the feet on it (the pogo at its rest length), which is reaching the
            // ground that ends the climb (the shared ladder rules).
            self.characters[id].pogo_velocity = 0.0;
            let (ray, hit) = self.pogo(id, mask)?;
            let above = hit.map(|h| h.fraction * ray - self.characters[id].c1);
            match above {
                Some(a) if desired.y <= 0.0 && a <= -desired.y => {
                    desired.y = -a.max(0.0);
                    (true, hit)
                }
                _ => (false, None),
            }
        } else {
            let (ray, hit) = self.pogo(id, mask)?;
            let c = &mut self.characters[id];
            // The sample: "avoid snapping to ground if still going up".
            let on_ground = if was_grounded {
                hit.is_some()
            } else {
                hit.is_some() && vel_y <= self.config.land_speed
            };
            c.pogo_velocity = match hit {
                None => 0.0,
                Some(h) => spring_damper(
                    self.config.pogo_hertz,
                    self.config.pogo_damping_ratio,
                    h.fraction * ray - c.c1,
                    c.pogo_velocity,
                    dt,
                ),
            };
            (on_ground, hit)
        };
        let c = &self.characters[id];
        let start = c.pos;
        let target = c.pos + desired + Vec2::new(0.0, c.pogo_velocity * dt);
        let (c1, c2, radius) = (
            to_b2(Vec2::new(0.0, c.c1)),
            to_b2(Vec2::new(0.0, c.c2)),
            c.radius,
        );
        let (drop_top, feet0) = (c.drop_top, c.pos.y);
        let filter = QueryFilter::new().mask(mask);
        let mut pos = c.pos;
        for _ in 0..self.config.max_iterations {
            {
                let query = self.world.world.query()?;
                query.collide_mover_into(
                    pos_b2(pos),
                    c1,
                    c2,
                    radius,
                    filter,
                    &mut self.mover_hits,
                )?;
            }
            self.planes.clear();
            for h in self.mover_hits.iter() {
                let tag = self.world.tags.get(&h.shape_id).copied();
                let mut push_limit = CollisionPlane::RIGID_PUSH_LIMIT;
                if let Some(t) = &tag {
                    // A one-way shape holds only from above: an upward plane, for feet that
                    // started the step not below its top.
                    if t.one_way
                        && !(h.plane.normal().y > 0.0
                            && self.one_way_counts(t, feet0, drop_top, on_ladder))
                    {
                        continue;
                    }
                    if t.platform.is_some() {
                        push_limit = self.config.platform_push_limit;
                    }
                }
                if let Ok(Some(p)) = h.into_collision_plane(push_limit, true) {
                    self.planes.push(p);
                }
            }
            let solved = solve_planes(to_b2(target - pos), &mut self.planes)?;
            self.solver_iterations += solved.iteration_count() as u64;
            let t = solved.translation();
            let fraction = {
                let query = self.world.world.query()?;
                // One-way shapes are cast against only when moving down onto them: the cast
                // reports no shape, so a rising character must not see them at all.
                let cast_mask = if t.y > 0.0 { mask & !ONE_WAY } else { mask };
                query.cast_mover(
                    pos_b2(pos),
                    c1,
                    c2,
                    radius,
                    t,
                    QueryFilter::new().mask(cast_mask),
                )?
            };
            let delta = Vec2::new(t.x, t.y) * fraction;
            pos += delta;
            if delta.length_squared() < self.config.tolerance * self.config.tolerance {
                break;
            }
        }
        let clipped = clip_vector(to_b2(self.characters[id].motion.vel), &self.planes)?;
        let moved = pos - start;
        let mut contacts = Contacts::default();
        for p in &self.planes {
            if p.push() <= 0.0 {
                continue;
            }
            let n = p.plane().normal();
            if n.y < -0.5 {
                contacts.ceiling = true;
            } else if n.y.abs() <= 0.5 && n.x * desired.x < 0.0 {
                contacts.wall = true;
            }
        }
        let c = &mut self.characters[id];
        c.pos = pos;
        c.motion.vel = Vec2::new(clipped.x, clipped.y);
        contacts.ground = on_ground && desired.y <= 0.0;
        contacts.wall &= moved.x.abs() < desired.x.abs() - 1e-6;
        contacts.ceiling &= desired.y > 0.0 && moved.y < desired.y;
        let ground_tag = hit.and_then(|h| h.tag);
        contacts.one_way = contacts.ground && ground_tag.is_some_and(|t| t.one_way);
        c.motion.apply_contacts(&self.params, input, contacts);
        if let Some(level) = &self.ladders {
            crate::ladder::leave(level, self.origin, &mut c.motion, c.pos, c.size, input);
        }
        c.one_way_ground = match (contacts.ground, ground_tag) {
            (true, Some(t)) if t.one_way => t.one_way_top.or_else(|| {
                t.platform
                    .map(|i| self.world.platform_top(i as usize, self.time))
            }),
            _ => None,
        };
        c.riding = if contacts.ground {
            ground_tag.and_then(|t| t.platform)
        } else {
            None
        };
        if c.drop_top.is_some_and(|top| c.pos.y + c.size.y < top) {
            c.drop_top = None;
        }
        c.ground_normal = match hit {
            Some(h) if contacts.ground => h.normal,
            _ => Vec2::ZERO,
        };
        Ok(())
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
    fn capsule_fills_the_box_above_the_leg() {
        let c = Box2dConfig::default();
        // A 0.8 x 2.2 box: the leg is 3/11 of 2.2 = 0.6, the capsule radius half the width.
        let (r, c1, c2) = c.capsule(Vec2::new(0.8, 2.2));
        assert!((r - 0.4).abs() < 1e-6);
        assert!((c1 - 1.0).abs() < 1e-6);
        assert!((c2 - 1.8).abs() < 1e-6);
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
            // under gravity is 0.029 tiles (derived in tests/box2d.rs); a tenth of a tile
            // bounds it loosely.
            assert!(
                (s.pos.y - 1.0).abs() < ONE_WAY_TOLERANCE,
                "{colliders:?}: {s:?}"
            );
            assert!((s.pos.x - 5.0).abs() < 1e-4, "{colliders:?}: {s:?}");
        }
    }
}

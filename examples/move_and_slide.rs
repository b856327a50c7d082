//! A third controller built only on platbench's public API: a collide-and-slide mover in the
//! style of Godot's `CharacterBody2D.move_and_slide()` (reference: the Godot 4.3 class docs of
//! `CharacterBody2D`, whose property defaults the config below takes) and of the kinematic
//! character examples of Rust physics crates.
//!
//! Each step: the shared motion ([`MotionState::integrate`]) turns the input into the desired
//! displacement; the mover first recovers from any overlap, then casts the character's shape
//! (parry2d shape casts) along the displacement against the level's colliders, stops
//! `safe_margin` short of the first hit, and slides the rest along the surface it hit, up to
//! `max_slides` times. A hit whose normal is within `floor_max_angle` of up is a floor. A
//! character that was on the floor and is not rising is snapped down onto a floor within
//! `floor_snap_length`. With `floor_stop_on_slope`, a character standing on a slope with no
//! horizontal move does not slide down it; with `floor_constant_speed`, it walks up and down
//! slopes at its flat-ground speed. One-way platforms follow the rule the built-in backends
//! use: one counts only for a character whose feet were on or above its top at the start of
//! the step, not climbing a ladder and not dropping through it. Moving platforms are not
//! modelled: the kind declares it, and the harness skips those levels.
//!
//! Written from Godot's documented behaviour, not its source; where Godot's code does what the
//! docs do not say (recovery iterations, exact floor snapping), this does the simple thing.
//!
//! `cargo run --release --example move_and_slide` runs the built-in comparison with it as extra
//! rows; every platbench command takes it (`-- report --out DIR`; docs/move-and-slide.md).

use std::rc::Rc;

use glam::Vec2;
use parry2d::bounding_volume::{Aabb, BoundingVolume};
use parry2d::math::Pose;
use parry2d::query::{self, ShapeCastOptions};
use parry2d::shape::SharedShape;

use platbench::level::outlines::{one_way_rects, solid_rects, ColliderBuilding};
use platbench::oneway::{drop_over, drop_start, OneWayCheck};
use platbench::prelude::*;

/// The backend's name, as in CSV files.
pub const NAME: &str = "move_and_slide";

/// How far below a one-way platform's top the feet may start and still stand on it, in tiles.
pub const ONE_WAY_TOLERANCE: f32 = 1e-3;

/// Godot's `FLOOR_ANGLE_THRESHOLD`-like slack on `floor_max_angle`, in radians, so that a
/// 45-degree ramp is a floor under a 45-degree limit despite rounding.
pub const FLOOR_ANGLE_SLACK: f32 = 0.01;

/// Settings of the collide-and-slide mover. Godot's defaults are given in pixels; at the 16
/// pixels per tile of pixel-art platformers they are the tile values below.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveAndSlideConfig {
    /// The character's collision shape, fitted to its box (default: a cuboid, Godot's
    /// `RectangleShape2D`).
    pub shape: CharacterShape,
    /// Gap the mover keeps from what it hits, in tiles: a cast stops this far short of a
    /// contact (Godot's `safe_margin`, default 0.08 px: 0.005 tiles).
    pub safe_margin: f32,
    /// How many times one step may hit something and slide on (Godot's `max_slides`, default 4).
    pub max_slides: u32,
    /// Steepest surface that counts as a floor, in radians from up (Godot's
    /// `floor_max_angle`, default 45 degrees).
    pub floor_max_angle: f32,
    /// How far below the feet a floor is snapped to after a step that was on the floor and is
    /// not rising, in tiles (Godot's `floor_snap_length`, default 1 px: 0.0625 tiles); 0 turns
    /// snapping off.
    pub floor_snap_length: f32,
    /// Whether a character on a slope with no horizontal move stays put instead of sliding
    /// down (Godot's `floor_stop_on_slope`, default true).
    pub floor_stop_on_slope: bool,
    /// Whether a character on the floor moves along slopes at the speed it would have on flat
    /// ground, rather than slower uphill and faster downhill (Godot's `floor_constant_speed`,
    /// default false).
    pub floor_constant_speed: bool,
}

impl Default for MoveAndSlideConfig {
    fn default() -> Self {
        MoveAndSlideConfig {
            shape: CharacterShape::Cuboid,
            safe_margin: 0.08 / 16.0,
            max_slides: 4,
            floor_max_angle: 45f32.to_radians(),
            floor_snap_length: 1.0 / 16.0,
            floor_stop_on_slope: true,
            floor_constant_speed: false,
        }
    }
}

impl MoveAndSlideConfig {
    /// Label for tables and file names: the shape, then each setting that differs from the default.
    pub fn label(&self) -> String {
        let d = MoveAndSlideConfig::default();
        let mut label = self.shape.label();
        if self.floor_constant_speed != d.floor_constant_speed {
            label += &format!(" constant_speed={}", self.floor_constant_speed);
        }
        if self.floor_snap_length != d.floor_snap_length {
            label += &format!(" snap={}", self.floor_snap_length);
        }
        if self.floor_stop_on_slope != d.floor_stop_on_slope {
            label += &format!(" stop_on_slope={}", self.floor_stop_on_slope);
        }
        if self.safe_margin != d.safe_margin {
            label += &format!(" margin={}", self.safe_margin);
        }
        if self.max_slides != d.max_slides {
            label += &format!(" slides={}", self.max_slides);
        }
        label
    }

    fn validate(&self) -> Result<(), BackendError> {
        let bad =
            |name, value: f32, expected| Err(platbench::backend::invalid(name, value, expected));
        if !(self.safe_margin.is_finite() && self.safe_margin >= 0.0) {
            return bad("safe_margin", self.safe_margin, "tiles, finite and >= 0");
        }
        if !(self.floor_max_angle > 0.0 && self.floor_max_angle < std::f32::consts::FRAC_PI_2) {
            return bad(
                "floor_max_angle",
                self.floor_max_angle,
                "radians, 0 < angle < pi/2",
            );
        }
        if !(self.floor_snap_length.is_finite() && self.floor_snap_length >= 0.0) {
            return bad(
                "floor_snap_length",
                self.floor_snap_length,
                "tiles, finite and >= 0",
            );
        }
        Ok(())
    }
}

/// A static collider of the level: its shape, where it is, and the top of a one-way platform.
struct Obstacle {
    shape: SharedShape,
    pose: Pose,
    aabb: Aabb,
    /// The top (world y) of a one-way platform; `None` for a solid.
    one_way_top: Option<f32>,
}

/// The level's colliders, in world coordinates: solid tiles merged into rectangles, one-way
/// tiles (and ladder tops), and each slope tile's outline (a convex polygon for a line slope, a
/// polyline for a height array).
pub struct LevelColliders {
    obstacles: Vec<Obstacle>,
}

impl LevelColliders {
    /// Builds the colliders of `level`.
    pub fn new(level: &Level) -> Self {
        let mut obstacles = Vec::new();
        let o = level.origin_f32();
        let mut push = |shape: SharedShape, pose: Pose, one_way_top| {
            let aabb = shape.compute_aabb(&pose);
            obstacles.push(Obstacle {
                shape,
                pose,
                aabb,
                one_way_top,
            });
        };
        for r in solid_rects(level, ColliderBuilding::Merged) {
            let half = r.half_extents();
            push(
                SharedShape::cuboid(half.x, half.y),
                Pose::from_translation(r.center() + o),
                None,
            );
        }
        // The shared one-way boxes, one per tile.
        for r in one_way_rects(level, ColliderBuilding::PerTile) {
            let half = r.half_extents();
            push(
                SharedShape::cuboid(half.x, half.y),
                Pose::from_translation(r.center() + o),
                Some(r.maxs.y + o.y),
            );
        }
        // Each slope in its tile's frame (the outline the shared outlines place in the level).
        for (i, j, slope) in level.slopes() {
            let pts: Vec<Vec2> = slope.outline();
            if pts.len() < 2 {
                continue;
            }
            let shape = SharedShape::convex_hull(&pts).filter(|_| pts.len() <= 5);
            let shape = shape.unwrap_or_else(|| SharedShape::polyline(pts, None));
            let corner = Vec2::new(i as f32, j as f32) + o;
            push(shape, Pose::from_translation(corner), None);
        }
        LevelColliders { obstacles }
    }
}

/// One character of the mover.
struct Character {
    pos: Vec2,
    size: Vec2,
    shape: SharedShape,
    motion: MotionState,
    ground_normal: Vec2,
    /// The top of the one-way platform it stands on.
    one_way_ground: Option<f32>,
    /// The top of the one-way platform it is dropping through.
    drop_top: Option<f32>,
}

/// The first thing a cast ran into.
#[derive(Clone, Copy)]
struct Hit {
    /// Fraction of the cast travelled before stopping `safe_margin` short.
    toi: f32,
    /// The obstacle's outward normal at the contact.
    normal: Vec2,
    one_way_top: Option<f32>,
}

/// The collide-and-slide backend over one level.
pub struct MoveAndSlide {
    colliders: Rc<LevelColliders>,
    /// The level's ladders, when it has any (the shared ladder rules read the level).
    ladders: Option<Level>,
    origin: Vec2,
    params: MotionParams,
    config: MoveAndSlideConfig,
    characters: Vec<Character>,
}

impl MoveAndSlide {
    /// What it models: everything but moving platforms.
    pub const SUPPORTED: Features = Features {
        slopes: true,
        one_way: true,
        ladders: true,
        moving_platforms: false,
    };

    /// Builds the mover over `level` with colliders built for it (the harness has already
    /// skipped a level with moving platforms).
    pub fn new(
        level: &Level,
        colliders: Rc<LevelColliders>,
        params: MotionParams,
        config: MoveAndSlideConfig,
    ) -> Result<Self, BackendError> {
        params.validate()?;
        config.validate()?;
        Ok(MoveAndSlide {
            colliders,
            ladders: level.features.ladders.then(|| level.geometry()),
            origin: level.origin_f32(),
            params,
            config,
            characters: Vec::new(),
        })
    }

    /// Whether one-way obstacle `top` blocks character `c` in this step.
    fn one_way_blocks(c: &Character, feet_at_start: f32, top: f32) -> bool {
        OneWayCheck {
            feet: feet_at_start,
            tolerance: ONE_WAY_TOLERANCE,
            passes_all: c.motion.on_ladder,
            dropping_through: c.drop_top,
        }
        .blocks(top)
    }

    /// The first obstacle the character's shape at `pos` runs into when moved by `motion`, and
    /// how far it may go toward it to stop `margin` short of it along its normal.
    fn cast(
        &self,
        c: &Character,
        feet_at_start: f32,
        pos: Vec2,
        motion: Vec2,
        margin: f32,
    ) -> Option<Hit> {
        let pose = CharacterShape::pose(pos, c.size);
        let from = c.shape.compute_aabb(&pose);
        let swept = from
            .merged(
                &c.shape
                    .compute_aabb(&CharacterShape::pose(pos + motion, c.size)),
            )
            .loosened(margin + 1e-3);
        let options = ShapeCastOptions {
            stop_at_penetration: false,
            ..ShapeCastOptions::with_max_time_of_impact(1.0)
        };
        let mut best: Option<Hit> = None;
        for o in &self.colliders.obstacles {
            if !o.aabb.intersects(&swept) {
                continue;
            }
            if let Some(top) = o.one_way_top {
                if !Self::one_way_blocks(c, feet_at_start, top) {
                    continue;
                }
            }
            // The obstacle first: `normal1` is then its outward normal, in world axes.
            let Ok(Some(hit)) = query::cast_shapes(
                &o.pose,
                Vec2::ZERO,
                &*o.shape,
                &pose,
                motion,
                &*c.shape,
                options,
            ) else {
                continue;
            };
            // A surface the move runs along or away from does not stop it (a floor under a
            // walk, a wall left behind).
            if motion.dot(hit.normal1) >= -1e-9 {
                continue;
            }
            // A one-way platform only stops a move down onto its top.
            if o.one_way_top.is_some() && (hit.normal1.y < 0.5 || motion.y > 0.0) {
                continue;
            }
            // Back off along the move until the gap along the normal is the margin.
            let approach = -motion.dot(hit.normal1);
            let toi = (hit.time_of_impact - margin / approach).clamp(0.0, hit.time_of_impact);
            if best.is_none_or(|b| toi < b.toi) {
                best = Some(Hit {
                    toi,
                    normal: hit.normal1,
                    one_way_top: o.one_way_top,
                });
            }
        }
        best
    }

    /// Pushes the character at `pos` out to `safe_margin` from anything closer (the recovery
    /// Godot's docs describe: "if the body is at least this close to another body, it will
    /// consider them to be colliding and will be pushed away"), up to 4 passes, and returns
    /// the floor it touches within the margin, if any.
    fn recover(
        &self,
        c: &Character,
        feet_at_start: f32,
        pos: &mut Vec2,
    ) -> Option<(Vec2, Option<f32>)> {
        let margin = self.config.safe_margin;
        let reach = margin + 1e-3;
        let mut floor = None;
        for _ in 0..4 {
            floor = None;
            let pose = CharacterShape::pose(*pos, c.size);
            let aabb = c.shape.compute_aabb(&pose).loosened(reach);
            let mut pushed = false;
            for o in &self.colliders.obstacles {
                if !o.aabb.intersects(&aabb) {
                    continue;
                }
                let Ok(Some(contact)) = query::contact(&o.pose, &*o.shape, &pose, &*c.shape, reach)
                else {
                    continue;
                };
                let n = contact.normal1;
                if let Some(top) = o.one_way_top {
                    // A one-way platform holds only a character on its top.
                    if !Self::one_way_blocks(c, feet_at_start, top) || n.y < 0.5 {
                        continue;
                    }
                }
                if self.is_floor(n) {
                    floor = Some((n, o.one_way_top));
                }
                if contact.dist < margin - 1e-6 {
                    *pos += n * (margin - contact.dist);
                    pushed = true;
                    break;
                }
            }
            if !pushed {
                break;
            }
        }
        floor
    }

    fn is_floor(&self, n: Vec2) -> bool {
        n.y >= (self.config.floor_max_angle + FLOOR_ANGLE_SLACK).cos()
    }

    fn is_ceiling(&self, n: Vec2) -> bool {
        -n.y >= (self.config.floor_max_angle + FLOOR_ANGLE_SLACK).cos()
    }

    fn step_character(&mut self, id: CharacterId, input: &Input, dt: f32) {
        let c = &mut self.characters[id];
        if let Some(level) = &self.ladders {
            platbench::ladder::enter(level, self.origin, &mut c.motion, &mut c.pos, c.size, input);
        }
        let was_on_floor = c.motion.grounded;
        let desired = c.motion.integrate(&self.params, input, dt);
        c.drop_top = drop_start(c.drop_top, c.motion.drop_through, c.one_way_ground);
        let c = &self.characters[id];
        let feet_at_start = c.pos.y;
        let mut pos = c.pos;
        let cfg = &self.config;
        let mut contacts = Contacts::default();
        let mut floor: Option<(Vec2, Option<f32>)> = None;
        let mut motion = desired;
        // The fraction of the step's move not yet made, for a constant-speed floor.
        let mut left = 1.0f32;
        for slide in 0..cfg.max_slides {
            if motion.length_squared() < 1e-12 {
                break;
            }
            let Some(hit) = self.cast(c, feet_at_start, pos, motion, cfg.safe_margin) else {
                pos += motion;
                break;
            };
            pos += motion * hit.toi;
            let rest = motion * (1.0 - hit.toi);
            left *= 1.0 - hit.toi;
            let n = hit.normal;
            if self.is_floor(n) {
                floor = Some((n, hit.one_way_top));
                // Standing still on a slope: gravity's pull is not turned into a slide.
                if cfg.floor_stop_on_slope && desired.x.abs() < 1e-9 && slide == 0 {
                    break;
                }
            } else if self.is_ceiling(n) {
                contacts.ceiling = true;
            } else if n.x * desired.x < 0.0 {
                contacts.wall = true;
            }
            let mut slid = rest - n * rest.dot(n);
            if cfg.floor_constant_speed && was_on_floor && self.is_floor(n) && slid.x.abs() > 1e-9 {
                // As far along the slope as flat ground would have taken it in the time left.
                slid = slid.normalize_or_zero() * desired.x.abs() * left;
            }
            motion = slid;
        }
        // Snap to the floor: only after a step that began on the floor and does not rise.
        if floor.is_none()
            && was_on_floor
            && desired.y <= 0.0
            && cfg.floor_snap_length > 0.0
            && !c.motion.on_ladder
        {
            let down = Vec2::new(0.0, -(cfg.floor_snap_length + cfg.safe_margin));
            if let Some(hit) = self.cast(c, feet_at_start.min(pos.y), pos, down, cfg.safe_margin) {
                if self.is_floor(hit.normal) {
                    pos += down * hit.toi;
                    floor = Some((hit.normal, hit.one_way_top));
                }
            }
        }
        // Out to the margin from whatever the move came closer to; a floor within the margin is
        // stood on.
        if let Some(f) = self.recover(c, feet_at_start, &mut pos) {
            floor = floor.or(Some(f));
        }
        // A jump's take-off does not land.
        contacts.ground = floor.is_some() && desired.y <= 0.0;
        contacts.one_way = floor.is_some_and(|(_, top)| top.is_some());
        let c = &mut self.characters[id];
        let moved = pos - c.pos;
        c.pos = pos;
        contacts.wall &= moved.x.abs() < desired.x.abs() - 1e-6;
        contacts.ceiling &= desired.y > 0.0 && moved.y < desired.y;
        c.motion.apply_contacts(&self.params, input, contacts);
        if let Some(level) = &self.ladders {
            platbench::ladder::leave(level, self.origin, &mut c.motion, c.pos, c.size, input);
        }
        c.one_way_ground = if contacts.ground {
            floor.and_then(|(_, top)| top)
        } else {
            None
        };
        c.drop_top = drop_over(c.drop_top, c.pos.y + c.size.y);
        c.ground_normal = match floor {
            Some((n, _)) if contacts.ground => n,
            _ => Vec2::ZERO,
        };
    }
}

impl Controller for MoveAndSlideConfig {
    type Mover = MoveAndSlide;
    const NAME: &'static str = NAME;

    fn features(&self) -> Features {
        MoveAndSlide::SUPPORTED
    }

    fn build(&self, setup: Setup<'_>) -> Result<MoveAndSlide, BackendError> {
        let level = setup.level;
        let colliders = setup
            .shared
            .get_or_build(NAME, || LevelColliders::new(level));
        let mut mover = MoveAndSlide::new(level, colliders, setup.params.clone(), self.clone())?;
        // The characters (the harness has checked their spawns, sizes and velocities).
        let origin = mover.origin;
        mover
            .characters
            .extend(setup.characters.iter().map(|spec| Character {
                pos: spec.spawn + origin,
                size: spec.size,
                shape: self.shape.build(spec.size),
                motion: MotionState::with_velocity(spec.velocity),
                ground_normal: Vec2::ZERO,
                one_way_ground: None,
                drop_top: None,
            }));
        Ok(mover)
    }

    fn step(&self, m: &mut MoveAndSlide, inputs: &[Input], dt: f32) {
        for id in 0..m.characters.len() {
            let input = inputs.get(id).copied().unwrap_or_default();
            m.step_character(id, &input, dt);
        }
    }

    fn state(&self, m: &MoveAndSlide, id: CharacterId) -> CharacterState {
        let c = &m.characters[id];
        CharacterState {
            pos: c.pos - m.origin,
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            ground_normal: c.ground_normal,
            platform: None,
            ladder: c.motion.on_ladder,
            crushed: false,
        }
    }

    fn description() -> &'static str {
        "Godot-style collide-and-slide over parry2d shape casts (examples/move_and_slide.rs)"
    }

    /// Godot's defaults with a box and with a capsule, the box with constant speed on floors,
    /// and the box with a floor snap of 4 px (0.25 tiles); each with its design and source.
    fn configs() -> Vec<RunConfig> {
        let configs = [
            MoveAndSlideConfig::default(),
            MoveAndSlideConfig {
                shape: CharacterShape::Capsule,
                ..Default::default()
            },
            MoveAndSlideConfig {
                floor_constant_speed: true,
                ..Default::default()
            },
            // What a Godot user raises to keep walking down a 45-degree ramp at run speed: the
            // ground drops run_speed * dt = 0.1 tiles a step there, more than the 1 px default.
            MoveAndSlideConfig {
                floor_snap_length: 0.25,
                ..Default::default()
            },
        ];
        let whys = [
            "a box: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes (Godot 4.3 CharacterBody2D docs)",
            "a capsule: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes (Godot 4.3 CharacterBody2D docs)",
            "floor_constant_speed: run speed along slopes, not slower up and faster down (Godot 4.3 CharacterBody2D docs)",
            "a 4 px floor snap: stays grounded down a 45-degree ramp at run speed (Godot 4.3 CharacterBody2D docs)",
        ];
        configs
            .into_iter()
            .zip(whys)
            .map(|(c, why)| RunConfig::new(c.label(), c).with_why(why))
            .collect()
    }

    fn drawn() -> Vec<(&'static str, &'static str)> {
        vec![("cuboid", "#6a1b9a")]
    }

    fn shape(&self) -> CharacterShape {
        self.shape
    }

    /// The safe margin, kept to everything it touches (and the stress holds it to it).
    fn declared_contact(&self, _size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        DeclaredContact {
            gap: self.safe_margin,
            ..DeclaredContact::default()
        }
    }
}

/// The registry of the built-in backends with this one added.
pub fn registry() -> platbench::registry::Registry {
    platbench::registry::Registry::builtin().with::<MoveAndSlideConfig>()
}

#[allow(dead_code)]
fn main() -> std::process::ExitCode {
    platbench::cli::main_with(registry())
}

//! The collide-and-slide step: shape casts, Godot's slide rules, the floor snap and the recovery
//! from overlaps.

use std::rc::Rc;

use glam::Vec2;
use parry2d::bounding_volume::BoundingVolume;
use parry2d::query::{self, ShapeCastOptions};
use parry2d::shape::SharedShape;

use platbench::oneway::{drop_over, drop_start, OneWayCheck};
use platbench::prelude::*;

use super::colliders::LevelColliders;
use super::config::{MoveAndSlideConfig, FLOOR_ANGLE_SLACK, ONE_WAY_TOLERANCE};

/// One character of the mover.
pub(crate) struct Character {
    pub(crate) pos: Vec2,
    pub(crate) size: Vec2,
    pub(crate) shape: SharedShape,
    pub(crate) motion: MotionState,
    pub(crate) ground_normal: Vec2,
    /// The top of the one-way platform it stands on.
    pub(crate) one_way_ground: Option<f32>,
    /// The top of the one-way platform it is dropping through.
    pub(crate) drop_top: Option<f32>,
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
    pub(crate) origin: Vec2,
    params: MotionParams,
    config: MoveAndSlideConfig,
    pub(crate) characters: Vec<Character>,
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
    /// the floor it touches within the margin, if any. Called once, after the moves; Godot
    /// recovers before each move instead (`GodotSpace2D::test_body_motion`, "STEP 1").
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

    /// The floor a cast of `floor_snap_length` (and the margin) straight down from `pos` finds,
    /// and how far down it is; with `wall_as_floor`, anything but a ceiling counts (Godot's
    /// `_apply_floor_snap`). None on a ladder or with snapping off.
    fn floor_below(
        &self,
        c: &Character,
        feet: f32,
        pos: Vec2,
        wall_as_floor: bool,
    ) -> Option<(Vec2, Hit)> {
        let cfg = &self.config;
        if cfg.floor_snap_length <= 0.0 || c.motion.on_ladder {
            return None;
        }
        let down = Vec2::new(0.0, -(cfg.floor_snap_length + cfg.safe_margin));
        let hit = self.cast(c, feet.min(pos.y), pos, down, cfg.safe_margin)?;
        let stands = self.is_floor(hit.normal) || (wall_as_floor && !self.is_ceiling(hit.normal));
        stands.then_some((down * hit.toi, hit))
    }

    /// Moves `pos` down onto the floor below, if any, and returns it.
    fn snap(
        &self,
        c: &Character,
        feet: f32,
        pos: &mut Vec2,
        wall_as_floor: bool,
    ) -> Option<(Vec2, Option<f32>)> {
        let (drop, hit) = self.floor_below(c, feet, *pos, wall_as_floor)?;
        *pos += drop;
        Some((hit.normal, hit.one_way_top))
    }

    fn is_floor(&self, n: Vec2) -> bool {
        n.y >= (self.config.floor_max_angle + FLOOR_ANGLE_SLACK).cos()
    }

    fn is_ceiling(&self, n: Vec2) -> bool {
        -n.y >= (self.config.floor_max_angle + FLOOR_ANGLE_SLACK).cos()
    }

    /// One step of one character: the shared motion's move, made by the rules of Godot's
    /// `CharacterBody2D::_move_and_slide_grounded` (scene/2d/physics/character_body_2d.cpp), then
    /// the snap, the recovery and the contacts the shared motion applies.
    pub(crate) fn step_character(&mut self, id: CharacterId, input: &Input, dt: f32) {
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
        // The state Godot's `CharacterBody2D::_move_and_slide_grounded` keeps through one call
        // (scene/2d/physics/character_body_2d.cpp): a hit sets on-floor, on-ceiling or on-wall
        // for the rest of the step; rising is judged on the velocity; `motion_slide_up` is the
        // move with its vertical part removed.
        let rising = desired.y > 0.0;
        let slide_up = Vec2::new(desired.x, 0.0);
        let mut on_wall = false;
        // The first-slide rule: with `floor_stop_on_slope`, the first hit on a floor does not
        // slide; the rest is cast again unchanged, and sliding starts from the second hit.
        let mut sliding = !cfg.floor_stop_on_slope;
        // Constant speed applies once, on the first hit that may slide.
        let mut constant_ok = sliding;
        let mut travelled_x = 0.0f32;
        for slide in 0..cfg.max_slides {
            if motion.length_squared() < 1e-12 {
                break;
            }
            let Some(hit) = self.cast(c, feet_at_start, pos, motion, cfg.safe_margin) else {
                // Walking down a slope leaves it without a hit: with constant speed, a first move
                // that a snap would put back on the floor is redone along the previous floor at
                // flat-ground speed (Godot's `_on_floor_if_snapped` branch).
                if cfg.floor_constant_speed
                    && slide == 0
                    && was_on_floor
                    && !rising
                    && self
                        .floor_below(c, feet_at_start, pos + motion, false)
                        .is_some()
                {
                    let along = motion - c.ground_normal * motion.dot(c.ground_normal);
                    motion = along.normalize_or_zero() * slide_up.length();
                    sliding = true;
                    constant_ok = false;
                    continue;
                }
                pos += motion;
                break;
            };
            let travel = motion * hit.toi;
            pos += travel;
            let rest = motion - travel;
            let n = hit.normal;
            if self.is_floor(n) {
                floor = Some((n, hit.one_way_top));
            } else if self.is_ceiling(n) {
                contacts.ceiling = true;
            } else {
                on_wall = true;
                contacts.wall |= n.x * desired.x < 0.0;
            }
            let on_floor = floor.is_some();
            // `floor_stop_on_slope`: a move straight down onto a floor ends there, so gravity's
            // pull is not turned into a slide. (Godot also undoes a travel within the margin:
            // there the travel includes its recovery's push, which here comes after the moves.)
            // Straight down within Godot's tolerance: the unit velocity within 0.01 of down.
            let straight_down = (desired.normalize_or_zero() + Vec2::Y).length() < 0.01;
            if on_floor && cfg.floor_stop_on_slope && straight_down {
                break;
            }
            if rest.length_squared() < 1e-12 {
                break;
            }
            if cfg.floor_block_on_wall && on_wall && slide_up.dot(n) <= 0.0 {
                // `floor_block_on_wall`: a wall hit while walking does not become a climb.
                if was_on_floor && !on_floor && !rising {
                    // Left the floor into a wall: the rest of the move is cancelled and a snap
                    // down, taking a wall for a floor, keeps it stood (Godot also undoes a travel
                    // within the margin, its recovery's push, as above).
                    floor = self.snap(c, feet_at_start, &mut pos, true);
                    break;
                } else if !on_floor {
                    // In the air: only the vertical part of the rest slides along the wall.
                    let up = Vec2::new(0.0, rest.y);
                    motion = up - n * up.dot(n);
                } else {
                    // On the floor: the rest is cast again unslid, so it stays at the wall.
                    motion = rest;
                }
            } else if cfg.floor_constant_speed
                && on_floor
                && !on_wall
                && !contacts.ceiling
                && constant_ok
                && was_on_floor
                && motion.dot(n) < 0.0
            {
                // `floor_constant_speed`: along the slope for the horizontal distance left.
                constant_ok = false;
                let along = (rest - n * rest.dot(n)).normalize_or_zero();
                motion = along * (slide_up.length() - travelled_x - travel.x.abs()).max(0.0);
            } else if sliding || !on_floor {
                // Regular sliding; a slide that would turn against the velocity stops instead.
                let slid = rest - n * rest.dot(n);
                motion = if slid.dot(desired) > 0.0 {
                    slid
                } else {
                    Vec2::ZERO
                };
            } else {
                motion = rest;
            }
            travelled_x += travel.x.abs();
            constant_ok = !constant_ok && !sliding;
            sliding = true;
        }
        // Snap to the floor: only after a step that began on the floor and does not rise.
        if floor.is_none() && was_on_floor && !rising {
            floor = self.snap(c, feet_at_start, &mut pos, false);
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

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

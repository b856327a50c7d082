//! One step of the Box2D mover, as Box2D's `Mover` sample takes it: the pogo's cast down and its
//! spring, then the collide-solve-cast loop and the velocity clipped against the planes, with
//! one-way shapes taking part only from above.

use glam::Vec2;

use boxdd::{clip_vector, solve_planes, CollisionPlane, Position, QueryFilter, ShapeProxy};

use crate::backend::CharacterId;
use crate::motion::{Contacts, Input};
use crate::oneway::{drop_over, drop_start, OneWayCheck};

use super::{Box2dBackend, GroundCarry, PogoShape, ShapeTag, ONE_WAY, PLATFORM, SOLID};

/// How far below a one-way platform's top the feet may be and still land on it, and how far
/// from a ladder's top they may be and still stand on it (the shared ladder rules'
/// `enter_within`), in tiles: the pogo holds the feet with a spring, which rests them below the
/// surface by its sag under gravity (0.029 tiles at 60 Hz, `tests/controllers/box2d.rs`) and dips further on
/// a landing. A tenth of a tile is a chosen margin over that sag, not a measured bound on the
/// dip.
pub const ONE_WAY_TOLERANCE: f32 = 0.1;

/// Box2D's implicit spring-damper (`b2SpringDamper`): the new velocity of a spring of
/// `hertz` and `damping_ratio` stretched by `offset` moving at `velocity`, after `dt`.
fn spring_damper(hertz: f32, damping_ratio: f32, offset: f32, velocity: f32, dt: f32) -> f32 {
    let omega = 2.0 * std::f32::consts::PI * hertz;
    let h = omega * dt;
    (velocity - omega * h * offset) / (1.0 + 2.0 * damping_ratio * h + h * h)
}

/// What the pogo found.
#[derive(Clone, Copy, Debug)]
struct PogoHit {
    fraction: f32,
    normal: Vec2,
    tag: Option<ShapeTag>,
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
    /// Whether a one-way shape of `tag` takes part for a character with feet at `feet`: never
    /// on a ladder or while dropping through it, and only when the feet are not below its top.
    fn one_way_counts(
        &self,
        tag: &ShapeTag,
        feet: f32,
        drop_top: Option<f32>,
        ladder: bool,
    ) -> bool {
        let top = match (tag.one_way_top, tag.platform) {
            (Some(t), _) => t,
            (None, Some(i)) => self.world.platform_top(i as usize, self.time),
            (None, None) => return !ladder,
        };
        OneWayCheck {
            feet,
            tolerance: ONE_WAY_TOLERANCE,
            passes_all: ladder,
            dropping_through: drop_top,
        }
        .blocks(top)
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
    pub(super) fn step_character(
        &mut self,
        id: CharacterId,
        input: &Input,
        dt: f32,
    ) -> boxdd::Result<()> {
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
        c.drop_top = drop_start(c.drop_top, c.motion.drop_through, c.one_way_ground);
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
        // The user-side carry (`GroundCarry::Ground`): the displacement for this step of the
        // body the pogo stands on, which the world step has just moved.
        let carry = match hit.and_then(|h| h.tag?.platform) {
            Some(i) if on_ground && !on_ladder && self.config.carry == GroundCarry::Ground => {
                let body = self.world.platforms[i as usize];
                let v = self.world.world.body(body)?.linear_velocity()?;
                Vec2::new(v.x, v.y) * dt
            }
            _ => Vec2::ZERO,
        };
        let c = &self.characters[id];
        let start = c.pos;
        let target = c.pos + desired + Vec2::new(0.0, c.pogo_velocity * dt) + carry;
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
        c.drop_top = drop_over(c.drop_top, c.pos.y + c.size.y);
        c.ground_normal = match hit {
            Some(h) if contacts.ground => h.normal,
            _ => Vec2::ZERO,
        };
        Ok(())
    }
}

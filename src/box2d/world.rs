//! The level as a Box2D world: static tile shapes (one box per tile, or merged outlines as chain
//! loops, which Box2D's docs advise for static game worlds), one-way platforms and ladder tops
//! in their own filter category, and moving platforms as kinematic bodies moved by the world
//! step.

use std::collections::HashMap;

use boxdd::{
    BodyBuilder, BodyId, BodyType, ChainDef, Filter, Foundation, Polygon, Position, ShapeDef,
    ShapeId, Transform, World, WorldTransform,
};
use glam::Vec2;

use crate::backend::BackendError;
pub use crate::level::outlines::ColliderBuilding;
use crate::level::outlines::{one_way_rects, slope_outlines, solid_rects};
use crate::level::{Level, Platform};

/// Filter category of the level's solid shapes.
pub const SOLID: u64 = 1;
/// Filter category of one-way platforms (and ladder tops): the mover's query filter includes it
/// only while the character may land on them.
pub const ONE_WAY: u64 = 1 << 1;
/// Filter category of moving platforms' shapes.
pub const PLATFORM: u64 = 1 << 2;

/// What the backend needs to know of a shape a query returns; solid static shapes are not
/// listed (they are rigid and never one-way).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeTag {
    /// Top of the one-way platform (world y), for a static one-way shape.
    pub one_way_top: Option<f32>,
    /// Whether the shape is one-way (static or moving).
    pub one_way: bool,
    /// Index of the moving platform it belongs to.
    pub platform: Option<u32>,
}

/// The Box2D world of one level.
pub struct LevelWorld {
    /// The Box2D world (its own per backend instance: moving platforms mutate it).
    pub world: World,
    /// The shapes that are not plain solids.
    pub tags: HashMap<ShapeId, ShapeTag>,
    /// One kinematic body per moving platform, in the level's order.
    pub platforms: Vec<BodyId>,
    /// The platforms' specs, for their motion.
    specs: Vec<Platform>,
    /// The level's corner in the world.
    origin: Vec2,
    /// Number of static shapes built for the level.
    pub static_shapes: usize,
}

/// A Box2D call that cannot fail on the validated geometry the backend hands it, or the
/// backend's error naming what Box2D refused.
pub fn b2<T>(what: &'static str, r: boxdd::Result<T>) -> Result<T, BackendError> {
    r.map_err(|e| BackendError::InvalidParameter {
        name: what,
        value: e.to_string(),
        expected: "geometry Box2D accepts",
    })
}

fn filter(category: u64) -> Filter {
    Filter {
        category_bits: category,
        ..Filter::default()
    }
}

fn position(p: Vec2) -> Position {
    Position::from([p.x, p.y])
}

/// The points of a closed outline in counter-clockwise order (Box2D: "a counter-clockwise
/// winding order orients the normal outwards").
fn counter_clockwise(mut points: Vec<Vec2>) -> Vec<Vec2> {
    let n = points.len();
    let area: f32 = (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum();
    if area < 0.0 {
        points.reverse();
    }
    // A chain refuses points closer than Box2D's linear slop (0.005): they would make a
    // degenerate segment.
    let slop = super::LINEAR_SLOP;
    points.dedup_by(|a, b| (*a - *b).length() <= slop);
    if points.len() > 1 && (points[0] - points[points.len() - 1]).length() <= slop {
        points.pop();
    }
    points
}

impl LevelWorld {
    /// Builds the world for `level` with `building`'s static shapes.
    pub fn new(level: &Level, building: ColliderBuilding) -> Result<Self, BackendError> {
        let foundation = b2("box2d foundation", Foundation::initialize_default())?;
        let mut world = b2(
            "box2d world",
            foundation.create_world(foundation.world_def()),
        )?;
        let origin = level.origin_f32();
        // The static shapes live in the level's own coordinates on a ground body at the level's
        // corner, as each moving platform's box lives on its own body: Box2D runs a query in
        // the frame of the body it tests (`b2ShapeCastShape` after `b2ToRelativeTransform` in
        // physics_world.c), so the arithmetic stays as fine as the level is small, wherever
        // the level is placed. With the vertices in world coordinates on a body at the world's
        // origin, a pogo cast 1e5 tiles out ran at an f32 spacing of 1/128 tile, coarser than
        // the separation the cast stops at (the linear slop, 0.005): it ended at a distance of
        // exactly 0 and Box2D's `B2_ASSERT( distanceOutput.distance > 0.0f && ... )`
        // (distance.c line 668, `b2ShapeCast`) aborted the process.
        let ground = b2(
            "box2d ground body",
            world.create_body(b2(
                "box2d body",
                foundation.body_builder().position(position(origin)).build(),
            )?),
        )?;
        let solid = b2(
            "box2d shape",
            ShapeDef::builder().filter(filter(SOLID)).build(),
        )?;
        let mut static_shapes = 0;
        let mut tags = HashMap::new();
        let add_box = |world: &mut World,
                       r: &parry2d::bounding_volume::Aabb,
                       def: &ShapeDef|
         -> Result<ShapeId, BackendError> {
            let half = r.half_extents();
            let c = r.center();
            let poly = b2(
                "box2d box",
                Polygon::offset_box_polygon(
                    half.x,
                    half.y,
                    b2(
                        "box2d transform",
                        Transform::from_pos_angle([c.x, c.y], 0.0),
                    )?,
                ),
            )?;
            b2(
                "box2d polygon",
                b2("box2d body", world.body(ground))?.create_polygon(def, &poly),
            )
        };
        // Per tile, the boxes one at a time (not collected first: 16 bytes a tile).
        let rects: Box<dyn Iterator<Item = parry2d::bounding_volume::Aabb>> = match building {
            ColliderBuilding::PerTile => Box::new(level.solid_boxes()),
            ColliderBuilding::Merged => Box::new(solid_rects(level, building).into_iter()),
        };
        for r in rects {
            match building {
                ColliderBuilding::PerTile => {
                    add_box(&mut world, &r, &solid)?;
                }
                ColliderBuilding::Merged => {
                    let (lo, hi) = (r.mins, r.maxs);
                    let loop_points = [lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)];
                    let def = b2(
                        "box2d chain",
                        ChainDef::builder()
                            .points(loop_points.iter().map(|p| [p.x, p.y]))
                            .is_loop(true)
                            .filter(filter(SOLID))
                            .build(),
                    )?;
                    b2(
                        "box2d chain",
                        b2("box2d body", world.body(ground))?.create_chain(&def),
                    )?;
                }
            }
            static_shapes += 1;
        }
        for points in slope_outlines(level, building) {
            let pts = counter_clockwise(points);
            if pts.len() < 3 {
                continue;
            }
            match building {
                // A line slope's tile: its convex polygon, as Rapier's backend builds it; and any
                // outline of three points (a chain loop needs four).
                ColliderBuilding::PerTile if pts.len() <= 5 => {
                    let poly = b2(
                        "box2d slope polygon",
                        Polygon::from_points(pts.iter().map(|p| [p.x, p.y]), 0.0),
                    )?;
                    b2(
                        "box2d polygon",
                        b2("box2d body", world.body(ground))?.create_polygon(&solid, &poly),
                    )?;
                }
                _ if pts.len() < 4 => {
                    let poly = b2(
                        "box2d slope polygon",
                        Polygon::from_points(pts.iter().map(|p| [p.x, p.y]), 0.0),
                    )?;
                    b2(
                        "box2d polygon",
                        b2("box2d body", world.body(ground))?.create_polygon(&solid, &poly),
                    )?;
                }
                _ => {
                    let def = b2(
                        "box2d chain",
                        ChainDef::builder()
                            .points(pts.iter().map(|p| [p.x, p.y]))
                            .is_loop(true)
                            .filter(filter(SOLID))
                            .build(),
                    )?;
                    b2(
                        "box2d chain",
                        b2("box2d body", world.body(ground))?.create_chain(&def),
                    )?;
                }
            }
            static_shapes += 1;
        }
        // Empty for a level without one-way tiles or ladders (level::outlines decides).
        let one_way = b2(
            "box2d shape",
            ShapeDef::builder().filter(filter(ONE_WAY)).build(),
        )?;
        for r in one_way_rects(level, building) {
            let id = add_box(&mut world, &r, &one_way)?;
            let top = r.maxs.y + origin.y;
            tags.insert(
                id,
                ShapeTag {
                    one_way_top: Some(top),
                    one_way: true,
                    platform: None,
                },
            );
            static_shapes += 1;
        }
        let mut platforms = Vec::with_capacity(level.platforms.len());
        for (i, p) in level.platforms.iter().enumerate() {
            let b = p.aabb(0.0).translated(origin);
            let c = b.center();
            let body = b2(
                "box2d platform body",
                world.create_body(b2(
                    "box2d body",
                    BodyBuilder::from(foundation.body_def())
                        .body_type(BodyType::Kinematic)
                        .position(position(c))
                        .build(),
                )?),
            )?;
            let half = b.half_extents();
            let category = if p.one_way { ONE_WAY } else { PLATFORM };
            let def = b2(
                "box2d shape",
                ShapeDef::builder().filter(filter(category)).build(),
            )?;
            let poly = b2("box2d box", Polygon::box_polygon(half.x, half.y))?;
            let id = b2(
                "box2d polygon",
                b2("box2d body", world.body(body))?.create_polygon(&def, &poly),
            )?;
            tags.insert(
                id,
                ShapeTag {
                    one_way_top: None,
                    one_way: p.one_way,
                    platform: Some(i as u32),
                },
            );
            platforms.push(body);
        }
        Ok(LevelWorld {
            world,
            tags,
            platforms,
            specs: level.platforms.clone(),
            origin,
            static_shapes,
        })
    }

    /// Centre of platform `i` at time `t`, in the world.
    pub fn platform_center(&self, i: usize, t: f64) -> Vec2 {
        self.specs[i].aabb(t).translated(self.origin).center()
    }

    /// The top of platform `i` at time `t` (world y).
    pub fn platform_top(&self, i: usize, t: f64) -> f32 {
        self.specs[i].aabb(t).translated(self.origin).maxs.y
    }

    /// Moves every platform to its place at `t1` over one world step of `dt`, as Box2D's
    /// sample moves its elevator: a target transform for the kinematic body, then the step,
    /// which gives the body the velocity that reaches it.
    pub fn step_platforms(&mut self, t1: f64, dt: f32) -> Result<(), BackendError> {
        if self.platforms.is_empty() || dt <= 0.0 {
            return Ok(());
        }
        for i in 0..self.platforms.len() {
            let c = self.platform_center(i, t1);
            let target = b2(
                "box2d platform target",
                WorldTransform::from_pos_angle(position(c), 0.0),
            )?;
            let id = self.platforms[i];
            b2(
                "box2d platform target",
                b2("box2d body", self.world.body(id))?.set_target_transform(target, dt, true),
            )?;
        }
        b2("box2d step", self.world.step(dt, 4).map(|_| ()))?;
        Ok(())
    }
}

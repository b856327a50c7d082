//! Box2D far from the origin and at its bound: the pogo stands and walks where Box2D used to
//! assert, and a level as wide as Box2D's bound runs to its far end while a wider one is
//! refused.
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use glam::Vec2;
use platbench::backend::CharacterSpec;
use platbench::box2d::{Box2dBackend, Box2dConfig, ColliderBuilding, PogoShape};
use platbench::level::parse_level;
use platbench::motion::{Input, MotionParams};

use super::box2d::DT;

/// Walks a character of the stress's size right for 3 s (after 1 s standing) on a flat floor
/// `width` tiles wide placed at `origin`, from `spawn_x` (level coordinates), with every pogo
/// shape on both buildings; returns each run's last state.
fn walk_far(
    width: usize,
    origin: f64,
    spawn_x: f32,
) -> Vec<(String, platbench::backend::CharacterState)> {
    let row = |c: &str| c.repeat(width);
    let text = format!(
        "map = \"\"\"\n{}\n{}\n{}\n{}\n\"\"\"\n",
        row("."),
        row("."),
        row("."),
        row("#")
    );
    let mut level = parse_level(&text, "far.toml").unwrap();
    level.origin = glam::DVec2::splat(origin);
    let mut out = Vec::new();
    for colliders in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
        for pogo_shape in [PogoShape::Segment, PogoShape::Point, PogoShape::Circle] {
            let config = Box2dConfig {
                colliders,
                pogo_shape,
                ..Default::default()
            };
            let mut b = Box2dBackend::new(&level, MotionParams::default(), config).unwrap();
            let id = b
                .add_character(CharacterSpec {
                    spawn: Vec2::new(spawn_x, 1.5),
                    size: Vec2::new(0.8, 0.9),
                    velocity: Vec2::ZERO,
                })
                .unwrap();
            for i in 0..240 {
                let input = Input {
                    right: i >= 60,
                    ..Default::default()
                };
                b.step(&[input], DT);
            }
            let label = format!("origin {origin}, x {spawn_x}, {colliders:?}, {pogo_shape:?}");
            assert_eq!(b.failure(id), None, "{label}");
            out.push((label, b.state(id)));
        }
    }
    out
}

/// Far from the origin the pogo's cast runs in the level's own coordinates (the ground body
/// sits at the level's corner), so it stops a linear slop short of the floor as at the origin:
/// with its shapes at world coordinates on a body at the world's origin, the cast 1e5 tiles out
/// ran at an f32 spacing of 1/128 tile, ended at a distance of exactly 0, and Box2D's
/// `B2_ASSERT( distanceOutput.distance > 0.0f ... )` (distance.c line 668, `b2ShapeCast`)
/// killed the process (`platbench stress`, in a build without `NDEBUG`, as every dependent's
/// is). This test binary is such a build: an abort fails it.
#[test]
fn far_from_the_origin_the_pogo_stands_and_walks_where_box2d_used_to_assert() {
    for origin in [1e5, -1e5, 1e6, 1e7] {
        for (label, s) in walk_far(40, origin, 5.0) {
            assert!(s.pos.is_finite() && s.vel.is_finite(), "{label}: {s:?}");
            if origin.abs() <= 1e6 {
                // Positions there are f32 world coordinates, spaced 1/128 tile at 1e5 and
                // 1/16 at 1e6: standing on the floor (its top at y = 1) within a spacing of
                // the one-way tolerance, and walking 2 s at the run speed (6 tiles/s) minus
                // its ramp.
                assert!(s.grounded, "{label}: {s:?}");
                assert!(
                    (s.pos.y - 1.0).abs() < platbench::box2d::ONE_WAY_TOLERANCE + 1.0 / 16.0,
                    "{label}: {s:?}"
                );
                assert!(s.pos.x > 14.0, "{label}: {s:?}");
            }
        }
    }
}

/// Box2D's casts keep its linear slop within [`platbench::box2d::MAX_LEVEL_EXTENT`] tiles of
/// the level's corner: a walk at the far end of a floor that wide holds, and a level one tile
/// wider is refused as a bound (past it, 6e4 tiles along such a floor, the cast asserted).
#[test]
fn a_level_as_wide_as_box2ds_bound_runs_to_its_far_end_and_a_wider_one_is_refused() {
    let max = platbench::box2d::MAX_LEVEL_EXTENT as usize;
    for (label, s) in walk_far(max, 0.0, max as f32 - 30.0) {
        assert!(s.grounded && s.pos.is_finite(), "{label}: {s:?}");
        assert!((s.pos.y - 1.0).abs() < 0.1, "{label}: {s:?}");
    }
    let text = format!(
        "map = \"\"\"\n{}\n{}\n\"\"\"\n",
        ".".repeat(max + 1),
        "#".repeat(max + 1)
    );
    let level = parse_level(&text, "wide.toml").unwrap();
    let err = Box2dBackend::new(&level, MotionParams::default(), Box2dConfig::default()).err();
    match err {
        Some(platbench::backend::BackendError::Unsupported {
            beyond_bound: true,
            ref feature,
            ..
        }) => assert!(feature.contains("16385 x 2 tiles"), "{feature}"),
        e => panic!("{e:?}"),
    }
}

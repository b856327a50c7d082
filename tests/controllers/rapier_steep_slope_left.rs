//! A minimal scene for Rapier's maintainers, written with rapier2d alone (no platbench code):
//! rapier2d 0.36.1's `KinematicCharacterController` in 2D climbs a slope steeper than
//! `max_slope_climb_angle` when the slope rises to the left, and blocks the same slope rising to
//! the right.
//!
//! Mechanism: `compute_hit_info` measures the slope as `up.angle_to(normal)`, which in 2D is a
//! signed angle (since rapier 0.32, #909, which replaced the unsigned `angle`). For a surface
//! rising to the left the normal leans right and the angle is negative, so
//! `angle_with_floor >= max_slope_climb_angle` (the wall test) never holds and such a slope is
//! never a wall; for the same reason `is_nonslip_slope` always holds and it never slides.
//!
//! The scene: a flat ground (top y = 0) and a 63.4-degree ramp (rise 2 per run 1, 4 high), one
//! convex polygon, on either side of a capsule (radius 0.4, half-height 0.05) with Rapier's
//! default controller (climb limit 45 degrees). Each step: `vy -= 30 dt`, desired
//! `(±6 dt, vy dt)`, `move_shape`, `vy = 0` when grounded; 3 s at 60 Hz. If Rapier changes this
//! behaviour, this test fails and docs/rapier.md's claim about it must change with it.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use glam::Vec2;
use rapier2d::control::KinematicCharacterController;
use rapier2d::parry::query::DefaultQueryDispatcher;
use rapier2d::prelude::{
    BroadPhaseBvh, ColliderBuilder, ColliderSet, IntegrationParameters, Pose, QueryFilter,
    RigidBodySet, SharedShape,
};

/// Walks toward the ramp for 3 s and returns the highest the feet got.
fn highest_feet(ramp: &[Vec2], walk: f32) -> f32 {
    let mut colliders = ColliderSet::new();
    let bodies = RigidBodySet::new();
    let mut handles = vec![colliders.insert(
        ColliderBuilder::cuboid(50.0, 0.5)
            .translation(Vec2::new(0.0, -0.5))
            .build(),
    )];
    handles.push(
        colliders.insert(
            ColliderBuilder::convex_hull(ramp)
                .expect("a polygon")
                .build(),
        ),
    );
    let mut broad_phase = BroadPhaseBvh::new();
    broad_phase.update(
        &IntegrationParameters::default(),
        &colliders,
        &bodies,
        &handles,
        &[],
        &mut Vec::new(),
    );
    let dispatcher = DefaultQueryDispatcher;
    let queries =
        broad_phase.as_query_pipeline(&dispatcher, &bodies, &colliders, QueryFilter::default());
    let controller = KinematicCharacterController::default();
    let capsule = SharedShape::capsule_y(0.05, 0.4);
    // The capsule's centre, 1% of its 0.9 height above the ground.
    let mut centre = Vec2::new(0.0, 0.45 + 0.009);
    let (dt, mut vy, mut highest) = (1.0 / 60.0, 0.0f32, 0.0f32);
    for _ in 0..180 {
        vy -= 30.0 * dt;
        let mvt = controller.move_shape(
            dt,
            &queries,
            &*capsule,
            &Pose::from_translation(centre),
            Vec2::new(walk * 6.0 * dt, vy * dt),
            |_| {},
        );
        centre += mvt.translation;
        if mvt.grounded {
            vy = 0.0;
        }
        highest = highest.max(centre.y - 0.45);
    }
    highest
}

#[test]
fn a_too_steep_slope_rising_to_the_left_is_climbed() {
    // 63.4 degrees, above the 45-degree climb limit. Rising to the right, 3 tiles to the right
    // of the start: blocked, the feet stay within the offset band of the ground (0.1 is far
    // above it and far below the ramp's 4 tiles).
    let rising_right = [
        Vec2::new(3.0, 0.0),
        Vec2::new(5.0, 0.0),
        Vec2::new(5.0, 4.0),
    ];
    let right = highest_feet(&rising_right, 1.0);
    assert!(right < 0.1, "rising to the right: feet reached {right}");
    // The mirror image, walked to the left: climbed (above 1 tile: a quarter of the ramp, where
    // a blocked character cannot be).
    let rising_left = [
        Vec2::new(-3.0, 0.0),
        Vec2::new(-5.0, 0.0),
        Vec2::new(-5.0, 4.0),
    ];
    let left = highest_feet(&rising_left, -1.0);
    assert!(left > 1.0, "rising to the left: feet reached only {left}");
}

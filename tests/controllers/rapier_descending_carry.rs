//! A minimal scene for Rapier's maintainers, written with rapier2d alone (no platbench code):
//! rapier2d 0.36.1's `KinematicCharacterController` carries a rider sideways on a kinematic
//! platform that moves sideways or rises, and not at all on one that descends while moving
//! sideways: the mechanism behind `platforms.diagonal`'s and `platforms.circle`'s
//! `carry_drift` (docs/rapier.md, "Moving platforms").
//!
//! Mechanism, in `move_shape`: the rider carried is the one whose cast hit the platform; after
//! the hit, `detect_grounded_status_and_apply_friction` sets, for each contact with a kinematic
//! body, the normal part of the remaining translation to the platform's own motion along the
//! normal (`normal * (normal_target_mvt - normal_current_mvt)`) and adds its tangential motion
//! once (`kinematic_friction_translation`). For a descending platform that normal part points
//! into the platform, so the next cast, which starts at the offset, is blocked at time 0;
//! `handle_slopes` drops the part into the surface (`decompose_hit`'s `penetration_part`) and
//! keeps the sideways part, but the next contact puts the descent back before the next cast,
//! and so on for all 20 iterations: the sideways part is never cast alone and never applied.
//! (Fed less than the platform's drop, the first cast misses the platform and the carry never
//! starts.) Rising, the normal part points away from the platform and the cast goes through.
//!
//! The scene: a platform 4 wide and 0.5 tall (top at y = 0), a kinematic velocity-based body
//! moving at (-2, vy) tiles/s, and Rapier's 2D testbed capsule (radius 0.15, half-height 0.3,
//! 0.9 tall as platbench's character) whose feet are the offset (1% of its height) plus this
//! step's drop above the top, as after the platform has moved first; one `move_shape` at 60 Hz
//! asking for the testbed's push, 0.1 down. If Rapier changes this behaviour, this test fails
//! and docs/rapier.md's explanation must change with it.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(feature = "rapier", feature = "box2d"))]

use glam::Vec2;
use rapier2d::control::KinematicCharacterController;
use rapier2d::parry::query::DefaultQueryDispatcher;
use rapier2d::prelude::{
    BroadPhaseBvh, ColliderBuilder, ColliderSet, IntegrationParameters, Pose, QueryFilter,
    RigidBodyBuilder, RigidBodySet, SharedShape,
};

/// One testbed-fed step of a rider on a platform moving at `velocity`: the translation the
/// controller applied and the times of impact of its casts.
fn ride(velocity: Vec2) -> (Vec2, Vec<f32>) {
    let dt = 1.0f32 / 60.0;
    let mut bodies = RigidBodySet::new();
    let mut colliders = ColliderSet::new();
    let body = bodies.insert(
        RigidBodyBuilder::kinematic_velocity_based()
            .translation(Vec2::new(0.0, -0.25))
            .linvel(velocity)
            .build(),
    );
    let handle =
        colliders.insert_with_parent(ColliderBuilder::cuboid(2.0, 0.25), body, &mut bodies);
    let mut broad_phase = BroadPhaseBvh::new();
    broad_phase.update(
        &IntegrationParameters::default(),
        &colliders,
        &bodies,
        &[handle],
        &[],
        &mut Vec::new(),
    );
    let dispatcher = DefaultQueryDispatcher;
    let queries =
        broad_phase.as_query_pipeline(&dispatcher, &bodies, &colliders, QueryFilter::default());
    let controller = KinematicCharacterController::default();
    let capsule = SharedShape::capsule_y(0.3, 0.15);
    let offset = 0.009;
    // A descending platform has already dropped this step's distance below the rider.
    let drop = (-velocity.y * dt).max(0.0);
    let centre = Vec2::new(0.0, 0.45 + offset + drop);
    let mut tois = Vec::new();
    let mvt = controller.move_shape(
        dt,
        &queries,
        &*capsule,
        &Pose::from_translation(centre),
        Vec2::new(0.0, -0.1),
        |c| tois.push(c.hit.time_of_impact),
    );
    (mvt.translation, tois)
}

#[test]
fn a_rider_is_carried_sideways_unless_its_platform_descends() {
    let dt = 1.0f32 / 60.0;
    let sideways = -2.0 * dt; // the platform's sideways step, -0.033 tiles
                              // Sideways only, and rising: carried by the platform's step (within 1e-3 tiles, a
                              // thirtieth of it, for the normal nudge and rounding).
    for vy in [0.0f32, 2.0] {
        let (t, tois) = ride(Vec2::new(-2.0, vy));
        println!("vy {vy}: translation {t}, casts' times of impact {tois:?}");
        assert!((t.x - sideways).abs() < 1e-3, "vy {vy}: {t}");
    }
    // Descending: not carried at all (within the same 1e-3), while every cast after the first
    // hit is blocked at time 0 (the first reaches the platform, this step's drop away): within
    // 1e-4 tiles, the normal nudge's size (measured: 0 to 3.8e-6).
    let (t, tois) = ride(Vec2::new(-2.0, -2.0));
    println!("vy -2: translation {t}, casts' times of impact {tois:?}");
    assert!(t.x.abs() < 1e-3, "descending: {t}");
    assert!(tois.len() > 2, "{tois:?}");
    assert!(tois[1..].iter().all(|&toi| toi < 1e-4), "{tois:?}");
}

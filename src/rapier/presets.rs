//! Rapier's presets, as data beside the controller: the configurations of the built-in
//! comparison, the ones `platbench stress` checks, and the grid `platbench sweep` measures.

use super::kind::{run, run_with};
use super::{CharacterShape, ColliderBuilding, GroundedMove, Length, RapierConfig};
use crate::backend::Precision;
use crate::config::RunConfig;
use crate::config::Setting;

/// Rapier with every character shape its users pick, each on one collider per tile and on
/// merged colliders, fed gravity on every grounded step (the naive feed: what a game that
/// integrates its own gravity and hands the controller `v * dt` does; the set-up of the
/// reference figures, docs/rapier-reference.md, and the one that shows rapier #613 and the
/// ground prediction's threshold on the elevator); then, per shape and
/// collider building, Rapier fed as its own examples feed it
/// ([`GroundedMove::NoneExceptTestbedOnPlatforms`]: no vertical move while grounded on static
/// ground, as the bevy_rapier character example; the 2D testbed's push down on a moving
/// platform), the advised rows, which `examples/rapier_setups.rs` measured to leave the fewest
/// stuck frames and no rider lost on the elevator. (Rapier's docs also advise a larger offset;
/// the same command measured it to help no shape as much, and to leave the merged cuboid
/// stuck.)
pub(crate) fn configs() -> Vec<RunConfig> {
    let mut set = Vec::new();
    for shape in CharacterShape::ALL {
        for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            let why = match (building, shape) {
                (ColliderBuilding::Merged, CharacterShape::Cuboid) => WHY_NAIVE_STUCK,
                _ => WHY_DEFAULT,
            };
            set.push(run(building, shape).with_why(why));
        }
    }
    for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
        for shape in CharacterShape::ALL {
            let advised = run_with(RapierConfig {
                colliders: building,
                shape,
                grounded_move: GroundedMove::NoneExceptTestbedOnPlatforms,
                ..Default::default()
            });
            set.push(advised.with_why(WHY_ADVISED));
        }
    }
    set
}

/// The design of Rapier fed gravity every step ([`RunConfig::why`]): its offset (its docs say
/// it must not be zero), its ground prediction (docs/rapier.md) and its slide, which projects
/// a horizontal move onto a slope (cos²θ of it horizontally; `KinematicCharacterController`).
pub(crate) const WHY_DEFAULT: &str = "naive feed (gravity each step); grounds offset+0.05 tiles early (predict_ground); slopes at cos²θ (KCC)";

/// The merged cuboid fed gravity every step ([`RunConfig::why`]): the set-up of rapier #613.
pub(crate) const WHY_NAIVE_STUCK: &str = "naive feed (gravity each step): a box on a long merged floor sticks (rapier #613; docs/rapier.md)";

/// The design of Rapier fed as its examples feed it ([`RunConfig::why`]).
pub(crate) const WHY_ADVISED: &str = "advised: no vertical move grounded (bevy_rapier example); testbed's push on platforms (examples2d)";

/// The capsule on per-tile and merged colliders, and on per-tile colliders fed as the
/// bevy_rapier example feeds a character (no vertical move while grounded; gravity on a
/// platform, `grounded=none-but-platforms`): the set-up that walks, so that `progress` is measured on
/// one that holds it at the base case; then that set-up again on rapier2d-f64, so that
/// how far each precision holds is read off the same probes.
pub(crate) fn stress_configs() -> Vec<RunConfig> {
    // The bevy_rapier example's feed (the advised rows' feed on static ground; gravity on a
    // platform), not the advised rows themselves: docs/stability.md says which.
    let bevy = RapierConfig {
        grounded_move: GroundedMove::NoneExceptOnPlatforms,
        ..Default::default()
    };
    vec![
        run(ColliderBuilding::PerTile, CharacterShape::Capsule),
        run(ColliderBuilding::Merged, CharacterShape::Capsule),
        run_with(bevy.clone()),
        run_with(RapierConfig {
            precision: Precision::F64,
            ..bevy
        }),
    ]
}

/// dt, substeps, offset, snap distance, collider building and shape, grounded feed.
pub(crate) fn tradeoff_settings() -> Vec<Setting> {
    let r = RapierConfig::default;
    let mut g = Vec::new();
    for hz in [30.0f32, 60.0, 120.0, 240.0, 480.0] {
        g.push(Setting::new(
            &format!("per-tile capsule dt=1/{hz}"),
            r(),
            1,
            Some(1.0 / hz),
        ));
    }
    for k in [2, 4] {
        g.push(Setting::new(
            &format!("per-tile capsule substeps={k}"),
            r(),
            k,
            Some(1.0 / 60.0),
        ));
    }
    for off in [0.005f32, 0.02] {
        let c = RapierConfig {
            offset: Length::Relative(off),
            ..r()
        };
        g.push(Setting::new(
            &format!("per-tile capsule offset={off}h"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    for (name, snap) in [("none", None), ("0.4h", Some(Length::Relative(0.4)))] {
        let c = RapierConfig {
            snap_to_ground: snap,
            ..r()
        };
        g.push(Setting::new(
            &format!("per-tile capsule snap={name}"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    for (name, colliders, shape) in [
        (
            "merged capsule",
            ColliderBuilding::Merged,
            CharacterShape::Capsule,
        ),
        (
            "per-tile cuboid",
            ColliderBuilding::PerTile,
            CharacterShape::Cuboid,
        ),
        (
            "merged cuboid",
            ColliderBuilding::Merged,
            CharacterShape::Cuboid,
        ),
    ] {
        let c = RapierConfig {
            colliders,
            shape,
            ..r()
        };
        g.push(Setting::new(name, c, 1, Some(1.0 / 60.0)));
    }
    // How a grounded step is fed (`GroundedMove`): the bevy_rapier example's feed, the variant
    // that feeds gravity on platforms, the advised feed (the built-in advised rows: the
    // testbed's push on platforms) and Rapier's 2D testbed's push everywhere.
    for grounded_move in [
        GroundedMove::None,
        GroundedMove::NoneExceptOnPlatforms,
        GroundedMove::NoneExceptTestbedOnPlatforms,
        GroundedMove::Testbed,
    ] {
        let name = grounded_move.label();
        let c = RapierConfig {
            grounded_move,
            ..r()
        };
        g.push(Setting::new(
            &format!("per-tile capsule grounded={name}"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    for (name, offset) in [("0.02", 0.02f32), ("0.05", 0.05)] {
        let c = RapierConfig {
            offset: Length::Absolute(offset),
            ..r()
        };
        g.push(Setting::new(
            &format!("per-tile capsule offset={name}"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    g
}

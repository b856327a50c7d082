//! Box2D's mover's presets, as data beside the controller: the configurations of the built-in
//! comparison, the ones `platbench stress` checks, and the grid `platbench sweep` measures.

use super::kind::run_with;
use super::{Box2dConfig, ColliderBuilding};
use crate::config::RunConfig;
use crate::config::Setting;

/// The design of the sample's mover ([`RunConfig::why`]): its pogo, no rider carry, no slope
/// limit (docs/box2d.md).
pub(crate) const WHY: &str = "stands on a 5 Hz pogo spring, not a contact; carries no rider; no slope limit (Box2D's Mover sample)";

/// The sample's capsule on one box per tile and on merged chain loops.
pub(crate) fn configs() -> Vec<RunConfig> {
    [ColliderBuilding::PerTile, ColliderBuilding::Merged]
        .into_iter()
        .map(|colliders| {
            run_with(Box2dConfig {
                colliders,
                ..Default::default()
            })
            .with_why(WHY)
        })
        .collect()
}

pub(crate) fn stress_configs() -> Vec<RunConfig> {
    configs()
}

/// dt, substeps, the loop's iterations and tolerance, the pogo spring, collider building.
pub(crate) fn tradeoff_settings() -> Vec<Setting> {
    let d = Box2dConfig::default;
    let mut g = Vec::new();
    for hz in [30.0f32, 60.0, 120.0, 240.0, 480.0] {
        g.push(Setting::new(
            &format!("per-tile capsule dt=1/{hz}"),
            d(),
            1,
            Some(1.0 / hz),
        ));
    }
    for k in [2, 4] {
        g.push(Setting::new(
            &format!("per-tile capsule substeps={k}"),
            d(),
            k,
            Some(1.0 / 60.0),
        ));
    }
    for n in [1u32, 10] {
        let c = Box2dConfig {
            max_iterations: n,
            ..d()
        };
        g.push(Setting::new(
            &format!("per-tile capsule iterations={n}"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    for tol in [0.001f32, 0.05] {
        let c = Box2dConfig {
            tolerance: tol,
            ..d()
        };
        g.push(Setting::new(
            &format!("per-tile capsule tolerance={tol}"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    for hz in [10.0f32, 20.0] {
        let c = Box2dConfig {
            pogo_hertz: hz,
            ..d()
        };
        g.push(Setting::new(
            &format!("per-tile capsule pogo={hz}Hz"),
            c,
            1,
            Some(1.0 / 60.0),
        ));
    }
    let c = Box2dConfig {
        colliders: ColliderBuilding::Merged,
        ..d()
    };
    g.push(Setting::new("merged capsule", c, 1, Some(1.0 / 60.0)));
    g
}

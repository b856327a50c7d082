//! Box2D's mover's presets, as data beside the controller: the configurations of the built-in
//! comparison, the ones `platbench stress` checks, and the grid `platbench sweep` measures.

use super::kind::run_with;
use super::{Box2dConfig, ColliderBuilding, GroundCarry};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::level::DEFAULT_CHARACTER_SIZE;

/// The design of the sample's mover ([`RunConfig::why`]): its pogo, no rider carry, no slope
/// limit (docs/box2d.md).
pub(crate) const WHY: &str = "stands on a 5 Hz pogo spring, not a contact; carries no rider; no slope limit (Box2D's Mover sample)";

/// The sample's design carried by its ground and on a spring scaled to this character
/// ([`RunConfig::why`]): the advised set-up (docs/box2d.md).
pub(crate) const WHY_ADVISED: &str = "adds its ground body's step (user-side carry, Box2D docs); pogo 5·√(2.2/0.9) = 7.8 Hz (sample's, scaled)";

/// The carry with the trade-off grid's stiffest spring, its best without the carry
/// ([`RunConfig::why`]).
pub(crate) const WHY_STIFF: &str = "adds its ground body's step (user-side carry, Box2D docs); pogo 20 Hz (grid's best spring without carry)";

/// The sample's pogo frequency scaled to the built-in character's height
/// ([`Box2dConfig::scaled_pogo_hertz`] of [`DEFAULT_CHARACTER_SIZE`]: 7.82 Hz).
pub fn advised_pogo_hertz() -> f32 {
    Box2dConfig::scaled_pogo_hertz(DEFAULT_CHARACTER_SIZE.y)
}

/// The stiffest spring of the trade-off grid, in Hz: its best Box2D setting without the carry
/// (`per-tile capsule pogo=20Hz` in compare/tradeoff/tradeoff.csv, 0.1096 against the sample's
/// 0.1227; with the carry the advised 7.8 Hz scores better, 0.0825 against 0.0890).
pub const STIFF_POGO_HERTZ: f32 = 20.0;

/// The sample's capsule on one box per tile and on merged chain loops; then, per tile, the
/// advised set-up (the user-side carry and the spring scaled to the character, docs/box2d.md)
/// and the carry with the trade-off grid's stiffest spring.
pub(crate) fn configs() -> Vec<RunConfig> {
    let mut set: Vec<RunConfig> = [ColliderBuilding::PerTile, ColliderBuilding::Merged]
        .into_iter()
        .map(|colliders| {
            run_with(Box2dConfig {
                colliders,
                ..Default::default()
            })
            .with_why(WHY)
        })
        .collect();
    for (hertz, why) in [
        (advised_pogo_hertz(), WHY_ADVISED),
        (STIFF_POGO_HERTZ, WHY_STIFF),
    ] {
        let config = Box2dConfig {
            carry: GroundCarry::Ground,
            pogo_hertz: hertz,
            ..Default::default()
        };
        set.push(run_with(config).with_why(why));
    }
    set
}

/// The sample's two rows (the carry and the spring change no bound the stress probes).
pub(crate) fn stress_configs() -> Vec<RunConfig> {
    configs().into_iter().take(2).collect()
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
    for hz in [10.0f32, STIFF_POGO_HERTZ] {
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
    // The built-in rows with the user-side carry (the advised spring and the stiffest), so
    // the grid holds Box2D's advised set-up as it holds Rapier's advised feed.
    for hz in [advised_pogo_hertz(), STIFF_POGO_HERTZ] {
        let c = Box2dConfig {
            carry: GroundCarry::Ground,
            pogo_hertz: hz,
            ..d()
        };
        // Named as the built-in rows are (`per-tile capsule carry=ground pogo=7.8Hz`).
        g.push(Setting::new(&c.label(), c, 1, Some(1.0 / 60.0)));
    }
    let c = Box2dConfig {
        colliders: ColliderBuilding::Merged,
        ..d()
    };
    g.push(Setting::new("merged capsule", c, 1, Some(1.0 / 60.0)));
    g
}

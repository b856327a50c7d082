//! The sweep's presets, as data beside the controller: the configurations of the built-in
//! comparison, the ones `platbench stress` checks, and the grid `platbench sweep` measures.

use super::kind::{run_default, run_double, run_integer};
use super::{Positions, SweepConfig};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::motion::{JumpMode, MotionParams};

/// The default sweep's design ([`RunConfig::why`]): the seed's slope rule.
pub(crate) const WHY_DEFAULT: &str = "stands a box on the slope under its centre: overhangs ramps by half-width x gradient (Gaul's slides)";

/// The continuous jump formula's design ([`RunConfig::why`]).
pub(crate) const WHY_CONTINUOUS: &str = "jumps at v = sqrt(2gh): exact for continuous motion, short by up to v*dt/2 stepped (Gaul's slides)";

/// Integer positions' design ([`RunConfig::why`]).
pub(crate) const WHY_INTEGER: &str = "positions on an integer grid, 32 a tile: moves, climbs and contacts snap to it (docs/sweep.md)";

/// The default sweep; the sweep with the seed's continuous jump formula, so the two jump
/// modes' apex errors stand side by side; and the sweep on integer positions (32 subpixels
/// per tile; levels it does not model are skipped). Each with its design and source.
pub(crate) fn configs() -> Vec<RunConfig> {
    let continuous = RunConfig {
        label: "jump=continuous".into(),
        params: MotionParams {
            jump_mode: JumpMode::Continuous,
            ..Default::default()
        },
        ..run_default()
    };
    vec![
        run_default().with_why(WHY_DEFAULT),
        continuous.with_why(WHY_CONTINUOUS),
        run_integer(32).with_why(WHY_INTEGER),
    ]
}

pub(crate) fn stress_configs() -> Vec<RunConfig> {
    vec![run_default(), run_integer(32), run_double()]
}

/// dt from 1/30 to 1/480 s, substeps, the epsilon, the jump mode and integer positions.
pub(crate) fn tradeoff_settings() -> Vec<Setting> {
    let p = MotionParams::default;
    let s = SweepConfig::default;
    let mut g = Vec::new();
    for hz in [30.0f32, 60.0, 120.0, 240.0, 480.0] {
        g.push(setting(&format!("dt=1/{hz}"), s(), p(), 1, Some(1.0 / hz)));
    }
    for k in [2, 4] {
        g.push(setting(
            &format!("substeps={k}"),
            s(),
            p(),
            k,
            Some(1.0 / 60.0),
        ));
    }
    for eps in [1e-2f32, 1e-4, 1e-6] {
        let c = SweepConfig {
            epsilon: eps,
            ..s()
        };
        g.push(setting(
            &format!("epsilon={eps}"),
            c,
            p(),
            1,
            Some(1.0 / 60.0),
        ));
    }
    let continuous = MotionParams {
        jump_mode: JumpMode::Continuous,
        ..p()
    };
    g.push(setting(
        "jump=continuous",
        s(),
        continuous,
        1,
        Some(1.0 / 60.0),
    ));
    for per_tile in [16, 32] {
        let c = SweepConfig {
            positions: Positions::Integer { per_tile },
            ..s()
        };
        g.push(setting(
            &format!("positions=integer/{per_tile}"),
            c,
            p(),
            1,
            Some(1.0 / 60.0),
        ));
    }
    g
}

/// [`Setting::new`] with motion parameters of its own (the jump-mode settings change them).
fn setting(
    label: &str,
    config: SweepConfig,
    params: MotionParams,
    substeps: u32,
    dt: Option<f32>,
) -> Setting {
    let mut s = Setting::new(label, config, substeps, dt);
    s.run.params = params;
    s
}

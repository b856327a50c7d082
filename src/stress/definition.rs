//! The stress matrix's definition: its dimensions and the values each takes, the base case, the
//! pairs run on small grids, the invariants checked with the documented tolerances they are held
//! to, and how a dimension's value is written.

use crate::backend::Precision;

/// One dimension of the stress matrix and the values it takes (the base case is the default
/// everywhere else).
#[derive(Clone, Debug)]
pub struct Dimension {
    /// Name, as in `stability.csv`.
    pub name: &'static str,
    /// Values, in the dimension's unit, in increasing order.
    pub values: Vec<f64>,
    /// The base case's value (one of `values`): where every other dimension stays while this
    /// one is varied.
    pub base: f64,
}

/// The base case: origin at 0, dt 1/60 s, fast mover at 100 tiles/s, a 0.8-tile-wide
/// character, the seed's epsilon 1e-3.
pub const BASE: Case = Case {
    offset: 0.0,
    dt: 1.0 / 60.0,
    speed: 100.0,
    width: 0.8,
    epsilon: 1e-3,
};

/// The base case's value of dimension `name` exactly as the dimensions list it (the f64 of
/// [`BASE`]'s f32 would not compare equal to `1.0 / 60.0`).
fn base_value(name: &str) -> f64 {
    match name {
        "dt" => 1.0 / 60.0,
        "speed" => 100.0,
        "width" => 0.8,
        "epsilon" => 1e-3,
        _ => 0.0,
    }
}

/// The largest offset (tiles) at which f32 configurations are run. Past it an f32 position's
/// spacing is over a tile (8 tiles at 1e8): no probe's step can move a character, every f32
/// configuration measured has broken at or before 1e7 (or refuses the level: integer
/// positions past 2^24 tiles, Box2D), and Rapier's f32 casts there take seconds a point. The
/// offsets past it ([`F64_OFFSETS`]) are run on f64 configurations only.
pub const F32_OFFSET_LIMIT: f64 = crate::limits::MAX_F32_ORIGIN;

/// The offsets past [`F32_OFFSET_LIMIT`] that f64 configurations are run at, up to 1e15 tiles
/// (f64 spacing 1/8 tile there, where an f32 position is at 1e6: the f64 edge, if it is the
/// same spacing as the f32 one, falls inside the range). The probe level's origin is f64
/// ([`Level::origin`](crate::level::Level::origin)), so each offset is placed exactly (1e12 at
/// 1,000,000,000,000, where an f32 origin would be 999,999,995,904);
/// [`crate::limits::MAX_ORIGIN`] is the last of them.
pub const F64_OFFSETS: [f64; 8] = [1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15];

/// The dimensions of DESIGN.md's stress matrix (the offset's values past [`F32_OFFSET_LIMIT`]
/// are run on f64 configurations only, [`points`](super::points)).
pub fn dimensions() -> Vec<Dimension> {
    let dim = |name, values: Vec<f64>| Dimension {
        name,
        base: base_value(name),
        values,
    };
    vec![
        dim(
            "offset",
            [0.0, 1e3, 1e4, 1e5, 1e6, 1e7]
                .into_iter()
                .chain(F64_OFFSETS)
                .collect(),
        ),
        dim("dt", vec![1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.05, 0.2]),
        dim("speed", vec![10.0, 100.0, 1000.0]),
        dim("width", vec![0.01, 0.1, 0.8, 3.0, 10.0]),
        dim("epsilon", vec![1e-9, 1e-7, 1e-5, 1e-3, 1e-1]),
    ]
}

/// The offsets of the combination grids for configurations in `precision`: the three decades
/// before the precision's one-dimension edge (where the sweep's positions still snap and rest),
/// so that the grid shows what a finer step, a faster mover or a smaller epsilon adds there. In
/// f32 1e4, 1e5 and 1e6 tiles (spacing 1/1024, 1/128 and 1/16 tile; 1e7 breaks every
/// configuration alone; the walk's progress alone already leaves its band at 1e5 and 1e6, by
/// the rounding of its 0.1-tile step). In f64 1e11, 1e12 and 1e13 (spacing 2^-16, 2^-13 and
/// 2^-9 tile, about 1.5e-5, 1.2e-4 and 2.0e-3; each holds alone, 1e14 breaks): an f64 world's
/// positions there are as coarse as an f32 world's at 1e3 to 1e5, so the same interactions (a
/// step of a few spacings or under one, an epsilon under one spacing) reach it there, where an
/// f32 grid would show an f64 configuration nothing (its spacing at 1e6 is 1.2e-10 tile).
pub fn pair_offsets(precision: Precision) -> Vec<f64> {
    match precision {
        Precision::F32 => vec![1e4, 1e5, 1e6],
        Precision::F64 => vec![1e11, 1e12, 1e13],
    }
}

/// The pairs of dimensions whose failures interact, each on a small grid (the base case
/// elsewhere), for configurations in `precision`: an epsilon below the spacing far out, a step
/// too small to move a position far out, a time step too coarse for a fast mover, a tiny
/// character at speed, and a fast mover far out. The grids straddle the one-dimension edges
/// measured alone; the offsets are the precision's own ([`pair_offsets`]).
pub fn pairs(precision: Precision) -> Vec<(Dimension, Dimension)> {
    let dim = |name, values: Vec<f64>| Dimension {
        name,
        base: base_value(name),
        values,
    };
    let offsets = || dim("offset", pair_offsets(precision));
    let dts = match precision {
        // 1e-3 s rather than the one-dimension 1e-4: its walking step (6e-3 tiles) is
        // already under the f32 spacing at 1e5 tiles (1/128), at a tenth of the cost.
        Precision::F32 => vec![1e-3, 1.0 / 240.0, 0.05],
        // 1e-4 s as well: its walking step (6e-4 tiles) is 5 f64 spacings at 1e12 and under
        // one at 1e13, where 1e-3 s (6e-3 tiles, 3.07 spacings) rounds to 3: the steps that
        // f32 meets at 1e4 to 1e5. 0.05 s stays for the coarse side (a jump's steps).
        Precision::F64 => vec![1e-4, 1e-3, 0.05],
    };
    vec![
        (offsets(), dim("epsilon", vec![1e-7, 1e-5, 1e-3])),
        (offsets(), dim("dt", dts)),
        (
            dim("speed", vec![100.0, 1000.0]),
            dim("dt", vec![1.0 / 240.0, 0.05, 0.2]),
        ),
        (
            dim("width", vec![0.01, 0.1, 10.0]),
            dim("speed", vec![100.0, 1000.0]),
        ),
        (offsets(), dim("speed", vec![10.0, 1000.0])),
    ]
}

/// One point of the matrix: the value of every dimension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Offset of the probe level's origin from the world origin, in tiles (both axes), in f64 so
    /// that the far offsets are exact ([`F64_OFFSETS`]).
    pub offset: f64,
    /// Time step, in seconds.
    pub dt: f32,
    /// The fast mover's speed towards the wall, in tiles/s.
    pub speed: f32,
    /// The character's width, in tiles (its height is 1.125 times that).
    pub width: f32,
    /// The overlap tolerance, in tiles, for a configuration that has one (others ignore it).
    pub epsilon: f32,
}

impl Case {
    /// The value of dimension `name` (0 for an unknown name).
    pub fn get(&self, name: &str) -> f64 {
        match name {
            "offset" => self.offset,
            "dt" => self.dt as f64,
            "speed" => self.speed as f64,
            "width" => self.width as f64,
            "epsilon" => self.epsilon as f64,
            _ => 0.0,
        }
    }

    /// This case with dimension `name` set to `v` (an unknown name changes nothing).
    pub fn with(mut self, name: &str, v: f64) -> Self {
        match name {
            "offset" => self.offset = v,
            "dt" => self.dt = v as f32,
            "speed" => self.speed = v as f32,
            "width" => self.width = v as f32,
            "epsilon" => self.epsilon = v as f32,
            _ => {}
        }
        self
    }
}

/// The invariants, in the order they are checked and named (the first that breaks colours a
/// combination cell).
pub const INVARIANTS: [&str; 9] = [
    "finite",
    "penetration",
    "no_tunneling",
    "stable_rest",
    "no_flicker",
    "carry_no_drift",
    "progress",
    "no_stuck",
    "jump_height",
];

/// The least fraction of the commanded distance a walk over flat seamed ground must cover.
/// The commanded distance already includes the acceleration ramp, so an exact controller
/// covers 1.0 up to rounding; 1% is what rounding a walking step (0.1 tiles at 1/60 s) onto
/// the f32 grid can cost where the spacing is a few thousandths of a tile, and the loss the
/// report already calls progress lost (`progress_ratio < 0.99`). Rapier's walks at 1e5 tiles (91%
/// to 96% per tile) are broken by it. The most is [`PROGRESS_MAX`].
pub const PROGRESS_MIN: f64 = 0.99;

/// How far the fraction of the commanded distance a walk covers may be from 1, either way:
/// `1 - PROGRESS_MIN`, 1%. Rounding a step to the nearest representable position lengthens it
/// as readily as it shortens it (a 0.1-tile step is 1.6 spacings of 1/16 tile at 1e6 tiles and
/// rounds up to 2: 125%), so the band is symmetric about 1 with the tolerance the short side
/// already had: a walk that overshoots by more than 1% has not held either (it carries the
/// character past where the game put it, a ledge or a door), and every configuration is held
/// to the same band.
pub const PROGRESS_BAND: f64 = 1.0 - PROGRESS_MIN;

/// The largest fraction of the commanded distance a walk may cover: `1 + PROGRESS_BAND`, 101%.
pub const PROGRESS_MAX: f64 = 1.0 + PROGRESS_BAND;

/// How far a jump's apex may miss the requested height, in tiles: one pixel of a 16-pixel tile
/// (the seed's slope tiles are drawn in 16ths), below which a player sees no difference and the
/// seed's "jump exactly 3 tiles" still holds.
pub const JUMP_TOLERANCE: f64 = 1.0 / 16.0;

/// A setting's value, short: four significant digits at most, powers of ten for the very large
/// and very small (1e6 tiles, 1e-9 epsilon, dt 0.0167).
pub fn format_setting(v: f64) -> String {
    if v != 0.0 && v.is_finite() && (v.abs() >= 1e4 || v.abs() < 1e-3) {
        let rounded: f64 = format!("{v:.3e}").parse().unwrap_or(v);
        format!("{rounded:e}")
    } else {
        let rounded: f64 = format!("{v:.4}").parse().unwrap_or(v);
        format!("{rounded}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_print_short() {
        // The stress matrix's own values (dimensions above) as the report shows them.
        let shown: Vec<String> = [0.0, 1e3, 1e6, 1e7, 1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.2, 1e-9]
            .iter()
            .map(|&v| format_setting(v))
            .collect();
        assert_eq!(
            shown,
            ["0", "1000", "1e6", "1e7", "1e-4", "0.0042", "0.0167", "0.2", "1e-9"]
        );
    }
}

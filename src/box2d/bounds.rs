//! The bounds the Box2D backend is kept within, by design: Box2D's linear slop and the capsule
//! radius it needs over it ([`check_radius`]), and the largest level whose f32 shape casts keep
//! that slop ([`check_extent`]). Beyond either Box2D asserts, so both are refused as
//! `Unsupported`.

use glam::Vec2;

use crate::backend::BackendError;
use crate::level::Level;

use super::{kind, Box2dConfig};

/// Box2D's linear slop at one length unit per metre (`B2_LINEAR_SLOP`, 0.005 m; one tile is one
/// metre here): `b2SolvePlanes` keeps the capsule this far off every plane ("add slop to
/// prevent jitter").
pub const LINEAR_SLOP: f32 = 0.005;

/// The largest width or height of a level Box2D runs, in tiles (2^14). Its static shapes are kept
/// in the level's own coordinates ([`LevelWorld`](super::LevelWorld)), and Box2D's f32 shape casts
/// run in those coordinates: within 2^14 tiles of the level's corner the f32 spacing is at most
/// 2^-10 tile, a fifth of the linear slop the pogo's cast stops short by; Box2D's `constants.h`:
/// "Positions greater than about 16km will have precision problems in single precision" (one tile
/// is one metre here). Farther out the cast can end at a distance of exactly 0, which Box2D asserts
/// against (`b2ShapeCast`, distance.c line 668, `distanceOutput.distance > 0.0f`), killing the
/// process unless its C code is built with `NDEBUG`: a pogo cast 6e4 tiles along a flat floor did
/// (2e4 and 4e4 ran). A larger level is refused as `Unsupported`, a bound kept by design. The
/// level's origin is not bounded by this: placing it moves the ground body, not the arithmetic.
pub const MAX_LEVEL_EXTENT: u32 = 1 << 14;

/// Refuses a character whose capsule radius is not over twice Box2D's linear slop, where Box2D
/// asserts (a bound kept by design).
pub fn check_radius(config: &Box2dConfig, size: Vec2) -> Result<(), BackendError> {
    let (radius, _, _) = config.capsule(size);
    if radius <= 2.0 * LINEAR_SLOP {
        return Err(BackendError::Unsupported {
            backend: kind::NAME,
            feature: format!(
                "a character of size {size} (Box2D's mover needs a capsule radius, half the width or half the height above the pogo leg, over 0.01 tiles, twice its linear slop)"
            ),
            level: String::new(),
            beyond_bound: true,
        });
    }
    Ok(())
}

/// Refuses a level wider or taller than [`MAX_LEVEL_EXTENT`] tiles, as a bound kept by design.
pub fn check_extent(level: &Level) -> Result<(), BackendError> {
    if level.width.max(level.height) > MAX_LEVEL_EXTENT {
        return Err(BackendError::Unsupported {
            backend: kind::NAME,
            feature: format!(
                "a level of {} x {} tiles (Box2D's f32 shape casts run in the level's own \
                 coordinates and keep its linear slop only within {MAX_LEVEL_EXTENT} tiles \
                 of the level's corner; beyond, a cast can end at a distance of exactly 0, \
                 where Box2D asserts and aborts the process)",
                level.width, level.height
            ),
            level: level.name.clone(),
            beyond_bound: true,
        });
    }
    Ok(())
}

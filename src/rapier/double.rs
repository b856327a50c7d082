//! The Rapier backend in double precision: the same source as [`crate::rapier`]
//! (`backend.rs`, `colliders.rs`, `platforms.rs`) compiled on rapier2d-f64 and parry2d-f64,
//! whose positions are glam's `DVec2`. A configuration runs here when its
//! [`RapierConfig::precision`](super::RapierConfig::precision) is f64.
//!
//! World positions (the characters', the colliders', the platforms') are f64, placed at the
//! level's origin; the level's own geometry and the harness's inputs stay f32 in level
//! coordinates (a few hundred tiles, spacing under 1e-4 tile) and are widened exactly; what the
//! backend reports ([`crate::backend::CharacterState`]) is brought back to level coordinates in
//! f64 before it is rounded to f32, so it keeps the precision of the world it ran in.

// Loading these files a second time is the point (clippy's duplicate_mod warns of it as a
// mistake): each build resolves `super::precision` to its own engine and types.
#[allow(clippy::duplicate_mod)]
#[path = "backend.rs"]
mod backend;
#[allow(clippy::duplicate_mod)]
#[path = "colliders.rs"]
pub mod colliders;
#[allow(clippy::duplicate_mod)]
#[path = "platforms.rs"]
pub mod platforms;

pub use backend::{build_shape, controller, pose, Move, RapierBackend};
pub use colliders::{one_way_top, StaticWorld};
pub use platforms::Platforms;

use super::{CharacterShape, GroundedMove, Length, PlatformCarry, PlatformOrder, RapierConfig};
use super::{CLIMB_LIMIT_MARGIN, GROUND_PREDICTION, ONE_WAY_TOLERANCE};

/// The f64 build: rapier2d-f64 and parry2d-f64, glam's `DVec2`.
mod precision {
    use glam::{DVec2, Vec2};

    pub use ::rapier2d_f64 as engine;
    /// The engine's scalar.
    pub type Real = f64;
    /// The engine's vector.
    pub type Vect = DVec2;
    /// The backend's name in this precision (the same kind as the f32 build's; the
    /// configuration's label says f64).
    pub const NAME: &str = "rapier";

    /// A vector of the harness (f32) in the engine's type (exact).
    #[inline]
    pub fn v(x: Vec2) -> Vect {
        x.as_dvec2()
    }
    /// A vector of the engine in the harness's f32 (rounded to nearest).
    #[inline]
    pub fn back(x: Vect) -> Vec2 {
        x.as_vec2()
    }
    /// A scalar of the harness (f32) in the engine's type (exact).
    #[inline]
    pub fn s(x: f32) -> Real {
        x as f64
    }
    /// Where `level`'s corner sits in the engine's world: its f64 origin, exactly.
    #[inline]
    pub fn level_origin(level: &crate::level::Level) -> Vect {
        level.origin
    }
    /// A one-way top's bits, for a collider's `user_data`.
    pub fn top_bits(top: Real) -> u128 {
        top.to_bits() as u128
    }
    /// A one-way top from a collider's `user_data`.
    pub fn top_from_bits(data: u128) -> Real {
        Real::from_bits(data as u64)
    }
    /// [`crate::ladder::enter`] in level coordinates (the ladder rules read tiles, for which
    /// f32 level coordinates are exact enough); only the x it clamps to the ladder's centre is
    /// written back, so a position it does not touch keeps its f64 bits.
    pub fn ladder_enter(
        level: &crate::level::Level,
        origin: Vect,
        m: &mut crate::motion::MotionState,
        pos: &mut Vect,
        size: Vec2,
        input: &crate::motion::Input,
    ) {
        let mut local = back(*pos - origin);
        let before = local;
        crate::ladder::enter(level, Vec2::ZERO, m, &mut local, size, input);
        if local.x != before.x {
            pos.x = origin.x + local.x as f64;
        }
    }
    /// [`crate::ladder::leave`] in level coordinates (it moves nothing).
    pub fn ladder_leave(
        level: &crate::level::Level,
        origin: Vect,
        m: &mut crate::motion::MotionState,
        pos: Vect,
        size: Vec2,
        input: &crate::motion::Input,
    ) {
        crate::ladder::leave(level, Vec2::ZERO, m, back(pos - origin), size, input)
    }
}

//! The mover's settings (Godot 4's `CharacterBody2D` properties and their defaults, in tiles) and
//! the constants its rules share.

use platbench::prelude::*;

/// How far below a one-way platform's top the feet may start and still stand on it, in tiles.
pub const ONE_WAY_TOLERANCE: f32 = 1e-3;

/// Godot's `FLOOR_ANGLE_THRESHOLD`-like slack on `floor_max_angle`, in radians, so that a
/// 45-degree ramp is a floor under a 45-degree limit despite rounding.
pub const FLOOR_ANGLE_SLACK: f32 = 0.01;

/// Settings of the collide-and-slide mover. Godot's defaults are given in pixels; at the 16
/// pixels per tile of pixel-art platformers they are the tile values below.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveAndSlideConfig {
    /// The character's collision shape, fitted to its box (default: a cuboid, Godot's
    /// `RectangleShape2D`).
    pub shape: CharacterShape,
    /// Gap the mover keeps from what it hits, in tiles: a cast stops this far short of a
    /// contact (Godot's `safe_margin`, default 0.08 px: 0.005 tiles).
    pub safe_margin: f32,
    /// How many times one step may hit something and slide on (Godot's `max_slides`, default 4).
    pub max_slides: u32,
    /// Steepest surface that counts as a floor, in radians from up (Godot's
    /// `floor_max_angle`, default 45 degrees).
    pub floor_max_angle: f32,
    /// How far below the feet a floor is snapped to after a step that was on the floor and is
    /// not rising, in tiles (Godot's `floor_snap_length`, default 1 px: 0.0625 tiles); 0 turns
    /// snapping off.
    pub floor_snap_length: f32,
    /// Whether a character on a slope with no horizontal move stays put instead of sliding
    /// down, and the first hit of a step on a floor is cast again unslid rather than slid along
    /// (Godot's `floor_stop_on_slope`, default true).
    pub floor_stop_on_slope: bool,
    /// Whether a wall hit while walking on the floor stops the move instead of sliding up it: a
    /// character that walked off its floor into the wall has the move cancelled and is snapped
    /// back down, one still on the floor casts the rest again unslid, and one in the air slides
    /// only the vertical part of the rest (Godot's `floor_block_on_wall`, default true).
    pub floor_block_on_wall: bool,
    /// Whether a character on the floor moves along slopes at the speed it would have on flat
    /// ground, rather than slower uphill and faster downhill (Godot's `floor_constant_speed`,
    /// default false). As in Godot, the speed along the slope is the flat-ground speed, so the
    /// horizontal speed on a slope is lower.
    pub floor_constant_speed: bool,
}

impl Default for MoveAndSlideConfig {
    fn default() -> Self {
        MoveAndSlideConfig {
            shape: CharacterShape::Cuboid,
            safe_margin: 0.08 / 16.0,
            max_slides: 4,
            floor_max_angle: 45f32.to_radians(),
            floor_snap_length: 1.0 / 16.0,
            floor_stop_on_slope: true,
            floor_block_on_wall: true,
            floor_constant_speed: false,
        }
    }
}

impl MoveAndSlideConfig {
    /// Label for tables and file names: the shape, then each setting that differs from the default.
    pub fn label(&self) -> String {
        let d = MoveAndSlideConfig::default();
        let mut label = self.shape.label();
        if self.floor_constant_speed != d.floor_constant_speed {
            label += &format!(" constant_speed={}", self.floor_constant_speed);
        }
        if self.floor_snap_length != d.floor_snap_length {
            label += &format!(" snap={}", self.floor_snap_length);
        }
        if self.floor_stop_on_slope != d.floor_stop_on_slope {
            label += &format!(" stop_on_slope={}", self.floor_stop_on_slope);
        }
        if self.floor_block_on_wall != d.floor_block_on_wall {
            label += &format!(" block_on_wall={}", self.floor_block_on_wall);
        }
        if self.safe_margin != d.safe_margin {
            label += &format!(" margin={}", self.safe_margin);
        }
        if self.max_slides != d.max_slides {
            label += &format!(" slides={}", self.max_slides);
        }
        label
    }

    pub(crate) fn validate(&self) -> Result<(), BackendError> {
        let bad =
            |name, value: f32, expected| Err(platbench::backend::invalid(name, value, expected));
        if !(self.safe_margin.is_finite() && self.safe_margin >= 0.0) {
            return bad("safe_margin", self.safe_margin, "tiles, finite and >= 0");
        }
        if !(self.floor_max_angle > 0.0 && self.floor_max_angle < std::f32::consts::FRAC_PI_2) {
            return bad(
                "floor_max_angle",
                self.floor_max_angle,
                "radians, 0 < angle < pi/2",
            );
        }
        if !(self.floor_snap_length.is_finite() && self.floor_snap_length >= 0.0) {
            return bad(
                "floor_snap_length",
                self.floor_snap_length,
                "tiles, finite and >= 0",
            );
        }
        Ok(())
    }
}

//! The sweep as a kind of backend: what the harness needs to know of it (its name, shape,
//! contact tolerance, the level features each position mode models, its built-in
//! configurations and its `platbench sweep` grid), on the public API of [`SweepBackend`] and
//! [`SweepConfig`] only.

use glam::Vec2;

use super::{Positions, SweepBackend, SweepConfig, DOUBLE_SUPPORTED, INTEGER_SUPPORTED};
use crate::backend::{
    BackendError, Capabilities, CharacterId, CharacterState, DeclaredContact, Precision,
    ShownByDefault,
};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::controller::{Controller, Setup};
use crate::level::{Features, Level};
use crate::motion::Input;
use crate::shape::CharacterShape;

/// The backend's name, as in CSV files.
pub const NAME: &str = "sweep";

impl Controller for SweepConfig {
    type Mover = SweepBackend;
    const NAME: &'static str = NAME;

    fn shape(&self) -> CharacterShape {
        CharacterShape::Cuboid
    }

    /// The float mode models every feature; the f64 and integer modes fewer.
    fn features(&self) -> Features {
        match self.positions {
            Positions::Float => SweepBackend::SUPPORTED,
            Positions::Double => DOUBLE_SUPPORTED,
            Positions::Integer { .. } => INTEGER_SUPPORTED,
        }
    }

    /// On integer positions, a grid that holds the level's origin.
    fn check_level(&self, level: &Level) -> Result<(), BackendError> {
        if let Positions::Integer { per_tile } = self.positions {
            super::grid::Grid::new(per_tile, level.origin_f32(), &level.name)?;
        }
        Ok(())
    }

    fn declared_contact(&self, size: Vec2, max_climb_angle: f32) -> DeclaredContact {
        match self.positions {
            Positions::Float | Positions::Double => DeclaredContact {
                gap: 0.0,
                overlap_tolerance: self.epsilon,
                gap_tolerance: self.epsilon,
                slope_overhang: size.x * 0.5 * max_climb_angle.tan(),
                stance_half_width: 0.0,
                stance_sink: 0.0,
                surface_grid: 0,
            },
            // No gap and no tolerance (it snaps exactly), and the seed's centre-column stance
            // on slopes for the box it really moves.
            Positions::Integer { per_tile } => DeclaredContact {
                slope_overhang: self.moved_size(size).x * 0.5 * max_climb_angle.tan(),
                surface_grid: per_tile,
                ..DeclaredContact::default()
            },
        }
    }

    /// The epsilon in float mode; none on integer positions (they snap exactly).
    fn contact_tolerance(&self, _size: Vec2) -> f64 {
        match self.positions {
            Positions::Float | Positions::Double => self.epsilon as f64,
            Positions::Integer { .. } => 0.0,
        }
    }

    /// Integer positions round the box up to whole subpixels (0.8 x 0.9 tiles at 32 per tile
    /// is 26 x 29 subpixels, 0.8125 x 0.90625 tiles).
    fn moved_size(&self, size: Vec2) -> Vec2 {
        match self.positions {
            Positions::Integer { per_tile } => {
                super::grid::subpixel_size(size, per_tile as i64).as_vec2() / per_tile as f32
            }
            Positions::Float | Positions::Double => size,
        }
    }

    fn epsilon(&self) -> Option<f32> {
        matches!(self.positions, Positions::Float | Positions::Double).then_some(self.epsilon)
    }

    /// f64 in the f64 mode ([`Positions::Double`]), else f32 (the integer mode's tile faces are
    /// f32, exact to 2^24 tiles).
    /// Positions on a grid in the integer mode (whole subpixels, the seed's "integer
    /// positions"); nothing else declared: the float modes use the machine's float arithmetic,
    /// which the seed does not promise is the same across platforms, and the sweep pushes no
    /// bodies.
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            integer_positions: matches!(self.positions, Positions::Integer { .. }),
            ..Capabilities::default()
        }
    }

    fn precision(&self) -> Precision {
        match self.positions {
            Positions::Double => Precision::F64,
            _ => Precision::F32,
        }
    }

    /// Integer positions hold to 2^24 tiles ([`super::grid::MAX_GRID_EXTENT`]: their tile faces
    /// are f32, exact that far, and their positions whole subpixels, which an f32 spacing over a
    /// tile does not touch); the float and f64 modes by their precision, as any backend.
    fn max_origin(&self) -> f64 {
        match self.positions {
            Positions::Integer { .. } => super::grid::MAX_GRID_EXTENT,
            Positions::Float | Positions::Double => crate::backend::max_origin_in(self.precision()),
        }
    }

    /// Integer positions place a level only where every tile face and every platform's box is
    /// exact in the broadphase's f32 boxes: within 2^24 tiles of the world's origin
    /// ([`super::grid::MAX_GRID_EXTENT`]); past it an odd face rounds to its even neighbour (a
    /// floor at 2^24 to 2^24 + 1 loses its height). The float and f64 modes: none.
    fn max_reach(&self) -> Option<f64> {
        match self.positions {
            Positions::Integer { .. } => Some(super::grid::MAX_GRID_EXTENT),
            _ => None,
        }
    }

    /// The float mode and the f64 mode are each other's build in the other precision.
    fn with_precision(&self, precision: Precision) -> Option<SweepConfig> {
        let positions = match (self.positions, precision) {
            (Positions::Float, Precision::F64) => Positions::Double,
            (Positions::Double, Precision::F32) => Positions::Float,
            _ => return None,
        };
        Some(SweepConfig {
            positions,
            ..self.clone()
        })
    }

    /// Sets the epsilon (integer positions ignore it).
    fn with_epsilon(&self, epsilon: f32) -> Option<SweepConfig> {
        Some(SweepConfig {
            epsilon,
            ..self.clone()
        })
    }

    fn build(&self, setup: Setup<'_>) -> Result<SweepBackend, BackendError> {
        let mut sweep = SweepBackend::new(setup.level, setup.params.clone(), self.clone())?;
        for c in setup.characters {
            sweep.add_character(*c)?;
        }
        Ok(sweep)
    }

    fn step(&self, mover: &mut SweepBackend, inputs: &[Input], dt: f32) {
        mover.step(inputs, dt);
    }

    fn state(&self, mover: &SweepBackend, id: CharacterId) -> CharacterState {
        mover.state(id)
    }

    fn description() -> &'static str {
        "sweep-and-snap kinematic controller (AABBs, x-then-y moves snapped flush)"
    }

    fn shapes() -> Vec<CharacterShape> {
        vec![CharacterShape::Cuboid]
    }

    fn configs() -> Vec<RunConfig> {
        super::presets::configs()
    }

    fn stress_configs() -> Vec<RunConfig> {
        super::presets::stress_configs()
    }

    fn tradeoff_settings() -> Vec<Setting> {
        super::presets::tradeoff_settings()
    }

    fn drawn() -> Vec<(&'static str, &'static str)> {
        vec![("default", "#1565c0")]
    }

    fn shown_by_default() -> ShownByDefault {
        // The reference the report's replays watch every other controller against.
        ShownByDefault::Listed(vec!["default"])
    }

    fn colour() -> Option<&'static str> {
        Some("#1565c0")
    }
}

/// The default sweep configuration, labelled `default`.
pub fn run_default() -> RunConfig {
    RunConfig::new("default", SweepConfig::default())
}

/// The sweep on integer positions, `per_tile` subpixels per tile.
pub fn run_integer(per_tile: u32) -> RunConfig {
    RunConfig::new(
        format!("positions=integer/{per_tile}"),
        SweepConfig {
            positions: Positions::Integer { per_tile },
            ..Default::default()
        },
    )
}

/// The default sweep in f64 world coordinates ([`Positions::Double`]), labelled `default f64`.
pub fn run_double() -> RunConfig {
    RunConfig::new(
        "default f64",
        SweepConfig {
            positions: Positions::Double,
            ..Default::default()
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::{origin_supported, runs};
    use crate::level::Tile;

    #[test]
    fn each_mode_holds_the_origins_its_storage_places_and_refuses_farther() {
        let level = |o: f64| {
            let mut l = Level::from_tiles(
                "l",
                2,
                2,
                vec![Tile::Solid, Tile::Solid, Tile::Empty, Tile::Empty],
            );
            l.origin = glam::DVec2::new(o, 0.0);
            l
        };
        let float = SweepConfig::default();
        let double = SweepConfig {
            positions: Positions::Double,
            ..float.clone()
        };
        let integer = SweepConfig {
            positions: Positions::Integer { per_tile: 32 },
            ..float.clone()
        };
        // Float: to limits::MAX_F32_ORIGIN (1e7, f32 spacing 1 tile); integer positions to
        // 2^24 (their f32 tile faces' exact extent); f64 to limits::MAX_ORIGIN (1e15).
        for (o, f, i, d) in [
            (1e7, true, true, true),
            (1.6e7, false, true, true),
            (2e7, false, false, true),
            (1e15, false, false, true),
            (2e15, false, false, false),
        ] {
            let l = level(o);
            assert_eq!(origin_supported(&float, &l).is_ok(), f, "float at {o}");
            assert_eq!(runs(&integer, &l), i, "integer at {o}");
            assert_eq!(runs(&double, &l), d, "f64 at {o}");
        }
        // Integer positions bound the level's reach, not its origin alone: the 2 x 2 level's
        // last faces at origin 2^24 - 2 are 2^24 (exact in f32), at 2^24 - 1 they are 2^24 + 1
        // (rounded to 2^24); to the left its corner is the farthest face; a platform whose
        // path reaches past 2^24 is refused with it.
        let edge = super::super::grid::MAX_GRID_EXTENT;
        assert!(runs(&integer, &level(edge - 2.0)));
        assert!(!runs(&integer, &level(edge - 1.0)));
        assert!(runs(&integer, &level(-edge)));
        assert!(!runs(&integer, &level(-edge - 1.0)));
        let mut platform = level(edge - 10.0);
        platform.platforms.push(crate::level::Platform {
            start: glam::Vec2::new(0.0, 0.0),
            size: glam::Vec2::new(1.0, 0.5),
            motion: crate::level::PlatformMotion::Waypoints {
                points: vec![glam::Vec2::ZERO, glam::Vec2::new(9.5, 0.0)],
                speed: 1.0,
            },
            one_way: false,
        });
        assert!(!runs(&integer, &platform), "a path to 2^24 + 0.5");
        assert!(runs(&double, &platform));
        let e = origin_supported(&float, &level(-2e7))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a level origin of (-20000000, 0) tiles in f32"),
            "{e}"
        );
    }
}

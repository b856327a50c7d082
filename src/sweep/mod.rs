//! The sweep-and-snap controller of the seed slides.
//!
//! One step per character, `step.rs`'s numbered steps in the order they run, each a named
//! function in the file of its stage:
//!
//! 1. ladder enter (`ladders.rs`);
//! 2. forces and integration, symplectic Euler with a force accumulator (`integrate.rs`, the
//!    shared [`crate::motion`]);
//! 3. the x move, swept and snapped flush to the closest obstacle found through the parry2d
//!    broadphase (`resolve.rs`, `broadphase.rs`), one-way boxes skipped (`oneway.rs`);
//! 4. the climb limit (`slopes.rs`);
//! 5. the y move, one-way boxes blocking only a fall from entirely above (`oneway.rs`);
//! 6. ground on slopes, the seed's centre column (`slopes.rs`);
//! 7. contacts: the blocked axis loses its velocity and the other gets friction
//!    (`integrate.rs`);
//! 8. ladder leave (`ladders.rs`);
//!
//! then, once every character has stepped, the moving platforms move and carry or push them
//! (`platforms.rs`). The step, its stages and the one sweep-and-snap are generic over how
//! positions are stored (`space.rs`): f32 with the seed's epsilon, f64 with the same epsilon
//! ([`Positions::Double`]), or whole subpixels ([`grid`]); the mode is chosen once, when the
//! backend is built. A level without slopes, one-way platforms, ladders or platforms runs none
//! of their code ([`SweepStats`] counts it).

mod broadphase;
pub mod grid;
mod integrate;
pub mod kind;
mod ladders;
mod oneway;
mod platforms;
mod presets;
mod resolve;
mod slopes;
mod space;
mod step;

use glam::Vec2;

use crate::backend::{require_supported, BackendError, CharacterId, CharacterSpec, CharacterState};
use crate::level::{Features, Level};
use crate::motion::{Input, MotionParams, MotionState};
use broadphase::{NearCache, StaticTiles};
use grid::Grid;
use platforms::Platforms;
use resolve::Obstacles;
use space::{Body, DoubleSpace, FloatSpace, Frame, GridSpace, Space};

/// How the sweep stores positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Positions {
    /// f32 world coordinates with the seed's epsilon tolerance.
    Float,
    /// Whole subpixels (`per_tile` per tile) with the fractions carried between steps, snapping
    /// flush in exact integer arithmetic ([`grid`]). Slopes use the float mode's centre-column
    /// rules with every surface height rounded up to a whole subpixel
    /// ([`crate::level::round_height_up`]); moving platforms move in whole subpixels along
    /// their path rounded to the grid, and carry, push and crush in integers.
    Integer {
        /// Subpixels per tile (16 and 32 are what pixel-art platformers use).
        per_tile: u32,
    },
    /// f64 world coordinates with the seed's epsilon tolerance: the float mode's rules, every
    /// move swept and snapped in f64, for levels far from the world's origin. Moving platforms
    /// follow their path in level coordinates placed at the origin in f64, and carry, push and
    /// crush by f64 displacements.
    Double,
}

/// The features the f64 mode models: all of them.
pub const DOUBLE_SUPPORTED: Features = Features::ALL;

/// The features the integer mode models.
pub const INTEGER_SUPPORTED: Features = Features {
    slopes: true,
    one_way: true,
    ladders: true,
    moving_platforms: true,
};

/// Settings of the sweep controller.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepConfig {
    /// The seed's overlap tolerance, in tiles: an overlap smaller than this is not a collision,
    /// so rounding after a snap never reads as a new hit. The seed: "try 0.001, and lower until
    /// unstable".
    pub epsilon: f32,
    /// How much farther than the steepest walkable slope the ground may drop away under a
    /// walking character and still be followed rather than left, in tiles. Height-array slopes
    /// drop in steps (the seed's tile drops 2/16 of a tile between two columns), so following
    /// them at run speed needs a little more than the walkable gradient. Default: 1/8 tile.
    pub snap_down: f32,
    /// How positions are stored: f32 tiles with the epsilon tolerance (default), f64 tiles with
    /// the same tolerance, or whole subpixels, where `epsilon` plays no part.
    pub positions: Positions,
    /// How a rider follows the moving platform it stands on when the platform moves down
    /// (default [`RiderFollow::Solid`], Celeste's rule: measured on every built-in platform
    /// scenario, it keeps the rider where the gravity rule leaves it airborne, and agrees with
    /// it everywhere else; `tests/behaviour/platforms.rs`).
    pub rider_follow: RiderFollow,
}

/// How a rider follows the moving platform it stands on (the seed: "on integrate platform,
/// integrate objects in list too"; the rules differ only when the platform moves down).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RiderFollow {
    /// A rider follows a descending platform only as far as it could fall in one step from
    /// the platform's previous downward speed under gravity; a platform that drops away faster
    /// (starts down, or turns from rising to falling, more sharply than gravity) leaves it
    /// airborne, as a body resting on it would be in the world.
    Gravity,
    /// Celeste's rule: a rider is moved with every move of the solid it rides, down as well as
    /// up, whatever the platform's acceleration; it leaves only by jumping or walking off.
    #[default]
    Solid,
}

impl Default for SweepConfig {
    fn default() -> Self {
        SweepConfig {
            epsilon: 0.001,
            snap_down: 0.125,
            positions: Positions::Float,
            rider_follow: RiderFollow::Solid,
        }
    }
}

/// One character, its position stored in the coordinate `C` of the backend's mode.
struct Character<C> {
    /// Its box (in the mode's coordinate: the feet in float, the corner on the grid).
    body: Body<C>,
    /// The moving platform it stands on (the seed's rider list, kept on the rider's side: a
    /// platform's riders are the characters whose `riding` names it).
    riding: Option<u32>,
    /// Whether a platform pushed it into the level this step.
    crushed: bool,
    /// Its size as asked, in tiles (the ladder rules' box; the moved box is `body`'s).
    size: Vec2,
    motion: MotionState,
    /// The normal of the ground it stands on (zero in the air), for the trace.
    ground_normal: Vec2,
    /// The static boxes around it, kept between steps.
    near: NearCache<C>,
    /// The cells under its centre the slope rules read, kept between their lookups.
    column: slopes::Column,
}

/// How often each feature's code ran: evidence that a step costs only what the level contains.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepStats {
    /// Character steps that ran the slope rules.
    pub slope_steps: u64,
    /// Character steps that ran the one-way platform rule.
    pub one_way_steps: u64,
    /// Character steps that ran the ladder rules.
    pub ladder_steps: u64,
    /// Platform moves (one per platform per step).
    pub platform_moves: u64,
}

/// The sweep backend over one level, in the position mode its configuration chose.
pub struct SweepBackend {
    mode: Mode,
}

/// The backend in each position mode, chosen once when it is built.
enum Mode {
    Float(Sweep<FloatSpace>),
    Double(Sweep<DoubleSpace>),
    Integer(Sweep<GridSpace>),
}

/// The backend in one position mode `S`.
struct Sweep<S: Space> {
    space: S,
    /// `space`'s frame and tolerances.
    frame: Frame<S::Coord>,
    tiles: StaticTiles,
    /// Moving platforms and their boxes at the current frame (empty on levels without them).
    platforms: Platforms<S::Coord>,
    /// Steps taken, for the platforms' time.
    steps: u64,
    /// `tan(max_climb_angle)`: the steepest walkable rise per unit of horizontal move.
    climb_gradient: f32,
    /// The level's grid, for the per-column feature rules (slopes).
    level: Level,
    /// Which of the level's columns hold a slope tile.
    slope_columns: slopes::SlopeColumns,
    stats: SweepStats,
    params: MotionParams,
    /// [`SweepConfig::snap_down`], tiles.
    snap_down: f32,
    characters: Vec<Character<S::Coord>>,
}

impl SweepBackend {
    /// What this backend models today.
    pub const SUPPORTED: Features = Features::ALL;

    /// Builds the backend for `level`; refuses levels with features it does not model.
    pub fn new(
        level: &Level,
        params: MotionParams,
        config: SweepConfig,
    ) -> Result<Self, BackendError> {
        let (name, supported) = match config.positions {
            Positions::Float => ("sweep", Self::SUPPORTED),
            Positions::Integer { .. } => ("sweep (integer positions)", INTEGER_SUPPORTED),
            Positions::Double => ("sweep (f64 positions)", DOUBLE_SUPPORTED),
        };
        require_supported(name, &level.name, level.features, supported)?;
        let grid = match config.positions {
            Positions::Float | Positions::Double => None,
            Positions::Integer { per_tile } => {
                Some(Grid::new(per_tile, level.origin_f32(), &level.name)?)
            }
        };
        params.validate()?;
        if !(config.snap_down.is_finite() && config.snap_down >= 0.0) {
            return Err(BackendError::InvalidParameter {
                name: "snap_down",
                value: config.snap_down.to_string(),
                expected: "a finite number >= 0 (tiles)",
            });
        }
        if !(config.epsilon.is_finite() && config.epsilon >= 0.0) {
            return Err(BackendError::InvalidParameter {
                name: "epsilon",
                value: config.epsilon.to_string(),
                expected: "a finite number >= 0 (tiles)",
            });
        }
        let eps = config.epsilon;
        let mode = match grid {
            Some(grid) => Mode::Integer(Sweep::new(
                GridSpace { grid },
                StaticTiles::new(level),
                level,
                params,
                &config,
            )),
            None if config.positions == Positions::Double => {
                // The f64 mode keeps the static boxes in the level's own coordinates (exact in
                // f32) and places them at the origin in f64.
                let mut local = level.geometry();
                local.origin = glam::DVec2::ZERO;
                let origin = level.origin;
                let space = DoubleSpace { eps, origin };
                let tiles = StaticTiles::new(&local);
                Mode::Double(Sweep::new(space, tiles, level, params, &config))
            }
            None => {
                let space = FloatSpace {
                    eps,
                    origin: level.origin_f32(),
                };
                let tiles = StaticTiles::new(level);
                Mode::Float(Sweep::new(space, tiles, level, params, &config))
            }
        };
        Ok(SweepBackend { mode })
    }

    /// How often each feature's code has run.
    pub fn stats(&self) -> SweepStats {
        match &self.mode {
            Mode::Float(s) => s.stats,
            Mode::Double(s) => s.stats,
            Mode::Integer(s) => s.stats,
        }
    }

    /// Adds a character and returns its id; refuses a non-finite spawn or velocity, or a size
    /// that is not positive.
    pub fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        Ok(match &mut self.mode {
            Mode::Float(s) => s.add_character(&spec),
            Mode::Double(s) => s.add_character(&spec),
            Mode::Integer(s) => s.add_character(&spec),
        })
    }

    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    #[inline]
    pub fn step(&mut self, inputs: &[Input], dt: f32) {
        match &mut self.mode {
            Mode::Float(s) => s.step(inputs, dt),
            Mode::Double(s) => s.step(inputs, dt),
            Mode::Integer(s) => s.step(inputs, dt),
        }
    }

    /// The state of character `id` after the last step, in level coordinates.
    #[inline]
    pub fn state(&self, id: CharacterId) -> CharacterState {
        match &self.mode {
            Mode::Float(s) => s.state(id),
            Mode::Double(s) => s.state(id),
            Mode::Integer(s) => s.state(id),
        }
    }
}

/// What a character's step reads of the backend: the level and its static and moving boxes in
/// the mode's space, the motion and the settings the stages use.
struct World<'a, S: Space> {
    space: &'a S,
    /// `space`'s frame and tolerances.
    frame: Frame<S::Coord>,
    tiles: &'a StaticTiles,
    /// The moving platforms, placed at the current frame as a move comes within their reach.
    platforms: &'a Platforms<S::Coord>,
    level: &'a Level,
    /// Which of the level's columns hold a slope tile.
    slope_columns: &'a slopes::SlopeColumns,
    params: &'a MotionParams,
    /// `tan(max_climb_angle)`.
    climb_gradient: f32,
    /// [`SweepConfig::snap_down`], tiles.
    snap_down: f32,
}

impl<'a, S: Space> World<'a, S> {
    /// What a character's move runs into: the level and the moving platforms.
    fn obstacles(&self) -> Obstacles<'a, S> {
        Obstacles {
            space: self.space,
            tiles: self.tiles,
            moving: Some(self.platforms),
            eps: self.frame.eps_coord,
        }
    }

    /// `c`'s feet in the frame, tiles.
    fn feet(&self, c: &Character<S::Coord>) -> Vec2 {
        self.space.feet(&c.body)
    }
}

impl<S: Space> Sweep<S> {
    fn new(
        space: S,
        tiles: StaticTiles,
        level: &Level,
        params: MotionParams,
        config: &SweepConfig,
    ) -> Self {
        Sweep {
            frame: space.frame(),
            platforms: Platforms::new(level, &space, config.rider_follow, params.gravity),
            space,
            tiles,
            steps: 0,
            climb_gradient: params.max_climb_angle.tan(),
            level: level.geometry(),
            slope_columns: slopes::SlopeColumns::new(level),
            stats: SweepStats::default(),
            params,
            snap_down: config.snap_down,
            characters: Vec::new(),
        }
    }

    fn add_character(&mut self, spec: &CharacterSpec) -> CharacterId {
        self.characters.push(Character {
            body: self.space.spawn(spec.spawn, spec.size),
            size: spec.size,
            motion: MotionState::with_velocity(spec.velocity),
            ground_normal: Vec2::ZERO,
            riding: None,
            crushed: false,
            near: NearCache::default(),
            column: slopes::Column::default(),
        });
        self.characters.len() - 1
    }

    fn step(&mut self, inputs: &[Input], dt: f32) {
        let w = World {
            space: &self.space,
            frame: self.frame,
            tiles: &self.tiles,
            platforms: &self.platforms,
            level: &self.level,
            slope_columns: &self.slope_columns,
            params: &self.params,
            climb_gradient: self.climb_gradient,
            snap_down: self.snap_down,
        };
        for (id, c) in self.characters.iter_mut().enumerate() {
            let input = inputs.get(id).copied().unwrap_or_default();
            c.crushed = false;
            step::step(&w, &mut self.stats, c, &input, dt);
        }
        // The seed's order: platforms move after every character has moved.
        if !self.platforms.states.is_empty() {
            self.stats.platform_moves += self.platforms.states.len() as u64;
            let t1 = (self.steps + 1) as f64 * dt as f64;
            let (s, tiles) = (&self.space, &self.tiles);
            self.platforms.step(s, tiles, &mut self.characters, t1, dt);
        }
        self.steps += 1;
    }

    fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        CharacterState {
            pos: self.space.feet(&c.body) - self.frame.origin,
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            // The normal of the ground the step stood it on (a slope's, on slopes).
            ground_normal: if c.motion.grounded {
                c.ground_normal
            } else {
                Vec2::ZERO
            },
            platform: c.riding,
            ladder: c.motion.on_ladder,
            crushed: c.crushed,
        }
    }
}

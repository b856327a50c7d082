//! The sweep-and-snap controller of the seed slides.
//!
//! One step per character: the shared motion integrates the velocity (symplectic Euler with a
//! force accumulator, [`crate::motion`]), then [`resolve`] moves the box along x, then along
//! y, each time snapping flush to the closest obstacle found through the parry2d broadphase
//! ([`broadphase`]); the blocked axis loses its velocity and the other gets friction. Levels
//! with slopes add the centre-column rules of [`slopes`]; a level without them runs none of
//! that code ([`SweepStats`] counts it).

pub mod broadphase;
pub mod grid;
pub mod kind;
pub mod platforms;
pub mod resolve;
pub mod slopes;

use glam::Vec2;
use parry2d::bounding_volume::Aabb;

use crate::backend::{
    require_supported, Backend, BackendError, CharacterId, CharacterSpec, CharacterState,
};
use crate::level::{Features, Level};
use crate::motion::{Contacts, Input, MotionParams, MotionState};
use broadphase::{BoxKind, NearCache, StaticTiles};
use grid::{move_axis_grid, Grid, GridBox, GridPos};
use resolve::{move_axis, Axis};

/// How the sweep stores positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Positions {
    /// f32 world coordinates with the seed's epsilon tolerance.
    Float,
    /// Whole subpixels (`per_tile` per tile) with the fractions carried between steps, snapping
    /// flush in exact integer arithmetic ([`grid`]). Levels with slopes or moving platforms are
    /// refused in this mode for now.
    Integer {
        /// Subpixels per tile (16 and 32 are what pixel-art platformers use).
        per_tile: u32,
    },
}

/// The features the integer mode models.
pub const INTEGER_SUPPORTED: Features = Features {
    slopes: false,
    one_way: true,
    ladders: true,
    moving_platforms: false,
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
    /// How positions are stored: f32 tiles with the epsilon tolerance (default), or whole
    /// subpixels, where `epsilon` and `snap_down` play no part.
    pub positions: Positions,
}

impl Default for SweepConfig {
    fn default() -> Self {
        SweepConfig {
            epsilon: 0.001,
            snap_down: 0.125,
            positions: Positions::Float,
        }
    }
}

struct Character {
    /// Feet position in world coordinates, in float mode (in integer mode, `on_grid` is the
    /// position and this stays at the spawn).
    pos: Vec2,
    /// The moving platform it stands on (the seed's rider list, kept on the rider's side: a
    /// platform's riders are the characters whose `riding` names it).
    riding: Option<u32>,
    /// Whether a platform pushed it into the level this step.
    crushed: bool,
    size: Vec2,
    motion: MotionState,
    /// The normal of the ground it stands on (zero in the air), for the trace.
    ground_normal: Vec2,
    /// The static boxes around it, kept between steps.
    near: NearCache,
    /// Its box on the subpixel grid, in integer mode (unused otherwise).
    on_grid: GridPos,
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

/// The sweep backend over one level.
pub struct SweepBackend {
    tiles: StaticTiles,
    /// Moving platforms and their boxes at the current frame (empty on levels without them).
    platforms: Vec<platforms::PlatformState>,
    platform_boxes: Vec<(Aabb, BoxKind)>,
    /// Steps taken, for the platforms' time.
    frame: u64,
    /// `tan(max_climb_angle)`: the steepest walkable rise per unit of horizontal move.
    climb_gradient: f32,
    /// The level's grid, for the per-column feature rules (slopes).
    level: Level,
    stats: SweepStats,
    /// The level's corner in the world.
    origin: Vec2,
    params: MotionParams,
    config: SweepConfig,
    /// The subpixel grid, in integer mode.
    grid: Option<Grid>,
    characters: Vec<Character>,
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
        };
        require_supported(name, &level.name, level.features, supported)?;
        let grid = match config.positions {
            Positions::Float => None,
            Positions::Integer { per_tile } => {
                Some(Grid::new(per_tile, level.origin, &level.name)?)
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
        Ok(SweepBackend {
            tiles: StaticTiles::new(level),
            platforms: level
                .platforms
                .iter()
                .map(|p| platforms::PlatformState::new(p, level.origin))
                .collect(),
            platform_boxes: level
                .platforms
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let kind = BoxKind::Platform {
                        index: i as u32,
                        one_way: p.one_way,
                    };
                    (p.aabb(0.0).translated(level.origin), kind)
                })
                .collect(),
            frame: 0,
            climb_gradient: params.max_climb_angle.tan(),
            level: level.geometry(),
            stats: SweepStats::default(),
            origin: level.origin,
            params,
            config,
            grid,
            characters: Vec::new(),
        })
    }

    /// How often each feature's code has run.
    pub fn stats(&self) -> SweepStats {
        self.stats
    }

    /// Moves one character by one step.
    fn step_character(&mut self, id: usize, input: &Input, dt: f32) {
        let eps = self.config.epsilon;
        let slopes = self.level.features.slopes;
        let p = &self.params;
        let c = &mut self.characters[id];
        if self.level.features.ladders {
            self.stats.ladder_steps += 1;
            crate::ladder::enter(
                &self.level,
                self.origin,
                &mut c.motion,
                &mut c.pos,
                c.size,
                input,
            );
        }
        let was_grounded = c.motion.grounded;
        let delta = c.motion.integrate(p, input, dt);
        let start = c.pos;

        // Standing on a slope, the box overhangs the ground by up to half its width times the
        // climb gradient: solids within that height above the slope under the centre are the
        // slope rules' business, not obstacles (the seed's centre model), and so is the mass
        // under a ramp along x.
        let overhang = c.size.x * 0.5 * self.climb_gradient + eps;
        let under = |pos: Vec2| {
            if slopes {
                slopes::slope_under(&self.level, self.origin, pos, overhang)
            } else {
                None
            }
        };
        let floor_x = under(c.pos);
        // One-way platforms never block along x (the seed: "don't collide x axis step").
        let skip_x = |t: &Aabb, kind: BoxKind| match kind {
            BoxKind::UnderSlope | BoxKind::OneWay => true,
            BoxKind::Platform { one_way, .. } => one_way,
            BoxKind::Solid => floor_x.is_some_and(|h| t.maxs.y <= h + overhang),
        };
        let mut wall = move_axis(
            &self.tiles,
            &mut c.near,
            &self.platform_boxes,
            &mut c.pos,
            c.size,
            Axis::X,
            delta.x,
            eps,
            skip_x,
        )
        .is_some();
        // How far the ground under the centre may rise during this x move (the climb limit).
        let rise_allow = self.climb_gradient * (c.pos.x - start.x).abs() + eps;
        if slopes {
            self.stats.slope_steps += 1;
            if slopes::climb_blocked(&self.level, self.origin, c.pos.x, c.pos.y, rise_allow) {
                c.pos.x = start.x;
                wall = true;
            }
        }

        let before_y = c.pos.y;
        let floor_y = under(c.pos);
        let one_way_level = self.level.features.one_way || self.level.features.ladders;
        if one_way_level {
            self.stats.one_way_steps += 1;
        }
        let dropping = c.motion.drop_through || c.motion.on_ladder;
        // A one-way platform blocks only a fall that started entirely above it (the seed:
        // "collide y only if previously entirely above platform"; "collide only if falling" is
        // wrong, because a jump can start falling while inside the platform).
        let skip_y = |t: &Aabb, kind: BoxKind| match kind {
            BoxKind::OneWay | BoxKind::Platform { one_way: true, .. } => {
                dropping || delta.y >= 0.0 || before_y < t.maxs.y - eps
            }
            BoxKind::Platform { .. } => false,
            _ => floor_y.is_some_and(|h| t.maxs.y > h + eps && t.maxs.y <= h + overhang),
        };
        let hit_y = move_axis(
            &self.tiles,
            &mut c.near,
            &self.platform_boxes,
            &mut c.pos,
            c.size,
            Axis::Y,
            delta.y,
            eps,
            skip_y,
        );
        let mut ground = hit_y.is_some() && delta.y < 0.0;
        let ceiling = hit_y.is_some() && delta.y > 0.0;
        let mut one_way = matches!(
            hit_y,
            Some(BoxKind::OneWay | BoxKind::Platform { one_way: true, .. })
        );
        c.riding = match hit_y {
            Some(BoxKind::Platform { index, .. }) if ground => Some(index),
            _ => None,
        };
        let mut normal = Vec2::Y;
        if slopes {
            if let Some(g) =
                slopes::resolve_up(&self.level, self.origin, &mut c.pos, before_y, rise_allow)
            {
                (ground, normal, one_way) = (true, g.normal, false);
            } else if !ground && was_grounded && delta.y <= 0.0 {
                // Walking down: follow the ground by the drop the steepest walkable slope gives
                // at this speed, plus this step's fall.
                let max_drop = rise_allow + self.config.snap_down - delta.y.min(0.0);
                if let Some(g) = slopes::follow_down(&self.level, self.origin, &mut c.pos, max_drop)
                {
                    (ground, normal) = (true, g.normal);
                }
            }
        }
        let contacts = Contacts {
            wall,
            ground,
            ceiling,
            one_way,
        };
        c.motion.apply_contacts(p, input, contacts);
        if self.level.features.ladders {
            crate::ladder::leave(
                &self.level,
                self.origin,
                &mut c.motion,
                c.pos,
                c.size,
                input,
            );
        }
        c.ground_normal = if ground { normal } else { Vec2::ZERO };
    }
}

impl SweepBackend {
    /// Moves one character by one step on the subpixel grid: the same motion and contact rules
    /// as [`Self::step_character`], with the moves made in whole subpixels ([`grid`]).
    fn step_on_grid(&mut self, grid: &Grid, id: usize, input: &Input, dt: f32) {
        let p = &self.params;
        let features = self.level.features;
        let c = &mut self.characters[id];
        if features.ladders {
            self.stats.ladder_steps += 1;
            // The ladder rules work in level coordinates, exact for the feet on the grid.
            let mut feet = grid.feet(&c.on_grid.b);
            let before = feet;
            crate::ladder::enter(
                &self.level,
                Vec2::ZERO,
                &mut c.motion,
                &mut feet,
                c.size,
                input,
            );
            if feet != before {
                let size = c.on_grid.b.max - c.on_grid.b.min;
                c.on_grid.b = grid.place(feet, size);
                c.on_grid.remainder = Vec2::ZERO;
            }
        }
        let delta = c.motion.integrate(p, input, dt);

        let n = c.on_grid.whole_move(grid, Axis::X, delta.x);
        // One-way platforms never block along x.
        let skip_x = |_: &GridBox, kind: BoxKind| kind == BoxKind::OneWay;
        let wall = move_axis_grid(
            &self.tiles,
            &mut c.near,
            grid,
            &mut c.on_grid,
            Axis::X,
            n,
            true,
            skip_x,
        )
        .is_some();
        if wall {
            c.on_grid.remainder.x = 0.0;
        }

        if features.one_way || features.ladders {
            self.stats.one_way_steps += 1;
        }
        let bottom = c.on_grid.b.min.y;
        let dropping = c.motion.drop_through || c.motion.on_ladder;
        // A one-way platform blocks only a fall that started entirely above it: in whole
        // subpixels, feet at or above its top.
        let skip_y = |t: &GridBox, kind: BoxKind| match kind {
            BoxKind::OneWay => dropping || delta.y >= 0.0 || bottom < t.max.y,
            _ => false,
        };
        let mut n = c.on_grid.whole_move(grid, Axis::Y, delta.y);
        if c.motion.drop_through && n == 0 {
            // The first step of a drop through a one-way platform falls less than a subpixel;
            // it must still leave the top, or the next step (no longer dropping) lands on it.
            n = -1;
            c.on_grid.remainder.y = 0.0;
        }
        let mut hit_y = move_axis_grid(
            &self.tiles,
            &mut c.near,
            grid,
            &mut c.on_grid,
            Axis::Y,
            n,
            true,
            skip_y,
        );
        if n == 0 && delta.y < 0.0 {
            // A fall of less than a subpixel this step moves nothing: the ground is there if
            // the box rests on it (Celeste's "collide check one pixel down"). A move of a
            // subpixel or more that ends on a face has already reported it.
            hit_y = move_axis_grid(
                &self.tiles,
                &mut c.near,
                grid,
                &mut c.on_grid,
                Axis::Y,
                -1,
                false,
                skip_y,
            );
        }
        if hit_y.is_some() {
            c.on_grid.remainder.y = 0.0;
        }
        let ground = hit_y.is_some() && delta.y < 0.0;
        let contacts = Contacts {
            wall,
            ground,
            ceiling: hit_y.is_some() && delta.y > 0.0,
            one_way: hit_y == Some(BoxKind::OneWay),
        };
        c.motion.apply_contacts(p, input, contacts);
        if features.ladders {
            crate::ladder::leave(
                &self.level,
                Vec2::ZERO,
                &mut c.motion,
                grid.feet(&c.on_grid.b),
                c.size,
                input,
            );
        }
        c.ground_normal = if ground { Vec2::Y } else { Vec2::ZERO };
    }
}

impl Backend for SweepBackend {
    fn name(&self) -> &'static str {
        "sweep"
    }

    fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError> {
        spec.validate()?;
        self.characters.push(Character {
            on_grid: self
                .grid
                .map(|g| GridPos::spawn(&g, spec.spawn, spec.size))
                .unwrap_or_default(),
            pos: spec.spawn + self.origin,
            size: spec.size,
            motion: MotionState::with_velocity(spec.velocity),
            ground_normal: Vec2::ZERO,
            riding: None,
            crushed: false,
            near: NearCache::default(),
        });
        Ok(self.characters.len() - 1)
    }

    fn step(&mut self, inputs: &[Input], dt: f32) {
        for id in 0..self.characters.len() {
            let input = inputs.get(id).copied().unwrap_or_default();
            self.characters[id].crushed = false;
            match self.grid {
                Some(grid) => self.step_on_grid(&grid, id, &input, dt),
                None => self.step_character(id, &input, dt),
            }
        }
        // The seed's order: platforms move after every character has moved.
        if !self.platforms.is_empty() {
            self.move_platforms(dt);
        }
        self.frame += 1;
    }

    fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        CharacterState {
            pos: match &self.grid {
                Some(g) => g.feet(&c.on_grid.b),
                None => c.pos - self.origin,
            },
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

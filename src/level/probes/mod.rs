//! The standard probes: scenarios for a level that comes with none (an imported map carries no
//! scripts). At each spawn point the character drops, walks left, walks right and jumps; and it
//! rides the platform nearest to the spawn, set down on the platform's top at t = 0 so that
//! the whole run measures carrying.

use glam::Vec2;

mod map_problems;

use super::DEFAULT_CHARACTER_SIZE;
use super::{character_box, InputEvent, Level, PlatformMotion, ScenarioSpec};

/// A place where a character starts, from a map's spawn object.
#[derive(Clone, Debug, PartialEq)]
pub struct SpawnPoint {
    /// Name, the prefix of its probes' scenario names (the object's name, or `spawn<ID>`).
    pub name: String,
    /// Where the character's feet (bottom centre) start, in tiles.
    pub position: Vec2,
}

/// The timing of the probes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeConfig {
    /// Length of the drop probe, in seconds: time to fall and come to rest.
    pub drop_duration: f32,
    /// Time the character stands (or falls) before a walk or jump begins, in seconds, so that
    /// it starts from the ground when the spawn is a little above it.
    pub settle: f32,
    /// How long a walk probe holds its direction, in seconds.
    pub walk_time: f32,
    /// Idle time after a walk or jump, in seconds: the rest metrics need 0.5 s at the end.
    pub rest: f32,
    /// How long the jump button is held, in seconds (the jump's height does not depend on it).
    pub jump_hold: f32,
    /// Length of the jump probe after the settle time, in seconds: up, down and rest.
    pub jump_time: f32,
    /// Shortest ride, in seconds.
    pub ride_min: f32,
    /// Longest ride, in seconds (a ride lasts one round trip of the platform's path within
    /// these bounds).
    pub ride_max: f32,
    /// How far every controller certainly walks in a walk probe, in tiles: a walk that meets
    /// a bottomless column or an open side of the map within it, on flat ground, measures the
    /// map, so it is not run (`map_problems`). Default: half the default run speed (6 tiles/s,
    /// [`crate::motion::MotionParams`]) times the walk time, leaving the controllers'
    /// acceleration its margin.
    pub certain_reach: f32,
}

impl Default for ProbeConfig {
    fn default() -> Self {
        ProbeConfig {
            drop_duration: 2.0,
            settle: 1.0,
            walk_time: 3.0,
            rest: 1.0,
            jump_hold: 0.2,
            jump_time: 2.0,
            ride_min: 2.0,
            ride_max: 12.0,
            certain_reach: 0.5 * 6.0 * 3.0,
        }
    }
}

/// A level's probe scenarios and the notes on those left out, as (subject, message).
pub type Probes = (Vec<ScenarioSpec>, Vec<(String, String)>);

/// Why a level's probes cannot run: too many of them, checked before they are made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProbeError {
    /// More spawn points than a level may have (1,000, `MAX_SPAWNS` in src/limits.rs).
    #[error(
        "{count} spawn points; expected at most {max} (each makes up to five probe scenarios)"
    )]
    TooManySpawns {
        /// The spawn points given.
        count: usize,
        /// The most a level may have.
        max: usize,
    },
    /// A probe whose duration and step are out of range (a [`ProbeConfig`] of the caller's).
    #[error("probe {name}: {error}")]
    Timing {
        /// The probe's scenario name.
        name: String,
        /// What is wrong with its timing.
        error: crate::limits::TimingError,
    },
    /// More frames together than a level may run (50,000,000, `MAX_LEVEL_FRAMES` in
    /// src/limits.rs).
    #[error(
        "the probes up to {name} run {frames} frames together; expected at most {max} in one level"
    )]
    TooManyFrames {
        /// The probe whose frames pass the cap.
        name: String,
        /// The frames of the probes up to it.
        frames: u64,
        /// The most frames one level may run.
        max: u64,
    },
}

/// The probes at every spawn point, named `<spawn>-drop`, `<spawn>-walk_left`,
/// `<spawn>-walk_right`, `<spawn>-jump` and `<spawn>-ride`; the ride is left out, with a note,
/// when the level has no platform or the platform's top has no room for the character. Returns
/// the scenarios and the notes as (subject, message). At most
/// 1,000 spawns (`MAX_SPAWNS`, checked before any probe is made), and the probes hold to the
/// frame caps of a level's scenarios ([`crate::limits::check_timing`], `MAX_LEVEL_FRAMES`).
pub fn probe_scenarios(
    level: &Level,
    spawns: &[SpawnPoint],
    cfg: &ProbeConfig,
) -> Result<Probes, ProbeError> {
    let max = crate::limits::MAX_SPAWNS;
    if spawns.len() > max {
        return Err(ProbeError::TooManySpawns {
            count: spawns.len(),
            max,
        });
    }
    let (out, notes) = probes(level, spawns, cfg);
    let mut frames = 0u64;
    for s in &out {
        frames += crate::limits::check_timing(s.duration as f64, s.dt as f64).map_err(|error| {
            ProbeError::Timing {
                name: s.name.clone(),
                error,
            }
        })?;
        if frames > crate::limits::MAX_LEVEL_FRAMES {
            return Err(ProbeError::TooManyFrames {
                name: s.name.clone(),
                frames,
                max: crate::limits::MAX_LEVEL_FRAMES,
            });
        }
    }
    Ok((out, notes))
}

/// The probes of [`probe_scenarios`], unchecked.
fn probes(level: &Level, spawns: &[SpawnPoint], cfg: &ProbeConfig) -> Probes {
    let mut out = Vec::new();
    let mut notes = Vec::new();
    for s in spawns {
        let at = s.position;
        let n = &s.name;
        let size = DEFAULT_CHARACTER_SIZE;
        // A probe the map makes impossible is the map's problem: said, not run.
        let mut map_problem = |probe: &str, why: String| {
            notes.push((
                format!("spawn {n:?}"),
                format!("map problem: probe {n}-{probe} is not run: {why}"),
            ))
        };
        if let Some(why) = map_problems::drop_problem(level, at, size) {
            // Every probe from this spawn falls first.
            map_problem("drop (and every other probe from this spawn)", why);
            continue;
        }
        out.push(ScenarioSpec::new(
            format!("{n}-drop"),
            at,
            cfg.drop_duration,
            Vec::new(),
        ));
        let walk_end = cfg.settle + cfg.walk_time;
        for (dir, left) in [("left", true), ("right", false)] {
            let press = |t: f32, on: bool| InputEvent {
                t,
                left: left.then_some(on),
                right: (!left).then_some(on),
                ..InputEvent::default()
            };
            if let Some(why) = map_problems::walk_problem(level, at, size, left, cfg.certain_reach)
            {
                map_problem(&format!("walk_{dir}"), why);
                continue;
            }
            out.push(ScenarioSpec::new(
                format!("{n}-walk_{dir}"),
                at,
                walk_end + cfg.rest,
                vec![press(cfg.settle, true), press(walk_end, false)],
            ));
        }
        let jump = |t: f32, on: bool| InputEvent {
            t,
            jump: Some(on),
            ..InputEvent::default()
        };
        out.push(ScenarioSpec::new(
            format!("{n}-jump"),
            at,
            cfg.settle + cfg.jump_time,
            vec![
                jump(cfg.settle, true),
                jump(cfg.settle + cfg.jump_hold, false),
            ],
        ));
        match ride(level, at, cfg) {
            Ok((index, spawn, duration)) => {
                let mut r = ScenarioSpec::new(format!("{n}-ride"), spawn, duration, Vec::new());
                r.ride = Some(index);
                out.push(r);
            }
            Err(why) => notes.push((format!("spawn {n:?}"), format!("no ride probe: {why}"))),
        }
    }
    (out, notes)
}

/// Why a spawn gets no ride probe ([`ride`]); the import's note carries its text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum RideError {
    /// The level has no moving platform to ride.
    #[error("the map has no moving platform")]
    NoPlatform,
    /// The spawn on top of the nearest platform is inside a solid tile.
    #[error("on top of platform {platform} the character would stand inside the solid tile at ({x}, {y})")]
    InsideSolid {
        /// The platform's index in the level.
        platform: usize,
        /// The solid tile's left edge, tiles.
        x: f32,
        /// The solid tile's bottom edge, tiles.
        y: f32,
    },
}

/// The platform nearest to `at` (by the distance to its box at t = 0), the spawn on the middle
/// of its top, and the ride's length.
fn ride(level: &Level, at: Vec2, cfg: &ProbeConfig) -> Result<(u32, Vec2, f32), RideError> {
    let (index, p) = level
        .platforms
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| {
            let d = |p: &super::Platform| {
                let b = p.aabb(0.0);
                (at.clamp(b.mins, b.maxs) - at).length()
            };
            d(a).total_cmp(&d(b))
        })
        .ok_or(RideError::NoPlatform)?;
    let spawn = p.start + Vec2::new(p.size.x * 0.5, p.size.y);
    if let Some(t) = level
        .solids_overlapping(&character_box(spawn, DEFAULT_CHARACTER_SIZE))
        .next()
    {
        return Err(RideError::InsideSolid {
            platform: index,
            x: t.mins.x,
            y: t.mins.y,
        });
    }
    let round_trip = match &p.motion {
        PlatformMotion::Waypoints { points, speed } => {
            let len: f32 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
            2.0 * len / speed
        }
        PlatformMotion::Sine { period, .. } | PlatformMotion::Circle { period, .. } => *period,
    };
    let duration = round_trip.clamp(cfg.ride_min, cfg.ride_max);
    Ok((index as u32, spawn, duration))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{Platform, Tile};

    #[test]
    fn five_probes_per_spawn_and_the_ride_starts_on_the_nearest_platform() {
        // Wide enough that no walk reaches an open side within the certain reach (9 tiles).
        let mut l = Level::from_tiles("t", 30, 10, {
            let mut t = vec![Tile::Solid; 30];
            t.extend(vec![Tile::Empty; 270]);
            t
        });
        for x in [2.0, 12.0] {
            l.platforms.push(Platform {
                start: Vec2::new(x, 4.0),
                size: Vec2::new(3.0, 0.5),
                motion: PlatformMotion::Waypoints {
                    points: vec![Vec2::new(x, 4.0), Vec2::new(x + 4.0, 4.0)],
                    speed: 2.0,
                },
                one_way: false,
            });
        }
        let spawns = [SpawnPoint {
            name: "a".into(),
            position: Vec2::new(11.0, 1.0),
        }];
        let (s, notes) = probe_scenarios(&l, &spawns, &ProbeConfig::default()).unwrap();
        assert!(notes.is_empty());
        let names: Vec<&str> = s.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["a-drop", "a-walk_left", "a-walk_right", "a-jump", "a-ride"]
        );
        let ride = &s[4];
        // Platform 1 (at x = 12) is nearer to x = 11 than platform 0 (ends at x = 5).
        assert_eq!(ride.ride, Some(1));
        assert_eq!(ride.spawn, Vec2::new(13.5, 4.5));
        // One round trip: 2 x 4 tiles at 2 tiles/s.
        assert_eq!(ride.duration, 4.0);
        assert_eq!(s[1].inputs[0].left, Some(true));
        assert_eq!(s[2].inputs[0].right, Some(true));

        // Past the spawn cap, an error before any probe is made; a probe longer than a
        // scenario may run (MAX_FRAMES at 60 Hz is under 2 days), an error naming it.
        let many = vec![spawns[0].clone(); crate::limits::MAX_SPAWNS + 1];
        let e = probe_scenarios(&l, &many, &ProbeConfig::default()).unwrap_err();
        assert!(
            matches!(e, ProbeError::TooManySpawns { count: 1001, .. }),
            "{e}"
        );
        let long = ProbeConfig {
            drop_duration: 1e6,
            ..ProbeConfig::default()
        };
        let e = probe_scenarios(&l, &spawns, &long).unwrap_err();
        assert!(e.to_string().contains("probe a-drop"), "{e}");

        l.platforms.clear();
        let (s, notes) = probe_scenarios(&l, &spawns, &ProbeConfig::default()).unwrap();
        assert_eq!(s.len(), 4);
        assert!(notes[0].1.contains("no moving platform"), "{notes:?}");
    }
}

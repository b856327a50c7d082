//! The stress matrix's probes: the probe level (a long floor, a wall, two moving platforms) and
//! the characters run on it (a drop, a walk, a jump, a fast mover, two rides), and the check that
//! they run at a base time step.

use glam::Vec2;

use crate::level::{InputEvent, Level, Platform, PlatformMotion, ScenarioSpec, Tile};

use super::definition::BASE;

/// Period of the probe level's moving platforms, in seconds.
const RIDE_PERIOD: f32 = 4.0;

/// The probe level's width and height, in tiles ([`probe_level`]).
pub(crate) const PROBE_SIZE: (u32, u32) = (300, 40);
/// The probe level's tiles: what each thread of `platbench stress` builds a world of.
pub(crate) const PROBE_TILES: u64 = PROBE_SIZE.0 as u64 * PROBE_SIZE.1 as u64;

/// The probe level: a floor 300 tiles long with a one-tile wall at x = 250, 40 tiles high (room
/// for a 10-tile character), and for the rides (a level of their own, so that a configuration
/// without moving platforms still runs the static probes) two 12-tile platforms swaying on
/// sines of period [`RIDE_PERIOD`]: platform 0 across x = 8..28 (amplitude 4 tiles, up to 6.3 tiles/s), platform 1 up and down
/// y = 4..8 (amplitude 2 tiles, up to 3.1 tiles/s, its largest downward acceleration 4.9 tiles/s²,
/// well under gravity, so a rider can stay on). Rides along one axis at a time: on a diagonal or
/// circular path Rapier's controller loses its platform even at the base case (the built-in
/// `platforms` level measures that), which would hide every extreme behind it.
/// Merged, the floor is one 300-tile box: long enough to matter, short of the thousands of tiles
/// on which Rapier's rounded shapes sink (a separate finding).
pub(super) fn probe_level(offset: f64, with_platforms: bool) -> Level {
    let (w, h) = PROBE_SIZE;
    let mut tiles = vec![Tile::Empty; (w * h) as usize];
    for i in 0..w {
        tiles[i as usize] = Tile::Solid;
    }
    for j in 1..h - 2 {
        tiles[(j * w + 250) as usize] = Tile::Solid;
    }
    let mut l = Level::from_tiles("stress", w, h, tiles);
    l.origin = glam::DVec2::splat(offset);
    if with_platforms {
        for (x, amplitude) in [(12.0, Vec2::new(4.0, 0.0)), (30.0, Vec2::new(0.0, 2.0))] {
            l.platforms.push(Platform {
                start: Vec2::new(x, 6.0),
                size: Vec2::new(12.0, 0.5),
                motion: PlatformMotion::Sine {
                    amplitude,
                    period: RIDE_PERIOD,
                },
                one_way: false,
            });
        }
        l.features.moving_platforms = true;
    }
    l
}

/// How long the walk probe holds "right", in seconds: 60 tiles at the run speed of 6 tiles/s,
/// the walk on which Rapier was found stuck at 1e5 tiles (per tile its floor has a seam every tile,
/// 60 of them).
const WALK_TIME: f32 = 10.0;

/// The probes: a drop onto the floor then rest, a walk along the floor, a standing jump, a fast
/// mover aimed at the wall, and a rider standing on each moving platform for two of its periods
/// and a half.
pub(super) fn probes(size: Vec2, dt: f32, speed: f32) -> Vec<ScenarioSpec> {
    let spec = |name: &str, spawn: Vec2, duration: f32, inputs: Vec<InputEvent>| ScenarioSpec {
        size,
        dt,
        ..ScenarioSpec::new(name.into(), spawn, duration, inputs)
    };
    let ride = |name: &str, x: f32, platform: u32| ScenarioSpec {
        ride: Some(platform),
        ..spec(name, Vec2::new(x, 6.5), 2.5 * RIDE_PERIOD, vec![])
    };
    let right = InputEvent {
        t: 0.0,
        right: Some(true),
        ..Default::default()
    };
    let stop = InputEvent {
        t: WALK_TIME,
        right: Some(false),
        ..Default::default()
    };
    let jump = |t: f32, on: bool| InputEvent {
        t,
        jump: Some(on),
        ..Default::default()
    };
    vec![
        spec("drop", Vec2::new(50.5, 3.0), 2.0, vec![]),
        spec(
            "walk",
            Vec2::new(100.5, 1.0),
            WALK_TIME + 0.5,
            vec![right, stop],
        ),
        spec(
            "jump",
            Vec2::new(200.5, 1.0),
            1.5,
            vec![jump(0.25, true), jump(0.5, false)],
        ),
        ScenarioSpec {
            velocity: Vec2::new(speed, 0.0),
            ..spec("fast", Vec2::new(150.5 - size.x, 1.5), 2.0, vec![])
        },
        ride("ride_across", 18.0, 0),
        ride("ride_up_down", 36.0, 1),
    ]
}

/// A base time step at which a stress probe cannot run ([`check_base_dt`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the {probe} probe ({duration} s) cannot run at this base time step: {source}")]
pub struct ProbeTimingError {
    /// The probe's name.
    pub probe: String,
    /// Its duration, seconds.
    pub duration: f32,
    /// What is wrong with its timing.
    pub source: crate::limits::TimingError,
}

/// Checks that every probe can run at the base time step `dt` (seconds): each probe's duration
/// over `dt` is within the frame caps of [`crate::limits::check_timing`].
pub fn check_base_dt(dt: f32) -> Result<(), ProbeTimingError> {
    let size = Vec2::new(BASE.width, BASE.width * 1.125);
    for spec in probes(size, dt, BASE.speed) {
        crate::limits::check_timing(spec.duration as f64, dt as f64).map_err(|source| {
            ProbeTimingError {
                probe: spec.name.clone(),
                duration: spec.duration,
                source,
            }
        })?;
    }
    Ok(())
}

//! `[[scenario]]` entries, in a level file or in an imported map's side file: name, spawn,
//! timing, character, input script, motion overrides, expected end, platform ridden and
//! expectations (`expect`, in its own file), each checked against the level the scenario runs on.

use std::collections::HashMap;
use std::ops::Range;

use glam::Vec2;
use serde::Deserialize;
use toml::Spanned;

use crate::level::{
    character_box, valid_name, InputEvent, Level, MotionOverrides, ScenarioSpec,
    DEFAULT_CHARACTER_SIZE, DEFAULT_DT,
};
use crate::limits;

use super::error::{LevelError, Locator};
use super::expect::{parse_expect, RawExpect};
use super::numbers::{coord, finite, positive, ranged, vec2};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScenario {
    name: Spanned<String>,
    #[serde(deserialize_with = "super::exact::spanned")]
    spawn: Spanned<[f64; 2]>,
    duration: Spanned<f64>,
    dt: Option<Spanned<f64>>,
    #[serde(default, deserialize_with = "super::exact::opt_spanned")]
    size: Option<Spanned<[f64; 2]>>,
    #[serde(default, deserialize_with = "super::exact::opt_spanned")]
    velocity: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    inputs: Vec<Spanned<RawInput>>,
    motion: Option<Spanned<RawMotion>>,
    expect_y: Option<Spanned<f64>>,
    ride: Option<Spanned<u32>>,
    expect: Option<Spanned<RawExpect>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInput {
    t: f64,
    left: Option<bool>,
    right: Option<bool>,
    up: Option<bool>,
    down: Option<bool>,
    jump: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    jump_height: Option<f64>,
    run_speed: Option<f64>,
    gravity: Option<f64>,
}

/// The `[[scenario]]` entries of a side file: scenarios for a level that was not read from TOML
/// (an imported map). Nothing else may stand in the file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenarioFile {
    #[serde(default)]
    scenario: Vec<Spanned<RawScenario>>,
    /// A side file's `[import]` table, read before the import (`side`).
    #[serde(default)]
    #[allow(dead_code)]
    import: Option<toml::Value>,
}

/// Parses the `[[scenario]]` entries of a TOML text against `level` (an imported map's side
/// file): the same fields and checks as in a level file (unique names, `ride` naming one of the
/// level's platforms, spawns outside solid tiles), with errors at the file's line and column.
/// `file` names the text in errors.
pub fn parse_scenarios(
    text: &str,
    file: &str,
    level: &Level,
) -> Result<Vec<ScenarioSpec>, LevelError> {
    let loc = Locator { file, text };
    super::budget::check_budget(&loc)?;
    let raw: RawScenarioFile = toml::from_str(text).map_err(|e| loc.toml(&e))?;
    scenarios(&loc, level, &raw.scenario)
}

/// Checks and converts scenario entries against the level they run on.
pub(super) fn scenarios(
    loc: &Locator,
    level: &Level,
    raw: &[Spanned<RawScenario>],
) -> Result<Vec<ScenarioSpec>, LevelError> {
    for s in raw {
        if let Some(r) = &s.get_ref().ride {
            if *r.get_ref() as usize >= level.platforms.len() {
                return Err(loc.at(
                    &r.span(),
                    format!(
                        "ride = {} names no platform; the level has {} (numbered from 0)",
                        r.get_ref(),
                        level.platforms.len()
                    ),
                ));
            }
        }
    }
    let mut seen = HashMap::new();
    let mut out: Vec<ScenarioSpec> = Vec::with_capacity(raw.len());
    let mut level_frames = 0u64;
    for s in raw {
        let mut spec = parse_scenario(loc, s.get_ref())?;
        if let Some(e) = &s.get_ref().expect {
            spec.expect = parse_expect(loc, level, &spec, e)?;
        }
        if let Some(prev) = seen.insert(spec.name.clone(), s.span()) {
            let first = loc.at(&prev, "");
            return Err(loc.at(
                &s.get_ref().name.span(),
                format!(
                    "scenario name {:?} is used twice (first at line {}); expected unique names",
                    spec.name, first.line
                ),
            ));
        }
        check_spawn(loc, level, &spec, &s.get_ref().spawn.span())?;
        level_frames += limits::frames(spec.duration as f64, spec.dt as f64) as u64;
        if level_frames > limits::MAX_LEVEL_FRAMES {
            return Err(loc.at(
                &s.get_ref().duration.span(),
                format!(
                    "the scenarios up to {:?} run {level_frames} frames together; expected at most {} in one level (split the level into files, or shorten its scenarios)",
                    spec.name,
                    limits::MAX_LEVEL_FRAMES
                ),
            ));
        }
        out.push(spec);
    }
    Ok(out)
}

fn parse_scenario(loc: &Locator, s: &RawScenario) -> Result<ScenarioSpec, LevelError> {
    let name = s.name.get_ref().clone();
    if !valid_name(&name) {
        return Err(loc.at(
            &s.name.span(),
            format!(
                "scenario name {} must be 1 to {} ASCII letters, digits, '_' or '-' (it names output files)",
                crate::input::quoted(&name),
                crate::limits::MAX_NAME_BYTES
            ),
        ));
    }
    let duration = positive(loc, &s.duration.span(), "duration", *s.duration.get_ref())?;
    let dt = match &s.dt {
        Some(d) => {
            let v = *d.get_ref();
            if !limits::dt_in_range(v) {
                return Err(loc.at(
                    &d.span(),
                    format!(
                        "dt is {v}; expected a time step in seconds, {} <= dt <= {}",
                        limits::DT_RANGE.0,
                        limits::DT_RANGE.1
                    ),
                ));
            }
            v as f32
        }
        None => DEFAULT_DT,
    };
    limits::check_timing(duration as f64, dt as f64)
        .map_err(|m| loc.at(&s.duration.span(), m.to_string()))?;
    let spawn = vec2(loc, &s.spawn, "spawn", false)?;
    let size = match &s.size {
        Some(v) => {
            let [w, h] = *v.get_ref();
            Vec2::new(
                ranged(loc, &v.span(), "size width", w, limits::SIZE_RANGE, "tiles")?,
                ranged(
                    loc,
                    &v.span(),
                    "size height",
                    h,
                    limits::SIZE_RANGE,
                    "tiles",
                )?,
            )
        }
        None => DEFAULT_CHARACTER_SIZE,
    };
    let velocity = match &s.velocity {
        Some(v) => {
            let [x, y] = *v.get_ref();
            let r = (-limits::MAX_SPEED, limits::MAX_SPEED);
            Vec2::new(
                ranged(loc, &v.span(), "velocity x", x, r, "tiles/s")?,
                ranged(loc, &v.span(), "velocity y", y, r, "tiles/s")?,
            )
        }
        None => Vec2::ZERO,
    };
    if let Some(ev) = s.inputs.get(limits::MAX_INPUT_EVENTS) {
        return Err(loc.at(
            &ev.span(),
            format!(
                "scenario {name:?} has {} input events (this is event {}); expected at most {} in one scenario (split the script into scenarios)",
                s.inputs.len(),
                limits::MAX_INPUT_EVENTS + 1,
                limits::MAX_INPUT_EVENTS
            ),
        ));
    }
    let mut inputs = Vec::with_capacity(s.inputs.len());
    let mut last_t = f32::NEG_INFINITY;
    for ev in &s.inputs {
        let span = ev.span();
        let e = ev.get_ref();
        let t = finite(loc, &span, "input time t", e.t)?;
        if t < 0.0 || t > duration {
            return Err(loc.at(
                &span,
                format!("input time t = {t} is outside the scenario; expected 0 <= t <= duration ({duration})"),
            ));
        }
        if t < last_t {
            return Err(loc.at(
                &span,
                format!("input time t = {t} comes before the previous event's t = {last_t}; expected events in time order"),
            ));
        }
        last_t = t;
        inputs.push(InputEvent {
            t,
            left: e.left,
            right: e.right,
            up: e.up,
            down: e.down,
            jump: e.jump,
        });
    }
    let motion = match &s.motion {
        None => MotionOverrides::default(),
        Some(m) => {
            let span = m.span();
            let m = m.get_ref();
            let opt = |v: Option<f64>,
                       what: &str,
                       max: f64,
                       unit: &str|
             -> Result<Option<f32>, LevelError> {
                v.map(|x| ranged(loc, &span, what, x, (f64::MIN_POSITIVE, max), unit))
                    .transpose()
            };
            MotionOverrides {
                jump_height: opt(
                    m.jump_height,
                    "motion.jump_height",
                    limits::MAX_JUMP_HEIGHT,
                    "tiles",
                )?,
                run_speed: opt(
                    m.run_speed,
                    "motion.run_speed",
                    limits::MAX_SPEED,
                    "tiles/s",
                )?,
                gravity: opt(m.gravity, "motion.gravity", limits::MAX_ACCEL, "tiles/s²")?,
            }
        }
    };
    let expect_y = s
        .expect_y
        .as_ref()
        .map(|v| coord(loc, &v.span(), "expect_y", *v.get_ref()))
        .transpose()?;
    Ok(ScenarioSpec {
        name,
        spawn,
        size,
        velocity,
        duration,
        dt,
        inputs,
        motion,
        expect_y,
        ride: s.ride.as_ref().map(|r| *r.get_ref()),
        expect: Default::default(),
    })
}

fn check_spawn(
    loc: &Locator,
    level: &Level,
    spec: &ScenarioSpec,
    span: &Range<usize>,
) -> Result<(), LevelError> {
    let (x, y) = (spec.spawn.x, spec.spawn.y);
    if !(x >= 0.0 && x <= level.width as f32 && y >= 0.0 && y <= level.height as f32) {
        return Err(loc.at(
            span,
            format!(
                "spawn ({x}, {y}) is outside the map, which spans 0 <= x <= {} and 0 <= y <= {} tiles; expected the feet (bottom centre) inside the map, on or above open space",
                level.width, level.height
            ),
        ));
    }
    let b = character_box(spec.spawn, spec.size);
    if let Some(t) = level.solids_overlapping(&b).next() {
        return Err(loc.at(
            span,
            format!(
                "spawn ({}, {}) puts the {} x {} character inside the solid tile at ({}, {}); expected a spawn in empty space (the position is the feet, bottom centre)",
                spec.spawn.x, spec.spawn.y, spec.size.x, spec.size.y, t.mins.x, t.mins.y
            ),
        ));
    }
    Ok(())
}

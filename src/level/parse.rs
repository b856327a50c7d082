//! The TOML level format (DESIGN.md, "Level format"): metadata, a legend, an ASCII map and
//! `[[scenario]]` entries. Every error names the file, line and column and what was expected.

use std::collections::{BTreeMap, HashMap};
use std::ops::Range;

use glam::Vec2;
use serde::Deserialize;
use toml::Spanned;

use crate::limits;

use super::{
    InputEvent, Level, MotionOverrides, Platform, PlatformMotion, ScenarioSpec, Slope, Tile,
    DEFAULT_CHARACTER_SIZE, DEFAULT_DT,
};

/// A level file that could not be read, with where and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}:{column}: {message}")]
pub struct LevelError {
    /// The file (or `builtin:NAME`).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What was found and what was expected.
    pub message: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLevel {
    name: Option<String>,
    description: Option<String>,
    origin: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    legend: BTreeMap<Spanned<String>, Spanned<toml::Value>>,
    map: Spanned<String>,
    #[serde(default)]
    platform: Vec<Spanned<RawPlatform>>,
    #[serde(default)]
    scenario: Vec<Spanned<RawScenario>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: Spanned<String>,
    spawn: Spanned<[f64; 2]>,
    duration: Spanned<f64>,
    dt: Option<Spanned<f64>>,
    size: Option<Spanned<[f64; 2]>>,
    velocity: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    inputs: Vec<Spanned<RawInput>>,
    motion: Option<Spanned<RawMotion>>,
    expect_y: Option<Spanned<f64>>,
    ride: Option<Spanned<u32>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlatform {
    rect: [f64; 4],
    path: Option<Vec<[f64; 2]>>,
    speed: Option<f64>,
    sine: Option<RawSine>,
    circle: Option<RawCircle>,
    #[serde(default)]
    one_way: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSine {
    amplitude: [f64; 2],
    period: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCircle {
    radius: f64,
    period: f64,
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

/// Turns byte offsets into line and column.
struct Locator<'a> {
    file: &'a str,
    text: &'a str,
}

impl Locator<'_> {
    fn err(&self, offset: usize, message: impl Into<String>) -> LevelError {
        let offset = offset.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |p| p + 1);
        let column = before[line_start..].chars().count() + 1;
        LevelError {
            file: self.file.to_string(),
            line,
            column,
            message: message.into(),
        }
    }

    fn at(&self, span: &Range<usize>, message: impl Into<String>) -> LevelError {
        self.err(span.start, message)
    }
}

/// Parses a level file's text. `file` names it in errors.
pub fn parse_level(text: &str, file: &str) -> Result<Level, LevelError> {
    let loc = Locator { file, text };
    let raw: RawLevel = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        loc.err(offset, e.message().trim().to_string())
    })?;

    let legend = parse_legend(&loc, &raw.legend)?;
    let (width, height, tiles) = parse_map(&loc, &raw.map, &legend)?;
    let name = raw.name.unwrap_or_else(|| {
        std::path::Path::new(file)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("level")
            .to_string()
    });
    if !super::valid_name(&name) {
        return Err(loc.err(
            0,
            format!("level name {name:?} must be non-empty ASCII letters, digits, '_' or '-' (it names output files)"),
        ));
    }
    let mut level = Level::from_tiles(&name, width, height, tiles);
    level.description = raw.description.unwrap_or_default();
    if let Some(o) = &raw.origin {
        let [x, y] = *o.get_ref();
        let range = (-limits::MAX_ORIGIN, limits::MAX_ORIGIN);
        level.origin = glam::DVec2::new(
            ranged_f64(&loc, &o.span(), "origin x", x, range, "tiles")?,
            ranged_f64(&loc, &o.span(), "origin y", y, range, "tiles")?,
        );
    }
    level.source = file.to_string();

    for p in &raw.platform {
        level.platforms.push(parse_platform(&loc, p)?);
    }
    level.features.moving_platforms = !level.platforms.is_empty();
    level.scenarios = scenarios(&loc, &level, &raw.scenario)?;
    Ok(level)
}

/// The `[[scenario]]` entries of a side file: scenarios for a level that was not read from TOML
/// (an imported map). Nothing else may stand in the file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenarioFile {
    #[serde(default)]
    scenario: Vec<Spanned<RawScenario>>,
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
    let raw: RawScenarioFile = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        loc.err(offset, e.message().trim().to_string())
    })?;
    scenarios(&loc, level, &raw.scenario)
}

/// Checks and converts scenario entries against the level they run on.
fn scenarios(
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
        let spec = parse_scenario(loc, s.get_ref())?;
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

fn parse_legend(
    loc: &Locator,
    raw: &BTreeMap<Spanned<String>, Spanned<toml::Value>>,
) -> Result<HashMap<char, Tile>, LevelError> {
    let mut legend: HashMap<char, Tile> = HashMap::from([
        ('#', Tile::Solid),
        ('.', Tile::Empty),
        (' ', Tile::Empty),
        ('=', Tile::OneWay),
        ('H', Tile::Ladder),
        (
            '/',
            Tile::Slope(Slope::Line {
                left: 0.0,
                right: 1.0,
            }),
        ),
        (
            '\\',
            Tile::Slope(Slope::Line {
                left: 1.0,
                right: 0.0,
            }),
        ),
    ]);
    for (key, value) in raw {
        let mut chars = key.get_ref().chars();
        let c = match (chars.next(), chars.next()) {
            (Some(c), None) => c,
            _ => {
                return Err(loc.at(
                    &key.span(),
                    format!("legend key {:?} must be a single character", key.get_ref()),
                ))
            }
        };
        let tile = parse_legend_value(loc, value)?;
        if let Some(builtin) = legend.get(&c) {
            if *builtin != tile {
                return Err(loc.at(
                    &key.span(),
                    format!(
                        "legend key {c:?} is a built-in tile ({}) and cannot be redefined as {}; expected a character of your own (built in: '#' solid, '.' and ' ' empty, '=' one-way, 'H' ladder, '/' and '\\' slopes)",
                        tile_kind(builtin),
                        tile_kind(&tile)
                    ),
                ));
            }
        }
        legend.insert(c, tile);
    }
    Ok(legend)
}

/// A tile kind in words, for messages.
fn tile_kind(t: &Tile) -> &'static str {
    match t {
        Tile::Empty => "empty",
        Tile::Solid => "solid",
        Tile::OneWay => "one-way",
        Tile::Ladder => "ladder",
        Tile::Slope(_) => "a slope",
    }
}

fn parse_legend_value(loc: &Locator, value: &Spanned<toml::Value>) -> Result<Tile, LevelError> {
    let span = value.span();
    let expected = "expected \"solid\", \"empty\", \"oneway\", \"ladder\", { heights = [16 integers 0..=16] } or { line = [left, right] }";
    match value.get_ref() {
        toml::Value::String(s) => match s.as_str() {
            "solid" => Ok(Tile::Solid),
            "empty" => Ok(Tile::Empty),
            "oneway" => Ok(Tile::OneWay),
            "ladder" => Ok(Tile::Ladder),
            other => Err(loc.at(&span, format!("unknown tile kind {other:?}; {expected}"))),
        },
        toml::Value::Table(t) if t.len() == 1 && t.contains_key("heights") => {
            let arr = t["heights"].as_array();
            let heights: Option<Vec<u8>> = arr.map(|a| {
                a.iter()
                    .filter_map(|v| v.as_integer())
                    .filter(|h| (0..=16).contains(h))
                    .map(|h| h as u8)
                    .collect()
            });
            match (arr.map(|a| a.len()), heights) {
                (Some(16), Some(h)) if h.len() == 16 => {
                    let mut out = [0u8; 16];
                    out.copy_from_slice(&h);
                    Ok(Tile::Slope(Slope::Heights(out)))
                }
                _ => Err(loc.at(
                    &span,
                    "a height array is 16 integers; expected exactly 16 integers between 0 and 16 (sixteenths of a tile)",
                )),
            }
        }
        toml::Value::Table(t) if t.len() == 1 && t.contains_key("line") => {
            let pair: Option<Vec<f64>> = t["line"].as_array().map(|a| {
                a.iter()
                    .filter_map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
                    .collect()
            });
            match pair.as_deref() {
                Some(&[l, r]) if l.abs() <= 16.0 && r.abs() <= 16.0 => {
                    Ok(Tile::Slope(Slope::Line {
                        left: l as f32,
                        right: r as f32,
                    }))
                }
                _ => Err(loc.at(
                    &span,
                    "a line slope is [left, right]; expected two numbers between -16 and 16 (heights of the line at the tile's edges, in tiles; the surface is clamped into the tile)",
                )),
            }
        }
        other => Err(loc.at(
            &span,
            format!("found {} as a legend entry; {expected}", other.type_str()),
        )),
    }
}

fn parse_map(
    loc: &Locator,
    map: &Spanned<String>,
    legend: &HashMap<char, Tile>,
) -> Result<(u32, u32, Vec<Tile>), LevelError> {
    let span = map.span();
    // Where the string's content starts in the file: after the opening quotes, and after
    // the newline that TOML trims right after triple quotes.
    let raw = &loc.text[span.clone()];
    let mut content_start = span.start;
    if raw.starts_with("\"\"\"") || raw.starts_with("'''") {
        content_start += 3;
        let rest = &loc.text[content_start..];
        if rest.starts_with("\r\n") {
            content_start += 2;
        } else if rest.starts_with('\n') {
            content_start += 1;
        }
    } else {
        content_start += 1;
    }
    let body = map.get_ref();
    let mut rows: Vec<&str> = body.split('\n').map(|r| r.trim_end_matches('\r')).collect();
    if rows.last() == Some(&"") {
        rows.pop();
    }
    if rows.is_empty() || rows.iter().all(|r| r.is_empty()) {
        return Err(loc.at(
            &span,
            "the map is empty; expected at least one row of tiles",
        ));
    }
    // Byte offset in the file of each row, for errors.
    let line_offsets: Vec<usize> = {
        let mut v = Vec::with_capacity(rows.len());
        let mut off = content_start;
        for r in &rows {
            v.push(off);
            off += r.len() + 1;
        }
        v
    };
    let width = rows[0].chars().count();
    for (r, row) in rows.iter().enumerate() {
        let n = row.chars().count();
        if n != width {
            return Err(loc.err(
                line_offsets[r] + row.len(),
                format!("map row {} has {n} tiles, expected {width} like the first row (rows must have equal length)", r + 1),
            ));
        }
    }
    let height = rows.len();
    if (width as u64) * (height as u64) > limits::MAX_TILES {
        return Err(loc.at(
            &span,
            format!(
                "the map is {width} x {height} tiles; expected at most {} tiles (as for Tiled maps)",
                limits::MAX_TILES
            ),
        ));
    }
    let mut tiles = vec![Tile::Empty; width * height];
    for (r, row) in rows.iter().enumerate() {
        let j = height - 1 - r;
        for (i, (byte, c)) in row.char_indices().enumerate() {
            let tile = legend.get(&c).ok_or_else(|| {
                loc.err(
                    line_offsets[r] + byte,
                    format!("unknown map character {c:?}; expected '#', '.', ' ', '=', 'H', '/', '\\' or a key of [legend]"),
                )
            })?;
            tiles[j * width + i] = *tile;
        }
    }
    Ok((width as u32, height as u32, tiles))
}

fn parse_platform(loc: &Locator, p: &Spanned<RawPlatform>) -> Result<Platform, LevelError> {
    let span = p.span();
    let r = p.get_ref();
    let [x, y, w, h] = r.rect;
    let start = Vec2::new(
        coord(loc, &span, "rect x", x)?,
        coord(loc, &span, "rect y", y)?,
    );
    let size = Vec2::new(
        ranged(
            loc,
            &span,
            "rect width",
            w,
            (f64::MIN_POSITIVE, limits::MAX_COORD),
            "tiles",
        )?,
        ranged(
            loc,
            &span,
            "rect height",
            h,
            (f64::MIN_POSITIVE, limits::MAX_COORD),
            "tiles",
        )?,
    );
    let kinds = r.path.is_some() as u8 + r.sine.is_some() as u8 + r.circle.is_some() as u8;
    if kinds != 1 {
        return Err(loc.at(
            &span,
            format!("a platform needs exactly one motion: `path` with `speed`, `sine` or `circle` (found {kinds})"),
        ));
    }
    let motion = if let Some(path) = &r.path {
        let speed = r
            .speed
            .ok_or_else(|| loc.at(&span, "a platform with a `path` needs a `speed` (tiles/s)"))?;
        let speed = ranged(
            loc,
            &span,
            "speed",
            speed,
            (f64::MIN_POSITIVE, limits::MAX_SPEED),
            "tiles/s",
        )?;
        let mut points = Vec::with_capacity(path.len());
        for [px, py] in path {
            points.push(Vec2::new(
                coord(loc, &span, "path x", *px)?,
                coord(loc, &span, "path y", *py)?,
            ));
        }
        if points.len() < 2 {
            return Err(loc.at(
                &span,
                format!(
                    "a platform path needs at least 2 waypoints, found {}",
                    points.len()
                ),
            ));
        }
        if points[0] != start {
            return Err(loc.at(
                &span,
                format!("the path starts at ({}, {}) but rect starts at ({}, {}); expected the first waypoint to be the rect's corner", points[0].x, points[0].y, start.x, start.y),
            ));
        }
        if points.windows(2).all(|w| w[0] == w[1]) {
            return Err(loc.at(
                &span,
                "the platform path has zero length; expected waypoints that differ",
            ));
        }
        PlatformMotion::Waypoints { points, speed }
    } else if let Some(s) = &r.sine {
        let [ax, ay] = s.amplitude;
        PlatformMotion::Sine {
            amplitude: Vec2::new(
                coord(loc, &span, "sine amplitude", ax)?,
                coord(loc, &span, "sine amplitude", ay)?,
            ),
            period: period(loc, &span, "sine period", s.period)?,
        }
    } else {
        let c = r
            .circle
            .as_ref()
            .ok_or_else(|| loc.at(&span, "missing motion"))?;
        PlatformMotion::Circle {
            radius: ranged(
                loc,
                &span,
                "circle radius",
                c.radius,
                (f64::MIN_POSITIVE, limits::MAX_COORD),
                "tiles",
            )?,
            period: period(loc, &span, "circle period", c.period)?,
        }
    };
    Ok(Platform {
        start,
        size,
        motion,
        one_way: r.one_way,
    })
}

fn finite(loc: &Locator, span: &Range<usize>, what: &str, v: f64) -> Result<f32, LevelError> {
    if !v.is_finite() || v.abs() > f32::MAX as f64 {
        return Err(loc.at(
            span,
            format!("{what} is {}; expected a finite number", limits::show(v)),
        ));
    }
    Ok(v as f32)
}

fn positive(loc: &Locator, span: &Range<usize>, what: &str, v: f64) -> Result<f32, LevelError> {
    let x = finite(loc, span, what, v)?;
    if x <= 0.0 {
        return Err(loc.at(
            span,
            format!("{what} is {}; expected a number > 0", limits::show(v)),
        ));
    }
    Ok(x)
}

/// A number within `range` (inclusive), in `unit`.
fn ranged(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
    range: (f64, f64),
    unit: &str,
) -> Result<f32, LevelError> {
    ranged_f64(loc, span, what, v, range, unit).map(|v| v as f32)
}

/// [`ranged`] kept in f64 (a level's origin, exact far beyond what an f32 holds).
fn ranged_f64(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
    range: (f64, f64),
    unit: &str,
) -> Result<f64, LevelError> {
    if !limits::within(v, range) {
        let lo = if range.0 == f64::MIN_POSITIVE {
            "0 < ".to_string()
        } else {
            format!("{} <= ", range.0)
        };
        return Err(loc.at(
            span,
            format!(
                "{what} is {}; expected {lo}{what} <= {} ({unit})",
                limits::show(v),
                range.1
            ),
        ));
    }
    Ok(v)
}

/// A coordinate or length within [`limits::MAX_COORD`] of zero, in tiles.
fn coord(loc: &Locator, span: &Range<usize>, what: &str, v: f64) -> Result<f32, LevelError> {
    ranged(
        loc,
        span,
        what,
        v,
        (-limits::MAX_COORD, limits::MAX_COORD),
        "tiles",
    )
}

/// A platform's period, in seconds.
fn period(loc: &Locator, span: &Range<usize>, what: &str, v: f64) -> Result<f32, LevelError> {
    ranged(
        loc,
        span,
        what,
        v,
        (limits::MIN_PERIOD, limits::MAX_DURATION),
        "seconds",
    )
}

fn vec2(
    loc: &Locator,
    v: &Spanned<[f64; 2]>,
    what: &str,
    must_be_positive: bool,
) -> Result<Vec2, LevelError> {
    let span = v.span();
    let [a, b] = *v.get_ref();
    let check = if must_be_positive { positive } else { finite };
    Ok(Vec2::new(
        check(loc, &span, what, a)?,
        check(loc, &span, what, b)?,
    ))
}

fn parse_scenario(loc: &Locator, s: &RawScenario) -> Result<ScenarioSpec, LevelError> {
    let name = s.name.get_ref().clone();
    if !super::valid_name(&name) {
        return Err(loc.at(
            &s.name.span(),
            format!("scenario name {name:?} must be non-empty ASCII letters, digits, '_' or '-' (it names output files)"),
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
    let b = super::character_box(spec.spawn, spec.size);
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

#[cfg(test)]
mod tests {
    use super::*;

    const OK: &str = r#"
name = "t"
map = """
....
#..#
####
"""

[[scenario]]
name = "drop"
spawn = [1.5, 2.0]
duration = 1.0
inputs = [ { t = 0.0, right = true }, { t = 0.5, right = false } ]
"#;

    #[test]
    fn parses_map_bottom_up() {
        let l = parse_level(OK, "t.toml").unwrap();
        assert_eq!((l.width, l.height), (4, 3));
        assert_eq!(l.tile(0, 0), Tile::Solid);
        assert_eq!(l.tile(0, 1), Tile::Solid);
        assert_eq!(l.tile(1, 1), Tile::Empty);
        assert_eq!(l.tile(0, 2), Tile::Empty);
        assert_eq!(l.scenarios.len(), 1);
        assert_eq!(l.scenarios[0].inputs[1].right, Some(false));
        assert_eq!(l.scenarios[0].size, DEFAULT_CHARACTER_SIZE);
    }

    fn err(text: &str) -> LevelError {
        parse_level(text, "bad.toml").unwrap_err()
    }

    #[test]
    fn unknown_map_character_names_line_and_column() {
        let e = err("map = \"\"\"\n....\n.x..\n\"\"\"\n");
        assert_eq!((e.line, e.column), (3, 2), "{e}");
        assert!(e.message.contains("unknown map character 'x'"), "{e}");
        assert!(e.to_string().starts_with("bad.toml:3:2:"));
    }

    #[test]
    fn ragged_rows_are_an_error() {
        let e = err("map = \"\"\"\n....\n...\n\"\"\"\n");
        assert_eq!(e.line, 3, "{e}");
        assert!(e.message.contains("has 3 tiles, expected 4"), "{e}");
    }

    #[test]
    fn toml_syntax_error_has_position() {
        let e = err("name = \"x\"\nmap = [\n");
        assert!(e.line >= 2, "{e}");
    }

    #[test]
    fn unknown_field_is_named() {
        let e = err("map = \"#\"\nmpa = 3\n");
        assert_eq!(e.line, 2, "{e}");
        assert!(e.message.contains("unknown field"), "{e}");
    }

    #[test]
    fn spawn_inside_solid_is_rejected() {
        let e = err("map = \"\"\"\n..\n##\n\"\"\"\n[[scenario]]\nname = \"a\"\nspawn = [0.5, 0.5]\nduration = 1.0\n");
        assert_eq!(e.line, 7, "{e}");
        assert!(e.message.contains("inside the solid tile"), "{e}");
    }

    #[test]
    fn inputs_out_of_order_and_bad_numbers() {
        let base = "map = \"\"\"\n..\n##\n\"\"\"\n[[scenario]]\nname = \"a\"\nspawn = [0.5, 1.0]\n";
        let e = err(&format!("{base}duration = -1.0\n"));
        assert!(e.message.contains("expected a number > 0"), "{e}");
        let e = err(&format!("{base}duration = nan\n"));
        assert!(e.message.contains("finite"), "{e}");
        let e = err(&format!(
            "{base}duration = 2.0\ninputs = [ {{ t = 1.0 }}, {{ t = 0.5 }} ]\n"
        ));
        assert!(e.message.contains("time order"), "{e}");
        assert_eq!(e.line, 9, "{e}");
    }

    #[test]
    fn legend_entries_and_features() {
        let text = "map = \"ab=H#\"\n[legend]\na = { heights = [12, 11, 10, 8, 7, 6, 5, 5, 5, 5, 5, 4, 3, 2, 1, 1] }\nb = { line = [0.0, 0.5] }\n";
        let l = parse_level(text, "f.toml").unwrap();
        assert!(l.features.slopes && l.features.one_way && l.features.ladders);
        assert_eq!(
            l.tile(1, 0),
            Tile::Slope(Slope::Line {
                left: 0.0,
                right: 0.5
            })
        );
        let e = err("map = \"a\"\n[legend]\na = { heights = [1, 2] }\n");
        assert_eq!(e.line, 3, "{e}");
        assert!(e.message.contains("exactly 16"), "{e}");
        let e = err("map = \"a\"\n[legend]\na = { line = [0.0] }\n");
        assert!(e.message.contains("line slope"), "{e}");
        let e = err("map = \"a\"\n[legend]\nab = \"solid\"\n");
        assert!(e.message.contains("single character"), "{e}");
    }

    #[test]
    fn platforms_parse_and_bad_ones_are_named() {
        let ok = "map = \"....\"\n[[platform]]\nrect = [0, 0, 2, 0.5]\npath = [[0, 0], [2, 0]]\nspeed = 1.0\n";
        let l = parse_level(ok, "p.toml").unwrap();
        assert!(l.features.moving_platforms);
        assert_eq!(l.platforms[0].size, Vec2::new(2.0, 0.5));
        let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\n");
        assert!(e.message.contains("exactly one motion"), "{e}");
        assert_eq!(e.line, 2, "{e}");
        let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\npath = [[0, 0]]\nspeed = 1\n");
        assert!(e.message.contains("at least 2 waypoints"), "{e}");
        let e = err(
            "map = \"#\"\n[[platform]]\nrect = [0, 0, 1, 1]\npath = [[1, 0], [2, 0]]\nspeed = 1\n",
        );
        assert!(e.message.contains("first waypoint"), "{e}");
        let e = err("map = \"#\"\n[[platform]]\nrect = [0, 0, -1, 1]\nsine = { amplitude = [1, 0], period = 2 }\n");
        assert!(e.message.contains("rect width"), "{e}");
    }

    #[test]
    fn empty_map_is_an_error() {
        let e = err("map = \"\"\n");
        assert!(e.message.contains("empty"), "{e}");
    }

    #[test]
    fn an_origin_is_exact_in_f64_up_to_1e15_tiles_and_an_error_beyond() {
        let with =
            |o: &str| format!("name = \"t\"\norigin = {o}\nmap = \"\"\"\n....\n####\n\"\"\"\n");
        // 1e12 and 1e15 - 0.125 are not f32s (the nearest are 999,999,995,904 and
        // 999,999,986,991,104): kept exactly, for an f64 backend to place the level there.
        let l = parse_level(&with("[1e12, -999999999999999.875]"), "o.toml").unwrap();
        assert_eq!(l.origin, glam::DVec2::new(1e12, -(1e15 - 0.125)));
        // Within 1e7 the f32 backends' origin is the one they always had (the f32 nearest).
        let l = parse_level(&with("[1234.5, 0.1]"), "o.toml").unwrap();
        assert_eq!(l.origin_f32(), Vec2::new(1234.5, 0.1f32));
        // Beyond limits::MAX_ORIGIN (1e15, the stress matrix's largest offset): located, with
        // the range expected.
        for (o, what) in [
            ("[2e15, 0.0]", "origin x"),
            ("[0.0, -1e16]", "origin y"),
            ("[nan, 0.0]", "origin x"),
            ("[1e308, 0.0]", "origin x"),
        ] {
            let e = parse_level(&with(o), "o.toml").unwrap_err();
            assert_eq!(
                (e.file.as_str(), e.line, e.column),
                ("o.toml", 2, 10),
                "{e}"
            );
            assert!(e.message.starts_with(&format!("{what} is ")), "{e}");
            assert!(
                e.message.contains(&format!(
                    "expected -1000000000000000 <= {what} <= 1000000000000000 (tiles)"
                )),
                "{e}"
            );
        }
        // Past 1e16 in exponent form: 1e308 is not printed as its 309 digits.
        let e = parse_level(&with("[1e308, 0.0]"), "o.toml").unwrap_err();
        assert!(e.message.starts_with("origin x is 1e308; expected"), "{e}");
    }
}

//! The report's scenario pictures and their replay: the level with each configuration's path,
//! and its character (its real shape) moving along the trace with the moving platforms, played
//! by a small inline script (real time or slowed, pause, a scrubber, arrow keys frame by frame,
//! zoom and pan, follow, a collapsed picker of the shown configurations, each shown character's
//! state at the frame, faulty frames marked). The data it plays is
//! `html_replay_data.rs`'s; the colours `html_colours.rs`'s. Everything is inline: the page
//! fetches nothing.

use std::fmt::Write as _;

use glam::Vec2;
use svg::node::element::{Circle, Group, Polygon, Polyline, Rectangle, Title};
use svg::Document;

use crate::backend::ShownByDefault;
use crate::level::{Level, ScenarioSpec, Tile};
use crate::metrics::MetricRow;
use crate::registry::Registry;
use crate::shape::CharacterShape;
use crate::trace::{Trace, TraceRow};
use crate::tradeoff::error_score;

pub use super::html_colours::{styles, Style};
use super::html_replay_data::{px, replay_json};
pub(crate) use super::replay_drawn::{Drawing, DrawnRun};

/// One configuration's run of a scenario, as the replay draws it.
pub struct ReplayRun<'a> {
    /// The trace (character 0 is drawn).
    pub trace: &'a Trace,
    /// The character's collision shape in this configuration.
    pub shape: CharacterShape,
    /// The outer size of the box the configuration really moves, in tiles.
    pub size: Vec2,
    /// Fault bits of each of character 0's rows ([`crate::metrics::faults`]), in frame order.
    pub faults: Vec<u8>,
}

/// One scenario and its runs (any configurations; the picker offers them all).
pub struct ScenarioTraces<'a> {
    /// The level.
    pub level: &'a Level,
    /// The scenario.
    pub spec: &'a ScenarioSpec,
    /// Its runs, in the order of the configurations.
    pub runs: Vec<ReplayRun<'a>>,
}

/// Pixels per tile in the pictures.
pub(crate) const SCALE: f32 = 22.0;
/// Largest picture width, in tiles: long levels are cropped around the trajectories. Wide
/// enough for every built-in walk (the 10 s walks cover about 63 tiles; at 60 the review found
/// characters leaving the picture in 9 of 64 scenarios), bounded so a run that flies off cannot
/// make the page huge.
const MAX_TILES: f32 = 80.0;
/// Most frames drawn per scenario: longer runs are drawn every `k`-th frame (the metrics and
/// the fault marks still read every frame: a drawn frame carries the faults of the frames it
/// stands for). 400 frames keep the built-in report under 10 MB with every configuration in it
/// (`platbench report` prints the size) and play at 30 or more drawn frames per second of a
/// scenario up to 13 s long.
pub(crate) const MAX_DRAWN_FRAMES: usize = 400;

/// Text escaped for HTML content and attribute values.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The drawing stride of a run of `frames` frames: every frame up to [`MAX_DRAWN_FRAMES`].
pub(crate) fn stride(frames: usize) -> usize {
    frames.div_ceil(MAX_DRAWN_FRAMES).max(1)
}

/// The frames drawn for a run of `frames` frames with `stride`: every `stride`-th, and the last.
pub(super) fn drawn_frames(frames: usize, stride: usize) -> impl Iterator<Item = usize> {
    let n = if frames == 0 {
        0
    } else {
        (frames - 1).div_ceil(stride) + 1
    };
    (0..n).map(move |k| (k * stride).min(frames.saturating_sub(1)))
}

/// The picture of one scenario with its replay: the level, each configuration's path (faulty
/// frames as red dots, airborne ones hollow), each character's shape and the platforms at frame
/// 0, the controls, the picker, and the drawn frames as inline JSON for the script. `shown`
/// lists the configurations visible before the reader picks. Returns the HTML and the
/// picture's own width in pixels (the page lays narrow pictures side by side).
pub(crate) fn scenario_replay(
    id: &str,
    s: &ScenarioTraces,
    styles: &[Style],
    shown: &[(String, String)],
) -> (String, f32) {
    let runs: Vec<(&ReplayRun, &Style)> = s
        .runs
        .iter()
        .filter_map(|r| Some((r, style_of(styles, &r.trace.backend, &r.trace.config)?)))
        .collect();
    let frames = runs
        .iter()
        .map(|(r, _)| r.trace.character(0).count())
        .max()
        .unwrap_or(0);
    let drawing = Drawing::of(frames);
    let drawn: Vec<(DrawnRun, &Style)> = runs
        .into_iter()
        .map(|(r, style)| {
            let mut b = drawing.run(r.size);
            r.trace.character(0).for_each(|row| b.row(*row));
            r.faults.iter().for_each(|&f| b.fault(f));
            (b.finish(&r.trace.backend, &r.trace.config, r.shape), style)
        })
        .collect();
    draw_replay(id, s.level, s.spec, &drawn, &drawing, shown)
}

/// The style of configuration `backend` `config` among `styles`; a run without one is not
/// drawn.
pub(crate) fn style_of<'s>(styles: &'s [Style], backend: &str, config: &str) -> Option<&'s Style> {
    styles
        .iter()
        .find(|st| st.backend == backend && st.config == config)
}

/// [`scenario_replay`] of runs already reduced to their drawn frames ([`DrawnRun`]), each with
/// its style, drawn at `drawing`'s frames.
pub(crate) fn draw_replay(
    id: &str,
    level: &Level,
    spec: &ScenarioSpec,
    rows: &[(DrawnRun, &Style)],
    drawing: &Drawing,
    shown: &[(String, String)],
) -> (String, f32) {
    let (stride, picked) = (drawing.stride, &drawing.picked);
    // The area to draw: the paths and the spawn, padded, within the level.
    let size = spec.size;
    let (mut lo, mut hi) = (spec.spawn, spec.spawn + size);
    for (run, _) in rows {
        if let Some((a, b)) = run.bounds {
            lo = lo.min(a);
            hi = hi.max(b);
        }
    }
    let lo = (lo - Vec2::splat(3.0)).max(Vec2::ZERO).floor();
    let mut hi = (hi + Vec2::splat(3.0))
        .min(Vec2::new(level.width as f32, level.height as f32))
        .ceil();
    hi.x = hi.x.min(lo.x + MAX_TILES);
    let (w, h) = (hi.x - lo.x, hi.y - lo.y);
    let to_px = |p: Vec2| ((p.x - lo.x) * SCALE, (hi.y - p.y) * SCALE);
    let mut doc = Document::new()
        .set("width", w * SCALE)
        .set("height", h * SCALE)
        .set("viewBox", (0, 0, w * SCALE, h * SCALE))
        .set("class", "scenario");
    doc = doc.add(level_group(level, lo, hi, &to_px));
    // Platforms at frame 0 (the script moves them).
    let mut plats = Group::new().set("class", "platforms");
    for p in &level.platforms {
        let b = p.aabb(0.0);
        let (x, y) = to_px(Vec2::new(b.mins.x, b.maxs.y));
        plats = plats.add(
            Rectangle::new()
                .set("class", "platform")
                .set("x", x)
                .set("y", y)
                .set("width", p.size.x * SCALE)
                .set("height", p.size.y * SCALE)
                .set("fill", "#cfd8dc")
                .set("stroke", "#455a64")
                .set("stroke-dasharray", "3,2"),
        );
    }
    doc = doc.add(plats);
    let is_shown = |t: &DrawnRun| shown.iter().any(|(b, c)| *b == t.backend && *c == t.config);
    // A point of a path: the character's centre at a drawn frame, in pixels.
    let centre = |r: &TraceRow, run: &DrawnRun| to_px(Vec2::new(r.x, r.y + run.size.y * 0.5));
    for (k, (run, style)) in rows.iter().enumerate() {
        let t = run;
        let colour = style.colour.as_str();
        let mut pts = String::new();
        for r in &run.rows {
            let (x, y) = centre(r, run);
            let _ = write!(
                pts,
                "{}{},{}",
                if pts.is_empty() { "" } else { " " },
                px(x),
                px(y)
            );
        }
        let mut g = Group::new()
            .set("class", format!("path backend-{}", t.backend))
            .set("data-k", k)
            .set("data-config", t.config.clone())
            .add(Title::new(format!("{} {}", t.backend, t.config)))
            .add(
                Polyline::new()
                    .set("points", pts)
                    .set("fill", "none")
                    .set("stroke", colour)
                    .set("stroke-opacity", 0.6)
                    .set("stroke-width", 1.5),
            );
        if !is_shown(t) {
            g = g.set("display", "none");
        }
        for (i, r) in run.rows.iter().enumerate() {
            let bad = run.faults.get(i).is_some_and(|&f| f != 0);
            if bad || (!r.is_grounded() && i % 4 == 0) {
                let (x, y) = centre(r, run);
                g = g.add(
                    Circle::new()
                        .set("cx", px(x))
                        .set("cy", px(y))
                        .set("r", 1.8)
                        .set("fill", if bad { "#d50000" } else { "none" })
                        .set("stroke", if bad { "#d50000" } else { colour }),
                );
            }
        }
        doc = doc.add(g);
    }
    // The characters at frame 0, on top of every path.
    for (k, (run, style)) in rows.iter().enumerate() {
        let (x, y) = run.rows.first().map_or((0.0, 0.0), |r| centre(r, run));
        let mut g = Group::new()
            .set("class", "body")
            .set("data-k", k)
            .set("transform", format!("translate({x:.1},{y:.1})"))
            .set("fill", style.colour.as_str())
            .set("fill-opacity", 0.45)
            .set("stroke", style.colour.as_str())
            .set("stroke-width", 1.5)
            .add(shape_element(run.shape, run.size));
        if !is_shown(run) {
            g = g.set("display", "none");
        }
        doc = doc.add(g);
    }
    let mut out = String::new();
    let _ = write!(
        out,
        "<div class=\"replay\" id=\"replay-{}\" tabindex=\"0\" aria-label=\"replay of {}: the arrow keys step a frame\"><div class=\"controls\"><button type=\"button\" class=\"play\">play</button> <select class=\"speed\" title=\"speed\"><option value=\"1\">real time</option><option value=\"0.5\">1/2 speed</option><option value=\"0.25\">1/4 speed</option><option value=\"0.1\">1/10 speed</option></select> <input type=\"range\" class=\"scrub\" min=\"0\" max=\"{}\" value=\"0\" step=\"1\" title=\"frame (the arrow keys step one)\"> <span class=\"clock\"></span> <span class=\"view\"><button type=\"button\" class=\"zoom-in\" title=\"zoom in (or the wheel over the focused picture)\">+</button><button type=\"button\" class=\"zoom-out\" title=\"zoom out\">&minus;</button><button type=\"button\" class=\"zoom-fit\" title=\"the whole picture\">fit</button> <label title=\"keep the shown characters in view\"><input type=\"checkbox\" class=\"follow\" checked> follow</label></span>",
        escape(id),
        escape(id),
        picked.len().saturating_sub(1)
    );
    out.push_str(&picker(rows, shown));
    out.push_str("</div>");
    // The picture and the state table side by side where both fit, else one above the other.
    out.push_str("<div class=\"stage\">");
    out.push_str(&doc.to_string());
    out.push_str("<table class=\"state\"><thead><tr><th>at this frame</th><th title=\"feet, tiles\">x, y</th><th title=\"tiles/s\">vx, vy</th><th title=\"grounded, and the ground's normal\">ground</th></tr></thead><tbody></tbody></table></div>");
    out.push_str("<script type=\"application/json\" class=\"replay-data\">");
    out.push_str(&replay_json(
        level,
        spec,
        rows,
        picked,
        stride,
        Vec2::new(lo.x, hi.y),
        &to_px,
    ));
    out.push_str("</script></div>");
    (out, w * SCALE)
}

/// The picker of a replay: a collapsed list of its configurations, grouped by backend, each a
/// checkbox with its colour; its summary says how many are shown. The colours are named once
/// per page (the legend above the scenarios), so the picker stays one line until opened.
fn picker(rows: &[(DrawnRun, &Style)], shown: &[(String, String)]) -> String {
    let is_shown = |t: &DrawnRun| shown.iter().any(|(b, c)| *b == t.backend && *c == t.config);
    let n = rows.iter().filter(|(r, _)| is_shown(r)).count();
    let mut out = format!(
        "<details class=\"picker\"><summary>configurations: <span class=\"count\">{n}</span> of {} shown</summary>",
        rows.len()
    );
    let mut backend: Option<&str> = None;
    for (k, (t, style)) in rows.iter().enumerate() {
        if backend != Some(t.backend.as_str()) {
            if backend.is_some() {
                out.push_str("</div>");
            }
            let _ = write!(out, "<div><b>{}</b>", escape(&t.backend));
            backend = Some(&t.backend);
        }
        let _ = write!(
            out,
            "<label><input type=\"checkbox\" data-k=\"{k}\" data-run=\"{} {}\"{}><i style=\"background:{}\"></i>{}</label>",
            escape(&t.backend),
            escape(&t.config),
            if is_shown(t) { " checked" } else { "" },
            escape(&style.colour),
            escape(&t.config)
        );
    }
    if backend.is_some() {
        out.push_str("</div>");
    }
    out.push_str("</details>");
    out
}

/// The solid tiles, slopes, one-way platforms and ladders between `lo` and `hi`.
fn level_group(level: &Level, lo: Vec2, hi: Vec2, to_px: &impl Fn(Vec2) -> (f32, f32)) -> Group {
    let mut tiles = Group::new().set("class", "tiles");
    for r in level.merged_solid_rects() {
        if r.maxs.x <= lo.x || r.mins.x >= hi.x || r.maxs.y <= lo.y || r.mins.y >= hi.y {
            continue;
        }
        let (x, y) = to_px(Vec2::new(r.mins.x, r.maxs.y));
        tiles = tiles.add(
            Rectangle::new()
                .set("x", x)
                .set("y", y)
                .set("width", (r.maxs.x - r.mins.x) * SCALE)
                .set("height", (r.maxs.y - r.mins.y) * SCALE)
                .set("fill", "#8d8d8d"),
        );
    }
    for j in lo.y as i64..hi.y as i64 {
        for i in lo.x as i64..hi.x as i64 {
            let o = Vec2::new(i as f32, j as f32);
            match level.tile(i, j) {
                Tile::Slope(slope) => {
                    let pts: Vec<(f32, f32)> =
                        slope.outline().iter().map(|p| to_px(*p + o)).collect();
                    tiles = tiles.add(Polygon::new().set("points", pts).set("fill", "#a1887f"));
                }
                Tile::OneWay => {
                    let (x, y) = to_px(o + Vec2::Y);
                    tiles = tiles.add(
                        Rectangle::new()
                            .set("x", x)
                            .set("y", y)
                            .set("width", SCALE)
                            .set("height", SCALE * 0.2)
                            .set("fill", "#6d4c41"),
                    );
                }
                Tile::Ladder => {
                    let (x, y) = to_px(o + Vec2::new(0.25, 1.0));
                    tiles = tiles.add(
                        Rectangle::new()
                            .set("x", x)
                            .set("y", y)
                            .set("width", SCALE * 0.5)
                            .set("height", SCALE)
                            .set("fill", "none")
                            .set("stroke", "#795548"),
                    );
                }
                _ => {}
            }
        }
    }
    tiles
}

/// The character's shape around its centre, in pixels, as [`CharacterShape::build`] makes it for
/// outer `size`: a box, a capsule (a box with fully rounded ends), a ball, a rounded box.
fn shape_element(shape: CharacterShape, size: Vec2) -> Box<dyn svg::Node> {
    let half = size * 0.5 * SCALE;
    let rect = |rx: f32| {
        Box::new(
            Rectangle::new()
                .set("x", -half.x)
                .set("y", -half.y)
                .set("width", 2.0 * half.x)
                .set("height", 2.0 * half.y)
                .set("rx", rx)
                .set("ry", rx),
        ) as Box<dyn svg::Node>
    };
    match shape {
        CharacterShape::Cuboid => rect(0.0),
        CharacterShape::Capsule => rect(half.x.min(half.y)),
        CharacterShape::Ball => Box::new(Circle::new().set("cx", 0).set("cy", 0).set("r", half.y)),
        CharacterShape::RoundCuboid { border_fraction } => {
            rect((border_fraction * size.x * SCALE).clamp(0.0, half.x.min(half.y)))
        }
    }
}

/// The replay script, inline once per report: plays, pauses, scrubs, steps (arrow keys), zooms
/// and pans (the SVG's viewBox), follows the shown characters, picks, and shows each shown
/// character's state at the frame. `#view=REPLAY_ID&frame=N` (a table value's link) shows that
/// replay at trace frame N, scrolled to and focused (`&show=BACKEND CONFIG` ticks that
/// configuration; `&alone` hides the rest of the page, for a screenshot). With `#selftest` it
/// checks every replay (the scrubber moves the characters and platforms, playing advances the
/// frame, the picker hides a character, the keys step, zoom and follow keep the characters in
/// view) and writes the result into `<pre id="selftest">`; with `#measure` it writes the page's
/// layout (width, height, where the contents end) into `<pre id="measure">`.
pub(crate) const SCRIPT: &str = include_str!("replay.js");

/// The replay's style sheet: the picture at most as wide as its column and 480 px tall (its own
/// size when smaller; a taller one, a fall of 50 tiles or the elevator's ride, is drawn smaller
/// so that it plays on one screen with its controls, and the zoom and follow show it closer),
/// the picker one line until opened, the state table compact.
pub(crate) const STYLE: &str = ".replay{margin:0.3em 0 1.2em;outline:none}\n.replay:focus-visible svg.scenario,.replay:focus svg.scenario{border-color:#1565c0}\n.replay .controls{margin:0.2em 0;font-size:12px}\n.replay .controls button,.replay .controls select{font-size:12px;padding:0 4px}\n.replay .scrub{width:9em;max-width:30%;vertical-align:middle}\n.replay .clock{font-family:monospace;font-size:11px}\n.replay .view{white-space:nowrap}\n.replay details.picker{display:inline-block;vertical-align:top;font-size:12px;margin-left:0.5em}\n.replay details.picker[open]{display:block;margin:0.3em 0}\n.replay details.picker summary{cursor:pointer}\n.replay .picker div{margin:0.1em 0}\n.replay .picker label{display:inline-block;margin-right:1em}\n.replay i{display:inline-block;width:1.2em;height:0.8em;margin:0 0.3em}\n.replay svg.scenario{display:block;cursor:grab;touch-action:none;max-height:480px}\n.replay .stage{display:flex;flex-wrap:wrap;align-items:flex-start;gap:4px 8px}\n.replay .stage svg{flex:0 1 auto;min-width:0}\n.replay table.state{font-size:11px;margin:0;font-variant-numeric:tabular-nums;white-space:nowrap}\n.replay table.state td:first-child{white-space:normal;min-width:10em;max-width:15em}\n.replay table.state td,.replay table.state th{padding:0 4px}\n.replay tr.bad td{background:#ffebee}\n.replay .fault{color:#d50000;font-weight:bold}\n.replay g.body.bad{stroke:#d50000;stroke-width:3;fill:#d50000}\n.replay-legend{font-size:13px;margin:0.5em 0}\n.replay-legend i{height:0.8em}\n";

/// The configurations a scenario's replay in the report shows before the reader picks,
/// from `rows`, that scenario's metric rows: per kind of `registry` in order, what its
/// [`crate::controller::BackendKind::shown_by_default`] asks for among the configurations that ran it. Each
/// entry is `(backend, config label)`.
pub fn shown_by_default(registry: &Registry, rows: &[MetricRow]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for k in registry.kinds() {
        let mut configs: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.backend == k.name()) {
            if !configs.contains(&r.config.as_str()) {
                configs.push(&r.config);
            }
        }
        let picked: Vec<&str> = match k.shown_by_default() {
            ShownByDefault::Listed(labels) => {
                labels.into_iter().filter(|l| configs.contains(l)).collect()
            }
            ShownByDefault::BestAndWorst => {
                let scored: Vec<(&str, f64)> = configs
                    .iter()
                    .map(|c| {
                        let own: Vec<MetricRow> = rows
                            .iter()
                            .filter(|r| r.backend == k.name() && r.config == *c)
                            .cloned()
                            .collect();
                        (*c, error_score(&own))
                    })
                    .collect();
                // The first of equals is the best; the last of equals the worst.
                let best = scored.iter().reduce(|a, b| if b.1 < a.1 { b } else { a });
                let worst = scored.iter().reduce(|a, b| if b.1 >= a.1 { b } else { a });
                let mut p: Vec<&str> = best.into_iter().chain(worst).map(|x| x.0).collect();
                p.dedup();
                p
            }
        };
        out.extend(
            picked
                .into_iter()
                .map(|c| (k.name().to_string(), c.to_string())),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::faults;

    #[test]
    fn subsampling_keeps_the_last_frame_and_every_fault() {
        assert_eq!(stride(400), 1);
        assert_eq!(stride(401), 2);
        let picked: Vec<usize> = drawn_frames(6, 2).collect();
        assert_eq!(picked, [0, 2, 4, 5]);
        // A fault at frame 3, which is not drawn, shows at drawn frame 4.
        let faults = [0, 0, 0, faults::STUCK, 0, 0];
        let drawing = Drawing { stride: 2, picked };
        let mut b = drawing.run(Vec2::ONE);
        faults.iter().for_each(|&f| b.fault(f));
        let shown = b.finish("b", "c", CharacterShape::Cuboid).faults;
        assert_eq!(shown, [0, 0, faults::STUCK, 0]);
    }

    #[test]
    fn configurations_without_a_colour_get_distinct_ones() {
        let reg = crate::registry::Registry::builtin();
        let configs: Vec<(String, String)> = reg
            .builtin_configs()
            .iter()
            .map(|r| (r.backend.backend().to_string(), r.label.clone()))
            .collect();
        let s = styles(&reg, &configs);
        for (i, a) in s.iter().enumerate() {
            for b in &s[i + 1..] {
                assert_ne!(a.colour, b.colour, "{a:?} {b:?}");
            }
        }
    }

    #[cfg(all(feature = "rapier", feature = "box2d"))]
    fn metric_row(backend: &str, config: &str, stuck: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: "s".into(),
            backend: backend.into(),
            config: config.into(),
            metric: "stuck_frames",
            value: stuck,
            unit: "frames",
            reference: 0.0,
            error: stuck,
            frame: None,
            q1: None,
            q3: None,
        }
    }

    #[test]
    #[cfg(all(feature = "rapier", feature = "box2d"))]
    fn replays_show_the_listed_reference_and_each_other_kinds_best_and_worst() {
        // stuck_frames weighs 1 in the default score, min(1, |error| / 1 frame): below one frame
        // (fractions, for the test), more is worse; at one and above every value scores 1.
        let rows = [
            metric_row("sweep", "jump=continuous", 0.0),
            metric_row("sweep", "default", 9.0),
            metric_row("rapier", "a", 0.25),
            metric_row("rapier", "b", 0.0),
            metric_row("rapier", "c", 0.75),
            metric_row("rapier", "d", 0.5),
        ];
        let shown = shown_by_default(&Registry::builtin(), &rows);
        let pair = |b: &str, c: &str| (b.to_string(), c.to_string());
        assert_eq!(
            shown,
            [
                pair("sweep", "default"),
                pair("rapier", "b"),
                pair("rapier", "c")
            ]
        );
        // One configuration is both its kind's best and worst: shown once.
        let one = shown_by_default(&Registry::builtin(), &rows[2..3]);
        assert_eq!(one, [pair("rapier", "a")]);
    }
}

//! The "pick a backend" report: one self-contained HTML file (inline SVG and CSS, no script, no
//! network) and a Markdown twin. Per behaviour, a table of every configuration's worst value
//! with the best marked and the measured reasons; per scenario, a drawing of the level with each
//! drawn configuration's trajectory; and a closing "which backend for which game" derived from
//! the numbers.

use std::fmt::Write as _;

use glam::Vec2;
use svg::node::element::{Circle, Group, Polygon, Polyline, Rectangle, Title};
use svg::Document;

use super::{format_setting, format_value, worst_matrix};
use crate::level::{Level, ScenarioSpec, Tile};
use crate::metrics::ground::Ground;
use crate::metrics::{registry, Behaviour, MetricRow};
use crate::shape::CharacterShape;
use crate::stress::{envelope, Envelope, StressRow};
use crate::trace::Trace;
use crate::tradeoff::{chart_svg, TradeoffRow};

/// A configuration drawn in the scenario pictures: `(backend, config label, CSS colour)`, as
/// [`crate::registry::Registry::drawn`] lists them.
pub type Drawn = (&'static str, &'static str, &'static str);

/// One scenario and its traces (any configurations; those the registry lists in
/// [`crate::registry::Registry::drawn`] are drawn).
pub struct ScenarioTraces<'a> {
    /// The level.
    pub level: &'a Level,
    /// The scenario.
    pub spec: &'a ScenarioSpec,
    /// Its traces.
    pub traces: Vec<&'a Trace>,
}

/// Pixels per tile in the pictures.
const SCALE: f32 = 22.0;
/// Largest picture width, in tiles: long levels are cropped around the trajectories.
const MAX_TILES: f32 = 60.0;

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The level around the scenario with each drawn configuration's path. Airborne frames are
/// hollow dots; frames where the character's shape is inside the level's solid geometry (tiles
/// or slopes, as `max_penetration` measures it, more than 1e-3 tiles) are red dots.
pub fn scenario_svg(s: &ScenarioTraces, drawn: &[Drawn]) -> String {
    let level = s.level;
    let size = s.spec.size;
    let drawn: Vec<(&Trace, &str)> = drawn
        .iter()
        .filter_map(|(b, c, colour)| {
            s.traces
                .iter()
                .find(|t| t.backend == *b && t.config == *c)
                .map(|t| (*t, *colour))
        })
        .collect();
    // The area to draw: the paths and the spawn, padded, within the level.
    let (mut lo, mut hi) = (s.spec.spawn, s.spec.spawn + size);
    for (t, _) in &drawn {
        for r in &t.rows {
            if r.x.is_finite() && r.y.is_finite() {
                lo = lo.min(Vec2::new(r.x - size.x, r.y));
                hi = hi.max(Vec2::new(r.x + size.x, r.y + size.y));
            }
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
    for p in &level.platforms {
        let b = p.aabb(0.0);
        let (x, y) = to_px(Vec2::new(b.mins.x, b.maxs.y));
        tiles = tiles.add(
            Rectangle::new()
                .set("x", x)
                .set("y", y)
                .set("width", p.size.x * SCALE)
                .set("height", p.size.y * SCALE)
                .set("fill", "#cfd8dc")
                .set("stroke", "#455a64")
                .set("stroke-dasharray", "3,2"),
        );
    }
    doc = doc.add(tiles);
    for (t, colour) in &drawn {
        // The configuration's shape: the sweep's box, or the shape its Rapier label names.
        let shape = t
            .config
            .rsplit(' ')
            .next()
            .and_then(CharacterShape::from_label)
            .unwrap_or(CharacterShape::Cuboid);
        let ground = Ground::new(level, shape, size);
        let pts: Vec<(f32, f32)> = t
            .rows
            .iter()
            .map(|r| to_px(Vec2::new(r.x, r.y + size.y * 0.5)))
            .collect();
        let mut g = Group::new()
            .set("class", format!("path backend-{}", t.backend))
            .set("data-config", t.config.clone())
            .add(Title::new(format!("{} {}", t.backend, t.config)))
            .add(
                Polyline::new()
                    .set("points", pts)
                    .set("fill", "none")
                    .set("stroke", *colour)
                    .set("stroke-opacity", 0.75)
                    .set("stroke-width", 2),
            );
        for (k, r) in t.rows.iter().enumerate() {
            let centre = Vec2::new(r.x, r.y + size.y * 0.5);
            let inside = ground.penetration(
                Vec2::new(r.x, r.y),
                r.t as f64,
                r.is_grounded() && r.ladder == 0,
            ) > 1e-3;
            if inside || (!r.is_grounded() && k % 4 == 0) {
                let (x, y) = to_px(centre);
                g = g.add(
                    Circle::new()
                        .set("cx", x)
                        .set("cy", y)
                        .set("r", 1.8)
                        .set("fill", if inside { "#d50000" } else { "none" })
                        .set("stroke", if inside { "#d50000" } else { *colour }),
                );
            }
        }
        doc = doc.add(g);
    }
    doc.to_string()
}

/// The metric table of one behaviour, as HTML rows and as Markdown.
fn behaviour_tables(rows: &[MetricRow], metrics: &[&str]) -> Option<(String, String)> {
    if !rows.iter().any(|r| metrics.contains(&r.metric)) {
        return None;
    }
    let m = worst_matrix(rows, |name| metrics.contains(&name));
    let mut html = String::from("<table><thead><tr><th>configuration</th>");
    let mut md = String::from("| configuration |");
    for (name, unit, _) in &m.metrics {
        let _ = write!(html, "<th>{name}<br><small>{unit}</small></th>");
        let _ = write!(md, " {name} ({unit}) |");
    }
    html.push_str("</tr></thead><tbody><tr class=\"ideal\"><td>ideal</td>");
    md.push_str("\n|---|");
    md.push_str(&"---|".repeat(m.metrics.len()));
    md.push_str("\n| ideal |");
    for (_, _, ideal) in &m.metrics {
        let _ = write!(html, "<td>{}</td>", format_value(*ideal));
        let _ = write!(md, " {} |", format_value(*ideal));
    }
    html.push_str("</tr>");
    for (ci, row) in m.cells.iter().enumerate() {
        if row.iter().all(|c| c.is_none()) {
            continue;
        }
        let c = m.label(ci);
        let _ = write!(html, "<tr><td>{}</td>", escape(&c));
        let _ = write!(md, "\n| {c} |");
        for cell in row {
            match cell {
                None => {
                    html.push_str("<td>-</td>");
                    md.push_str(" - |");
                }
                Some((v, best)) => {
                    let class = if *best { " class=\"best\"" } else { "" };
                    let _ = write!(html, "<td{class}>{}</td>", format_value(*v));
                    let _ = write!(
                        md,
                        " {}{} |",
                        format_value(*v),
                        if *best { " **best**" } else { "" }
                    );
                }
            }
        }
        html.push_str("</tr>");
    }
    html.push_str("</tbody></table>");
    Some((html, md))
}

/// "Which backend for which game": the statements of [`super::rules::RULES`], each evaluated
/// for every configuration on its worst values, with the numbers; then what each setting that
/// one configuration adds to another changes ([`super::rules::setting_effects`]).
pub fn recommendations(rows: &[MetricRow]) -> Vec<String> {
    let mut out = super::rules::evaluate(super::rules::RULES, rows);
    out.extend(super::rules::setting_effects(rows));
    out
}

/// Results of the slower commands the report can include: `platbench sweep`'s `tradeoff.csv`
/// and `platbench stress`'s `stability.csv`, read back from their files.
#[derive(Clone, Debug, Default)]
pub struct Extras {
    /// Rows of `tradeoff.csv`: drawn as the cost-against-error chart with the Pareto front listed.
    pub tradeoff: Option<Vec<TradeoffRow>>,
    /// Rows of `stability.csv`: summarised as each configuration's envelope per dimension.
    pub stability: Option<Vec<StressRow>>,
}

/// Setting values as a short comma-separated list ("-" when empty).
pub fn value_list(v: &[f64]) -> String {
    if v.is_empty() {
        return "-".into();
    }
    v.iter()
        .map(|&x| format_setting(x))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The speed-against-accuracy section: the chart and the settings on the Pareto front.
fn tradeoff_section(rows: &[TradeoffRow]) -> (String, String) {
    let mut html = String::from("<h2 id=\"tradeoff\">Speed against accuracy</h2><p>Each dot is one setting of <code>platbench sweep</code>: its cost (microseconds per character per second of game time) against its error score (0 is ideal); the line joins the Pareto front, the settings no other setting beats on both.</p>");
    let mut md = String::from("\n## Speed against accuracy\n\nThe chart is in the HTML report. Settings on the Pareto front (no other setting is both cheaper and more accurate):\n\n| backend | setting | us per character per game second | error score |\n|---|---|---:|---:|\n");
    html.push_str(&chart_svg(rows));
    html.push_str("<table><thead><tr><th>backend</th><th>setting</th><th>us per character per game second</th><th>error score</th></tr></thead><tbody>");
    let mut front: Vec<&TradeoffRow> = rows
        .iter()
        .filter(|r| r.pareto && r.scope == crate::tradeoff::ALL)
        .collect();
    front.sort_by(|a, b| a.cost_us.total_cmp(&b.cost_us));
    for r in front {
        let (b, s) = (escape(&r.backend), escape(&r.setting));
        let _ = write!(
            html,
            "<tr><td>{b}</td><td>{s}</td><td>{:.1}</td><td>{:.4}</td></tr>",
            r.cost_us, r.error
        );
        let _ = writeln!(
            md,
            "| {} | {} | {:.1} | {:.4} |",
            r.backend, r.setting, r.cost_us, r.error
        );
    }
    html.push_str("</tbody></table>");
    // The front of each behaviour's own score, cheapest first.
    html.push_str("<p>The front of each behaviour's own score (its metrics alone), cheapest first:</p><table><thead><tr><th>behaviour</th><th>settings on its front</th></tr></thead><tbody>");
    md.push_str("\nThe front of each behaviour's own score (its metrics alone), cheapest first:\n\n| behaviour | settings on its front |\n|---|---|\n");
    for b in crate::tradeoff::scored_behaviours() {
        let mut f: Vec<&TradeoffRow> = rows
            .iter()
            .filter(|r| r.pareto && r.scope == b.key())
            .collect();
        if f.is_empty() {
            continue;
        }
        f.sort_by(|x, y| x.cost_us.total_cmp(&y.cost_us));
        let list = f
            .iter()
            .map(|r| format!("{} {}", r.backend, r.setting))
            .collect::<Vec<_>>()
            .join(", ");
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td></tr>",
            b.title(),
            escape(&list)
        );
        let _ = writeln!(md, "| {} | {list} |", b.title());
    }
    html.push_str("</tbody></table>");
    // Each behaviour's front drawn, as platbench sweep draws it (tradeoff.<behaviour>.svg).
    for b in crate::tradeoff::scored_behaviours() {
        if rows.iter().any(|r| r.scope == b.key()) {
            let _ = write!(
                html,
                "<h3>Speed against accuracy: {}</h3>{}",
                b.title(),
                crate::tradeoff::chart_svg_scope(rows, b.key())
            );
        }
    }
    (html, md)
}

/// What broke where, for a table cell: `carry_no_drift at 0, 1000; finite at 1e7`, or `-`.
pub fn breaks_list(e: &Envelope) -> String {
    if e.breaks.is_empty() {
        return "-".into();
    }
    e.breaks
        .iter()
        .map(|(inv, vs)| format!("{inv} at {}", value_list(vs)))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The stability section: per configuration and dimension, the values at which every invariant
/// held and, per invariant, those at which it broke.
fn stability_section(rows: &[StressRow]) -> (String, String) {
    let mut html = String::from("<h2 id=\"stability\">Stability at the extremes</h2><p>From <code>platbench stress</code>: each dimension is pushed away from the base case alone; a value holds when every invariant (finite, penetration, no tunneling, stable rest, no flicker, carry without drift) held there, and the last column names each invariant that broke and where.</p><table><thead><tr><th>configuration</th><th>dimension</th><th>every invariant holds at</th><th>breaks at</th></tr></thead><tbody>");
    let mut md = String::from("\n## Stability at the extremes\n\n| configuration | dimension | every invariant holds at | breaks at |\n|---|---|---|---|\n");
    for e in envelope(rows) {
        let (config, dim) = (&e.config, &e.dimension);
        let (ok, bad) = (value_list(&e.holds), breaks_list(&e));
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{ok}</td><td>{bad}</td></tr>",
            escape(config),
            escape(dim)
        );
        let _ = writeln!(md, "| {config} | {dim} | {ok} | {bad} |");
    }
    html.push_str("</tbody></table>");
    (html, md)
}

/// Renders the report: (HTML, Markdown).
pub fn render_report(
    registry: &crate::registry::Registry,
    rows: &[MetricRow],
    scenarios: &[ScenarioTraces],
    extras: &Extras,
) -> (String, String) {
    let mut html = String::new();
    let mut md = String::new();
    html.push_str("<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>platbench report</title><style>\nbody{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}\ntable{border-collapse:collapse;margin:0.5em 0 1em;font-size:13px}\nth,td{border:1px solid #ccc;padding:3px 6px;text-align:right}\nth:first-child,td:first-child{text-align:left}\ntd.best{background:#c8e6c9;font-weight:bold}\ntr.ideal td{color:#777;font-style:italic}\nsvg.scenario{background:#fafafa;border:1px solid #ddd;max-width:100%;height:auto}\n.legend span{display:inline-block;margin-right:1em}\n.legend i{display:inline-block;width:1.5em;height:3px;vertical-align:middle;margin-right:0.3em}\n</style></head><body>\n");
    let configs = worst_matrix(rows, |_| false).configs.len();
    let _ = write!(html, "<h1>platbench report</h1><p>{} scenarios on {configs} configurations. Each table cell is a configuration's worst value over the scenarios; the best is highlighted.</p>", scenarios.len());
    let _ = write!(md, "# platbench report\n\n{} scenarios on {configs} configurations. Each table cell is a configuration's worst value over the scenarios; **best** marks the best.\n", scenarios.len());
    html.push_str("<h2 id=\"which\">Which backend for which game</h2><ul>");
    md.push_str("\n## Which backend for which game\n\n");
    for r in recommendations(rows) {
        let _ = write!(html, "<li>{}</li>", escape(&r));
        let _ = writeln!(md, "- {r}");
    }
    html.push_str("</ul><h2>By behaviour</h2>");
    md.push_str("\n## By behaviour\n");
    let all_notes = registry.notes(rows);
    let drawn = registry.drawn();
    for b in Behaviour::ALL.into_iter().filter(|b| *b != Behaviour::Cost) {
        let title = b.title();
        let metrics: Vec<&str> = registry::of_behaviour(b).map(|d| d.name).collect();
        if let Some((t_html, t_md)) = behaviour_tables(rows, &metrics) {
            let _ = write!(html, "<h3>{title}</h3>{t_html}");
            let _ = write!(md, "\n### {title}\n\n{t_md}\n");
            for n in all_notes
                .iter()
                .filter(|n| metrics.iter().any(|m| note_is_about(n, m)))
            {
                let _ = write!(html, "<p class=\"why\">{}</p>", escape(n));
                let _ = writeln!(md, "\n{n}");
            }
        }
    }
    for (h, m) in [
        extras.tradeoff.as_deref().map(tradeoff_section),
        extras.stability.as_deref().map(stability_section),
    ]
    .into_iter()
    .flatten()
    {
        html.push_str(&h);
        md.push_str(&m);
    }
    html.push_str("<h2>Scenarios</h2><p class=\"legend\">");
    md.push_str("\n## Scenarios\n\nPictures are in the HTML report. Paths:");
    for (b, c, colour) in &drawn {
        let _ = write!(
            html,
            "<span><i style=\"background:{colour}\"></i>{b} {c}</span>"
        );
        let _ = write!(md, " {b} {c} ({colour});");
    }
    html.push_str("<span>hollow dots: airborne; red dots: inside a solid tile or slope</span></p>");
    md.push('\n');
    for s in scenarios {
        let id = format!("{}.{}", s.level.name, s.spec.name);
        let _ = write!(html, "<h3 id=\"{id}\">{id}</h3>{}", scenario_svg(s, &drawn));
        let _ = writeln!(md, "- {id}");
    }
    html.push_str("\n</body></html>\n");
    (html, md)
}

/// Whether a summary note explains `metric` (the notes name the metrics they explain).
fn note_is_about(note: &str, metric: &str) -> bool {
    let key = match metric {
        "rest_gap" => "rest_gap",
        "slope_overlap" => "slope_overlap",
        "idle_drift" => "idle_drift",
        "land_frame_error" => "lands early",
        "max_penetration" => "sinks into",
        "false_grounded" => "false_grounded",
        "progress_ratio" => "progress",
        "steep_blocked" => "too-steep",
        "carry_airborne_frames" => "riders",
        "apex_error" => "jump=continuous",
        _ => return false,
    };
    note.contains(key)
}

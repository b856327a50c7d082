//! What makes the report navigable: the table of contents, the metric definitions every table
//! header links to, the links from a table's value to the replay of its scenario, the one
//! colour legend of the replays, and the page's style sheet (nothing wider than the window: a
//! wide table scrolls sideways on its own).

use std::fmt::Write as _;

use super::html_colours::Style;
use super::replay::escape;
use crate::metrics::{registry, MetricRow};

/// The page's style sheet (the replays' own is [`super::replay::STYLE`]). The body is at most
/// 1220 px wide, plus 2 em of padding: 1252 px, within a 1280 px window less its 15 px scroll
/// bar; anything wider scrolls inside its own `div.wide`.
pub(crate) const PAGE_STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:1220px;margin:1em auto;padding:0 1em;color:#222;overflow-wrap:break-word}\nh1{margin:0.2em 0}\nh2{border-bottom:1px solid #ddd;padding-bottom:0.1em;margin-top:1.5em}\n.lead{margin:0.3em 0}\n#verdict{margin:0.5em 0;padding:0.3em 0.8em;border-left:4px solid #1565c0;background:#f3f7fc}\n#toc{font-size:14px;margin:0.5em 0;padding:0.3em 0.8em;background:#fafafa;border:1px solid #e0e0e0}\n#toc ol{margin:0.2em 0;padding-left:1.5em}\n#toc li{margin:0.15em 0}\n#toc .sub{font-size:13px;color:#555}\n#toc .sub a{margin-right:0.6em;white-space:nowrap}\n.wide{overflow-x:auto;max-width:100%}\ntable{border-collapse:collapse;margin:0.5em 0 1em;font-size:13px}\nth,td{border:1px solid #ccc;padding:2px 5px;text-align:right}\nth{font-weight:600;vertical-align:bottom}\nth a{color:inherit}\nth:first-child,td:first-child{text-align:left}\ntd a{color:inherit;text-decoration:none;border-bottom:1px dotted #888}\ntd a:hover{background:#fff59d}\ntd.best{background:#c8e6c9;font-weight:bold}\ntr.ideal td{color:#777;font-style:italic}\ntable.defs td{text-align:left;vertical-align:top}\ntable.defs td:first-child{white-space:nowrap}\n:target{scroll-margin-top:0.5em}\ntr:target td{background:#fff59d}\nsvg{max-width:100%;height:auto}\n.replays{display:flex;flex-wrap:wrap;gap:0 20px}\n.replays>.scenario{flex:1 1 580px;min-width:0}\n.replays>.scenario.full{flex-basis:100%}\nh4{margin:0.6em 0 0.2em}\nsvg.scenario{background:#fafafa;border:1px solid #ddd}\n.legend span{display:inline-block;margin-right:1em}\n.legend i{display:inline-block;width:1.5em;height:3px;vertical-align:middle;margin-right:0.3em}\n";

/// `html` with each of its `<table>`s inside a `div.wide`, which scrolls sideways when the
/// table is wider than the page (the page itself never does).
pub(crate) fn wide(html: &str) -> String {
    html.replace("<table>", "<div class=\"wide\"><table>")
        .replace("</table>", "</table></div>")
}

/// A link of the table of contents: an id of the page and its title.
type Entry = (String, String);

/// The table of contents: the page's sections (its `h2`s) in order, each with its parts (the
/// behaviours, the levels) as one line of links.
#[derive(Default)]
pub(crate) struct Toc {
    /// Per section: its id, its title and its parts' ids and titles.
    entries: Vec<(Entry, Vec<Entry>)>,
}

impl Toc {
    /// Adds a section.
    pub fn add(&mut self, id: &str, title: &str) {
        self.entries.push(((id.into(), title.into()), Vec::new()));
    }

    /// Adds a part to the last section.
    pub fn sub(&mut self, id: &str, title: &str) {
        if let Some(e) = self.entries.last_mut() {
            e.1.push((id.into(), title.into()));
        }
    }

    /// The `<nav id="toc">`.
    pub fn render(&self) -> String {
        let mut out = String::from("<nav id=\"toc\"><b>Contents</b><ol>");
        for ((id, title), subs) in &self.entries {
            let _ = write!(
                out,
                "<li><a href=\"#{}\">{}</a>",
                escape(&fragment(id)),
                escape(title)
            );
            if !subs.is_empty() {
                out.push_str(": <span class=\"sub\">");
                for (sid, stitle) in subs {
                    let _ = write!(
                        out,
                        "<a href=\"#{}\">{}</a> ",
                        escape(&fragment(sid)),
                        escape(stitle)
                    );
                }
                out.push_str("</span>");
            }
            out.push_str("</li>");
        }
        out.push_str("</ol></nav>");
        out
    }
}

/// `s` percent-encoded for an address's fragment: letters, digits and `-._~` stay, every other
/// byte is `%XX` (the script reads it back with `decodeURIComponent`).
pub(crate) fn fragment(s: &str) -> String {
    let mut out = String::new();
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(char::from(b));
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

/// A table value linked to the replay of the scenario of `row` at `frame` (the start when
/// `None`): `#view=<level>.<scenario>&frame=<N>&show=<backend> <config>`, which the replay script
/// follows (it shows that replay at that frame, with that configuration ticked). Its tooltip
/// names the scenario and the value.
pub(crate) fn replay_link(row: &MetricRow, frame: Option<u32>, value: &str) -> String {
    format!(
        "<a href=\"{}\" title=\"{}.{} ({value})\">{value}</a>",
        escape(&replay_href(row, frame)),
        escape(&row.level),
        escape(&row.scenario)
    )
}

/// The fragment of [`replay_link`], unescaped: `#view=...&frame=...&show=...`.
pub(crate) fn replay_href(row: &MetricRow, frame: Option<u32>) -> String {
    let id = format!("{}.{}", row.level, row.scenario);
    let mut href = format!("#view={}", fragment(&id));
    if let Some(f) = frame {
        let _ = write!(href, "&frame={f}");
    }
    let _ = write!(
        href,
        "&show={}",
        fragment(&format!("{} {}", row.backend, row.config))
    );
    href
}

/// A behaviour table's header cell of metric `name`: its name, breakable at the underscores,
/// linked to its definition with its meaning as the tooltip, over its unit.
pub(crate) fn metric_header(name: &str, unit: &str) -> String {
    let meaning = registry::get(name).map_or("", |d| d.meaning);
    format!(
        "<th><a href=\"#metric-{}\" title=\"{}\">{}</a><br><small>{}</small></th>",
        escape(name),
        escape(meaning),
        escape(name).replace('_', "_<wbr>"),
        escape(unit)
    )
}

/// The metric definitions: every metric of the registry ([`registry::METRICS`]), each row
/// `id="metric-<name>"`, with its unit, behaviour, meaning, the scenarios it applies to and
/// what it measures against.
pub(crate) fn metric_definitions() -> String {
    let mut html = String::from("<h2 id=\"metrics\">Metric definitions</h2><p>Every metric the tables show (<code>src/metrics/registry.rs</code>): what it measures, where, and against what.</p><table class=\"defs\"><thead><tr><th>metric</th><th>unit</th><th>behaviour</th><th>meaning</th><th>applies to</th><th>measured against</th></tr></thead><tbody>");
    for d in registry::METRICS {
        let _ = write!(
            html,
            "<tr id=\"metric-{}\"><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(d.name),
            escape(d.name).replace('_', "_<wbr>"),
            escape(d.unit),
            escape(d.behaviour.title()),
            escape(d.meaning),
            escape(d.applies),
            escape(d.reference)
        );
    }
    html.push_str("</tbody></table>");
    html.replace(
        "<table class=\"defs\">",
        "<div class=\"wide\"><table class=\"defs\">",
    )
    .replace("</table>", "</table></div>")
}

/// The colour legend of the replays, once for the page (each configuration wears one colour in
/// every picture): per backend, its configurations' swatches.
pub(crate) fn legend(styles: &[Style]) -> String {
    let mut out = String::from("<div class=\"legend replay-legend\">");
    let mut backend: Option<&str> = None;
    for s in styles {
        if backend != Some(s.backend.as_str()) {
            if backend.is_some() {
                out.push_str("</div>");
            }
            let _ = write!(out, "<div><b>{}</b> ", escape(&s.backend));
            backend = Some(&s.backend);
        }
        let _ = write!(
            out,
            "<span><i style=\"background:{}\"></i>{}</span>",
            escape(&s.colour),
            escape(&s.config)
        );
    }
    if backend.is_some() {
        out.push_str("</div>");
    }
    out.push_str("</div>");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fragments_are_percent_encoded() {
        assert_eq!(fragment("jumps.x"), "jumps.x");
        assert_eq!(
            fragment("rapier per-tile cuboid grounded=none"),
            "rapier%20per-tile%20cuboid%20grounded%3Dnone"
        );
    }

    #[test]
    fn a_value_links_to_its_replay() {
        let row = MetricRow {
            level: "jumps".into(),
            scenario: "x".into(),
            backend: "sweep".into(),
            config: "default".into(),
            metric: "apex_error",
            value: 0.5,
            unit: "tiles",
            reference: 0.0,
            error: 0.5,
            frame: None,
            q1: None,
            q3: None,
        };
        assert_eq!(
            replay_link(&row, Some(37), "0.5"),
            "<a href=\"#view=jumps.x&amp;frame=37&amp;show=sweep%20default\" title=\"jumps.x (0.5)\">0.5</a>"
        );
        assert!(!replay_link(&row, None, "0.5").contains("frame="));
    }
}

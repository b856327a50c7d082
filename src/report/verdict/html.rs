//! The verdict, the scorecard and the capability table as HTML: the report's first screen. Every
//! grade that is not `ok` links to the replay of the scenario behind it, at its frame, and every
//! metric name to its definition.

use std::fmt::Write as _;

use super::{Column, Grade, ProfileVerdict, Scorecard, Worst};
use crate::metrics::registry::Behaviour;
use crate::report::replay::escape;

/// A link to `w`'s replay at its frame, showing `text`; its tooltip names the scenario, the
/// metric, its value and ideal, the frame, and what the metric measures.
fn link(w: &Worst, text: &str) -> String {
    let r = &w.row;
    let at = r.frame.map_or(String::new(), |f| format!(", frame {f}"));
    format!(
        "<a href=\"{}\" title=\"{}.{} ({} {}, ideal {}{at}: {})\">{}</a>",
        escape(&crate::report::html_nav::replay_href(r, r.frame)),
        escape(&r.level),
        escape(&r.scenario),
        r.metric,
        crate::report::format_value(r.value),
        crate::report::format_value(r.reference),
        escape(crate::metrics::registry::get(r.metric).map_or("", |d| d.meaning)),
        escape(text)
    )
}

/// `w` in words, its scenario linked to the replay and its metric to its definition.
fn worst_html(w: &Worst) -> String {
    let r = &w.row;
    let at = r.frame.map_or(String::new(), |f| format!(" frame {f}"));
    format!(
        "{}: <a href=\"#metric-{m}\">{m}</a> {} (ideal {})",
        link(w, &format!("{}.{}{at}", r.level, r.scenario)),
        crate::report::format_value(r.value),
        crate::report::format_value(r.reference),
        m = r.metric
    )
}

fn grade_class(g: Option<Grade>) -> &'static str {
    match g {
        Some(Grade::Keeps) => "g-ok",
        Some(Grade::Minor) => "g-minor",
        Some(Grade::Fails) => "g-fail",
        None => "g-none",
    }
}

fn grade_word(g: Option<Grade>) -> &'static str {
    g.map_or("not run", Grade::word)
}

/// The styles of the verdict's tables.
pub const STYLE: &str = "table.verdict,table.scorecard{font-size:12px;margin:0.3em 0}\n.verdict td,.verdict th{vertical-align:top;text-align:left;padding:2px 5px}\n.scorecard td,.scorecard th{padding:1px 5px}\n.scorecard td.design{max-width:420px;white-space:nowrap;overflow:hidden;text-overflow:ellipsis;text-align:left;font-size:11px;color:#555}\n#verdict h2{margin:0.2em 0}\n#verdict h3{margin:0.5em 0 0.2em}\n#verdict p.small{margin:0.2em 0}\n#verdict .small{font-size:12px;color:#555}\ntd.g-ok{background:#e8f5e9}\ntd.g-minor{background:#fff8e1}\ntd.g-fail{background:#ffebee;font-weight:bold}\ntd.g-none{color:#999}\n.scorecard td{text-align:center}\n.scorecard td:first-child{text-align:left}\n.verdict .small{font-size:12px;color:#555}\n";

/// The verdict of every profile, the scorecard and the capabilities.
pub fn render_verdict_html(card: &Scorecard, verdicts: &[ProfileVerdict], source: &str) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<h2>Which controller for which game</h2><p class=\"small\">{} scenarios, {} configurations. Each game profile picks the configuration that fails the least of what it weighs, then has the lowest weighted error (in brackets: the mean over scored metrics of min(1, error beyond one pixel / the clearly-wrong size), 0 all within a pixel, 1 all clearly off; a skipped scenario counts as clearly off). {}</p>",
        card.total_scenarios,
        card.cards.len(),
        escape(source)
    );
    h.push_str("<div class=\"wide\"><table class=\"verdict\"><thead><tr><th>game</th><th>pick (runner-up)</th><th>why</th><th>still off</th></tr></thead><tbody>");
    for v in verdicts {
        let p = &v.profile;
        let mut needs = String::new();
        if !p.needs.is_empty() {
            let n: Vec<&str> = p.needs.iter().map(|n| n.name()).collect();
            let _ = write!(needs, "; needs {}", n.join(", "));
        }
        let _ = write!(
            h,
            "<tr><td><b>{}</b>: {}<br><span class=\"small\">weighs {}{}</span></td>",
            escape(&p.name),
            escape(&p.title),
            escape(&p.describe_weights()),
            escape(&needs)
        );
        match v.pick {
            None => {
                let _ = write!(
                    h,
                    "<td colspan=\"3\">none: {}</td>",
                    escape(v.no_pick.as_deref().unwrap_or(""))
                );
            }
            Some(_) => {
                let (pick, runner) = super::render::pick_texts(card, v);
                let _ = write!(h, "<td><b>{}</b>", escape(&pick));
                if let Some(r) = runner {
                    let _ = write!(
                        h,
                        "<br><span class=\"small\">runner-up: {}</span>",
                        escape(&r)
                    );
                }
                h.push_str("</td>");
                let why: Vec<String> = v
                    .why
                    .iter()
                    .map(|r| {
                        if r.behaviour == Behaviour::Cost {
                            return "cost: cheaper per character step".to_string();
                        }
                        let mut s = format!(
                            "{} {} vs {}",
                            r.behaviour.key(),
                            grade_word(r.pick),
                            grade_word(r.other)
                        );
                        if let Some(w) = &r.worst {
                            let _ = write!(s, " ({})", worst_html(w));
                        }
                        s
                    })
                    .collect();
                let _ = write!(h, "<td>{}</td>", why.join("<br>"));
                let wrong: Vec<String> = v
                    .still_wrong
                    .iter()
                    .map(|r| {
                        let mut s = format!("{} {}", r.behaviour.key(), grade_word(r.pick));
                        if let Some(w) = &r.worst {
                            let _ = write!(s, " ({})", worst_html(w));
                        }
                        s
                    })
                    .collect();
                let _ = write!(
                    h,
                    "<td>{}</td>",
                    if wrong.is_empty() {
                        "nothing this profile weighs".to_string()
                    } else {
                        wrong.join("<br>")
                    }
                );
            }
        }
        h.push_str("</tr>");
    }
    h.push_str("</tbody></table></div>");
    h.push_str(&scorecard_html(card));
    h.push_str(&capabilities_html(card));
    h
}

/// The scorecard: a grade per configuration and behaviour, each grade that is not ok linked to
/// the replay of its worst scenario at its frame.
fn scorecard_html(card: &Scorecard) -> String {
    let mut h = String::from("<h3 id=\"scorecard\">Scorecard</h3><p class=\"small\">How each configuration does on each behaviour's scenarios, against each metric's reference (rest and penetration against the contact the configuration declares). <b>ok</b>: every scored metric within the clearly-wrong size beyond the one-pixel allowance (0.01 tiles past 1/16 tile at 16 pixels a tile, 0.01 ratio, exact frames and counts); <b>minor</b>: within ten times it (0.1 tiles past the pixel), 3 frames or 2 counts; <b>FAIL</b>: beyond, or a wrong result; <b>-</b>: not run. A row of a level with moving platforms, ladders, one-way platforms or slopes counts toward that feature. A grade that is not ok links to the replay of its worst scenario at its frame; hover it for the value.</p><div class=\"wide\"><table class=\"scorecard\"><thead><tr><th>configuration</th>");
    for c in Column::ALL {
        let _ = write!(h, "<th>{}</th>", c.header());
    }
    h.push_str("<th>design</th></tr></thead><tbody>");
    for (i, c) in card.cards.iter().enumerate() {
        let _ = write!(h, "<tr><td>{}</td>", escape(&c.facts.label));
        for col in Column::ALL {
            let g = card.column_grade(i, col);
            let class = grade_class(g.map(|(g, _)| g));
            let word = g.map_or("-", |(g, _)| g.word());
            match g {
                Some((g, Some(w))) if g != Grade::Keeps => {
                    let _ = write!(h, "<td class=\"{class}\">{}</td>", link(w, word));
                }
                _ => {
                    let _ = write!(h, "<td class=\"{class}\">{word}</td>");
                }
            }
        }
        let _ = write!(
            h,
            "<td class=\"design\" title=\"{0}\">{0}</td></tr>",
            escape(&c.facts.why)
        );
    }
    h.push_str("</tbody></table></div>");
    h
}

/// What each configuration declares, grouped as the terminal groups it.
fn capabilities_html(card: &Scorecard) -> String {
    let text = super::render::render_capabilities(card);
    let mut lines = text.lines().filter(|l| l.contains(" | "));
    let mut h = String::from("<h3 id=\"capabilities\">Declared capabilities</h3><p class=\"small\">Declared by each configuration: slopes to platforms are the level features it runs (measured above); pushes (dynamic bodies), grid (positions on a fixed grid), f64 (world positions) and x-platform (bit-identical results across machines, as built here) are not measured.</p><div class=\"wide\"><table>");
    if let Some(head) = lines.next() {
        h.push_str("<thead><tr>");
        for c in head.split(" | ") {
            let _ = write!(h, "<th>{}</th>", escape(c.trim()));
        }
        h.push_str("</tr></thead><tbody>");
    }
    for l in lines {
        h.push_str("<tr>");
        for c in l.split(" | ") {
            let _ = write!(h, "<td>{}</td>", escape(c.trim()));
        }
        h.push_str("</tr>");
    }
    h.push_str("</tbody></table></div>");
    h
}

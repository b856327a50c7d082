//! The "pick a backend" report: one self-contained HTML file (inline SVG, CSS and one small
//! script, nothing fetched) and a Markdown twin. Under the title, the verdict and a table of
//! contents; per behaviour, a table of every configuration's worst value with the best marked
//! and the measured reasons, each value a link to the replay of the scenario where it happened
//! and each metric a link to its definition; the definitions; the slower commands' sections
//! (`html_sections.rs`); and per scenario, grouped by level, a replay of every
//! configuration's run over the level ([`super::replay`]).

use std::collections::HashMap;
use std::fmt::Write as _;

pub(crate) use super::html_nav::wide;
use super::html_nav::{metric_definitions, metric_header, replay_link, Toc, PAGE_STYLE};
pub(crate) use super::html_sections::{breaks_list, pair_tables};
use super::html_sections::{stability_section, tradeoff_section};
use super::replay::{escape, scenario_replay, styles};
pub use super::replay::{ReplayRun, ScenarioTraces};
use super::{badness, column, format_metric, format_value, worst_matrix};
use crate::metrics::{registry, Behaviour, MetricRow};
use crate::stress::StressRow;
use crate::tradeoff::TradeoffRow;

/// Each configuration column's worst row of each metric, keyed by (metric, column): the row
/// whose value [`worst_matrix`] shows (the last of the largest badness, as `Iterator::max_by`
/// picks it there), so a table cell links to the scenario its value comes from.
fn worst_rows(rows: &[MetricRow]) -> HashMap<(&'static str, String), &MetricRow> {
    let mut out: HashMap<(&'static str, String), &MetricRow> = HashMap::new();
    for r in rows {
        let slot = out.entry((r.metric, column(r))).or_insert(r);
        if badness(r).total_cmp(&badness(slot)).is_ge() {
            *slot = r;
        }
    }
    out
}

/// The metric table of one behaviour, as HTML rows and as Markdown. Each metric's name links
/// to its definition; each value links to its scenario's replay at its frame.
fn behaviour_tables(
    rows: &[MetricRow],
    worst: &HashMap<(&'static str, String), &MetricRow>,
    metrics: &[&str],
) -> Option<(String, String)> {
    if !rows.iter().any(|r| metrics.contains(&r.metric)) {
        return None;
    }
    let m = worst_matrix(rows, |name| metrics.contains(&name));
    let mut html = String::from("<table><thead><tr><th>configuration</th>");
    let mut md = String::from("| configuration |");
    for (name, unit, _) in &m.metrics {
        html.push_str(&metric_header(name, unit));
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
        for (mi, cell) in row.iter().enumerate() {
            match cell {
                None => {
                    html.push_str("<td>-</td>");
                    md.push_str(" - |");
                }
                Some((v, best)) => {
                    let class = if *best { " class=\"best\"" } else { "" };
                    let value = format_metric(*v, m.metrics[mi].1);
                    let linked = match worst.get(&(m.metrics[mi].0, m.configs[ci].clone())) {
                        Some(r) => replay_link(r, r.frame, &value),
                        None => value.clone(),
                    };
                    let _ = write!(html, "<td{class}>{linked}</td>");
                    let _ = write!(md, " {value}{} |", if *best { " **best**" } else { "" });
                }
            }
        }
        html.push_str("</tr>");
    }
    html.push_str("</tbody></table>");
    Some((wide(&html), md))
}

/// "Which backend for which game": the statements of [`super::rules::RULES`], each evaluated
/// for every configuration on its extreme value in the statement's direction, with the numbers; then what each setting that
/// one configuration adds to another changes ([`super::rules::setting_effects`]).
pub(crate) fn recommendations(rows: &[MetricRow]) -> Vec<String> {
    let mut out = super::rules::evaluate(super::rules::RULES, rows);
    out.extend(super::rules::setting_effects(rows));
    out
}

/// What the report includes beside the run's own rows: the verdict, and the results of the
/// slower commands, `platbench sweep`'s `tradeoff.csv` and `platbench stress`'s
/// `stability.csv`, read back from their files.
#[derive(Clone, Debug, Default)]
pub(crate) struct Extras {
    /// The verdict, pre-rendered HTML: placed first, right under the title, in
    /// `<section id="verdict">` (left out when empty).
    pub verdict: String,
    /// The verdict as the terminal prints it, for the Markdown twin (left out when empty).
    pub verdict_text: String,
    /// Rows of `tradeoff.csv`: drawn as the cost-against-error chart with the Pareto front listed.
    pub tradeoff: Option<Vec<TradeoffRow>>,
    /// Rows of `stability.csv`: summarised as each configuration's envelope per dimension.
    pub stability: Option<Vec<StressRow>>,
}

/// The widest picture, in pixels, that a replay shares its row with another: half the page's
/// 1220 px ([`super::html_nav::PAGE_STYLE`]) less the 20 px gap. A wider one has the row to
/// itself.
const HALF_COLUMN: f32 = 600.0;

/// Renders the report: (HTML, Markdown).
pub(crate) fn render_report(
    registry: &crate::registry::Registry,
    rows: &[MetricRow],
    scenarios: &[ScenarioTraces],
    extras: &Extras,
) -> (String, String) {
    let mut html = String::new();
    let mut md = String::new();
    let mut toc = Toc::default();
    html.push_str("<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>platbench report</title><style>\n");
    html.push_str(PAGE_STYLE);
    html.push_str(super::verdict::STYLE);
    html.push_str(super::replay::STYLE);
    html.push_str("</style></head><body>\n");
    let configs = worst_matrix(rows, |_| false).configs.len();
    let _ = write!(html, "<h1>platbench report</h1>");
    if !extras.verdict.is_empty() {
        toc.add("verdict", "Verdict");
        let _ = write!(html, "<section id=\"verdict\">{}</section>", extras.verdict);
    }
    let _ = write!(html, "<p class=\"lead\">{} scenarios on {configs} configurations. Each table cell is a configuration's worst value over the scenarios (a link to that scenario's replay); the best is highlighted.</p>", scenarios.len());
    // The table of contents goes here once every section is known.
    let toc_at = html.len();
    let _ = write!(md, "# platbench report\n\n{} scenarios on {configs} configurations. Each table cell is a configuration's worst value over the scenarios; **best** marks the best.\n", scenarios.len());
    if !extras.verdict_text.is_empty() {
        let _ = write!(
            md,
            "\n## Which controller for which game\n\n```\n{}\n```\n",
            extras.verdict_text.trim_end()
        );
    }
    toc.add("statements", "What the worst values show");
    html.push_str("<h2 id=\"statements\">What the worst values show</h2><ul>");
    md.push_str("\n## What the worst values show\n\n");
    for r in recommendations(rows) {
        let _ = write!(html, "<li>{}</li>", escape(&r));
        let _ = writeln!(md, "- {r}");
    }
    toc.add("behaviour", "By behaviour");
    html.push_str("</ul><h2 id=\"behaviour\">By behaviour</h2>");
    md.push_str("\n## By behaviour\n");
    let all_notes = super::notes::notes(rows);
    let worst = worst_rows(rows);
    for b in Behaviour::ALL.into_iter().filter(|b| *b != Behaviour::Cost) {
        let title = b.title();
        let metrics: Vec<&str> = registry::of_behaviour(b).map(|d| d.name).collect();
        if let Some((t_html, t_md)) = behaviour_tables(rows, &worst, &metrics) {
            let id = format!("behaviour-{}", b.key());
            toc.sub(&id, title);
            let _ = write!(html, "<h3 id=\"{id}\">{title}</h3>{t_html}");
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
    toc.add("metrics", "Metric definitions");
    html.push_str(&metric_definitions());
    if extras.tradeoff.is_some() {
        toc.add("tradeoff", "Speed against accuracy");
    }
    if extras.stability.is_some() {
        toc.add("stability", "Stability at the extremes");
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
    // Every configuration that ran, in run order, each with one colour in every picture.
    let mut configs: Vec<(String, String)> = Vec::new();
    for s in scenarios {
        for r in &s.runs {
            let key = (r.trace.backend.clone(), r.trace.config.clone());
            if !configs.contains(&key) {
                configs.push(key);
            }
        }
    }
    let styles = styles(registry, &configs);
    toc.add("scenarios", "Scenarios");
    html.push_str("<h2 id=\"scenarios\">Scenarios</h2><p>Each scenario replays every configuration's run: <b>play</b> it in real time or slowed down, pause, drag the scrubber, or step frame by frame with the left and right arrow keys (click the picture first, or keep the mouse over it); zoom with + and &minus; (or the wheel over the clicked picture) and drag to pan; <b>follow</b> keeps the shown characters in view. Open <b>configurations</b> to pick the ones shown (by default the reference kind's listed configuration and the best and worst configuration of each other kind on that scenario, by the error score of its metrics). The table under each picture gives each shown character's state at the frame. Each character is drawn with its real shape; moving platforms move. A character turns red, and its row says why, on a faulty frame: inside a solid deeper than its configuration declares or inside a moving platform, stuck on open ground, airborne with the ground near after leaving it, grounded over air, or crushed. On the paths, red dots mark faulty frames and hollow dots airborne ones.</p>");
    html.push_str(&super::html_nav::legend(&styles));
    md.push_str("\n## Scenarios\n\nReplays are in the HTML report. Shown by default:\n");
    // Per level, its scenarios' replays side by side where they are narrow enough.
    let mut level: Option<&str> = None;
    for s in scenarios {
        if level != Some(s.level.name.as_str()) {
            if level.is_some() {
                html.push_str("</div>");
            }
            level = Some(&s.level.name);
            let lid = format!("level-{}", s.level.name);
            toc.sub(&lid, &s.level.name);
            let _ = write!(
                html,
                "<h3 id=\"{}\">{}</h3><div class=\"replays\">",
                escape(&lid),
                escape(&s.level.name)
            );
        }
        let id = format!("{}.{}", s.level.name, s.spec.name);
        let scenario_rows: Vec<MetricRow> = rows
            .iter()
            .filter(|r| r.level == s.level.name && r.scenario == s.spec.name)
            .cloned()
            .collect();
        let shown = super::replay::shown_by_default(registry, &scenario_rows);
        let (replay, width) = scenario_replay(&id, s, &styles, &shown);
        let _ = write!(
            html,
            "<div class=\"scenario{}\"><h4 id=\"{}\">{}</h4>{replay}</div>",
            if width > HALF_COLUMN { " full" } else { "" },
            escape(&id),
            escape(&id),
        );
        let list = shown
            .iter()
            .map(|(b, c)| format!("{b} {c}"))
            .collect::<Vec<_>>()
            .join(", ");
        let _ = writeln!(md, "- {id}: {list}");
    }
    if level.is_some() {
        html.push_str("</div>");
    }
    let _ = write!(html, "<script>{}</script>", super::replay::SCRIPT);
    html.push_str("\n</body></html>\n");
    html.insert_str(toc_at, &toc.render());
    (html, md)
}

/// Whether a summary note explains `metric` (a note starts with the metric it explains).
fn note_is_about(note: &str, metric: &str) -> bool {
    note.starts_with(&format!("{metric} "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(config: &str, scenario: &str, value: f64) -> MetricRow {
        MetricRow {
            level: "jumps".into(),
            scenario: scenario.into(),
            backend: "sweep".into(),
            config: config.into(),
            metric: "apex_error",
            value,
            unit: "tiles",
            reference: 0.0,
            error: value,
            frame: Some(7),
            q1: None,
            q3: None,
        }
    }

    fn page(verdict: &str) -> String {
        page_with(Extras {
            verdict: verdict.into(),
            ..Extras::default()
        })
    }

    fn page_with(extras: Extras) -> String {
        let rows = [
            row("default", "a", 0.01),
            row("default", "b", -0.2),
            row("other", "a", 0.0),
            row("other", "b", 0.05),
        ];
        render_report(&crate::registry::Registry::builtin(), &rows, &[], &extras).0
    }

    #[test]
    fn the_verdict_comes_first_then_the_contents() {
        let html = page("<p>Pick the sweep.</p>");
        let after_title = &html[html.find("</h1>").unwrap() + "</h1>".len()..];
        assert!(
            after_title.starts_with("<section id=\"verdict\"><p>Pick the sweep.</p></section>"),
            "{after_title:.200}"
        );
        let (toc, which) = (
            html.find("<nav id=\"toc\">").unwrap(),
            html.find("<h2").unwrap(),
        );
        assert!(toc < which);
        // The contents link every h2 of the page.
        let nav = &html[toc..html.find("</nav>").unwrap()];
        for h2 in html.split("<h2 id=\"").skip(1) {
            let id = &h2[..h2.find('"').unwrap()];
            assert!(nav.contains(&format!("href=\"#{id}\"")), "{id}: {nav}");
        }
        assert!(nav.contains("href=\"#verdict\""), "{nav}");
        assert!(nav.contains("href=\"#behaviour-jumping\""), "{nav}");
        // The slower commands' sections are linked when present.
        let extras = page_with(Extras {
            tradeoff: Some(Vec::new()),
            stability: Some(Vec::new()),
            ..Extras::default()
        });
        let nav = &extras[extras.find("<nav id=\"toc\">").unwrap()..extras.find("</nav>").unwrap()];
        for id in ["tradeoff", "stability"] {
            assert!(extras.contains(&format!("<h2 id=\"{id}\">")), "{id}");
            assert!(nav.contains(&format!("href=\"#{id}\"")), "{id}: {nav}");
        }
        // Without a verdict, no section and no link to it.
        let none = page("");
        assert!(!none.contains("id=\"verdict\"") && !none.contains("href=\"#verdict\""));
    }

    #[test]
    fn each_worst_value_links_to_the_scenario_it_comes_from() {
        let html = page("");
        // default's worst is b (|-0.2|), other's is b too (0.05), each at its row's frame (7).
        assert!(html.contains(
            "<a href=\"#view=jumps.b&amp;frame=7&amp;show=sweep%20default\" title=\"jumps.b (-0.2000)\">-0.2000</a>"
        ));
        assert!(html.contains("title=\"jumps.b (0.0500)\">0.0500</a>"));
        assert!(html.contains("<a href=\"#metric-apex_error\" title=\""));
        // Every metric of the registry has its definition.
        for d in registry::METRICS {
            assert!(
                html.contains(&format!("<tr id=\"metric-{}\">", d.name)),
                "{}",
                d.name
            );
        }
    }
}

//! The report's sections from the slower commands' results: the speed-against-accuracy chart
//! of `platbench sweep` and the stability tables of `platbench stress`, as HTML and Markdown
//! (and the pair grids `platbench stress` prints as text). Each of their tables scrolls
//! sideways on its own ([`super::html::wide`]) so the page never does.

use std::fmt::Write as _;

use super::format_setting;
use super::html::wide;
use super::replay::escape;
use crate::stress::{Envelope, StressRow};
use crate::tradeoff::{chart_svg, TradeoffRow};

/// Setting values as a short comma-separated list ("-" when empty).
pub(crate) fn value_list(v: &[f64]) -> String {
    if v.is_empty() {
        return "-".into();
    }
    v.iter()
        .map(|&x| format_setting(x))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The speed-against-accuracy section: the chart and the settings on the Pareto front.
pub(crate) fn tradeoff_section(rows: &[TradeoffRow]) -> (String, String) {
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
    (wide(&html), md)
}

/// What broke where, for a table cell: `carry_no_drift at 0, 1000; finite at 1e7`, or `-`.
pub(crate) fn breaks_list(e: &Envelope) -> String {
    if e.breaks.is_empty() {
        return "-".into();
    }
    e.breaks
        .iter()
        .map(|(inv, vs)| format!("{inv} at {}", value_list(vs)))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The colour of a combination cell whose first broken invariant is `first` (green where every
/// invariant held).
fn invariant_colour(first: Option<&str>) -> &'static str {
    const COLOURS: [&str; 9] = [
        "#b71c1c", "#e65100", "#6a1b9a", "#f9a825", "#00838f", "#1565c0", "#d81b60", "#795548",
        "#546e7a",
    ];
    match first {
        None => "#a5d6a7",
        Some(i) => crate::stress::INVARIANTS
            .iter()
            .position(|k| *k == i)
            .map_or("#212121", |k| COLOURS[k]),
    }
}

/// The shape of one pair of dimensions' grid, as [`pair_grids`] draws it and `report
/// --stability` bounds it before drawing: a row per configuration and first value, a column per
/// second value, each value as `==` tells them apart (a NaN is always a new one).
#[derive(Default)]
pub(crate) struct GridShape {
    /// The rows, in the order first seen.
    pub(crate) rows: Vec<(String, f64)>,
    row_keys: std::collections::HashSet<(String, u64)>,
    /// The columns, in the order first seen (of 0 and -0, the one that sorts first).
    pub(crate) columns: Vec<f64>,
    column_at: std::collections::HashMap<u64, usize>,
}

impl GridShape {
    /// Adds the cell of configuration `config` at values `a` and `b`.
    pub(crate) fn add(&mut self, config: &str, a: f64, b: f64) {
        use crate::stress::value_key;
        match value_key(a) {
            Some(ka) if !self.row_keys.insert((config.to_string(), ka)) => {}
            _ => self.rows.push((config.to_string(), a)),
        }
        match value_key(b).and_then(|kb| self.column_at.get(&kb).copied().map(|i| (kb, i))) {
            Some((_, i)) => {
                if b.total_cmp(&self.columns[i]).is_lt() {
                    self.columns[i] = b;
                }
            }
            None => {
                if let Some(kb) = value_key(b) {
                    self.column_at.insert(kb, self.columns.len());
                }
                self.columns.push(b);
            }
        }
    }

    /// How many cells the grid draws, measured or not.
    pub(crate) fn cells(&self) -> u64 {
        self.rows.len() as u64 * self.columns.len() as u64
    }
}

/// Each pair of dimensions' combination cells as a grid: per pair, a row per configuration and
/// first value, a column per second value, each cell `ok` or the invariants that broke there
/// (first broken first). Each grid is `(pair, header, rows)`. Cells are found by hash (values as
/// `==` matches them: a NaN matches none), so a grid costs time in proportion to its size.
pub(crate) fn pair_grids(rows: &[StressRow]) -> Vec<(String, Vec<String>, Vec<Vec<String>>)> {
    use crate::stress::{value_key, Cell};
    use std::collections::HashMap;
    let cells = crate::stress::cells(rows);
    let mut out: Vec<(String, Vec<String>, Vec<Vec<String>>)> = Vec::new();
    let mut pairs: Vec<(&str, Vec<&Cell>)> = Vec::new();
    let mut pair_at: HashMap<&str, usize> = HashMap::new();
    for c in &cells {
        let i = *pair_at.entry(&c.pair).or_insert_with(|| {
            pairs.push((&c.pair, Vec::new()));
            pairs.len() - 1
        });
        pairs[i].1.push(c);
    }
    for (pair, of_pair) in pairs {
        let mut shape = GridShape::default();
        // The first cell of each configuration and pair of values.
        let mut cell_at: HashMap<(&str, u64, u64), &Cell> = HashMap::new();
        for c in &of_pair {
            shape.add(&c.config, c.a, c.b);
            if let (Some(a), Some(b)) = (value_key(c.a), value_key(c.b)) {
                cell_at.entry((&c.config, a, b)).or_insert(c);
            }
        }
        let mut bs = std::mem::take(&mut shape.columns);
        bs.sort_by(f64::total_cmp);
        let (da, db) = pair.split_once(" x ").unwrap_or((pair, ""));
        let mut header = vec!["configuration".to_string(), format!("{da} \\ {db}")];
        header.extend(bs.iter().map(|&b| format_setting(b)));
        let mut grid = Vec::new();
        for (config, a) in &shape.rows {
            let (config, a) = (config.as_str(), *a);
            let mut row = vec![config.to_string(), format_setting(a)];
            for &b in &bs {
                let cell = value_key(a)
                    .zip(value_key(b))
                    .and_then(|(a, b)| cell_at.get(&(config, a, b)));
                row.push(match cell {
                    None => "-".into(),
                    Some(c) if c.broken.is_empty() => "ok".into(),
                    Some(c) => c.broken.join(", "),
                });
            }
            grid.push(row);
        }
        out.push((pair.to_string(), header, grid));
    }
    out
}

/// [`pair_grids`] as plain-text tables, for `platbench stress`.
pub(crate) fn pair_tables(rows: &[StressRow]) -> Vec<String> {
    pair_grids(rows)
        .into_iter()
        .map(|(_, header, grid)| {
            let mut t = comfy_table::Table::new();
            t.load_style(comfy_table::presets::ASCII_MARKDOWN);
            t.set_header(header);
            for r in grid {
                t.add_row(r);
            }
            t.to_string()
        })
        .collect()
}

/// The stability section: per configuration and dimension, the verdict (the last value where
/// every invariant held and the first where one broke, each side of the base case) and every
/// invariant that broke and where; then each pair's combination cells as a heat map coloured
/// by the first invariant that broke.
pub(crate) fn stability_section(rows: &[StressRow]) -> (String, String) {
    let mut html = String::from("<h2 id=\"stability\">Stability at the extremes</h2><p>From <code>platbench stress</code>: each dimension is pushed away from the base case alone; the verdict gives, each side of the base value, the last value where every invariant (finite, penetration, no tunneling, stable rest, no flicker, carry without drift, progress, no stuck step, jump height) held and the first where one broke, naming it; the last column names each invariant that broke and where.</p><table><thead><tr><th>configuration</th><th>dimension</th><th>verdict</th><th>each invariant that broke, where</th></tr></thead><tbody>");
    let mut md = String::from("\n## Stability at the extremes\n\n| configuration | dimension | verdict | each invariant that broke, where |\n|---|---|---|---|\n");
    let envelopes = crate::stress::envelopes_by_key(rows);
    for v in crate::stress::verdicts(rows) {
        let (config, dim) = (&v.config, &v.dimension);
        let ok = v.text();
        let bad = envelopes
            .get(&(v.config.clone(), v.dimension.clone()))
            .map_or("-".into(), breaks_list);
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(config),
            escape(dim),
            escape(&ok),
            escape(&bad)
        );
        let _ = writeln!(md, "| {config} | {dim} | {ok} | {bad} |");
    }
    html.push_str("</tbody></table>");
    html.push_str("<h3>How far from the origin each configuration holds</h3><p>The offset rows walked out from 0, with the invariants that already broke at 0 set aside (they break for another reason than the distance), so that f32 and f64 builds of one set-up compare on what the distance breaks:</p><table><thead><tr><th>configuration</th><th>offset (tiles)</th></tr></thead><tbody>");
    md.push_str("\n### How far from the origin each configuration holds\n\nThe offset rows walked out from 0, with the invariants that already broke at 0 set aside:\n\n| configuration | offset (tiles) |\n|---|---|\n");
    for r in crate::stress::reach(rows) {
        let text = r.text();
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td></tr>",
            escape(&r.config),
            escape(&text)
        );
        let _ = writeln!(md, "| {} | {text} |", r.config);
    }
    html.push_str("</tbody></table>");
    let grids = pair_grids(rows);
    if !grids.is_empty() {
        html.push_str("<h3>Combinations</h3><p>Pairs of dimensions whose failures interact, each on a small grid (the base case elsewhere). One cell per pair of values, coloured by the first invariant that broke there (green: every invariant held):</p><p class=\"legend\">");
        md.push_str("\n### Combinations\n\nPairs of dimensions whose failures interact, each on a small grid (the base case elsewhere); each cell names the invariants that broke there, first broken first (the HTML report colours it by the first):\n");
        for (i, c) in std::iter::once(None)
            .chain(crate::stress::INVARIANTS.iter().map(|i| Some(*i)))
            .map(|i| (i, invariant_colour(i)))
        {
            let _ = write!(
                html,
                "<span><i style=\"background:{c};height:1em\"></i>{}</span>",
                i.unwrap_or("every invariant holds")
            );
        }
        html.push_str("</p>");
        for (pair, header, grid) in grids {
            let _ = write!(html, "<h4>{}</h4><table><thead><tr>", escape(&pair));
            for h in &header {
                let _ = write!(html, "<th>{}</th>", escape(h));
            }
            html.push_str("</tr></thead><tbody>");
            let _ = write!(
                md,
                "\n#### {pair}\n\n| {} |\n|{}\n",
                header.join(" | "),
                "---|".repeat(header.len())
            );
            for row in grid {
                html.push_str("<tr>");
                for (k, cell) in row.iter().enumerate() {
                    if k < 2 {
                        let _ = write!(html, "<td>{}</td>", escape(cell));
                        continue;
                    }
                    let first = match cell.as_str() {
                        "ok" | "-" => None,
                        c => c.split(", ").next(),
                    };
                    let colour = if cell == "-" {
                        "#eeeeee"
                    } else {
                        invariant_colour(first)
                    };
                    let _ = write!(
                        html,
                        "<td style=\"background:{colour}\" title=\"{}\">{}</td>",
                        escape(cell),
                        escape(first.unwrap_or(cell))
                    );
                }
                html.push_str("</tr>");
                let _ = writeln!(md, "| {} |", row.join(" | "));
            }
            html.push_str("</tbody></table>");
        }
    }
    (wide(&html), md)
}

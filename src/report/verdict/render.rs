//! The verdict, the scorecard and the capability table as terminal text: every line at most
//! [`WIDTH`] columns, so they read the same in a 120-column terminal and a CI log.

use std::fmt::Write as _;

use unicode_width::{UnicodeWidthChar as _, UnicodeWidthStr as _};

use super::{Column, Grade, ProfileVerdict, Reason, Scorecard};
use crate::metrics::registry::Behaviour;

/// The widest line printed.
pub const WIDTH: usize = 120;

/// The columns `s` takes in a terminal (a wide character takes two).
pub(crate) fn columns(s: &str) -> usize {
    s.width()
}

/// The longest start of `s` that fits `width` columns, and the rest.
fn split_at_columns(s: &str, width: usize) -> (&str, &str) {
    let mut used = 0;
    for (i, c) in s.char_indices() {
        let w = c.width().unwrap_or(0);
        if used + w > width {
            return (&s[..i], &s[i..]);
        }
        used += w;
    }
    (s, "")
}

/// `text` wrapped at word boundaries to [`WIDTH`] columns, the first line after `first`, the
/// others after `indent`.
fn wrap(first: &str, indent: &str, text: &str) -> String {
    let mut out = String::new();
    let mut line = first.to_string();
    let mut empty = true;
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        if !empty && columns(&line) + 1 + columns(word) > WIDTH {
            out.push_str(line.trim_end());
            out.push('\n');
            line = indent.to_string();
            empty = true;
        }
        if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
        // A single word longer than the line is cut, never left to overflow.
        while columns(&line) > WIDTH {
            let (head, rest) = split_at_columns(&line, WIDTH);
            out.push_str(head);
            out.push('\n');
            line = format!("{indent}{rest}");
        }
    }
    out.push_str(line.trim_end());
    out.push('\n');
    out
}

fn grade_word(g: Option<Grade>) -> &'static str {
    g.map_or("not run", Grade::word)
}

/// A decider: `seams ok vs FAIL (flat_seams.walk ... stuck_frames 9 (ideal 0))`.
fn decider(r: &Reason) -> String {
    let mut s = format!(
        "{} {} vs {}",
        r.behaviour.key(),
        grade_word(r.pick),
        grade_word(r.other)
    );
    if r.pick == r.other {
        s.push_str(" but closer");
    }
    if let Some(w) = &r.worst {
        let _ = write!(s, " ({})", w.describe());
    }
    s
}

/// A weighted error as printed: `0`, three decimals, or two significant digits below 0.001 (so
/// that two errors that differ never print alike as `0.000`).
pub(crate) fn error_text(e: f64) -> String {
    if e == 0.0 {
        "0".into()
    } else if e < 1e-3 {
        format!("{e:.1e}")
    } else {
        format!("{e:.3}")
    }
}

/// Two weighted errors as printed, with as many digits as it takes to tell them apart.
fn error_pair(a: f64, b: f64) -> (String, String) {
    let (x, y) = (error_text(a), error_text(b));
    if x != y || a == b {
        return (x, y);
    }
    for digits in 4..=9 {
        let (x, y) = (format!("{a:.digits$}"), format!("{b:.digits$}"));
        if x != y {
            return (x, y);
        }
    }
    (format!("{a:e}"), format!("{b:e}"))
}

/// The behaviours of `profile` that configuration `c` fails, as ` FAIL on landing, seams`.
fn fails_text(card: &Scorecard, v: &ProfileVerdict, c: usize) -> String {
    let failed: Vec<&str> = v
        .profile
        .weights
        .iter()
        .filter(|(b, _)| *b != Behaviour::Cost && card.scenarios.get(b).is_some_and(|n| *n > 0))
        .filter(|(b, _)| {
            card.cards[c]
                .cells
                .get(b)
                .and_then(|x| x.grade())
                .is_none_or(|g| g == Grade::Fails)
        })
        .map(|(b, _)| b.key())
        .collect();
    if failed.is_empty() {
        String::new()
    } else {
        format!("; FAIL on {}", failed.join(", "))
    }
}

/// The pick's and the runner-up's lines: `sweep (error 0.001)`, `rapier ... (error 0.007;
/// FAIL on landing)`, or a tie `tie: a, b (error 0): ...` and no runner-up.
pub(crate) fn pick_texts(card: &Scorecard, v: &ProfileVerdict) -> (String, Option<String>) {
    let label = |c: usize| card.cards[c].facts.label.as_str();
    let Some((c, e)) = v.pick else {
        return (
            format!("none: {}", v.no_pick.as_deref().unwrap_or("")),
            None,
        );
    };
    let runner = v.runner_up.filter(|(r, _)| !v.tied.contains(r));
    if !v.tied.is_empty() {
        let mut names = vec![label(c)];
        names.extend(v.tied.iter().map(|t| label(*t)));
        return (
            format!(
                "tie: {} (error {}{}): nothing this run measures tells them apart; the order is the run's",
                names.join(", "),
                error_text(e),
                fails_text(card, v, c)
            ),
            runner.map(|(r, x)| {
                let (_, re) = error_pair(e, x);
                format!("{} (error {re}{})", label(r), fails_text(card, v, r))
            }),
        );
    }
    let re = v.runner_up.map_or(e, |(_, x)| x);
    let (pe, re) = error_pair(e, re);
    (
        format!("{} (error {pe}{})", label(c), fails_text(card, v, c)),
        v.runner_up
            .map(|(r, _)| format!("{} (error {re}{})", label(r), fails_text(card, v, r))),
    )
}

/// The verdict of every profile: pick, runner-up, why, and what the pick still gets wrong.
/// `source` says where the profiles come from.
pub fn render_verdict(card: &Scorecard, verdicts: &[ProfileVerdict], source: &str) -> String {
    let mut out = String::new();
    out.push_str(&wrap(
        "",
        "",
        &format!(
            "Which controller for which game: {} scenarios, {} configurations. Each profile picks the configuration that fails the least of what it weighs, then has the lowest weighted error (the mean over scored metrics of min(1, error beyond one pixel / the clearly-wrong size): 0 all within a pixel, 1 all clearly off).",
            card.total_scenarios,
            card.cards.len()
        ),
    ));
    out.push_str(&wrap("", "", source));
    for v in verdicts {
        let p = &v.profile;
        out.push('\n');
        out.push_str(&wrap(&format!("{}: ", p.name), "    ", &p.title));
        let mut weighs = format!("weighs {}", p.describe_weights());
        if !p.needs.is_empty() {
            let needs: Vec<&str> = p.needs.iter().map(|n| n.name()).collect();
            let _ = write!(weighs, "; needs {}", needs.join(", "));
        }
        out.push_str(&wrap("  ", "    ", &weighs));
        let label = |c: usize| card.cards[c].facts.label.as_str();
        match v.pick {
            None => {
                out.push_str(&wrap(
                    "  pick       ",
                    "             ",
                    &format!("none: {}", v.no_pick.as_deref().unwrap_or("")),
                ));
            }
            Some((c, _)) => {
                let (pick, runner) = pick_texts(card, v);
                out.push_str(&wrap("  pick       ", "             ", &pick));
                if let Some(runner) = runner {
                    out.push_str(&wrap("  runner-up  ", "             ", &runner));
                }
                if !v.why.is_empty() {
                    let ratio = |c: usize| {
                        let cheapest = card
                            .cards
                            .iter()
                            .filter_map(|x| x.median_cost())
                            .filter(|x| *x > 0.0)
                            .min_by(f64::total_cmp);
                        match (card.cards[c].median_cost(), cheapest) {
                            (Some(m), Some(lo)) => format!("{:.2}x", m / lo),
                            _ => "-".into(),
                        }
                    };
                    let why: Vec<String> = v
                        .why
                        .iter()
                        .map(|r| match (r.behaviour, v.runner_up) {
                            (Behaviour::Cost, Some((o, _))) => format!(
                                "cost {} vs {} the cheapest configuration's time per step",
                                ratio(c),
                                ratio(o)
                            ),
                            _ => decider(r),
                        })
                        .collect();
                    out.push_str(&wrap("  why        ", "             ", &why.join("; ")));
                }
                let wrong = if v.still_wrong.is_empty() {
                    "nothing this profile weighs".to_string()
                } else {
                    v.still_wrong
                        .iter()
                        .map(|r| {
                            let mut s = format!("{} {}", r.behaviour.key(), grade_word(r.pick));
                            if let Some(w) = &r.worst {
                                let _ = write!(s, " ({})", w.describe());
                            }
                            s
                        })
                        .collect::<Vec<_>>()
                        .join("; ")
                };
                out.push_str(&wrap("  still off  ", "             ", &wrong));
            }
        }
        // Left out, grouped by why: "does not declare f64_positions: every configuration".
        let mut reasons: Vec<(&str, Vec<&str>)> = Vec::new();
        for (c, why) in &v.left_out {
            match reasons.iter_mut().find(|(w, _)| w == why) {
                Some((_, list)) => list.push(label(*c)),
                None => reasons.push((why, vec![label(*c)])),
            }
        }
        for (why, list) in reasons {
            let who = if list.len() == card.cards.len() {
                "every configuration of this run".to_string()
            } else {
                list.join(", ")
            };
            out.push_str(&wrap(
                "  left out   ",
                "             ",
                &format!("{who} ({why})"),
            ));
        }
        if !v.unmeasured.is_empty() {
            let list: Vec<&str> = v.unmeasured.iter().map(|b| b.key()).collect();
            out.push_str(&wrap(
                "  unmeasured ",
                "             ",
                &format!(
                    "{} (no scenario of this run measures them)",
                    list.join(", ")
                ),
            ));
        }
    }
    out
}

/// The scorecard: one row per configuration, one grade per column, the cost when timed; under a
/// row that is not all `ok`, the scenario and metric behind each other grade.
pub fn render_scorecard(card: &Scorecard) -> String {
    let mut out = String::new();
    out.push_str(&wrap(
        "",
        "",
        "Scorecard: how each configuration does on each behaviour's scenarios, against each metric's reference (rest and penetration against the contact the configuration declares). ok: every scored metric within the clearly-wrong size beyond the one-pixel allowance (0.01 tiles past 1/16 tile at 16 pixels a tile, 0.01 ratio, exact frames and counts); minor: within ten times it (0.1 tiles past the pixel), 3 frames or 2 counts; FAIL: beyond, or a wrong result; -: not run. A row of a level with moving platforms, ladders, one-way platforms or slopes counts toward that feature. Under a row, its documented design and the scenario and metric behind each grade that is not ok. cost: median time per character step over the cheapest configuration's (run --timing).",
    ));
    let widths: Vec<usize> = Column::ALL
        .iter()
        .map(|c| c.header().len().max(5))
        .collect();
    // The grades take the right of the line (1 space between columns, 7 for the cost); a label
    // longer than what is left is printed on a line of its own above its grades.
    let cells: usize = widths.iter().map(|w| w + 1).sum::<usize>() + 7;
    let label_width = WIDTH - cells;
    let pad = |s: &str| -> String {
        let w = columns(s);
        if w <= label_width {
            format!("{s}{}", " ".repeat(label_width - w))
        } else {
            " ".repeat(label_width)
        }
    };
    let mut header = pad("configuration");
    for (c, w) in Column::ALL.iter().zip(&widths) {
        let _ = write!(header, " {:>w$}", c.header());
    }
    let _ = write!(header, " {:>6}", "cost");
    out.push_str(header.trim_end());
    out.push('\n');
    let cheapest = card
        .cards
        .iter()
        .filter_map(|c| c.median_cost())
        .filter(|x| *x > 0.0)
        .min_by(f64::total_cmp);
    for (i, c) in card.cards.iter().enumerate() {
        if columns(&c.facts.label) > label_width {
            out.push_str(&wrap("", "  ", &c.facts.label));
        }
        let mut line = pad(&c.facts.label);
        let mut notes = Vec::new();
        for (col, w) in Column::ALL.iter().zip(&widths) {
            let g = card.column_grade(i, *col);
            let word = g.map_or("-", |(g, _)| g.word());
            let _ = write!(line, " {word:>w$}");
            if let Some((g, Some(worst))) = g {
                if g != Grade::Keeps {
                    notes.push(format!("{}: {}", col.header(), worst.describe()));
                }
            }
        }
        let cost = match (c.median_cost(), cheapest) {
            (Some(m), Some(lo)) => format!("{:.1}x", m / lo),
            _ => "-".into(),
        };
        let _ = write!(line, " {cost:>6}");
        out.push_str(line.trim_end());
        out.push('\n');
        if !c.facts.why.is_empty() {
            out.push_str(&wrap("    design: ", "      ", &c.facts.why));
        }
        if !notes.is_empty() {
            out.push_str(&wrap("    ", "      ", &notes.join("; ")));
        }
    }
    out
}

/// The capability table: what each configuration declares, beside what the run measured. Rows
/// group the configurations of one backend that declare the same.
pub fn render_capabilities(card: &Scorecard) -> String {
    // The declarations the table shows (what `hunt` alone reads, such as carrying no rider,
    // does not split a group).
    let shown = |c: crate::backend::Capabilities| {
        (
            c.pushes_bodies,
            c.integer_positions,
            c.cross_platform_determinism,
        )
    };
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, c) in card.cards.iter().enumerate() {
        let f = &c.facts;
        let key = (
            f.backend.clone(),
            f.features,
            f.precision,
            shown(f.capabilities),
        );
        match groups.iter_mut().find(|(_, v)| {
            let g = &card.cards[v[0]].facts;
            (
                g.backend.clone(),
                g.features,
                g.precision,
                shown(g.capabilities),
            ) == key
        }) {
            Some((_, v)) => v.push(i),
            None => groups.push((f.backend.clone(), vec![i])),
        }
    }
    let mut out = String::new();
    out.push_str(&wrap(
        "",
        "",
        "Declared by each configuration: slopes to platforms are the level features it runs (measured above); pushes = pushes dynamic bodies, grid = positions on a fixed grid, f64 = f64 world positions, x-platform = bit-identical results across machines as built here (not measured).",
    ));
    let heads = [
        "slopes",
        "oneway",
        "ladders",
        "platforms",
        "pushes",
        "grid",
        "f64",
        "x-platform",
    ];
    let mut rows: Vec<(String, Vec<bool>)> = Vec::new();
    for (backend, members) in &groups {
        let all_of_backend = card
            .cards
            .iter()
            .filter(|c| c.facts.backend == *backend)
            .count()
            == members.len();
        let first = &card.cards[members[0]].facts;
        let label = if all_of_backend {
            backend.clone()
        } else if members.len() == 1 {
            first.label.clone()
        } else {
            format!("{} (+{} alike)", first.label, members.len() - 1)
        };
        let f = first;
        rows.push((
            label,
            vec![
                f.features.slopes,
                f.features.one_way,
                f.features.ladders,
                f.features.moving_platforms,
                f.capabilities.pushes_bodies,
                f.capabilities.integer_positions,
                f.precision == crate::backend::Precision::F64,
                f.capabilities.cross_platform_determinism,
            ],
        ));
    }
    let label_width = rows
        .iter()
        .map(|(l, _)| l.chars().count())
        .chain(["configuration".len()])
        .max()
        .unwrap_or(13)
        .min(40);
    let mut header = format!("{:<label_width$}", "configuration");
    for h in heads {
        let _ = write!(header, " | {h}");
    }
    out.push_str(&header);
    out.push('\n');
    for (label, v) in rows {
        let label: String = label.chars().take(label_width).collect();
        let mut line = format!("{label:<label_width$}");
        for (h, yes) in heads.iter().zip(v) {
            let _ = write!(
                line,
                " | {:<w$}",
                if yes { "yes" } else { "-" },
                w = h.len()
            );
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

//! "Which backend for which game" as data: each statement is a [`Rule`] over one metric
//! (metric, comparison, threshold, wording), evaluated for every configuration, the sweep
//! included, on its extreme value in the rule's direction over the scenarios it ran. No rule
//! names a backend or a scenario, or explains one controller's behaviour as design (each
//! configuration's own design is its [`crate::config::RunConfig::why`], printed beside its row);
//! a signed metric has a statement for each direction of fault; a statement that credits a
//! configuration says so only over the scenarios it ran. Adding a statement is adding one entry
//! to [`RULES`].

use std::collections::BTreeSet;

use super::{column, format_value, worst_matrix};
use crate::metrics::MetricRow;

/// How a configuration's value is compared with a rule's threshold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// The value is greater than the threshold (read on the configuration's largest value).
    Above,
    /// The value is less than the threshold (read on its smallest value).
    Below,
    /// The value's magnitude is greater than the threshold (read on its value farthest from
    /// ideal).
    MagnitudeAbove,
    /// The value's magnitude is at most the threshold (read on its value farthest from ideal): a
    /// statement that credits the configuration, made only over every scenario the metric was
    /// measured in (see [`Rule::partial`]).
    MagnitudeAtMost,
}

impl Comparison {
    fn holds(self, value: f64, threshold: f64) -> bool {
        match self {
            Comparison::Above => value > threshold,
            Comparison::Below => value < threshold,
            Comparison::MagnitudeAbove => value.abs() > threshold,
            Comparison::MagnitudeAtMost => value.abs() <= threshold,
        }
    }

    /// Whether a statement of this comparison credits a configuration (all its values within a
    /// bound) rather than states a fault it showed on some scenario.
    pub fn credits(self) -> bool {
        self == Comparison::MagnitudeAtMost
    }

    /// The value of `rows` this comparison reads: the largest for [`Comparison::Above`], the
    /// smallest for [`Comparison::Below`], the one farthest from ideal (a NaN first) otherwise.
    fn extreme(self, rows: &[&MetricRow]) -> Option<f64> {
        let finite = || rows.iter().map(|r| r.value).filter(|v| !v.is_nan());
        match self {
            Comparison::Above => finite().reduce(f64::max),
            Comparison::Below => finite().reduce(f64::min),
            _ => rows
                .iter()
                .max_by(|a, b| badness(a).total_cmp(&badness(b)))
                .map(|r| r.value),
        }
    }
}

/// How far a row is from ideal, a NaN farthest.
fn badness(r: &MetricRow) -> f64 {
    if r.error.is_nan() {
        f64::INFINITY
    } else {
        r.error.abs()
    }
}

/// One statement of the report: made when `metric`'s value (over the scenarios a configuration
/// ran, the extreme [`Comparison`] reads) compares to `threshold` as `comparison` says, for
/// every configuration it holds for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rule {
    /// The metric (a registry name).
    pub metric: &'static str,
    /// How its value is compared.
    pub comparison: Comparison,
    /// The threshold, in the metric's unit.
    pub threshold: f64,
    /// The statement; the configurations it holds for and their values follow it.
    pub wording: &'static str,
    /// For a statement that credits ([`Comparison::credits`]): its wording for a configuration
    /// that did not run every scenario the metric was measured in, followed by "on the levels it
    /// ran (skipped: ...)" (so it claims nothing of the levels it skipped). `None` for a fault,
    /// which is stated wherever it was seen.
    pub partial: Option<&'static str>,
}

/// A statement of a fault.
const fn fault(
    metric: &'static str,
    comparison: Comparison,
    threshold: f64,
    wording: &'static str,
) -> Rule {
    Rule {
        metric,
        comparison,
        threshold,
        wording,
        partial: None,
    }
}

/// A statement that credits a configuration whose every value is within `threshold` of 0.
const fn credit(
    metric: &'static str,
    threshold: f64,
    wording: &'static str,
    partial: &'static str,
) -> Rule {
    Rule {
        metric,
        comparison: Comparison::MagnitudeAtMost,
        threshold,
        wording,
        partial: Some(partial),
    }
}

use Comparison::{Above, Below};

/// Every statement the report can make, in print order. Thresholds: 0.01 is the error score's
/// clearly-wrong size for a length, a ratio or a speed ([`crate::metrics::MetricDef::scale`]),
/// 0 for a count of faults (any is one), 1e-4 tiles contact "exact" (a pixel-exact sprite).
pub const RULES: &[Rule] = &[
    credit(
        "rest_gap_declared",
        1e-4,
        "Rests exactly where it promises everywhere it rests (within 1e-4 tiles of its declared contact: flush, or its declared gap)",
        "Rests exactly where it promises (within 1e-4 tiles of its declared contact: flush, or its declared gap)",
    ),
    fault(
        "rest_gap_declared",
        Above,
        0.01,
        "Rests above the contact it declares (hovers higher than it promises), by up to (tiles)",
    ),
    fault(
        "rest_gap_declared",
        Below,
        -0.01,
        "Rests below the contact it declares (sinks lower than it promises), by (tiles)",
    ),
    credit(
        "rest_gap",
        1e-4,
        "Pixel-exact contact everywhere it rests, slopes included (sprites that must touch the ground)",
        "Pixel-exact contact where it rests (sprites that must touch the ground)",
    ),
    fault(
        "slope_overlap",
        Above,
        // A tenth of a tile: 1.6 pixels of a 16-pixel tile, visible.
        0.1,
        "Overhangs slopes visibly: a box-shaped sprite sinks a corner into ramps, by up to (tiles)",
    ),
    fault(
        "penetration_beyond_declared",
        Above,
        0.01,
        "Ends up inside the level beyond what it declares (sinks into floors or slopes, or stands part-way inside a slope too steep to climb), by up to",
    ),
    fault(
        "slope_gap_declared",
        Above,
        0.01,
        "Floats above walkable slopes beyond its declared contact while it reports grounded, on some frame, by up to (tiles)",
    ),
    fault(
        "slope_gap_declared",
        Below,
        -0.01,
        "Sinks into walkable slopes beyond its declared contact while it reports grounded, on some frame, by (tiles)",
    ),
    fault(
        "rest_jitter",
        Above,
        0.01,
        "Does not rest still: the feet move over the settled rest by up to (tiles)",
    ),
    fault(
        "bounce_frames",
        Above,
        0.0,
        "Bounces or lifts off after landing: frames airborne after first touching ground, up to",
    ),
    fault(
        "grounded_flicker",
        Above,
        0.0,
        "Flickers between grounded and airborne with ground under its feet: switches, up to",
    ),
    fault(
        "apex_error",
        Above,
        0.01,
        "Jumps higher than requested: apex minus the requested height, up to (tiles)",
    ),
    fault(
        "apex_error",
        Below,
        -0.01,
        "Jumps short of the requested height: apex minus the requested height, down to (tiles)",
    ),
    fault(
        "land_frame_error",
        Below,
        0.0,
        "Lands early: reports grounded before the integrator's landing frame, by (frames)",
    ),
    fault(
        "land_frame_error",
        Above,
        0.0,
        "Lands late: reports grounded after the integrator's landing frame, by (frames)",
    ),
    fault(
        "ladder_speed_error",
        Above,
        // A tenth of a tile a second: 2.5% of the default ladder speed (4 tiles/s).
        0.1,
        "Climbs ladders faster than the configured speed (quantized steps, or a push), by up to (tiles/s)",
    ),
    fault(
        "ladder_speed_error",
        Below,
        // As above, slower.
        -0.1,
        "Climbs ladders slower than the configured speed (quantized steps, or catching), by (tiles/s)",
    ),
    fault(
        "progress_ratio",
        Below,
        // Half the commanded walk lost.
        0.5,
        "Sticks on some flat floors: covers as little of the commanded walk as",
    ),
    fault(
        "progress_ratio",
        Above,
        // A tenth beyond the commanded walk, as the slope speed's bound.
        1.1,
        "Overshoots the commanded walk on flat floors: covers of it up to",
    ),
    fault(
        "stuck_frames",
        Above,
        // A sixth of a second at 60 Hz: a catch a player sees, not one step's rounding.
        10.0,
        "Catches on tile seams: stuck frames on open ground, up to",
    ),
    fault(
        "slope_airborne_frames",
        Above,
        0.0,
        "Leaves walkable slopes airborne while walking them (launches off crests or down ramps): frames, up to",
    ),
    fault(
        "slope_speed_ratio",
        Below,
        // A tenth below the run speed: a slow-down a player feels.
        0.9,
        "Slows horizontally on slopes (constant speed along the surface, a move projected onto the ramp, or catching on it): horizontal speed over the run speed down to",
    ),
    fault(
        "slope_speed_ratio",
        Above,
        // A tenth above the run speed.
        1.1,
        "Speeds up horizontally on slopes: horizontal speed over the run speed up to",
    ),
    fault(
        "slope_surface_speed_ratio",
        Above,
        // A tenth above the run speed.
        1.1,
        "Moves faster along slopes than it runs on flat ground (constant horizontal speed: 1.41 times the run speed along a 45-degree ramp): speed along the surface over the run speed up to",
    ),
    fault(
        "slope_surface_speed_ratio",
        Below,
        // A tenth below the run speed.
        0.9,
        "Moves slower along slopes than it runs on flat ground (a move projected onto the ramp, or catching on it): speed along the surface over the run speed down to",
    ),
    fault(
        "steep_blocked",
        Below,
        1.0,
        "Climbs a slope steeper than its climb limit",
    ),
    fault(
        "oneway_result",
        Below,
        1.0,
        "Ends a one-way platform scenario elsewhere than the one-way rule puts it (a top blocks only feet that start above it)",
    ),
    fault(
        "ladder_result",
        Below,
        1.0,
        "Ends a ladder scenario elsewhere than expected (top, bottom, floor)",
    ),
    fault(
        "carry_drift",
        Above,
        // A tenth of a tile: 1.6 pixels of a 16-pixel tile, visible.
        0.1,
        "Loses its grip on moving platforms: the rider drifts relative to its platform by up to (tiles)",
    ),
    fault(
        "carry_airborne_frames",
        Above,
        0.0,
        "Airborne while riding a moving platform (a platform dropping faster than gravity leaves any rider; beyond that the grip is lost): frames, up to",
    ),
    fault(
        "push_penetration",
        Above,
        // A tenth of a tile: visible.
        0.1,
        "Lets moving platforms into the character (pushed or squeezed), by up to (tiles)",
    ),
    fault(
        "crush_count",
        Above,
        0.0,
        "Ends up inside a moving platform that had room to push it (run through; a squeeze against the level is the crush the scenario designs): times, up to",
    ),
    fault(
        "idle_drift",
        Above,
        0.01,
        "Moves a character that stands still with no input, by up to (tiles)",
    ),
    fault(
        "false_grounded",
        Above,
        0.0,
        "Reports grounded with no ground under it (can jump from there): frames, up to",
    ),
    fault(
        "tunneled",
        Above,
        0.0,
        "Tunnels through a wall at speed",
    ),
    fault(
        "left_level",
        Above,
        0.0,
        "Leaves the level: falls below everything that could catch it, or walks off the side of the map",
    ),
    fault(
        "expect_reach",
        Above,
        0.0,
        "Misses a region a level says the character reaches by a time (expect.reach)",
    ),
    fault(
        "expect_grounded_at_end",
        Above,
        0.0,
        "Ends grounded or airborne other than a level says (expect.grounded_at_end)",
    ),
    fault(
        "expect_min_y",
        Above,
        0.0,
        "Goes lower than a level allows (expect.min_y)",
    ),
    fault(
        "expect_stay_in_map",
        Above,
        0.0,
        "Leaves the map of a level that says it stays in (expect.stay_in_map)",
    ),
    fault(
        "expect_land_on",
        Above,
        0.0,
        "Never stands on the moving platform a level says it lands on (expect.land_on)",
    ),
];

/// The statements `rules` make on `rows`: for each rule that holds for some configuration, its
/// wording followed by each such configuration and its value. A statement that credits is made
/// for a configuration that ran every scenario any configuration measured its metric in; one
/// that skipped some gets the rule's partial wording with the levels it skipped, one statement
/// per set of skipped levels.
pub fn evaluate(rules: &[Rule], rows: &[MetricRow]) -> Vec<String> {
    // Configurations in first-run order, labelled with their coverage ("over N of M").
    let m = worst_matrix(rows, |_| false);
    let columns: Vec<String> = rows.iter().map(column).collect();
    let ran: Vec<BTreeSet<(&str, &str)>> = m
        .configs
        .iter()
        .map(|c| {
            rows.iter()
                .zip(&columns)
                .filter(|(_, col)| *col == c)
                .map(|(r, _)| (r.level.as_str(), r.scenario.as_str()))
                .collect()
        })
        .collect();
    let mut out = Vec::new();
    for rule in rules {
        let of_metric: Vec<(&MetricRow, &String)> = rows
            .iter()
            .zip(&columns)
            .filter(|(r, _)| r.metric == rule.metric)
            .collect();
        let measured: BTreeSet<(&str, &str)> = of_metric
            .iter()
            .map(|(r, _)| (r.level.as_str(), r.scenario.as_str()))
            .collect();
        let mut holds: Vec<String> = Vec::new();
        // Credited over part of the scenarios: (skipped levels, configurations).
        let mut partial: Vec<(Vec<&str>, Vec<String>)> = Vec::new();
        for (ci, c) in m.configs.iter().enumerate() {
            let mine: Vec<&MetricRow> = of_metric
                .iter()
                .filter(|(_, col)| *col == c)
                .map(|(r, _)| *r)
                .collect();
            let Some(v) = rule.comparison.extreme(&mine) else {
                continue;
            };
            if !rule.comparison.holds(v, rule.threshold) {
                continue;
            }
            let said = format!("{} ({})", m.label(ci), format_value(v));
            let mut skipped: Vec<&str> = measured
                .difference(&ran[ci])
                .map(|(level, _)| *level)
                .collect();
            skipped.dedup();
            match (rule.partial, skipped.is_empty()) {
                (Some(_), false) => match partial.iter_mut().find(|(s, _)| *s == skipped) {
                    Some((_, cs)) => cs.push(said),
                    None => partial.push((skipped, vec![said])),
                },
                _ => holds.push(said),
            }
        }
        if !holds.is_empty() {
            out.push(format!(
                "{} [{}]: {}.",
                rule.wording,
                rule.metric,
                holds.join(", ")
            ));
        }
        for (skipped, cs) in partial {
            out.push(format!(
                "{} on the levels it ran (skipped: {}) [{}]: {}.",
                rule.partial.unwrap_or(rule.wording),
                skipped.join(", "),
                rule.metric,
                cs.join(", ")
            ));
        }
    }
    out
}

/// What one setting changes, with the numbers: for every configuration whose label is another
/// configuration's label plus one setting (`rapier per-tile capsule` and `rapier per-tile
/// capsule grounded=none-but-platforms`), the metrics whose worst value that setting moves
/// closer to ideal (what it fixes) and further from it (what it costs). It reads only the
/// labels, so it names no backend or setting itself: this is how the report says which remedy
/// fixes which failure, and at what price.
pub(crate) fn setting_effects(rows: &[MetricRow]) -> Vec<String> {
    let keep = |name: &str| name != "ns_per_character_step";
    let labels = worst_matrix(rows, keep).configs;
    let ran = |c: &str| -> std::collections::BTreeSet<(&str, &str)> {
        rows.iter()
            .filter(|r| column(r) == c)
            .map(|r| (r.level.as_str(), r.scenario.as_str()))
            .collect()
    };
    let mut out = Vec::new();
    for b in &labels {
        for a in &labels {
            let Some(setting) = b.strip_prefix(a.as_str()).and_then(|r| r.strip_prefix(' ')) else {
                continue;
            };
            if setting.contains(' ') {
                continue;
            }
            // Both configurations' worst values over the scenarios both ran, and only those.
            let (ra, rb) = (ran(a), ran(b));
            let both: std::collections::BTreeSet<_> = ra.intersection(&rb).copied().collect();
            let pair: Vec<MetricRow> = rows
                .iter()
                .filter(|r| {
                    let c = column(r);
                    (c == *a || c == *b) && both.contains(&(r.level.as_str(), r.scenario.as_str()))
                })
                .cloned()
                .collect();
            let m = worst_matrix(&pair, keep);
            let (Some(ai), Some(bi)) = (
                m.configs.iter().position(|c| c == a),
                m.configs.iter().position(|c| c == b),
            ) else {
                continue;
            };
            let (mut fixes, mut costs) = (Vec::new(), Vec::new());
            for (mi, (name, _, ideal)) in m.metrics.iter().enumerate() {
                let (Some((va, _)), Some((vb, _))) = (m.cells[ai][mi], m.cells[bi][mi]) else {
                    continue;
                };
                let (da, db) = ((va - ideal).abs(), (vb - ideal).abs());
                // Ties: f32 rounding, or 1% of the smaller distance from ideal.
                let tie = super::TIE_TOLERANCE + 0.01 * da.min(db);
                let change = format!("{name} {} -> {}", format_value(va), format_value(vb));
                if db + tie < da {
                    fixes.push(change);
                } else if da + tie < db {
                    costs.push(change);
                }
            }
            if fixes.is_empty() && costs.is_empty() {
                continue;
            }
            let list = |v: &[String]| {
                if v.is_empty() {
                    "nothing".to_string()
                } else {
                    v.join(", ")
                }
            };
            out.push(format!(
                "`{setting}` on {a}: better {}; worse {} (worst values over the {} scenarios both ran).",
                list(&fixes),
                list(&costs),
                both.len()
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests;

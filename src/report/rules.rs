//! "Which backend for which game" as data: each statement is a [`Rule`] over one metric
//! (metric, comparison, threshold, wording), evaluated for every configuration, the sweep
//! included, on its worst value over the scenarios it ran. No rule names a backend or a
//! scenario; adding a statement is adding one entry to [`RULES`].

use super::{format_value, worst_matrix};
use crate::metrics::MetricRow;

/// How a configuration's worst value is compared with a rule's threshold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// The value is greater than the threshold.
    Above,
    /// The value is less than the threshold.
    Below,
    /// The value's magnitude is greater than the threshold.
    MagnitudeAbove,
    /// The value's magnitude is at most the threshold.
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
}

/// One statement of the report: made when `metric`'s worst value (over the scenarios a
/// configuration ran) compares to `threshold` as `comparison` says, for every configuration
/// it holds for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rule {
    /// The metric (a registry name).
    pub metric: &'static str,
    /// How its worst value is compared.
    pub comparison: Comparison,
    /// The threshold, in the metric's unit.
    pub threshold: f64,
    /// The statement; the configurations it holds for and their values follow it.
    pub wording: &'static str,
}

/// Every statement the report can make, in print order.
pub const RULES: &[Rule] = &[
    Rule {
        metric: "rest_gap_declared",
        comparison: Comparison::MagnitudeAtMost,
        threshold: 1e-4,
        wording: "Rests exactly where it promises (within 1e-4 tiles of its declared contact: flush, or its offset)",
    },
    Rule {
        metric: "rest_gap",
        comparison: Comparison::MagnitudeAtMost,
        threshold: 1e-4,
        wording: "Pixel-exact contact everywhere it rests, slopes included (sprites that must touch the ground)",
    },
    Rule {
        metric: "slope_overlap",
        comparison: Comparison::Above,
        // A tenth of a tile: 1.6 pixels of a 16-pixel tile, visible.
        threshold: 0.1,
        wording: "Overhangs slopes visibly (the seed's centre-column rule does by design): a box-shaped sprite sinks a corner into ramps, by up to (tiles)",
    },
    Rule {
        metric: "penetration_beyond_declared",
        comparison: Comparison::Above,
        threshold: 0.01,
        wording: "Ends up inside the level beyond what it declares (sinks into floors or slopes, or stands part-way inside a slope too steep to climb), by up to",
    },
    Rule {
        metric: "slope_gap_declared",
        comparison: Comparison::MagnitudeAbove,
        // The error score's clearly-wrong size for a length (0.01 tiles).
        threshold: 0.01,
        wording: "Floats above (or sinks into) walkable slopes beyond its declared contact while it reports grounded, on some frame, by up to (tiles)",
    },
    Rule {
        metric: "rest_jitter",
        comparison: Comparison::Above,
        // The clearly-wrong size for a length (0.01 tiles).
        threshold: 0.01,
        wording: "Does not rest still: the feet move over the settled rest by up to (tiles)",
    },
    Rule {
        metric: "bounce_frames",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Bounces or lifts off after landing: frames airborne after first touching ground, up to",
    },
    Rule {
        metric: "grounded_flicker",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Flickers between grounded and airborne with ground under its feet: switches, up to",
    },
    Rule {
        metric: "apex_error",
        comparison: Comparison::MagnitudeAbove,
        // The clearly-wrong size for a length (0.01 tiles).
        threshold: 0.01,
        wording: "Jumps off the requested height: apex minus the requested height, by up to (tiles)",
    },
    Rule {
        metric: "land_frame_error",
        comparison: Comparison::Below,
        threshold: 0.0,
        wording: "Lands early: reports grounded before the integrator's landing frame, by",
    },
    Rule {
        metric: "ladder_speed_error",
        comparison: Comparison::MagnitudeAbove,
        threshold: 0.1,
        wording: "Climbs ladders off the configured speed (quantized steps), by up to (tiles/s)",
    },
    Rule {
        metric: "progress_ratio",
        comparison: Comparison::Below,
        threshold: 0.5,
        wording: "Sticks on some flat floors: covers as little of the commanded walk as",
    },
    Rule {
        metric: "stuck_frames",
        comparison: Comparison::Above,
        threshold: 10.0,
        wording: "Catches on tile seams: stuck frames on open ground, up to",
    },
    Rule {
        metric: "slope_airborne_frames",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Leaves walkable slopes airborne while walking them (launches off crests or down ramps): frames, up to",
    },
    Rule {
        metric: "slope_speed_ratio",
        comparison: Comparison::Below,
        // A tenth below the run speed: a slow-down a player feels.
        threshold: 0.9,
        wording: "Slows horizontally on slopes (constant speed along the surface, or catching on the ramp): horizontal speed over the run speed down to",
    },
    Rule {
        metric: "slope_surface_speed_ratio",
        comparison: Comparison::Above,
        // A tenth above the run speed.
        threshold: 1.1,
        wording: "Moves faster along slopes than it runs on flat ground (constant horizontal speed, the seed's model: 1.41 times the run speed along a 45-degree ramp, where Godot's floor_constant_speed keeps 1): speed along the surface over the run speed up to",
    },
    Rule {
        metric: "steep_blocked",
        comparison: Comparison::Below,
        threshold: 1.0,
        wording: "Climbs a slope steeper than its climb limit",
    },
    Rule {
        metric: "oneway_result",
        comparison: Comparison::Below,
        threshold: 1.0,
        wording: "Ends a one-way platform scenario elsewhere than the seed's rule puts it",
    },
    Rule {
        metric: "ladder_result",
        comparison: Comparison::Below,
        threshold: 1.0,
        wording: "Ends a ladder scenario elsewhere than expected (top, bottom, floor)",
    },
    Rule {
        metric: "carry_drift",
        comparison: Comparison::Above,
        // A tenth of a tile: 1.6 pixels of a 16-pixel tile, visible.
        threshold: 0.1,
        wording: "Loses its grip on moving platforms: the rider drifts relative to its platform by up to (tiles)",
    },
    Rule {
        metric: "carry_airborne_frames",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Airborne while riding a moving platform (a platform dropping faster than gravity leaves any rider; beyond that the grip is lost): frames, up to",
    },
    Rule {
        metric: "push_penetration",
        comparison: Comparison::Above,
        // A tenth of a tile: visible.
        threshold: 0.1,
        wording: "Lets moving platforms into the character (pushed or squeezed), by up to (tiles)",
    },
    Rule {
        metric: "crush_count",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Ends up crushed inside a moving platform (a platform squeezing it against the level): times, up to",
    },
    Rule {
        metric: "idle_drift",
        comparison: Comparison::Above,
        threshold: 0.01,
        wording: "Moves a character that stands still with no input, by up to (tiles)",
    },
    Rule {
        metric: "false_grounded",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Reports grounded with no ground under it (can jump from there): frames, up to",
    },
    Rule {
        metric: "tunneled",
        comparison: Comparison::Above,
        threshold: 0.0,
        wording: "Tunnels through a wall at speed",
    },
];

/// The statements `rules` make on `rows`: for each rule that holds for some configuration, its
/// wording followed by each such configuration and its worst value.
pub fn evaluate(rules: &[Rule], rows: &[MetricRow]) -> Vec<String> {
    let mut out = Vec::new();
    for rule in rules {
        let m = worst_matrix(rows, |name| name == rule.metric);
        let Some(mi) = m.metrics.iter().position(|(n, _, _)| *n == rule.metric) else {
            continue;
        };
        let holds: Vec<String> = (0..m.configs.len())
            .filter_map(|ci| {
                let (v, _) = m.cells[ci][mi]?;
                rule.comparison
                    .holds(v, rule.threshold)
                    .then(|| format!("{} ({})", m.label(ci), format_value(v)))
            })
            .collect();
        if !holds.is_empty() {
            out.push(format!(
                "{} [{}]: {}.",
                rule.wording,
                rule.metric,
                holds.join(", ")
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
            .filter(|r| super::column(r) == c)
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
                    let c = super::column(r);
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
mod tests {
    use super::*;

    fn row(backend: &str, config: &str, metric: &'static str, value: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: "s".into(),
            backend: backend.into(),
            config: config.into(),
            metric,
            value,
            unit: "tiles",
            reference: 0.0,
            error: value,
            frame: None,
        }
    }

    #[test]
    fn a_rule_is_evaluated_for_every_configuration_the_sweep_included() {
        let rows = vec![
            row("sweep", "default", "slope_overlap", 0.28),
            row("other", "x", "slope_overlap", 0.0),
            // Below the rule's tenth of a tile: not visible, not stated.
            row("third", "y", "slope_overlap", 0.02),
        ];
        let s = evaluate(RULES, &rows);
        assert_eq!(s.len(), 1, "{s:?}");
        assert!(s[0].contains("sweep (0.2800)"), "{s:?}");
        assert!(!s[0].contains("third"), "{s:?}");
        assert!(!s[0].contains("other"), "{s:?}");
    }

    #[test]
    fn every_rule_names_a_registered_metric() {
        for r in RULES {
            assert!(
                crate::metrics::registry::get(r.metric).is_some(),
                "{}",
                r.metric
            );
        }
    }

    #[test]
    fn a_setting_is_judged_only_over_the_scenarios_both_ran() {
        let at = |scenario: &str, config: &str, value: f64| MetricRow {
            scenario: scenario.into(),
            ..row("sweep", config, "rest_gap", value)
        };
        // The base configuration is bad only on a scenario the other never ran.
        let rows = vec![
            at("hard", "default", 0.5),
            at("easy", "default", 0.0),
            at("easy", "positions=integer/32", 0.0),
        ];
        assert!(
            setting_effects(&rows).is_empty(),
            "{:?}",
            setting_effects(&rows)
        );
        // Where both ran and it differs, it is reported, with both values.
        let rows = vec![
            at("easy", "default", 0.2),
            at("easy", "positions=integer/32", 0.0),
        ];
        let e = setting_effects(&rows);
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(e[0].contains("rest_gap 0.2000 -> 0"), "{e:?}");
    }

    #[test]
    fn every_scored_metric_has_a_statement() {
        // Found by review: metrics the default score charges had no statement in the report,
        // so a configuration's fault there showed only in a table.
        let scored: Vec<&str> = crate::metrics::registry::METRICS
            .iter()
            .filter(|d| d.weight > 0.0)
            .map(|d| d.name)
            .collect();
        assert!(!scored.is_empty());
        for m in scored {
            assert!(RULES.iter().any(|r| r.metric == m), "no rule for {m}");
        }
        for r in RULES {
            assert!(
                crate::metrics::registry::get(r.metric).is_some(),
                "{}",
                r.metric
            );
        }
    }
}

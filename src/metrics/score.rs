//! The error score of `platbench sweep`: which metrics count and how much. The default reads the
//! registry's weights ([`super::registry::MetricDef::weight`]), which charge no controller for
//! its declared design; `platbench sweep --score METRIC[=WEIGHT],...` replaces it.
//!
//! A setting's score is the weighted mean over its (scenario, metric) rows of
//! `min(1, max(0, |error| - allowance) / scale)`, `scale` the metric's "clearly wrong" size
//! (0.01 tiles, 0.01 for ratios, 0.01 tiles/s, one frame, count or boolean) and `allowance` the
//! error the game cannot show at its [`Score::pixels_per_tile`] (default 16): one pixel for a
//! length, one pixel per second for a speed, nothing for the other units
//! ([`registry::unit_allowance`]). 0 is every scored metric within a pixel of ideal, 1 every one
//! clearly wrong beyond that pixel. Metrics of one model group (the slope speed against constant horizontal
//! speed and against constant speed along the surface) count once per scenario, by the closer
//! model.

use std::collections::BTreeMap;

use super::registry::{self, Behaviour};
use super::MetricRow;

/// A model group's rows of one scenario on one configuration: level, scenario, backend,
/// configuration, group.
type GroupKey<'a> = (&'a str, &'a str, &'a str, &'a str, &'a str);

/// Why a `--score` list was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScoreError {
    /// A name that is not in the registry.
    #[error(
        "unknown metric {0:?} in --score (the names are those of metrics.csv's metric column)"
    )]
    UnknownMetric(String),
    /// A pixels-per-tile that is not a finite number > 0.
    #[error("--pixels-per-tile {0:?} is not a finite number > 0")]
    BadPixelsPerTile(String),
    /// A weight that is not a finite number >= 0.
    #[error("weight {value:?} of {metric} in --score is not a finite number >= 0")]
    BadWeight {
        /// The metric.
        metric: String,
        /// The weight as written.
        value: String,
    },
    /// Nothing with a positive weight.
    #[error("--score weighs no metric above 0")]
    Empty,
}

/// Metrics and their weights in the error score.
#[derive(Clone, Debug, PartialEq)]
pub struct Score {
    /// `(metric, weight)`; a metric not listed weighs 0.
    weights: Vec<(&'static str, f64)>,
    /// The game's pixels per tile, which sets the error not charged (one pixel for a length,
    /// one pixel per second for a speed): [`registry::DEFAULT_PIXELS_PER_TILE`] unless
    /// `platbench sweep --pixels-per-tile` sets it. A finite number > 0.
    pixels_per_tile: f64,
}

impl Default for Score {
    /// The registry's default weights, at [`registry::DEFAULT_PIXELS_PER_TILE`].
    fn default() -> Self {
        Score {
            weights: registry::METRICS
                .iter()
                .filter(|d| d.weight > 0.0)
                .map(|d| (d.name, d.weight))
                .collect(),
            pixels_per_tile: registry::DEFAULT_PIXELS_PER_TILE,
        }
    }
}

impl Score {
    /// Parses `METRIC[=WEIGHT],...` (weight 1 when omitted); only the listed metrics count.
    pub fn parse(spec: &str) -> Result<Score, ScoreError> {
        let mut weights = Vec::new();
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (name, w) = match item.split_once('=') {
                Some((n, w)) => (n.trim(), Some(w.trim())),
                None => (item, None),
            };
            let def =
                registry::get(name).ok_or_else(|| ScoreError::UnknownMetric(name.to_string()))?;
            let weight = match w {
                None => 1.0,
                Some(v) => v
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && *x >= 0.0)
                    .ok_or_else(|| ScoreError::BadWeight {
                        metric: name.to_string(),
                        value: v.to_string(),
                    })?,
            };
            weights.push((def.name, weight));
        }
        if !weights.iter().any(|(_, w)| *w > 0.0) {
            return Err(ScoreError::Empty);
        }
        Ok(Score {
            weights,
            pixels_per_tile: registry::DEFAULT_PIXELS_PER_TILE,
        })
    }

    /// The same score for a game drawn at `pixels_per_tile` pixels per tile (`--pixels-per-tile`,
    /// as written), which must be a finite number > 0.
    pub fn at_pixels_per_tile(self, pixels_per_tile: &str) -> Result<Score, ScoreError> {
        let ppt = pixels_per_tile
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or_else(|| ScoreError::BadPixelsPerTile(pixels_per_tile.to_string()))?;
        Ok(Score {
            pixels_per_tile: ppt,
            ..self
        })
    }

    /// The game's pixels per tile the score charges at (see [`Score::at_pixels_per_tile`]).
    pub fn pixels_per_tile(&self) -> f64 {
        self.pixels_per_tile
    }

    /// How much row `r` is charged before the cap at 1: its error less the pixel allowance, in
    /// clearly-wrong sizes ([`registry::charged`]; infinite for a NaN).
    pub fn charged(&self, r: &MetricRow) -> f64 {
        let unit = registry::get(r.metric).map_or(r.unit, |d| d.unit);
        registry::charged(unit, r.error, self.pixels_per_tile)
    }

    /// The weight of `metric` (0 if not scored).
    pub fn weight(&self, metric: &str) -> f64 {
        self.weights
            .iter()
            .filter(|(m, _)| *m == metric)
            .map(|(_, w)| *w)
            .sum()
    }

    /// The scored metrics as `METRIC=WEIGHT,...` (what `--score` takes), and the pixels per
    /// tile when not the default.
    pub fn describe(&self) -> String {
        self.weights
            .iter()
            .map(|(m, w)| format!("{m}={w}"))
            .collect::<Vec<_>>()
            .join(",")
            + &if self.pixels_per_tile == registry::DEFAULT_PIXELS_PER_TILE {
                String::new()
            } else {
                format!(" at {} pixels per tile", self.pixels_per_tile)
            }
    }

    /// The score of `rows` (see the module docs); 0 when nothing is scored.
    pub fn error(&self, rows: &[MetricRow]) -> f64 {
        self.error_where(rows, |_| true)
    }

    /// The score of the rows of one behaviour's metrics.
    pub fn error_of(&self, rows: &[MetricRow], behaviour: Behaviour) -> f64 {
        self.error_where(rows, |m| {
            registry::get(m).is_some_and(|d| d.behaviour == behaviour)
        })
    }

    fn error_where(&self, rows: &[MetricRow], keep: impl Fn(&str) -> bool) -> f64 {
        let (mut sum, mut weights) = (0.0, 0.0);
        // (level, scenario, backend, config, group) -> (closest model's error, weight)
        let mut groups: BTreeMap<GroupKey, (f64, f64)> = BTreeMap::new();
        for r in rows.iter().filter(|r| keep(r.metric)) {
            let w = self.weight(r.metric);
            if w == 0.0 {
                continue;
            }
            let e = self.charged(r);
            let e = if e.is_finite() { e.min(1.0) } else { 1.0 };
            match registry::get(r.metric).and_then(|d| d.model_group) {
                Some(g) => {
                    let key = (
                        r.level.as_str(),
                        r.scenario.as_str(),
                        r.backend.as_str(),
                        r.config.as_str(),
                        g,
                    );
                    let slot = groups.entry(key).or_insert((f64::INFINITY, 0.0));
                    *slot = (slot.0.min(e), slot.1.max(w));
                }
                None => {
                    sum += w * e;
                    weights += w;
                }
            }
        }
        for (e, w) in groups.values() {
            sum += w * e;
            weights += w;
        }
        if weights == 0.0 {
            0.0
        } else {
            sum / weights
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(metric: &'static str, unit: &'static str, value: f64, reference: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: "s".into(),
            backend: "b".into(),
            config: "c".into(),
            metric,
            value,
            unit,
            reference,
            error: value - reference,
            frame: None,
            q1: None,
            q3: None,
        }
    }

    #[test]
    fn the_default_charges_declared_gaps_not_touching() {
        // A rest 0.07 above the floor that the configuration declares (rest_gap_declared 0):
        // the default score does not charge it; scoring rest_gap (touching) does: 0.0075 beyond
        // the pixel (1/16 tile), 0.75 of the 0.01-tile scale.
        let rows = vec![
            row("rest_gap", "tiles", 0.07, 0.0),
            row("rest_gap_declared", "tiles", 0.0, 0.0),
        ];
        assert_eq!(Score::default().error(&rows), 0.0);
        let touching = Score::parse("rest_gap").unwrap();
        assert!((touching.error(&rows) - 0.75).abs() < 1e-9);
    }

    #[test]
    fn a_sub_pixel_error_is_free_and_a_lost_platform_is_not() {
        // The case: a 0.16-pixel hover (0.01 tiles at 16 px per tile) was charged as
        // much as losing a platform by 6 tiles (both 1). Now the hover is free and the loss 1.
        let hover = vec![row("rest_gap_declared", "tiles", 0.01, 0.0)];
        let lost = vec![row("carry_drift", "tiles", 6.0, 0.0)];
        assert_eq!(Score::default().error(&hover), 0.0);
        assert_eq!(Score::default().error(&lost), 1.0);
        // At 2 pixels per tile half a tile is free; at 1000 the hover is 10 pixels, charged
        // (0.01 - 0.001) / 0.01 = 0.9.
        let coarse = Score::default().at_pixels_per_tile("2").unwrap();
        assert_eq!(coarse.error(&[row("carry_drift", "tiles", 0.5, 0.0)]), 0.0);
        let fine = Score::default().at_pixels_per_tile("1000").unwrap();
        assert!((fine.error(&hover) - 0.9).abs() < 1e-9);
        // Counts have no allowance: one crush is clearly wrong at any resolution.
        assert_eq!(coarse.error(&[row("crush_count", "count", 1.0, 0.0)]), 1.0);
        assert!(matches!(
            Score::default().at_pixels_per_tile("0"),
            Err(ScoreError::BadPixelsPerTile(_))
        ));
        assert!(Score::default().at_pixels_per_tile("inf").is_err());
    }

    #[test]
    fn the_closer_slope_speed_model_counts_once() {
        // Constant speed along the surface kept (ratio 1), horizontal speed 0.7 of the run speed:
        // the closer model's error (0) counts, once.
        let rows = vec![
            row("slope_speed_ratio", "ratio", 0.7, 1.0),
            row("slope_surface_speed_ratio", "ratio", 1.0, 1.0),
        ];
        assert_eq!(Score::default().error(&rows), 0.0);
        // Scored against the seed's model alone, it is clearly wrong.
        assert_eq!(Score::parse("slope_speed_ratio").unwrap().error(&rows), 1.0);
    }

    #[test]
    fn a_bad_list_is_refused() {
        assert!(matches!(
            Score::parse("nope"),
            Err(ScoreError::UnknownMetric(_))
        ));
        assert!(matches!(
            Score::parse("rest_gap=-1"),
            Err(ScoreError::BadWeight { .. })
        ));
        assert!(matches!(Score::parse("rest_gap=0"), Err(ScoreError::Empty)));
        assert_eq!(
            Score::parse("rest_gap=2,tunneled")
                .unwrap()
                .weight("rest_gap"),
            2.0
        );
    }
}

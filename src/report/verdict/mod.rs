//! The verdict: which configuration to pick for which kind of game, and the scorecard it is
//! read from. Each configuration is graded per behaviour on whether it keeps its own documented
//! promise (the metrics of the default error score, which measure every controller against its
//! declared contact), and each game profile ([`super::profile`]) picks the configuration with
//! the lowest error over the behaviours it weighs.
//!
//! Everything is read from a stream of runs ([`VerdictRows::push_run`]) in memory that grows
//! with the configurations and levels, not with the rows.

mod html;
mod pick;
mod render;

use std::collections::{BTreeMap, BTreeSet};

pub use html::{render_verdict_html, STYLE};
pub use pick::{pick, ProfileVerdict, Reason};
pub use render::{render_capabilities, render_scorecard, render_verdict};

use crate::backend::{Capabilities, Precision};
use crate::config::RunConfig;
use crate::level::Features;
use crate::metrics::registry::{self, Behaviour};
use crate::metrics::score::Score;
use crate::metrics::MetricRow;

/// How a configuration does on one behaviour's scenarios.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Grade {
    /// Every scored metric within the size that counts as clearly wrong (0.01 tiles, 0.01 for a
    /// ratio or tiles/s, beyond a pixel of a 16-pixel tile or a pixel per second; exactly right
    /// for frames, counts and booleans).
    Keeps,
    /// Some metric off, but within ten times that size for lengths, ratios and speeds (0.1
    /// tiles beyond the pixel: 2.6 pixels of a 16-pixel tile in all) or 3 frames (50 ms at
    /// 60 Hz) or 2 counts.
    Minor,
    /// Beyond that, a boolean result wrong, or a value that is not a number.
    Fails,
}

impl Grade {
    /// The word the scorecard prints.
    pub fn word(self) -> &'static str {
        match self {
            Grade::Keeps => "ok",
            Grade::Minor => "minor",
            Grade::Fails => "FAIL",
        }
    }

    /// The grade of a row whose error is `error` in `unit`, judged as the error score charges
    /// it: beyond the pixel a 16-pixel tile cannot show (one pixel for a length, one pixel per
    /// second for a speed, [`registry::unit_allowance`] at
    /// [`registry::DEFAULT_PIXELS_PER_TILE`]), so kept is a charge of at most 1, minor of at
    /// most 10.
    pub fn of(unit: &str, error: f64) -> Grade {
        if error.is_nan() {
            return Grade::Fails;
        }
        let e = (error.abs() - registry::unit_allowance(unit, registry::DEFAULT_PIXELS_PER_TILE))
            .max(0.0);
        let (keeps, minor) = match unit {
            // The clearly-wrong size of the error score, and ten times it.
            "tiles" | "ratio" | "tiles/s" => {
                let s = registry::unit_scale(unit);
                (s, 10.0 * s)
            }
            // Whole numbers: exact is kept; 3 frames is 50 ms at 60 Hz; 2 counts.
            "frames" => (0.5, 3.0),
            "count" => (0.5, 2.0),
            // A boolean result is right or wrong.
            _ => (0.5, 0.5),
        };
        if e <= keeps {
            Grade::Keeps
        } else if e <= minor {
            Grade::Minor
        } else {
            Grade::Fails
        }
    }
}

/// The row that decided a cell's grade: the worst of its scored metrics, where it happened.
#[derive(Clone, Debug, PartialEq)]
pub struct Worst {
    /// Its grade.
    pub grade: Grade,
    /// Its error over the metric's clearly-wrong size (infinite for NaN).
    pub size: f64,
    /// The row.
    pub row: MetricRow,
}

impl Worst {
    /// `level.scenario frame N: metric value (ideal reference)`: where to look, and what.
    pub fn describe(&self) -> String {
        let r = &self.row;
        let at = r.frame.map_or(String::new(), |f| format!(" frame {f}"));
        format!(
            "{}.{}{at}: {} {} (ideal {})",
            r.level,
            r.scenario,
            r.metric,
            super::format_value(r.value),
            super::format_value(r.reference)
        )
    }
}

/// One configuration's results on one behaviour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cell {
    /// Weighted sum of the scored rows' capped errors (the error score's numerator).
    sum: f64,
    /// Sum of their weights.
    weight: f64,
    /// Scenarios it ran that measure this behaviour.
    pub ran: usize,
    /// Levels it ran that measure this behaviour.
    levels: BTreeSet<String>,
    /// Its worst row.
    pub worst: Option<Worst>,
}

impl Cell {
    /// The grade: its worst row's, `None` when it ran no scenario of the behaviour.
    pub fn grade(&self) -> Option<Grade> {
        if self.ran == 0 {
            None
        } else {
            Some(self.worst.as_ref().map_or(Grade::Keeps, |w| w.grade))
        }
    }

    /// The error score over the scenarios it ran (0 ideal, 1 clearly wrong everywhere).
    pub fn score(&self) -> f64 {
        if self.weight > 0.0 {
            self.sum / self.weight
        } else {
            0.0
        }
    }
}

/// What a configuration declares: its label and backend, the features it models, its precision
/// and capabilities.
#[derive(Clone, Debug, PartialEq)]
pub struct Facts {
    /// Its label as the tables print it (`backend` or `backend config`).
    pub label: String,
    /// Its backend.
    pub backend: String,
    /// The level features it models.
    pub features: Features,
    /// The precision of its world positions.
    pub precision: Precision,
    /// What else it declares.
    pub capabilities: Capabilities,
    /// Its documented design in one line ([`RunConfig::why`], else its controller's
    /// description): why it behaves as it does, attached to its row alike for every
    /// configuration.
    pub why: String,
}

impl Facts {
    /// The facts of a configuration of the run.
    pub fn of(run: &RunConfig) -> Facts {
        let backend = run.backend.backend().to_string();
        let label = if run.label == "default" {
            backend.clone()
        } else {
            format!("{backend} {}", run.label)
        };
        Facts {
            label,
            backend,
            features: run.backend.features(),
            precision: run.backend.precision(),
            capabilities: run.backend.capabilities(),
            why: run.why.clone(),
        }
    }
}

/// One configuration's row of the scorecard.
#[derive(Clone, Debug, PartialEq)]
pub struct Card {
    /// What it declares.
    pub facts: Facts,
    /// Per behaviour of [`Behaviour::ALL`] but cost.
    pub cells: BTreeMap<Behaviour, Cell>,
    /// Its time per character step on each scenario timed (ns), with `run --timing`.
    pub cost: Vec<f64>,
}

impl Card {
    /// The median time per character step over the scenarios timed, if any were.
    pub fn median_cost(&self) -> Option<f64> {
        let mut v: Vec<f64> = self
            .cost
            .iter()
            .copied()
            .filter(|x| x.is_finite())
            .collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let n = v.len();
        Some(if n % 2 == 1 {
            v[n / 2]
        } else {
            (v[n / 2 - 1] + v[n / 2]) / 2.0
        })
    }
}

/// The scorecard: every configuration's cells, and what any configuration ran.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scorecard {
    /// One card per configuration, in run order.
    pub cards: Vec<Card>,
    /// Per behaviour: the scenarios any configuration ran that measure it.
    pub scenarios: BTreeMap<Behaviour, usize>,
    /// Per behaviour: the levels any configuration ran that measure it.
    pub levels: BTreeMap<Behaviour, BTreeSet<String>>,
    /// Scenarios run in all.
    pub total_scenarios: usize,
}

impl Scorecard {
    /// The behaviour's error score of card `c`, counting each scenario of the behaviour it did
    /// not run as clearly wrong (1): a configuration is never credited for levels it skipped.
    /// `None` when no configuration ran the behaviour.
    pub fn score(&self, c: usize, b: Behaviour) -> Option<f64> {
        let total = *self.scenarios.get(&b)?;
        if total == 0 {
            return None;
        }
        let cell = self.cards[c].cells.get(&b);
        let ran = cell.map_or(0, |x| x.ran);
        let s = cell.map_or(1.0, Cell::score);
        Some((ran as f64 * s + (total - ran.min(total)) as f64) / total as f64)
    }

    /// The levels measuring `b` that card `c` did not run.
    pub fn skipped(&self, c: usize, b: Behaviour) -> Vec<String> {
        let ran = self.cards[c].cells.get(&b).map(|x| &x.levels);
        self.levels.get(&b).map_or_else(Vec::new, |all| {
            all.iter()
                .filter(|l| ran.is_none_or(|r| !r.contains(*l)))
                .cloned()
                .collect()
        })
    }

    /// Card `c`'s cost on the scale profiles weigh: 0 for the cheapest configuration's median
    /// time per step, `log10(ratio) / 2` above it (10 times the cheapest scores 0.5, 100 times
    /// or more 1). `None` without timing.
    pub fn cost_score(&self, c: usize) -> Option<f64> {
        let cheapest = self
            .cards
            .iter()
            .filter_map(Card::median_cost)
            .filter(|x| *x > 0.0)
            .min_by(f64::total_cmp)?;
        let mine = self.cards[c].median_cost()?;
        Some(((mine / cheapest).max(1.0).log10() / 2.0).min(1.0))
    }

    /// Card `c`'s grade in a scorecard column (the worst of its behaviours), with the row that
    /// set it.
    pub fn column_grade(&self, c: usize, col: Column) -> Option<(Grade, Option<&Worst>)> {
        let mut out: Option<(Grade, Option<&Worst>)> = None;
        for b in col.behaviours() {
            let Some(cell) = self.cards[c].cells.get(b) else {
                continue;
            };
            let Some(g) = cell.grade() else {
                continue;
            };
            let worse = out.is_none_or(|(og, ow)| {
                g > og
                    || (g == og
                        && cell.worst.as_ref().map_or(0.0, |w| w.size) > ow.map_or(0.0, |w| w.size))
            });
            if worse {
                out = Some((g, cell.worst.as_ref()));
            }
        }
        out
    }
}

/// A column of the scorecard: one or two behaviours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// Landing and resting.
    Landing,
    /// Jumping.
    Jumping,
    /// Walking over seams.
    Seams,
    /// Slopes.
    Slopes,
    /// One-way platforms.
    OneWay,
    /// Ladders.
    Ladders,
    /// Moving platforms.
    Platforms,
    /// Walls at speed.
    Walls,
    /// Standing still.
    Still,
}

impl Column {
    /// Every column, in print order.
    pub const ALL: [Column; 9] = [
        Column::Landing,
        Column::Jumping,
        Column::Seams,
        Column::Slopes,
        Column::OneWay,
        Column::Ladders,
        Column::Platforms,
        Column::Walls,
        Column::Still,
    ];

    /// The behaviours it grades.
    pub fn behaviours(self) -> &'static [Behaviour] {
        match self {
            Column::Landing => &[Behaviour::Landing],
            Column::Jumping => &[Behaviour::Jumping],
            Column::Seams => &[Behaviour::Seams],
            Column::Slopes => &[Behaviour::Slopes],
            Column::OneWay => &[Behaviour::OneWay],
            Column::Ladders => &[Behaviour::Ladders],
            Column::Platforms => &[Behaviour::Platforms],
            Column::Walls => &[Behaviour::Walls],
            Column::Still => &[Behaviour::Idle],
        }
    }

    /// Its header.
    pub fn header(self) -> &'static str {
        match self {
            Column::Landing => "landing",
            Column::Jumping => "jumps",
            Column::Seams => "seams",
            Column::Slopes => "slopes",
            Column::OneWay => "oneway",
            Column::Ladders => "ladders",
            Column::Platforms => "platforms",
            Column::Walls => "walls",
            Column::Still => "still",
        }
    }
}

/// The behaviour a row of a metric of behaviour `metric` counts toward on a level with
/// `features`: the metric's own on a level of plain tiles, or when it measures a feature
/// (slopes, one-way platforms, ladders, moving platforms); else the level's feature, the
/// platforms first. A character pushed into a wall by a platform, or lifted off by a lift, is
/// a moving-platform result whichever metric sees it: a landing or standing metric on such a
/// level is charged to that level's feature for every configuration alike.
pub fn behaviour_of(metric: Behaviour, features: Features) -> Behaviour {
    use Behaviour::*;
    if matches!(metric, Slopes | OneWay | Ladders | Platforms | Cost) {
        return metric;
    }
    if features.moving_platforms {
        Platforms
    } else if features.ladders {
        Ladders
    } else if features.one_way {
        OneWay
    } else if features.slopes {
        Slopes
    } else {
        metric
    }
}

/// The rows the verdict needs, gathered run by run.
#[derive(Clone, Debug)]
pub struct VerdictRows {
    score: Score,
    facts: Vec<Facts>,
    /// The features of each level of the run, by name: a row of a level with a feature counts
    /// toward that feature's behaviour ([`behaviour_of`]).
    levels: Vec<(String, Features)>,
    cards: Vec<Card>,
    /// Per behaviour: the (level, scenario) pairs any configuration ran.
    scenarios: BTreeMap<Behaviour, BTreeSet<(String, String)>>,
    /// Every (level, scenario) run.
    all: BTreeSet<(String, String)>,
}

impl VerdictRows {
    /// Gathers runs of the configurations `facts` declare (a run of another configuration adds
    /// a card with no declared features) on levels with the features `levels` gives by name.
    pub fn new(facts: Vec<Facts>, levels: Vec<(String, Features)>) -> Self {
        VerdictRows {
            score: Score::default(),
            cards: Vec::new(),
            facts,
            levels,
            scenarios: BTreeMap::new(),
            all: BTreeSet::new(),
        }
    }

    /// The card of `label`, added in run order.
    fn card(&mut self, r: &MetricRow) -> &mut Card {
        let label = super::column(r);
        if let Some(i) = self.cards.iter().position(|c| c.facts.label == label) {
            return &mut self.cards[i];
        }
        let facts = self
            .facts
            .iter()
            .find(|f| f.label == label)
            .cloned()
            .unwrap_or_else(|| Facts {
                label,
                backend: r.backend.clone(),
                features: Features::NONE,
                precision: Precision::F32,
                capabilities: Capabilities::default(),
                why: String::new(),
            });
        self.cards.push(Card {
            facts,
            cells: BTreeMap::new(),
            cost: Vec::new(),
        });
        let n = self.cards.len();
        &mut self.cards[n - 1]
    }

    /// Adds the rows of one run (one scenario on one configuration).
    pub fn push_run(&mut self, rows: &[MetricRow]) {
        let Some(first) = rows.first() else {
            return;
        };
        let key = (first.level.clone(), first.scenario.clone());
        self.all.insert(key.clone());
        let features = self
            .levels
            .iter()
            .find(|(l, _)| *l == first.level)
            .map_or(Features::NONE, |(_, f)| *f);
        // The scored rows of each behaviour, a model group's closer model only.
        let mut scored: BTreeMap<Behaviour, Vec<(&MetricRow, f64, f64)>> = BTreeMap::new();
        let mut groups: BTreeMap<&str, (&MetricRow, f64, f64)> = BTreeMap::new();
        let mut cost = Vec::new();
        for r in rows {
            let Some(def) = registry::get(r.metric) else {
                continue;
            };
            if def.behaviour == Behaviour::Cost {
                cost.push(r.value);
                continue;
            }
            let w = self.score.weight(r.metric);
            if w <= 0.0 {
                continue;
            }
            let size = self.score.charged(r);
            match def.model_group {
                Some(g) => {
                    let slot = groups.entry(g).or_insert((r, size, w));
                    if size < slot.1 {
                        *slot = (r, size, w);
                    }
                }
                None => scored
                    .entry(behaviour_of(def.behaviour, features))
                    .or_default()
                    .push((r, size, w)),
            }
        }
        for (r, size, w) in groups.into_values() {
            if let Some(def) = registry::get(r.metric) {
                scored
                    .entry(behaviour_of(def.behaviour, features))
                    .or_default()
                    .push((r, size, w));
            }
        }
        for b in scored.keys() {
            self.scenarios.entry(*b).or_default().insert(key.clone());
        }
        let card = self.card(first);
        card.cost.extend(cost);
        for (b, list) in scored {
            let cell = card.cells.entry(b).or_default();
            cell.ran += 1;
            if !cell.levels.contains(&first.level) {
                cell.levels.insert(first.level.clone());
            }
            for (r, size, w) in list {
                cell.sum += w * size.min(1.0);
                cell.weight += w;
                let grade = Grade::of(r.unit, r.error);
                let worse = cell
                    .worst
                    .as_ref()
                    .is_none_or(|x| (grade, size) > (x.grade, x.size));
                if worse {
                    cell.worst = Some(Worst {
                        grade,
                        size,
                        row: r.clone(),
                    });
                }
            }
        }
    }

    /// The scorecard of the runs so far.
    pub fn scorecard(&self) -> Scorecard {
        let mut levels: BTreeMap<Behaviour, BTreeSet<String>> = BTreeMap::new();
        for (b, set) in &self.scenarios {
            levels
                .entry(*b)
                .or_default()
                .extend(set.iter().map(|(l, _)| l.clone()));
        }
        Scorecard {
            cards: self.cards.clone(),
            scenarios: self.scenarios.iter().map(|(b, s)| (*b, s.len())).collect(),
            levels,
            total_scenarios: self.all.len(),
        }
    }

    /// The scorecard of `rows` (every row of a run, in run order) on `levels`.
    pub fn of(facts: Vec<Facts>, levels: Vec<(String, Features)>, rows: &[MetricRow]) -> Scorecard {
        let mut v = VerdictRows::new(facts, levels);
        let mut start = 0;
        for i in 1..=rows.len() {
            let split = i == rows.len() || {
                let (a, b) = (&rows[i - 1], &rows[i]);
                (&a.level, &a.scenario, &a.backend, &a.config)
                    != (&b.level, &b.scenario, &b.backend, &b.config)
            };
            if split {
                v.push_run(&rows[start..i]);
                start = i;
            }
        }
        v.scorecard()
    }
}

#[cfg(test)]
mod tests;

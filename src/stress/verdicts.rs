//! The stress matrix's verdicts: its rows judged per configuration (the envelope along each
//! dimension, the edges either side of the base value, the reach from the origin, the combination
//! cells) and the verdicts in words (whether a world of a given size holds is [`super::world`]).
//!
//! Rows are grouped once by configuration, dimension and value (hash maps, values compared as
//! `==` compares them), so a verdict costs time in proportion to the rows, whatever their
//! number: a `stability.csv` given to `platbench report` may hold any.

use std::collections::{HashMap, HashSet};

use super::definition::{dimensions, format_setting, INVARIANTS};
use super::execution::StressRow;

/// `v` as a hash key that matches as `==` does: 0 and -0 are one key; NaN, equal to nothing,
/// has none.
pub(crate) fn value_key(v: f64) -> Option<u64> {
    if v.is_nan() {
        None
    } else if v == 0.0 {
        Some(0)
    } else {
        Some(v.to_bits())
    }
}

/// Whether `v` is new to `seen` as `==` tells values apart (a NaN always is), noting it.
fn first_seen(seen: &mut HashSet<u64>, v: f64) -> bool {
    value_key(v).is_none_or(|k| seen.insert(k))
}

/// The one-dimension rows of one configuration (`backend config`) along one dimension, in
/// file order.
struct Group<'a> {
    config: String,
    dimension: &'a str,
    rows: Vec<&'a StressRow>,
}

/// The one-dimension rows of `rows` per configuration and dimension, in the order each pair
/// first appears.
fn one_dimension_groups(rows: &[StressRow]) -> Vec<Group<'_>> {
    let mut out: Vec<Group> = Vec::new();
    let mut index: HashMap<(String, &str), usize> = HashMap::new();
    for r in rows.iter().filter(|r| r.dimension2.is_empty()) {
        let config = format!("{} {}", r.backend, r.config);
        let i = *index
            .entry((config.clone(), r.dimension.as_str()))
            .or_insert_with(|| {
                out.push(Group {
                    config,
                    dimension: &r.dimension,
                    rows: Vec::new(),
                });
                out.len() - 1
            });
        out[i].rows.push(r);
    }
    out
}

/// One group's rows by value, each value's rows in file order ([`value_key`]: a NaN value's
/// rows match no value).
struct ByValue<'a>(HashMap<u64, Vec<&'a StressRow>>);

impl<'a> ByValue<'a> {
    fn of(rows: &[&'a StressRow]) -> Self {
        let mut m: HashMap<u64, Vec<&StressRow>> = HashMap::new();
        for r in rows {
            if let Some(k) = value_key(r.value) {
                m.entry(k).or_default().push(r);
            }
        }
        ByValue(m)
    }

    /// The rows whose value `== v`.
    fn at(&self, v: f64) -> &[&'a StressRow] {
        value_key(v)
            .and_then(|k| self.0.get(&k))
            .map_or(&[], Vec::as_slice)
    }
}

/// `values` sorted and deduplicated, as a verdict walks them.
fn sorted_values(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}

/// One configuration's results along one dimension of the matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct Envelope {
    /// Backend and configuration label.
    pub config: String,
    /// Dimension name.
    pub dimension: String,
    /// The values at which every invariant held, in matrix order.
    pub holds: Vec<f64>,
    /// Each invariant that broke somewhere, with the values at which it broke, in matrix order.
    pub breaks: Vec<(String, Vec<f64>)>,
}

impl Envelope {
    /// The values at which some invariant broke, in matrix order.
    pub fn broken_values(&self) -> Vec<f64> {
        let mut seen = HashSet::new();
        let mut v: Vec<f64> = Vec::new();
        for x in self.breaks.iter().flat_map(|(_, vs)| vs) {
            if first_seen(&mut seen, *x) {
                v.push(*x);
            }
        }
        v.sort_by(f64::total_cmp);
        v
    }
}

/// For each configuration and dimension, the values at which every invariant held and, per
/// invariant, those at which it broke (so an invariant that breaks everywhere, such as a
/// controller that cannot carry a rider at the base case, does not hide where the others hold).
pub fn envelope(rows: &[StressRow]) -> Vec<Envelope> {
    one_dimension_groups(rows).iter().map(envelope_of).collect()
}

/// [`envelope`] by `(config, dimension)`, for a verdict's envelope to be found in constant
/// time (the stress command's table and the report's stability section).
pub(crate) fn envelopes_by_key(rows: &[StressRow]) -> HashMap<(String, String), Envelope> {
    envelope(rows)
        .into_iter()
        .map(|e| ((e.config.clone(), e.dimension.clone()), e))
        .collect()
}

/// [`envelope`] of one group.
fn envelope_of(g: &Group) -> Envelope {
    let mut e = Envelope {
        config: g.config.clone(),
        dimension: g.dimension.to_string(),
        holds: Vec::new(),
        breaks: Vec::new(),
    };
    let mut held = HashSet::new();
    let mut broke: HashMap<&str, usize> = HashMap::new();
    for r in &g.rows {
        if r.holds {
            if first_seen(&mut held, r.value) {
                e.holds.push(r.value);
            }
        } else {
            match broke.get(r.invariant.as_str()) {
                Some(&i) => e.breaks[i].1.push(r.value),
                None => {
                    broke.insert(&r.invariant, e.breaks.len());
                    e.breaks.push((r.invariant.clone(), vec![r.value]));
                }
            }
        }
    }
    let bad: HashSet<u64> = e
        .broken_values()
        .into_iter()
        .filter_map(value_key)
        .collect();
    e.holds
        .retain(|v| value_key(*v).is_none_or(|k| !bad.contains(&k)));
    e
}

/// Where a configuration stops holding, on one side of a dimension's base value.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// The farthest value from the base, on this side, up to which every invariant held at
    /// every value (`None` when one broke at the base).
    pub last_holding: Option<f64>,
    /// The first value past it where an invariant broke, with those that broke there, in
    /// [`INVARIANTS`] order (`None`: every value on this side held).
    pub first_break: Option<(f64, Vec<String>)>,
}

/// One configuration's verdict along one dimension: from the base value down and up, the last
/// value where every invariant holds and the first where one breaks, and which.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Backend and configuration label.
    pub config: String,
    /// Dimension name.
    pub dimension: String,
    /// The base value.
    pub base: f64,
    /// Going from the base to smaller values.
    pub down: Edge,
    /// Going from the base to larger values.
    pub up: Edge,
}

/// The invariants that broke among `rows` (one value's rows of one configuration), in
/// [`INVARIANTS`] order, then any other in the order the rows name it.
fn broken(rows: &[&StressRow]) -> Vec<String> {
    let mut seen: HashSet<&str> = HashSet::new();
    let mut out: Vec<String> = Vec::new();
    for i in INVARIANTS {
        if rows.iter().any(|r| !r.holds && r.invariant == *i) {
            seen.insert(i);
            out.push(i.to_string());
        }
    }
    // An invariant another backend's rows name (none yet) after the known ones.
    for r in rows.iter().filter(|r| !r.holds) {
        if seen.insert(&r.invariant) {
            out.push(r.invariant.clone());
        }
    }
    out
}

/// Walks `values` (ordered away from the base, the base first) and finds the edge.
fn edge(values: &[f64], broken_at: impl Fn(f64) -> Vec<String>) -> Edge {
    let mut last = None;
    for &v in values {
        let b = broken_at(v);
        if !b.is_empty() {
            return Edge {
                last_holding: last,
                first_break: Some((v, b)),
            };
        }
        last = Some(v);
    }
    Edge {
        last_holding: last,
        first_break: None,
    }
}

/// Each configuration's verdict along each dimension of [`dimensions`], from the one-dimension
/// rows of `rows` (in the order the configurations and dimensions first appear).
pub fn verdicts(rows: &[StressRow]) -> Vec<Verdict> {
    let dims = dimensions();
    let mut out = Vec::new();
    for g in one_dimension_groups(rows) {
        let Some(d) = dims.iter().find(|d| d.name == g.dimension) else {
            continue;
        };
        let at = ByValue::of(&g.rows);
        let values = sorted_values(g.rows.iter().map(|r| r.value));
        let broken_at = |v: f64| broken(at.at(v));
        let base = if values.contains(&d.base) {
            d.base
        } else {
            values.first().copied().unwrap_or(d.base)
        };
        let mut down: Vec<f64> = values.iter().copied().filter(|&v| v <= base).collect();
        down.reverse();
        let up: Vec<f64> = values.iter().copied().filter(|&v| v >= base).collect();
        out.push(Verdict {
            config: g.config.clone(),
            dimension: g.dimension.to_string(),
            base,
            down: edge(&down, broken_at),
            up: edge(&up, broken_at),
        });
    }
    out
}

impl Verdict {
    /// The verdict in words: `holds to 1e6; breaks at 1e7 (stable_rest, progress)`, `holds
    /// from 1e-4 to 0.05; breaks at 0.2 (penetration)`, or `breaks at the base case 0.0167
    /// (carry_no_drift)`.
    pub fn text(&self) -> String {
        let f = format_setting;
        let names = |b: &[String]| b.join(", ");
        match (self.down.last_holding, self.up.last_holding) {
            (None, _) | (_, None) => {
                let b = self
                    .up
                    .first_break
                    .as_ref()
                    .or(self.down.first_break.as_ref())
                    .map_or(String::new(), |(_, b)| names(b));
                format!("breaks at the base case {} ({b})", f(self.base))
            }
            (Some(lo), Some(hi)) => {
                let mut t = if lo == hi {
                    format!("holds at {}", f(lo))
                } else if lo == self.base {
                    format!("holds to {}", f(hi))
                } else {
                    format!("holds from {} to {}", f(lo), f(hi))
                };
                for (v, b) in [&self.down.first_break, &self.up.first_break]
                    .into_iter()
                    .flatten()
                {
                    t.push_str(&format!("; breaks at {} ({})", f(*v), names(b)));
                }
                t
            }
        }
    }
}

/// How far from the world's origin a configuration holds: its `offset` rows walked out from 0
/// as a [`Verdict`] walks them, with the invariants that already broke at offset 0 set aside
/// (they break for a reason other than the distance, such as Rapier's carry), so that an f32
/// and an f64 build of one set-up compare on what the distance alone breaks.
#[derive(Clone, Debug, PartialEq)]
pub struct Reach {
    /// Backend and configuration label.
    pub config: String,
    /// The invariants broken at offset 0, set aside, in [`INVARIANTS`] order.
    pub at_origin: Vec<String>,
    /// From offset 0 outwards: the last offset where every other invariant held, and the first
    /// where one broke.
    pub edge: Edge,
}

impl Reach {
    /// `holds to 1e13; breaks at 1e14 (progress); set aside, broken at 0: carry_no_drift`.
    pub fn text(&self) -> String {
        let f = format_setting;
        let mut t = match (self.edge.last_holding, &self.edge.first_break) {
            (Some(v), _) => format!("holds to {}", f(v)),
            (None, _) => "breaks at 0".to_string(),
        };
        if let Some((v, b)) = &self.edge.first_break {
            if self.edge.last_holding.is_some() {
                t.push_str(&format!("; breaks at {} ({})", f(*v), b.join(", ")));
            } else {
                t.push_str(&format!(" ({})", b.join(", ")));
            }
        }
        if !self.at_origin.is_empty() {
            t.push_str(&format!(
                "; set aside, broken at 0: {}",
                self.at_origin.join(", ")
            ));
        }
        t
    }
}

/// Each configuration's [`Reach`], from the one-dimension `offset` rows of `rows`.
pub fn reach(rows: &[StressRow]) -> Vec<Reach> {
    one_dimension_groups(rows)
        .into_iter()
        .filter(|g| g.dimension == "offset")
        .map(|g| {
            let at = ByValue::of(&g.rows);
            let at_origin = broken(at.at(0.0));
            let aside: HashSet<&str> = at_origin.iter().map(String::as_str).collect();
            let values = sorted_values(g.rows.iter().map(|r| r.value).filter(|&v| v >= 0.0));
            let edge = edge(&values, |v| {
                broken(at.at(v))
                    .into_iter()
                    .filter(|i| !aside.contains(i.as_str()))
                    .collect()
            });
            Reach {
                config: g.config,
                at_origin,
                edge,
            }
        })
        .collect()
}

/// One combination cell of one configuration: the first invariant (in [`INVARIANTS`] order)
/// that broke there, or `None` where every invariant held.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Backend and configuration label.
    pub config: String,
    /// The pair, as `offset x epsilon`.
    pub pair: String,
    /// The first dimension's value.
    pub a: f64,
    /// The second dimension's value.
    pub b: f64,
    /// The invariants that broke, in [`INVARIANTS`] order (empty: every one held).
    pub broken: Vec<String>,
}

/// The combination cells of `rows`, in the order they first appear.
pub fn cells(rows: &[StressRow]) -> Vec<Cell> {
    let mut out: Vec<Cell> = Vec::new();
    // Each cell by its configuration, pair and values ([`value_key`]: a NaN value's row is a
    // cell of its own, as `==` matches it to none).
    let mut index: HashMap<(String, String, u64, u64), usize> = HashMap::new();
    for r in rows.iter().filter(|r| !r.dimension2.is_empty()) {
        let config = format!("{} {}", r.backend, r.config);
        let pair = format!("{} x {}", r.dimension, r.dimension2);
        let b = r.value2.unwrap_or(f64::NAN);
        let key = value_key(r.value)
            .zip(value_key(b))
            .map(|(ka, kb)| (config.clone(), pair.clone(), ka, kb));
        let i = match key.as_ref().and_then(|k| index.get(k)) {
            Some(&i) => i,
            None => {
                out.push(Cell {
                    config,
                    pair,
                    a: r.value,
                    b,
                    broken: Vec::new(),
                });
                if let Some(k) = key {
                    index.insert(k, out.len() - 1);
                }
                out.len() - 1
            }
        };
        if !r.holds {
            out[i].broken.push(r.invariant.clone());
        }
    }
    for c in &mut out {
        let order = |i: &String| INVARIANTS.iter().position(|k| k == i).unwrap_or(usize::MAX);
        c.broken.sort_by_key(order);
    }
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    fn row(value: f64, invariant: &str, holds: bool) -> StressRow {
        StressRow {
            backend: "b".into(),
            config: "c".into(),
            dimension: "offset".into(),
            value,
            dimension2: String::new(),
            value2: None,
            invariant: invariant.into(),
            holds,
            measured: 0.0,
            tolerance: 0.0,
        }
    }

    #[test]
    fn envelope_names_each_broken_invariant_and_keeps_only_values_where_all_held() {
        let rows = [
            row(0.0, "finite", true),
            row(0.0, "carry_no_drift", false),
            row(1.0, "finite", true),
            row(1.0, "carry_no_drift", true),
            row(2.0, "finite", false),
            row(2.0, "carry_no_drift", false),
        ];
        let e = envelope(&rows);
        assert_eq!(e.len(), 1);
        assert_eq!(e[0].holds, vec![1.0]);
        assert_eq!(
            e[0].breaks,
            vec![
                ("carry_no_drift".to_string(), vec![0.0, 2.0]),
                ("finite".to_string(), vec![2.0])
            ]
        );
        assert_eq!(e[0].broken_values(), vec![0.0, 2.0]);
    }

    /// A one-dimension row of configuration `b c`.
    pub(in crate::stress) fn at(
        dimension: &str,
        value: f64,
        invariant: &str,
        holds: bool,
    ) -> StressRow {
        StressRow {
            dimension: dimension.into(),
            ..row(value, invariant, holds)
        }
    }

    #[test]
    fn verdict_walks_out_from_the_base_value_on_each_side() {
        // dt: base 1/60; 1e-4 breaks progress, 0.2 breaks penetration; 1/240 and 0.05 hold.
        let mut rows = Vec::new();
        for v in [1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.05, 0.2] {
            rows.push(at("dt", v, "penetration", v != 0.2));
            rows.push(at("dt", v, "progress", v != 1e-4));
        }
        let v = &verdicts(&rows)[0];
        assert_eq!(v.base, 1.0 / 60.0);
        assert_eq!(v.down.last_holding, Some(1.0 / 240.0));
        assert_eq!(
            v.down.first_break,
            Some((1e-4, vec!["progress".to_string()]))
        );
        assert_eq!(v.up.last_holding, Some(0.05));
        assert_eq!(
            v.text(),
            "holds from 0.0042 to 0.05; breaks at 1e-4 (progress); breaks at 0.2 (penetration)"
        );
        // Broken at the base: named as such, whatever holds farther out.
        let rows = [
            at("offset", 0.0, "carry_no_drift", false),
            at("offset", 1e3, "carry_no_drift", true),
        ];
        assert_eq!(
            verdicts(&rows)[0].text(),
            "breaks at the base case 0 (carry_no_drift)"
        );
    }

    #[test]
    fn reach_sets_aside_what_broke_at_the_origin() {
        // carry breaks everywhere; progress from 1e14 on; penetration only at 1e15.
        let mut rows = Vec::new();
        for v in [0.0, 1e7, 1e13, 1e14, 1e15] {
            rows.push(at("offset", v, "carry_no_drift", false));
            rows.push(at("offset", v, "progress", v < 1e14));
            rows.push(at("offset", v, "penetration", v < 1e15));
        }
        let r = &reach(&rows)[0];
        assert_eq!(r.at_origin, vec!["carry_no_drift".to_string()]);
        assert_eq!(r.edge.last_holding, Some(1e13));
        assert_eq!(
            r.text(),
            "holds to 1e13; breaks at 1e14 (progress); set aside, broken at 0: carry_no_drift"
        );
        // The verdict itself still reads the break at the base case.
        assert!(verdicts(&rows)[0]
            .text()
            .starts_with("breaks at the base case"));
    }
}

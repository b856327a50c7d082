//! The stress matrix's world verdict: whether a configuration holds in a world of a given size,
//! from its offsets alone and the combination cells within that size, in words.

use std::collections::HashMap;

use super::definition::format_setting;
use super::execution::StressRow;
use super::verdicts::{reach, verdicts, Edge};

/// Whether a configuration holds in a world `size` tiles across (positions up to `size` tiles
/// from the origin), read from its `offset` rows.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldVerdict {
    /// Backend and configuration label.
    pub config: String,
    /// `Some(true)`: every invariant held at every measured offset up to the first one at or
    /// past `size`, and in every combination cell with an offset within `size`; `Some(false)`:
    /// one broke at a measured offset within `size`, or in such a combination cell; `None`:
    /// held at every measured offset and cell within `size`, broke at the next offset past it,
    /// so the offsets between were not measured.
    pub holds: Option<bool>,
    /// The verdict in words, naming the offsets and invariants (for one broken at offset 0, how
    /// far those that held there hold, [`reach`]).
    pub text: String,
    /// The combination cells with an offset within `size` where an invariant broke, as
    /// `offset x dt at (1e5, 1e-4): progress`.
    pub combinations: Vec<String>,
}

/// Which configurations hold in a world `size` tiles across: each configuration's `offset` rows
/// (the base case elsewhere), and the combination cells within that offset that broke (any one
/// of them is a break in that world).
pub fn world_verdicts(rows: &[StressRow], size: f64) -> Vec<WorldVerdict> {
    let f = format_setting;
    let reaches = reach(rows);
    // Each configuration's reach, offsets and broken combination cells at an offset, found
    // once (by `backend config`), so the verdicts take time in proportion to the rows.
    let reach_of: HashMap<&str, &super::verdicts::Reach> = reaches
        .iter()
        .rev()
        .map(|r| (r.config.as_str(), r))
        .collect();
    let mut offsets: HashMap<String, Vec<f64>> = HashMap::new();
    let mut broken_cells: HashMap<String, Vec<&StressRow>> = HashMap::new();
    for r in rows.iter().filter(|r| r.dimension == "offset") {
        let config = format!("{} {}", r.backend, r.config);
        if r.dimension2.is_empty() {
            offsets.entry(config).or_default().push(r.value);
        } else if !r.holds {
            broken_cells.entry(config).or_default().push(r);
        }
    }
    let mut out = Vec::new();
    for v in verdicts(rows)
        .into_iter()
        .filter(|v| v.dimension == "offset")
    {
        let mut values: Vec<f64> = offsets.get(&v.config).cloned().unwrap_or_default();
        values.sort_by(f64::total_cmp);
        values.dedup();
        let cover = values.iter().copied().find(|&x| x >= size);
        let first_break = v.up.first_break.clone();
        let (holds, text) = match (&first_break, cover) {
            (Some((b, inv)), _) if *b <= size => {
                let mut t = format!("breaks at offset {} ({})", f(*b), inv.join(", "));
                // Broken at the origin already: how far the others hold ([`reach`]), so that
                // an f32 and an f64 build still read apart.
                if *b == 0.0 {
                    if let Some(r) = reach_of.get(v.config.as_str()) {
                        let aside = |e: &Edge| match (e.last_holding, &e.first_break) {
                            (Some(l), Some((x, i))) => format!(
                                "; those that held at 0 hold to {}, break at {} ({})",
                                f(l),
                                f(*x),
                                i.join(", ")
                            ),
                            (Some(l), None) => format!("; those that held at 0 hold to {}", f(l)),
                            (None, _) => String::new(),
                        };
                        t.push_str(&aside(&r.edge));
                    }
                }
                (Some(false), t)
            }
            (Some((b, inv)), Some(c)) if *b == c => (
                None,
                format!(
                    "holds to offset {}, breaks at {} ({}); {} itself not measured",
                    v.up.last_holding.map_or("-".into(), f),
                    f(*b),
                    inv.join(", "),
                    f(size)
                ),
            ),
            (_, Some(c)) => (
                Some(true),
                format!("holds at every offset measured up to {}", f(c)),
            ),
            (_, None) => (
                None,
                format!(
                    "holds to offset {}, the largest measured; {} not measured",
                    v.up.last_holding.map_or("-".into(), f),
                    f(size)
                ),
            ),
        };
        let mut combinations: Vec<(String, Vec<String>)> = Vec::new();
        let mut cell_at: HashMap<String, usize> = HashMap::new();
        let within = broken_cells.get(&v.config).into_iter().flatten();
        for r in within.filter(|r| r.value <= size) {
            let cell = format!(
                "{} x {} at ({}, {})",
                r.dimension,
                r.dimension2,
                f(r.value),
                r.value2.map_or("-".into(), f)
            );
            match cell_at.get(&cell) {
                Some(&i) => combinations[i].1.push(r.invariant.clone()),
                None => {
                    cell_at.insert(cell.clone(), combinations.len());
                    combinations.push((cell, vec![r.invariant.clone()]));
                }
            }
        }
        // A cell within the world that breaks is a break within it: the world's positions
        // reach that offset, and the cell's other value (a dt, a speed, an epsilon) is one the
        // matrix holds alone at the base case.
        // Broken already (at the origin, say): the cells that break an invariant that held
        // there are still said, so a configuration broken at 0 does not read sturdier than one
        // that is not.
        let at_origin: std::collections::HashSet<&str> = reach_of
            .get(v.config.as_str())
            .map(|r| r.at_origin.iter().map(String::as_str).collect())
            .unwrap_or_default();
        let more = combinations
            .iter()
            .filter(|(_, inv)| inv.iter().any(|i| !at_origin.contains(i.as_str())))
            .count();
        let cells = |n: usize| {
            let (noun, verb) = if n == 1 { ("", "s") } else { ("s", "") };
            format!("{n} combination cell{noun} within it break{verb}")
        };
        let (holds, text) = match (holds, combinations.len()) {
            (Some(false), _) if more > 0 => (holds, format!("{text}; and {} more", cells(more))),
            (Some(false), _) | (_, 0) => (holds, text),
            (_, n) => (Some(false), format!("{text}; but {}", cells(n))),
        };
        out.push(WorldVerdict {
            config: v.config.clone(),
            holds,
            text,
            combinations: combinations
                .into_iter()
                .map(|(c, inv)| format!("{c}: {}", inv.join(", ")))
                .collect(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stress::verdicts::tests::at;

    #[test]
    fn world_verdict_needs_the_first_offset_past_the_world_to_hold() {
        let rows: Vec<StressRow> = [0.0, 1e5, 1e6, 1e7]
            .iter()
            .map(|&v| at("offset", v, "progress", v < 1e7))
            .chain([StressRow {
                dimension2: "dt".into(),
                value2: Some(1e-3),
                ..at("offset", 1e5, "jump_height", false)
            }])
            .collect();
        let w = |size| world_verdicts(&rows, size).remove(0);
        // Without the combination cell: the offsets alone decide.
        let alone: Vec<StressRow> = rows[..4].to_vec();
        let a = |size| world_verdicts(&alone, size).remove(0).holds;
        assert_eq!(a(1e6), Some(true));
        assert_eq!(a(5e5), Some(true));
        // 5e6: 1e6 held, 1e7 broke; between them nothing was measured.
        assert_eq!(a(5e6), None);
        assert_eq!(a(1e7), Some(false));
        // The cell at offset 1e5 broke: every world that reaches 1e5 breaks, whatever its
        // offsets alone say; a world within 1e4 does not reach it.
        for size in [1e5, 5e5, 1e6, 5e6, 1e7] {
            assert_eq!(w(size).holds, Some(false), "{size}");
        }
        assert_eq!(
            w(1e6).text,
            "holds at every offset measured up to 1e6; but 1 combination cell within it breaks"
        );
        assert_eq!(
            w(1e6).combinations,
            vec!["offset x dt at (1e5, 0.001): jump_height"]
        );
        assert_eq!(w(1e4).holds, Some(true));
        assert!(w(1e4).combinations.is_empty());
        // Broken at the origin (the carry): the invariants that held there are followed out.
        let rows: Vec<StressRow> = [0.0, 1e5, 1e14]
            .iter()
            .flat_map(|&v| {
                [
                    at("offset", v, "carry_no_drift", false),
                    at("offset", v, "progress", v < 1e14),
                ]
            })
            .collect();
        assert_eq!(
            world_verdicts(&rows, 1e5)[0].text,
            "breaks at offset 0 (carry_no_drift); those that held at 0 hold to 1e5, break at 1e14 (progress)"
        );
        // A cell within the world that breaks another invariant is said too (without it, Rapier f64
        // read sturdier than the f64 sweep); one that breaks only the carry again is not news.
        let mut more = rows.clone();
        more.push(StressRow {
            dimension2: "dt".into(),
            value2: Some(1e-4),
            ..at("offset", 1e5, "progress", false)
        });
        more.push(StressRow {
            dimension2: "dt".into(),
            value2: Some(1e-3),
            ..at("offset", 1e5, "carry_no_drift", false)
        });
        assert_eq!(
            world_verdicts(&more, 1e5)[0].text,
            "breaks at offset 0 (carry_no_drift); those that held at 0 hold to 1e5, break at 1e14 (progress); and 1 combination cell within it breaks more"
        );
    }
}

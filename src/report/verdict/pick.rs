//! A profile's pick: the eligible configuration with the lowest weighted error, the runner-up,
//! what decided between them, and what the pick still gets wrong.

use super::{Grade, Scorecard, Worst};
use crate::metrics::registry::Behaviour;
use crate::report::profile::{Need, Profile};

/// Two weighted errors closer than this tie (then the earlier configuration in run order is
/// picked): far below any difference one scenario's metric can make.
const TIE: f64 = 1e-9;

/// One behaviour that separates the pick from the runner-up, or that the pick gets wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct Reason {
    /// The behaviour.
    pub behaviour: Behaviour,
    /// The pick's grade on it (`None`: not run).
    pub pick: Option<Grade>,
    /// The other configuration's grade (`None`: not run), for a decider.
    pub other: Option<Grade>,
    /// The row that set the grade that matters: the other's worst for a decider, the pick's
    /// for what it still gets wrong.
    pub worst: Option<Worst>,
    /// The profile's weight times the difference in error (a decider), or the pick's error.
    pub size: f64,
}

/// A profile's verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileVerdict {
    /// The profile.
    pub profile: Profile,
    /// The pick (a card index) and its weighted error.
    pub pick: Option<(usize, f64)>,
    /// The runner-up: the best eligible configuration of another backend (or of the same, when
    /// no other backend is eligible) and its weighted error.
    pub runner_up: Option<(usize, f64)>,
    /// Up to three behaviours where the pick beats the runner-up the most, by weighted error.
    pub why: Vec<Reason>,
    /// Weighted behaviours the pick does not keep its promise on.
    pub still_wrong: Vec<Reason>,
    /// Why nothing was picked, when nothing was.
    pub no_pick: Option<String>,
    /// Configurations left out, each with why (a need not met).
    pub left_out: Vec<(usize, String)>,
    /// Weighted behaviours no configuration ran (not counted).
    pub unmeasured: Vec<Behaviour>,
    /// Configurations that tie with the pick (same failed weight, weighted errors within
    /// 1e-9): nothing this run measures separates them, and the pick is only the first in run
    /// order.
    pub tied: Vec<usize>,
    /// Each ranked configuration's weight of failed behaviours (see `failed_weight`).
    pub failed: Vec<(usize, f64)>,
}

/// Configuration `c`'s weighted error over the measured behaviours `profile` weighs.
pub fn weighted_error(card: &Scorecard, profile: &Profile, c: usize) -> f64 {
    let (mut sum, mut weights) = (0.0, 0.0);
    for (b, w) in &profile.weights {
        let s = match b {
            Behaviour::Cost => match card.cost_score(c) {
                Some(s) => s,
                None => continue,
            },
            b => match card.score(c, *b) {
                Some(s) => s,
                None => continue,
            },
        };
        sum += w * s;
        weights += w;
    }
    if weights > 0.0 {
        sum / weights
    } else {
        0.0
    }
}

/// The weight of the behaviours `profile` weighs that configuration `c` fails, or did not run
/// where another configuration did (a skipped behaviour is not credited).
pub fn failed_weight(card: &Scorecard, profile: &Profile, c: usize) -> f64 {
    profile
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
        .map(|(_, w)| *w)
        .sum()
}

/// The verdict of `profile` on `card`.
pub fn pick(card: &Scorecard, profile: &Profile) -> ProfileVerdict {
    let mut v = ProfileVerdict {
        profile: profile.clone(),
        pick: None,
        runner_up: None,
        why: Vec::new(),
        still_wrong: Vec::new(),
        no_pick: None,
        left_out: Vec::new(),
        unmeasured: Vec::new(),
        tied: Vec::new(),
        failed: Vec::new(),
    };
    // What the run measured of what the profile weighs.
    let measured = |b: Behaviour| match b {
        Behaviour::Cost => card.cards.iter().any(|c| c.median_cost().is_some()),
        b => card.scenarios.get(&b).is_some_and(|n| *n > 0),
    };
    for (b, _) in &profile.weights {
        if !measured(*b) {
            v.unmeasured.push(*b);
        }
    }
    if v.unmeasured.len() == profile.weights.len() {
        v.no_pick = Some("nothing this profile weighs was measured by this run".into());
        return v;
    }
    for need in &profile.needs {
        if let Need::Feature(b) = need {
            if !measured(*b) {
                v.no_pick = Some(format!(
                    "it needs {} and no level of this run has them",
                    need.name()
                ));
                return v;
            }
        }
    }
    // Eligibility: every need met, run or declared.
    let mut eligible = Vec::new();
    for (i, c) in card.cards.iter().enumerate() {
        let mut missing = Vec::new();
        for need in &profile.needs {
            match need {
                Need::Feature(b) => {
                    let skipped = card.skipped(i, *b);
                    if !skipped.is_empty() {
                        missing.push(format!("skipped {}", skipped.join(", ")));
                    }
                }
                n => {
                    let f = &c.facts;
                    if !n.declared_by(f.features, f.precision, f.capabilities) {
                        missing.push(format!("does not declare {}", n.name()));
                    }
                }
            }
        }
        if missing.is_empty() {
            eligible.push(i);
        } else {
            v.left_out.push((i, missing.join("; ")));
        }
    }
    if eligible.is_empty() {
        v.no_pick = Some(if profile.needs.contains(&Need::F64Positions) {
            "no configuration of this run meets its needs (`--precision f32,f64` adds the f64 builds; `platbench stress` measures how far from the origin each stays exact)".into()
        } else {
            "no configuration of this run meets its needs".into()
        });
        return v;
    }
    if v.unmeasured.contains(&Behaviour::Cost) {
        v.no_pick = Some(
            "cost decides this profile and this run did not time it: run `platbench run --timing`"
                .into(),
        );
        return v;
    }
    let mut ranked: Vec<(usize, f64)> = eligible
        .iter()
        .map(|&c| (c, weighted_error(card, profile, c)))
        .collect();
    // First the weight of the behaviours a configuration fails (or did not run), then the
    // weighted error: a FAIL on what the profile weighs is not averaged away by many rows that
    // are right. Stable: ties keep run order, and are said as ties.
    let failed = |c: usize| failed_weight(card, profile, c);
    ranked.sort_by(|a, b| {
        failed(a.0)
            .total_cmp(&failed(b.0))
            .then(if (a.1 - b.1).abs() <= TIE {
                std::cmp::Ordering::Equal
            } else {
                a.1.total_cmp(&b.1)
            })
    });
    let (p, ps) = ranked[0];
    v.pick = Some((p, ps));
    let same = |c: usize, e: f64| failed(c) == failed(p) && (e - ps).abs() <= TIE;
    v.tied = ranked[1..]
        .iter()
        .filter(|(c, e)| same(*c, *e))
        .map(|(c, _)| *c)
        .collect();
    let backend = |c: usize| card.cards[c].facts.backend.as_str();
    v.runner_up = ranked
        .iter()
        .skip(1)
        .find(|(c, _)| backend(*c) != backend(p))
        .or_else(|| ranked.get(1))
        .copied();
    v.failed = ranked.iter().map(|(c, _)| (*c, failed(*c))).collect();
    let grade = |c: usize, b: Behaviour| card.cards[c].cells.get(&b).and_then(|x| x.grade());
    let worst = |c: usize, b: Behaviour| {
        card.cards[c]
            .cells
            .get(&b)
            .and_then(|x| x.worst.clone())
            .filter(|w| w.grade != Grade::Keeps)
    };
    if let Some((r, _)) = v.runner_up.filter(|(r, _)| !v.tied.contains(r)) {
        let mut why: Vec<Reason> = profile
            .weights
            .iter()
            .filter(|(b, _)| *b != Behaviour::Cost)
            .filter_map(|(b, w)| {
                let d = w * (card.score(r, *b)? - card.score(p, *b)?);
                // Under the same grade, a difference below 1% of "clearly off" is rounding,
                // not a reason.
                let said = grade(p, *b) != grade(r, *b) || d >= 0.01 * w;
                (d > TIE && said).then(|| Reason {
                    behaviour: *b,
                    pick: grade(p, *b),
                    other: grade(r, *b),
                    worst: worst(r, *b),
                    size: d,
                })
            })
            .collect();
        if profile.weight(Behaviour::Cost) > 0.0 {
            if let (Some(a), Some(b)) = (card.cost_score(p), card.cost_score(r)) {
                let d = profile.weight(Behaviour::Cost) * (b - a);
                if d > TIE {
                    why.push(Reason {
                        behaviour: Behaviour::Cost,
                        pick: None,
                        other: None,
                        worst: None,
                        size: d,
                    });
                }
            }
        }
        // A FAIL the pick avoids first (what ranks it), then by weighted error, same grades
        // included: the behaviour that moved the error most is said even when both fail it.
        let fails = |r: &Reason| r.other == Some(Grade::Fails) && r.pick != Some(Grade::Fails);
        why.sort_by(|a, b| fails(b).cmp(&fails(a)).then(b.size.total_cmp(&a.size)));
        why.truncate(3);
        v.why = why;
    }
    for (b, _) in &profile.weights {
        if *b == Behaviour::Cost {
            continue;
        }
        let g = grade(p, *b);
        if g.is_some_and(|g| g != Grade::Keeps) {
            v.still_wrong.push(Reason {
                behaviour: *b,
                pick: g,
                other: None,
                worst: worst(p, *b),
                size: card.score(p, *b).unwrap_or(0.0),
            });
        }
    }
    v.still_wrong
        .sort_by(|a, b| b.pick.cmp(&a.pick).then(b.size.total_cmp(&a.size)));
    v
}

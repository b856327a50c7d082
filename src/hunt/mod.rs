//! Hunting for the scenario nobody wrote: generated levels and input scripts (`generate`) run
//! on every selected configuration and checked against invariants that hold for any controller
//! ([`INVARIANTS`]); each failure is shrunk (`shrink`) to a small level that still fails the
//! same invariant on the same configuration, and handed over as a level file in platbench's
//! own format ([`Finding::toml`]).
//!
//! Cases are drawn in rounds of [`ROUND`] from the seed, each from a random stream of its own,
//! and run on threads with their results taken in order: the findings are the same for a seed
//! whatever the number of threads. `budget` stops new rounds and cuts a shrink short (said in
//! its finding); `cases` bounds the rounds instead, for a run that is the same everywhere.

mod generate;
mod invariants;
mod shrink;
mod sketch;

use std::collections::{BTreeMap, HashSet};
use std::time::{Duration, Instant};

pub use invariants::{Violation, INVARIANTS};

use crate::config::RunConfig;
use crate::metrics::evaluate;
use crate::parallel::for_each_ordered;
use sketch::Sketch;

/// The most tiles a generated level holds (its largest width and height): what each thread of
/// a hunt builds a world of.
pub(crate) const LEVEL_TILES: u64 = (generate::ranges::WIDTH.1 * generate::ranges::HEIGHT.1) as u64;

/// Cases per round: fixed, so a seed's findings do not depend on the number of threads.
pub const ROUND: u64 = 8;

/// What to hunt with.
#[derive(Clone, Debug)]
pub struct HuntOptions {
    /// The seed every case is drawn from.
    pub seed: u64,
    /// No new round starts after this long, and a shrink still running is cut short.
    pub budget: Duration,
    /// Run at most this many cases (rounded up to whole rounds); `None`: until the budget.
    pub cases: Option<u64>,
    /// Threads to run on.
    pub jobs: usize,
    /// Findings kept per configuration and invariant: later failures of a kind already found
    /// this often are counted, not shrunk.
    pub per_kind: usize,
}

impl Default for HuntOptions {
    fn default() -> Self {
        HuntOptions {
            seed: 0,
            budget: Duration::from_secs(60),
            cases: None,
            jobs: crate::parallel::default_jobs(),
            per_kind: 3,
        }
    }
}

/// A failure, shrunk.
#[derive(Clone, Debug)]
pub struct Finding {
    /// The configuration's backend.
    pub backend: String,
    /// The configuration's label.
    pub config: String,
    /// The broken invariant on the shrunk level.
    pub violation: Violation,
    /// The seed.
    pub seed: u64,
    /// The generated case it was shrunk from.
    pub case: u64,
    /// The level's name, also its file's stem.
    pub name: String,
    /// The level file, with its header comment.
    pub toml: String,
    /// Size of the generated level: width, height (tiles), non-empty tiles, platforms, events.
    pub generated: [usize; 5],
    /// The same of the shrunk level.
    pub shrunk: [usize; 5],
    /// The shrunk scenario's length, s.
    pub duration: f32,
    /// Candidates run to shrink it.
    pub tries: usize,
    /// Whether the shrink stopped before a fixed point (the tries or the budget ran out).
    pub cut_short: bool,
}

/// Where a hunt stands.
#[derive(Clone, Debug, Default)]
pub struct Progress {
    /// Cases generated.
    pub cases: u64,
    /// Runs (cases times the configurations that model them).
    pub runs: u64,
    /// Case and configuration pairs not run: the configuration does not model the level's
    /// features (an external controller without ladders), or refused it.
    pub skipped: u64,
    /// Runs that broke an invariant.
    pub failures: u64,
    /// Findings so far.
    pub findings: usize,
    /// Time since the start.
    pub elapsed: Duration,
}

/// What a hunt found.
#[derive(Clone, Debug, Default)]
pub struct HuntOutcome {
    /// The findings, in the order they were found.
    pub findings: Vec<Finding>,
    /// Where it stopped.
    pub progress: Progress,
    /// Failing runs per (backend, configuration, invariant), shrunk or not.
    pub failures: BTreeMap<(String, String, &'static str), u64>,
}

fn size(s: &Sketch) -> [usize; 5] {
    [
        s.width(),
        s.height(),
        s.tiles(),
        s.platforms.len(),
        s.events.len(),
    ]
}

/// Runs `sketch` on `run` and returns the invariants it breaks; `None` when it does not run:
/// the configuration does not model the level (its features) or the level does not parse.
fn run_case(sketch: &Sketch, run: &RunConfig) -> Option<Vec<Violation>> {
    let level = sketch.level("hunt_case").ok()?;
    let spec = &level.scenarios[0];
    if !crate::backend::runs_scenario(&*run.backend, &level, spec) {
        return None;
    }
    Some(match evaluate(&level, spec, run) {
        Ok(e) => invariants::check(&level, spec, run, &e),
        Err(e) if e.is_unsupported() => return None,
        Err(e) => vec![Violation {
            invariant: "runs",
            metric: String::new(),
            value: 1.0,
            bound: 0.0,
            frame: None,
            detail: e.to_string(),
        }],
    })
}

/// [`run_case`], with a case that does not run breaking nothing.
fn violations(sketch: &Sketch, run: &RunConfig) -> Vec<Violation> {
    run_case(sketch, run).unwrap_or_default()
}

/// A file-name-safe form of a configuration label.
fn slug(label: &str) -> String {
    let s: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    s.split('-')
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("-")
}

/// Hunts on `runs` with `options`; calls `progress` after every round and `found` on each new
/// finding, in order. `reproduce(file, run)` gives the command line that reproduces a finding
/// written to `file` (the caller knows how its controllers are selected).
pub fn hunt(
    runs: &[RunConfig],
    options: &HuntOptions,
    reproduce: &(dyn Fn(&str, &RunConfig) -> String + Sync),
    mut progress: impl FnMut(&Progress),
    mut found: impl FnMut(&Finding),
) -> HuntOutcome {
    let started = Instant::now();
    let out_of_time = || started.elapsed() >= options.budget;
    let mut outcome = HuntOutcome::default();
    let mut seen: HashSet<(usize, &'static str, String)> = HashSet::new();
    let mut per_kind: BTreeMap<(usize, &'static str), usize> = BTreeMap::new();
    let mut names: BTreeMap<String, usize> = BTreeMap::new();
    let mut round = 0u64;
    while !out_of_time() && options.cases.is_none_or(|n| round * ROUND < n) && !runs.is_empty() {
        let first = round * ROUND;
        round += 1;
        // Every case of the round on every configuration.
        let n = ROUND as usize * runs.len();
        let mut failing: Vec<(u64, usize, Violation)> = Vec::new();
        let _ = for_each_ordered(
            options.jobs,
            n,
            || (),
            |(), k| {
                let case = first + (k / runs.len()) as u64;
                let sketch = generate::generate(options.seed, case);
                (
                    case,
                    k % runs.len(),
                    run_case(&sketch, &runs[k % runs.len()]),
                )
            },
            |_, (case, c, vs)| -> Result<(), ()> {
                let Some(vs) = vs else {
                    outcome.progress.skipped += 1;
                    return Ok(());
                };
                outcome.progress.runs += 1;
                if !vs.is_empty() {
                    outcome.progress.failures += 1;
                }
                for v in vs {
                    let key = (
                        runs[c].backend.backend().to_string(),
                        runs[c].label.clone(),
                        v.invariant,
                    );
                    *outcome.failures.entry(key).or_default() += 1;
                    let kind = per_kind.entry((c, v.invariant)).or_default();
                    if *kind < options.per_kind {
                        *kind += 1;
                        failing.push((case, c, v));
                    }
                }
                Ok(())
            },
        );
        outcome.progress.cases += ROUND;
        // Shrink the round's new failures, in order.
        let shrunk: Vec<Option<Finding>> = {
            let mut v = Vec::new();
            let _ = for_each_ordered(
                options.jobs,
                failing.len(),
                || (),
                |(), k| {
                    let (case, c, ref v) = failing[k];
                    shrink_one(
                        options.seed,
                        case,
                        &runs[c],
                        v.invariant,
                        reproduce,
                        &out_of_time,
                    )
                },
                |_, f| -> Result<(), ()> {
                    v.push(f);
                    Ok(())
                },
            );
            v
        };
        for (f, (_, c, v)) in shrunk.into_iter().zip(&failing) {
            let Some(mut f) = f else { continue };
            let body = f
                .toml
                .lines()
                .filter(|l| !l.starts_with('#'))
                .collect::<String>();
            if !seen.insert((*c, v.invariant, body)) {
                // The same shrunk failure again: counted, not reported twice.
                if let Some(k) = per_kind.get_mut(&(*c, v.invariant)) {
                    *k -= 1;
                }
                continue;
            }
            let n = names.entry(f.name.clone()).or_default();
            *n += 1;
            let name = format!("{}-{n}", f.name);
            f.toml = f.toml.replace(&f.name, &name);
            f.name = name;
            found(&f);
            outcome.findings.push(f);
        }
        outcome.progress.findings = outcome.findings.len();
        outcome.progress.elapsed = started.elapsed();
        progress(&outcome.progress);
    }
    outcome.progress.elapsed = started.elapsed();
    outcome
}

/// Shrinks case `case`'s failure of `invariant` on `run` and writes it up; `None` if the
/// failure does not come back when the case is run again (it always should: runs are
/// deterministic).
fn shrink_one(
    seed: u64,
    case: u64,
    run: &RunConfig,
    invariant: &'static str,
    reproduce: &(dyn Fn(&str, &RunConfig) -> String + Sync),
    out_of_time: &(dyn Fn() -> bool + Sync),
) -> Option<Finding> {
    let start = generate::generate(seed, case);
    let generated = size(&start);
    let breaks = |s: &Sketch| {
        violations(s, run)
            .into_iter()
            .find(|v| v.invariant == invariant)
    };
    breaks(&start)?;
    let shrunk = shrink::shrink(start, &mut |s| breaks(s).is_some(), out_of_time);
    let violation = breaks(&shrunk.sketch)?;
    let backend = run.backend.backend().to_string();
    let name = format!(
        "hunt-{}-{}-{}",
        invariant.replace('_', "-"),
        backend,
        slug(&run.label)
    );
    let file = format!("{name}.toml");
    let s = &shrunk.sketch;
    let what = INVARIANTS
        .iter()
        .find(|i| i.0 == invariant)
        .map_or("", |i| i.2);
    let measured = if violation.metric.is_empty() {
        match violation.detail.as_str() {
            "" => format!(
                "read from the trace (no metric row shows it): {} against at most {}, at frame {}",
                round6(violation.value),
                round6(violation.bound),
                frame(&violation)
            ),
            d => format!("the run fails: {d}"),
        }
    } else {
        format!(
            "{} = {} (at most {} holds), first shown at frame {}",
            violation.metric,
            round6(violation.value),
            round6(violation.bound),
            frame(&violation)
        )
    };
    let shrunk_size = size(s);
    let header = vec![
        format!("Found by platbench hunt: the invariant `{invariant}` fails for {backend} \"{}\".", run.label),
        format!("  {invariant}: {what}."),
        format!("  measured: {measured}."),
        format!(
            "  seed {seed}, case {case}: shrunk from {} x {} tiles, {} platform(s), {} input event(s) to {} x {} tiles, {} platform(s), {} input event(s) in {} tries{}.",
            generated[0], generated[1], generated[3], generated[4],
            shrunk_size[0], shrunk_size[1], shrunk_size[3], shrunk_size[4],
            shrunk.tries,
            if shrunk.cut_short { " (cut short: not a fixed point)" } else { "" }
        ),
        format!("  reproduce: {}", reproduce(&file, run)),
    ];
    Some(Finding {
        backend,
        config: run.label.clone(),
        violation,
        seed,
        case,
        toml: s.toml(&name, &header),
        name,
        generated,
        shrunk: shrunk_size,
        duration: s.duration,
        tries: shrunk.tries,
        cut_short: shrunk.cut_short,
    })
}

fn frame(v: &Violation) -> String {
    v.frame.map_or("-".into(), |f| f.to_string())
}

fn round6(v: f64) -> String {
    format!("{}", (v * 1e6).round() / 1e6)
}

//! The selection options every command that runs controllers takes alike (`run`, `report`,
//! `stress`, `sweep`): which backends, shapes and precisions, the time step and overlap
//! tolerance, the threads, and which levels and scenarios.

use anyhow::{bail, Result};
use clap::Args;

use super::Harness;
use crate::backend::Precision;
use crate::config::RunConfig;
use crate::level::Level;

/// Which configurations and scenarios a command runs, and on how many threads.
#[derive(Args, Default, Clone)]
#[command(allow_negative_numbers = true)]
pub(crate) struct Selection {
    /// Backends to run (repeat or comma-separate); every registered backend by default.
    #[arg(long = "backend", value_name = "BACKEND", value_delimiter = ',', value_parser = clap::builder::NonEmptyStringValueParser::new())]
    pub(crate) backends: Vec<String>,
    /// Character shapes to run, of the backends that offer several (Rapier's, in a build with
    /// its feature; repeat or comma-separate); all of them by default.
    #[arg(long = "shape", value_name = "SHAPE", value_delimiter = ',', value_parser = ["capsule", "cuboid", "ball", "round-cuboid"])]
    pub(crate) shapes: Vec<String>,
    /// Precisions to run each configuration in (repeat or comma-separate: f32, f64): each
    /// configuration runs in every listed precision it has a build in (Rapier's: both, on
    /// rapier2d and rapier2d-f64; labels of the f64 builds end in ` f64`); one with none of them
    /// is left out, said on stderr. Default: each configuration's own.
    #[arg(long = "precision", value_name = "PRECISION", value_delimiter = ',', value_parser = ["f32", "f64"])]
    pub(crate) precisions: Vec<String>,
    /// Override every scenario's time step, in seconds (`stress`: the step of every probe but
    /// those of its dt dimension; `sweep`: of every setting but those that set their own dt,
    /// labelled `dt=`).
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds, allow_negative_numbers = true)]
    pub(crate) dt: Option<f32>,
    /// The overlap tolerance of the configurations that have one (the sweep's epsilon), in
    /// tiles (`stress` still varies it in its epsilon dimension; `sweep` keeps it on the
    /// settings that set their own, labelled `epsilon=`).
    #[arg(long, value_name = "TILES", value_parser = parse_tiles, allow_negative_numbers = true)]
    pub(crate) epsilon: Option<f32>,
    /// Run only these levels or scenarios: LEVEL or LEVEL.SCENARIO (repeat or comma-separate;
    /// `platbench levels` lists the built-in ones). `stress` runs its own probe levels and
    /// refuses it.
    #[arg(
        long = "scenario",
        value_name = "LEVEL[.SCENARIO]",
        value_delimiter = ','
    )]
    pub(crate) scenarios: Vec<String>,
    /// Threads to run on: independent runs fan out over them, and the output is the same
    /// whatever the number. Default: the cores available (timing always runs on one thread).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub(crate) jobs: Option<u32>,
    /// An external controller to run beside the registered ones: a controller file (TOML:
    /// name, command, args, working_directory, mode, step_timeout_ms; docs/protocol.md) whose
    /// program speaks the step protocol over stdin/stdout or TCP (repeatable). Its name joins
    /// the --backend values. `--controller godot3` is the built-in Godot 3 client (needs
    /// godot3-server; docs/godot3.md).
    #[arg(long = "controller", value_name = "FILE")]
    pub(crate) controllers: Vec<std::path::PathBuf>,
}

impl Selection {
    /// The threads `--jobs` asks for, or the cores available.
    pub(crate) fn jobs(&self) -> usize {
        super::jobs_or_cores(self.jobs)
    }

    /// `--dt`, checked against the documented range.
    pub(crate) fn dt(&self) -> Result<Option<f32>> {
        if let Some(dt) = self.dt {
            let (lo, hi) = crate::limits::DT_RANGE;
            if !crate::limits::dt_in_range(dt as f64) {
                bail!("--dt {dt}: expected a time step in seconds, {lo} <= dt <= {hi}");
            }
        }
        Ok(self.dt)
    }

    /// `--epsilon`, checked against the documented range.
    pub(crate) fn epsilon(&self) -> Result<Option<f32>> {
        if let Some(eps) = self.epsilon {
            if !crate::limits::within(eps as f64, (0.0, crate::limits::MAX_EPSILON)) {
                bail!(
                    "--epsilon {eps}: expected tiles, 0 <= epsilon <= {}",
                    crate::limits::MAX_EPSILON
                );
            }
        }
        Ok(self.epsilon)
    }

    /// `levels` cut to `--scenario` and with every scenario at `--dt`: a filter that matches
    /// nothing is an error naming what there is.
    pub(crate) fn levels(&self, mut levels: Vec<Level>) -> Result<Vec<Level>> {
        for want in &self.scenarios {
            let (level, scenario) = match want.split_once('.') {
                Some((l, s)) => (l, Some(s)),
                None => (want.as_str(), None),
            };
            let found = levels.iter().any(|l| {
                l.name == level && scenario.is_none_or(|s| l.scenarios.iter().any(|x| x.name == s))
            });
            if !found {
                let names: Vec<String> = levels
                    .iter()
                    .flat_map(|l| {
                        l.scenarios
                            .iter()
                            .map(move |s| format!("{}.{}", l.name, s.name))
                    })
                    .collect();
                bail!(
                    "--scenario {want}: no such level or scenario among the levels run; expected LEVEL or LEVEL.SCENARIO, one of: {}",
                    names.join(", ")
                );
            }
        }
        if !self.scenarios.is_empty() {
            let keep = |l: &str, s: &str| {
                self.scenarios.iter().any(|w| match w.split_once('.') {
                    Some((wl, ws)) => wl == l && ws == s,
                    None => w == l,
                })
            };
            for l in &mut levels {
                let name = l.name.clone();
                l.scenarios.retain(|s| keep(&name, &s.name));
            }
            levels.retain(|l| !l.scenarios.is_empty());
        }
        if let Some(dt) = self.dt()? {
            // The frame caps hold for the step given here as for a step in the file.
            for l in &mut levels {
                let mut level_frames = 0u64;
                for s in &mut l.scenarios {
                    s.dt = dt;
                    level_frames += crate::limits::check_timing(s.duration as f64, dt as f64)
                        .map_err(|m| {
                            anyhow::anyhow!("--dt {dt} on {} scenario {}: {m}", l.source, s.name)
                        })?;
                }
                if level_frames > crate::limits::MAX_LEVEL_FRAMES {
                    bail!(
                        "--dt {dt}: the scenarios of {} would run {level_frames} frames together; expected at most {}",
                        l.source,
                        crate::limits::MAX_LEVEL_FRAMES
                    );
                }
            }
        }
        Ok(levels)
    }

    /// `base` cut to `--backend` and `--shape`, with `--epsilon` set where `keeps_epsilon` is
    /// false, and built in each `--precision`. Each entry carries a payload of the caller's (a
    /// sweep setting's time step) through unchanged.
    pub(crate) fn configs<T: Clone>(
        &self,
        h: &Harness,
        base: Vec<(RunConfig, T)>,
        keeps_epsilon: impl Fn(&RunConfig) -> bool,
    ) -> Result<Vec<(RunConfig, T)>> {
        let registry = &h.registry;
        let mut set = base;
        if !self.backends.is_empty() {
            set.retain(|(c, _)| self.backends.iter().any(|b| b == c.backend.backend()));
        }
        // `--shape` picks among the shapes of the backends that offer a choice.
        let has_choice = |c: &RunConfig| {
            registry
                .get(c.backend.backend())
                .is_some_and(|k| k.shapes().len() > 1)
        };
        if !self.shapes.is_empty() {
            if !set.iter().any(|(c, _)| has_choice(c)) {
                let offering: Vec<&str> = registry
                    .kinds()
                    .iter()
                    .filter(|k| k.shapes().len() > 1)
                    .map(|k| k.name())
                    .collect();
                if offering.is_empty() {
                    bail!(
                        "--shape {}: no backend of this build offers a choice of character shape (Rapier's does: platbench's `rapier` feature); drop --shape",
                        self.shapes.join(",")
                    );
                }
                bail!(
                    "--shape {} picks the character shapes of a backend that offers several ({}), but none of them runs (--backend {}); drop --shape, or add --backend {}",
                    self.shapes.join(","),
                    offering.join(", "),
                    self.backends.join(","),
                    offering.join(",")
                );
            }
            set.retain(|(c, _)| !has_choice(c) || self.shapes.contains(&c.shape().label()));
        }
        if let Some(eps) = self.epsilon()? {
            if !set.iter().any(|(c, _)| c.backend.epsilon().is_some()) {
                eprintln!(
                    "warning: --epsilon {eps}: none of the selected configurations has an overlap tolerance to set (the sweep's float modes do); it changes nothing"
                );
            }
            for (c, _) in &mut set {
                if keeps_epsilon(c) || c.backend.epsilon().is_none_or(|own| own == eps) {
                    continue;
                }
                if let Some(b) = c.backend.with_epsilon(eps) {
                    // The label stays: `run --epsilon` against a baseline compares like with
                    // like (the analysis commands, stress and sweep, say it in theirs).
                    c.backend = b;
                }
            }
        }
        if !self.precisions.is_empty() {
            set = self.in_precisions(set)?;
        }
        if set.is_empty() {
            let or_all = |v: &[String]| {
                if v.is_empty() {
                    "all".to_string()
                } else {
                    v.join(",")
                }
            };
            bail!(
                "the selection (--backend {}, --shape {}) leaves no configuration to run",
                or_all(&self.backends),
                or_all(&self.shapes)
            );
        }
        Ok(set)
    }

    /// Each configuration of `set` in every `--precision` it has a build in.
    fn in_precisions<T: Clone>(&self, set: Vec<(RunConfig, T)>) -> Result<Vec<(RunConfig, T)>> {
        let mut wanted: Vec<Precision> = Vec::new();
        for p in self
            .precisions
            .iter()
            .filter_map(|p| Precision::from_label(p))
        {
            if !wanted.contains(&p) {
                wanted.push(p);
            }
        }
        let mut out = Vec::new();
        for (c, t) in set {
            let own = c.backend.precision();
            let mut any = false;
            // A build already in the set (the f64 configuration of a set that has its f32 one
            // too, built back in f32) is not run twice.
            let fresh = |out: &Vec<(RunConfig, T)>, label: &str| {
                !out.iter()
                    .any(|(o, _)| o.backend.backend() == c.backend.backend() && o.label == label)
            };
            for &p in &wanted {
                if p == own {
                    if fresh(&out, &c.label) {
                        out.push((c.clone(), t.clone()));
                    }
                    any = true;
                } else if let Some(b) = c.backend.with_precision(p) {
                    let label = match p {
                        Precision::F64 => format!("{} f64", c.label),
                        Precision::F32 => c.label.trim_end_matches(" f64").to_string(),
                    };
                    if fresh(&out, &label) {
                        let run = RunConfig {
                            backend: b,
                            label,
                            ..c.clone()
                        };
                        out.push((run, t.clone()));
                    }
                    any = true;
                }
            }
            if !any {
                eprintln!(
                    "  left out {} {}: no build in {}",
                    c.backend.backend(),
                    c.label,
                    self.precisions.join(", ")
                );
            }
        }
        if out.is_empty() {
            bail!(
                "--precision {}: no configuration that runs has a build in it",
                self.precisions.join(",")
            );
        }
        Ok(out)
    }

    /// The configurations of `run` and `report`: the registry's built-in set, selected.
    pub(crate) fn builtin_configs(&self, h: &Harness) -> Result<Vec<RunConfig>> {
        let base = h.registry.builtin_configs().into_iter().map(|c| (c, ()));
        Ok(self
            .configs(h, base.collect(), |_| false)?
            .into_iter()
            .map(|(c, ())| c)
            .collect())
    }
}

/// The threads a command that builds `levels`' worlds may fan out over: `asked`, or as many as
/// keep their worlds within [`crate::limits::RUN_MEMORY`] on the largest of them
/// ([`jobs_within_memory_noted`]).
pub(crate) fn jobs_for_levels(asked: usize, levels: &[crate::level::Level]) -> usize {
    let largest = levels
        .iter()
        .map(|l| l.width as u64 * l.height as u64)
        .max()
        .unwrap_or(0);
    jobs_within_memory_noted(asked, largest)
}

/// [`crate::limits::jobs_within_memory`] for a largest level of `tiles` tiles: each thread
/// builds the world of the level it runs, so on a large level fewer threads, said on stderr.
pub(crate) fn jobs_within_memory_noted(asked: usize, tiles: u64) -> usize {
    let jobs = crate::limits::jobs_within_memory(asked, tiles);
    if jobs < asked {
        eprintln!(
            "platbench: {jobs} thread{} rather than {asked}: a thread running a level of {tiles} tiles takes up to {} MB, and a run keeps within {} MB",
            if jobs == 1 { "" } else { "s" },
            tiles.saturating_mul(crate::limits::THREAD_BYTES_PER_TILE) / 1_000_000,
            crate::limits::RUN_MEMORY / 1_000_000,
        );
    }
    jobs
}

/// A time step: seconds as a number (`0.0166`) or a fraction (`1/60`, divided in f32 as
/// the built-in default is). Its range is checked with the scenario's.
fn parse_seconds(s: &str) -> Result<f32, String> {
    let v = |t: &str| t.trim().parse::<f32>().ok();
    let value = match s.split_once('/') {
        Some((a, b)) => v(a).zip(v(b)).map(|(a, b)| a / b),
        None => v(s),
    };
    value.ok_or_else(|| {
        format!("found {s:?}; expected seconds, a number such as 0.0166 or a fraction such as 1/60")
    })
}

/// A length in tiles, a number; its range is checked with the configuration's.
fn parse_tiles(s: &str) -> Result<f32, String> {
    s.trim()
        .parse::<f32>()
        .map_err(|_| format!("found {s:?}; expected a number of tiles such as 0.001"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stress_and_hunt_take_fewer_threads_only_past_what_their_levels_allow() {
        // The probe level (300 x 40 tiles) is up to 16.8 MB a thread: 127 threads within
        // RUN_MEMORY (2 GiB), so `stress --jobs 1024` takes 127, and 64 keep every one.
        assert_eq!(jobs_within_memory_noted(64, crate::stress::PROBE_TILES), 64);
        assert_eq!(
            jobs_within_memory_noted(1024, crate::stress::PROBE_TILES),
            127
        );
        // A hunt's generated level is at most 20 x 10 tiles: every thread `--jobs` allows
        // (1024) fits.
        assert_eq!(
            jobs_within_memory_noted(1024, crate::hunt::LEVEL_TILES),
            1024
        );
    }
}

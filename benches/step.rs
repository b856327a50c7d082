//! Cost of one character step for each configuration of the built-in comparison on every
//! built-in scenario, and of the bound (a direct tile-grid sweep on a floor, [`bound`]); the
//! run ends with the sweep's cost on each scenario as a ratio to the bound's (criterion; `--
//! LEVEL` filters, e.g. `cargo bench --bench step -- ladders`). Benches measure; no test asserts
//! a time.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, Criterion};
use platbench::backend::{Backend, CharacterSpec};
use platbench::config::RunConfig;
use platbench::level::{parse_level, Level, ScenarioSpec};
use platbench::scenario::{effective_params, input_script};

mod bound;
#[path = "../compare/builtin.rs"]
mod builtin;

/// A backend for `spec` on `run` with its character placed, or why it cannot be built (a level
/// feature the configuration does not model: none in the built-in set; a level of your own may
/// have one).
fn try_fresh(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
) -> Result<Box<dyn Backend>, platbench::scenario::RunError> {
    let params = effective_params(&run.params, spec);
    platbench::scenario::Runner::new(level).build(run, &params, &[CharacterSpec::of(spec)])
}

/// A backend for `spec` on `run`; only called for pairs [`try_fresh`] built.
fn fresh(level: &Level, spec: &ScenarioSpec, run: &RunConfig) -> Box<dyn Backend> {
    try_fresh(level, spec, run).expect("built once already")
}

fn step_cost(c: &mut Criterion) {
    for (file, text) in builtin::LEVELS {
        let level = parse_level(text, file).expect("built-in level parses");
        for spec in &level.scenarios {
            let script = input_script(spec);
            let mut group = c.benchmark_group(format!("step/{}.{}", level.name, spec.name));
            for run in platbench::registry::Registry::builtin().builtin_configs() {
                let name = format!("{}/{}", run.backend.backend(), run.label);
                // A pair the configuration does not model is skipped, and said so (as `run` does).
                if let Err(e) = try_fresh(&level, spec, &run) {
                    eprintln!("skipped {}.{} {name}: {e}", level.name, spec.name);
                    continue;
                }
                group.bench_function(name, |b| {
                    // One iteration is one step of the scenario's script; when the script ends the
                    // backend is rebuilt outside the timed region, so only steps are measured.
                    b.iter_custom(|iters| {
                        let mut total = Duration::ZERO;
                        let mut left = iters as usize;
                        while left > 0 {
                            let mut backend = fresh(&level, spec, &run);
                            let n = left.min(script.len());
                            let start = Instant::now();
                            for input in script.range(0..n) {
                                backend.step(std::slice::from_ref(black_box(input)), spec.dt);
                            }
                            total += start.elapsed();
                            left -= n;
                        }
                        total
                    });
                });
            }
            group.finish();
        }
    }
}

criterion_group!(benches, bound::bench, step_cost);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    bound::ratios::print();
}

//! The harness itself (criterion): the built-in scenario set run on every configuration of the
//! built-in registry and measured, as `platbench run` does it (fan-out over threads, metrics,
//! the rows the summary keeps, the summary), on one thread and on every core. The throughput is
//! in game seconds simulated and measured (criterion's elements: one per game second summed over
//! every (scenario, configuration) run), so a regression in the runner, the metrics or the
//! fan-out shows beside the per-step benches. Benches measure; no test asserts a time.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use platbench::config::RunConfig;
use platbench::level::Level;
use platbench::metrics::{evaluate_recorded, MetricRow};
use platbench::parallel::{default_jobs, for_each_ordered};
use platbench::registry::Registry;
use platbench::report::summary_rows::SummaryRows;
use platbench::report::summary_table_in;
use platbench::scenario::Runner;
use platbench::trace::RowStore;

/// Runs every (level, scenario, configuration) on `jobs` threads and returns the summary.
fn run_set(levels: &[Level], configs: &[RunConfig], jobs: usize) -> String {
    let mut items = Vec::new();
    for (li, level) in levels.iter().enumerate() {
        for si in 0..level.scenarios.len() {
            for (ci, c) in configs.iter().enumerate() {
                if c.backend.supports(level) {
                    items.push((li, si, ci));
                }
            }
        }
    }
    let mut kept = SummaryRows::default();
    for_each_ordered(
        jobs,
        items.len(),
        || None::<(usize, Runner)>,
        |cache, i| -> Vec<MetricRow> {
            let (li, si, ci) = items[i];
            if cache.as_ref().is_none_or(|(l, _)| *l != li) {
                *cache = Some((li, Runner::new(&levels[li])));
            }
            let (_, runner) = cache.as_mut().expect("set just above");
            // As `platbench run` measures: the rows streamed into a store.
            let store = RowStore::default();
            evaluate_recorded(runner, &levels[li].scenarios[si], &configs[ci], store)
                .expect("the built-in set runs")
                .metrics
        },
        |_, rows| {
            kept.push_run(rows);
            Ok::<(), ()>(())
        },
    )
    .expect("the consumer never fails");
    let (rows, coverage) = kept.into_parts();
    summary_table_in(&rows, &coverage)
}

fn builtin_set(c: &mut Criterion) {
    let levels = platbench::suite::builtin_levels().expect("the built-in levels parse");
    let configs = Registry::builtin().builtin_configs();
    let game_seconds: f64 = levels
        .iter()
        .map(|l| {
            let n = configs.iter().filter(|c| c.backend.supports(l)).count();
            l.scenarios.iter().map(|s| s.duration as f64).sum::<f64>() * n as f64
        })
        .sum();
    let mut g = c.benchmark_group("harness/builtin_set");
    g.throughput(Throughput::Elements(game_seconds.round() as u64));
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(20));
    let mut jobs = vec![1];
    if default_jobs() > 1 {
        jobs.push(default_jobs());
    }
    for j in jobs {
        g.bench_with_input(BenchmarkId::new("jobs", j), &j, |b, &j| {
            b.iter(|| run_set(&levels, &configs, j))
        });
    }
    g.finish();
}

criterion_group!(benches, builtin_set);
criterion_main!(benches);

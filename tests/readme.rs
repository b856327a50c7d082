//! The README's metric catalog and summary claims, checked against the code (issue 17, item 10).

mod common;

use common::{builtin_levels, evaluate_all};
use platbench::metrics::registry::METRICS;
use platbench::report::summary_table;
use platbench::scenario::RunConfig;

fn readme() -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md")
}

#[test]
fn the_readme_lists_every_metric_of_the_registry_with_its_unit() {
    let text = readme();
    assert!(!METRICS.is_empty());
    for d in METRICS {
        let row = format!("| `{}` ({}) |", d.name, d.unit);
        assert!(text.contains(&row), "README misses {row}");
    }
}

#[test]
fn integer_positions_are_compared_over_39_of_63_scenarios() {
    // README, summary: "over 39 of 63". The integer mode refuses slopes and moving platforms,
    // so it runs the 39 scenarios of the 9 levels it models out of the built-in set's 63.
    let levels = builtin_levels();
    let total: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    assert_eq!(total, 63);
    let mut rows = Vec::new();
    for run in [RunConfig::sweep_default(), RunConfig::sweep_integer(32)] {
        for l in &levels {
            for s in &l.scenarios {
                match platbench::metrics::evaluate(l, s, &run) {
                    Ok(e) => rows.extend(e.metrics),
                    Err(platbench::backend::BackendError::Unsupported { .. }) => {}
                    Err(e) => panic!("{e}"),
                }
            }
        }
    }
    let summary = summary_table(&rows);
    assert!(
        summary.contains("sweep positions=integer/32 (over 39 of 63)"),
        "{summary}"
    );
    assert!(!summary.contains("sweep (over"), "{summary}");
    // The same count the shared helper sees.
    let evals = evaluate_all(&levels, &RunConfig::sweep_default());
    assert_eq!(evals.len(), 63);
}

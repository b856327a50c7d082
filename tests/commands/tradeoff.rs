//! The speed-versus-accuracy sweep on a small level: every setting measured, the error score in
//! range, a Pareto front that is not empty and contains the cheapest setting.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use platbench::level::parse_level;
use platbench::metrics::score::Score;
use platbench::tradeoff::{chart_svg, grid, run_tradeoff, ALL};

#[test]
fn tradeoff_measures_every_setting_and_marks_a_front() {
    let level = parse_level(
        "map = \"\"\"\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"walk\"\nspawn = [1.5, 1.0]\nduration = 0.5\ninputs = [ { t = 0.0, right = true } ]\n",
        "t.toml",
    )
    .unwrap();
    let settings = grid();
    let all_rows = run_tradeoff(
        std::slice::from_ref(&level),
        &settings,
        &Score::default(),
        |_, _, _| {},
    )
    .unwrap();
    let rows: Vec<_> = all_rows
        .iter()
        .filter(|r| r.scope == ALL)
        .cloned()
        .collect();
    assert_eq!(rows.len(), settings.len());
    for r in &rows {
        assert!(r.cost_us.is_finite() && r.cost_us > 0.0, "{r:?}");
        assert!((0.0..=1.0).contains(&r.error), "{r:?}");
    }
    let cheapest = rows
        .iter()
        .min_by(|a, b| a.cost_us.total_cmp(&b.cost_us))
        .unwrap();
    // Nothing is cheaper than the cheapest, so only an equally cheap, more accurate setting
    // could dominate it.
    let dominated = rows
        .iter()
        .any(|r| r.cost_us <= cheapest.cost_us && r.error < cheapest.error);
    assert_eq!(cheapest.pareto, !dominated);
    assert!(rows.iter().any(|r| r.pareto));
    let svg = chart_svg(&rows);
    // The legend has one dot per backend of the grid (sweep, rapier, box2d).
    let mut backends: Vec<&str> = rows.iter().map(|r| r.backend.as_str()).collect();
    backends.dedup();
    assert_eq!(backends.len(), 3);
    assert_eq!(
        svg.matches("<circle").count(),
        rows.len() + backends.len(),
        "a dot per setting and one per backend in the legend"
    );
}

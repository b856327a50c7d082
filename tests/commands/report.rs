//! The HTML report as a reader gets it: self-contained, one replay per scenario, every
//! backend's path in each.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{assert_success, platbench};

#[test]
fn report_is_self_contained_with_one_picture_per_scenario() {
    let dir = tempfile::tempdir().unwrap();
    let out = platbench()
        .args(["report", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_success(&out);
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    let md = std::fs::read_to_string(dir.path().join("report.md")).unwrap();
    // The Markdown twin lists each scenario as "- level.scenario: configurations shown".
    let scenarios = md
        .lines()
        .filter(|l| {
            l.strip_prefix("- ")
                .and_then(|l| l.split_once(": "))
                .is_some_and(|(id, _)| id.contains('.') && !id.contains(' '))
        })
        .count();
    let pictures = html.matches("<svg").count();
    assert!(pictures >= 60, "{pictures} pictures");
    assert_eq!(pictures, scenarios, "one picture per scenario listed");
    // Every picture holds the sweep's path and Rapier's.
    for svg in html.split("<svg").skip(1) {
        let svg = &svg[..svg.find("</svg>").unwrap()];
        assert!(svg.contains("class=\"path backend-sweep\""));
        assert!(svg.contains("class=\"path backend-rapier\""));
    }
    // One inline script (the replay's, plus each replay's inline data) and nothing fetched
    // from the network (the SVG namespace is only a name).
    assert_eq!(html.matches("<script>").count(), 1);
    assert_eq!(
        html.matches("<script type=\"application/json\" class=\"replay-data\">")
            .count(),
        pictures
    );
    assert!(!html.contains("<script src"));
    assert!(!html.contains("src=\"http") && !html.contains("href=\"http"));
    // Small enough to open at once: under 10 MB with every configuration's replay in it.
    assert!(html.len() < 10_000_000, "{} bytes", html.len());
    // The verdict first, then the statements the worst values support.
    let verdict = html
        .find("<section id=\"verdict\"><h2>Which controller for which game</h2>")
        .expect("the verdict section");
    assert!(verdict < html.find("id=\"statements\"").expect("the statements"));
    for section in [
        "Landing and resting",
        "Slopes",
        "Moving platforms",
        "Ladders",
    ] {
        assert!(html.contains(section) && md.contains(section), "{section}");
    }
}

/// `platbench report` on one small level, writing into `DIR/report` (a directory of its own:
/// `DIR` holds the input files), with `extra` arguments.
fn report_on_flat_seams(dir: &std::path::Path, extra: &[&std::ffi::OsStr]) -> std::process::Output {
    platbench()
        .args(["report", "compare/levels/flat_seams.toml", "--out"])
        .arg(dir.join("report"))
        .args(extra)
        .output()
        .unwrap()
}

/// Writes `rows` as a CSV file the way `platbench sweep` and `platbench stress` do.
fn write_csv<T: serde::Serialize>(path: &std::path::Path, rows: &[T]) {
    let mut w = csv::Writer::from_path(path).unwrap();
    for r in rows {
        w.serialize(r).unwrap();
    }
    w.flush().unwrap();
}

#[test]
fn report_includes_the_tradeoff_chart_and_the_stability_table_when_given() {
    use platbench::stress::StressRow;
    use platbench::tradeoff::TradeoffRow;
    let dir = tempfile::tempdir().unwrap();
    let trade =
        |backend: &str, setting: &str, cost_us: f64, error: f64, pareto: bool| TradeoffRow {
            backend: backend.into(),
            setting: setting.into(),
            cost_us,
            error,
            pareto,
            scenarios: 62,
            scope: platbench::tradeoff::ALL.into(),
        };
    write_csv(
        &dir.path().join("tradeoff.csv"),
        &[
            trade("sweep", "dt=1/60", 20.0, 0.010, true),
            trade("rapier", "per-tile", 400.0, 0.012, false),
            trade("sweep", "dt=1/480", 150.0, 0.009, true),
        ],
    );
    let stress = |value: f64, holds: bool| StressRow {
        backend: "sweep".into(),
        config: "default".into(),
        dimension: "offset".into(),
        value,
        dimension2: String::new(),
        value2: None,
        invariant: "penetration".into(),
        holds,
        measured: 0.0,
        tolerance: 0.0,
    };
    let pair = |value: f64, value2: f64, invariant: &str, holds: bool| StressRow {
        dimension2: "dt".into(),
        value2: Some(value2),
        invariant: invariant.into(),
        ..stress(value, holds)
    };
    write_csv(
        &dir.path().join("stability.csv"),
        &[
            stress(0.0, true),
            stress(1e6, true),
            stress(1e7, false),
            pair(1e5, 1e-4, "progress", false),
            pair(1e5, 1e-4, "jump_height", false),
            pair(1e5, 0.05, "progress", true),
        ],
    );
    let out = report_on_flat_seams(
        dir.path(),
        &[
            "--tradeoff".as_ref(),
            dir.path().join("tradeoff.csv").as_os_str(),
            "--stability".as_ref(),
            dir.path().join("stability.csv").as_os_str(),
        ],
    );
    assert_success(&out);
    let html = std::fs::read_to_string(dir.path().join("report/report.html")).unwrap();
    let md = std::fs::read_to_string(dir.path().join("report/report.md")).unwrap();
    assert!(html.contains("class=\"tradeoff\""), "the chart is drawn");
    // The Pareto front is listed cheapest first, and only the front.
    let (a, b) = (
        md.find("| sweep | dt=1/60 |").unwrap(),
        md.find("| sweep | dt=1/480 |").unwrap(),
    );
    assert!(a < b);
    assert!(!md.contains("| rapier | per-tile |"));
    // The stability table gives the verdict (the last value where every invariant held, the
    // first where one broke and which) and each invariant that broke where; the combination
    // cells are a grid, the broken one naming its invariants first broken first (in the HTML
    // coloured by the first: progress's colour, not the green of a cell that held).
    assert!(
        md.contains(
            "| sweep default | offset | holds to 1e6; breaks at 1e7 (penetration) | penetration at 1e7 |"
        ),
        "{md}"
    );
    assert!(md.contains("#### offset x dt"), "{md}");
    assert!(
        md.contains("| sweep default | 1e5 | progress, jump_height | ok |"),
        "{md}"
    );
    assert!(
        html.contains("background:#d81b60\" title=\"progress, jump_height\""),
        "{html}"
    );
    assert!(html.contains("Stability at the extremes"));
    // How far from the origin it holds (stress::reach): nothing broke at 0, so nothing is set
    // aside, and the edge is the verdict's.
    assert!(
        md.contains("| sweep default | holds to 1e6; breaks at 1e7 (penetration) |"),
        "{md}"
    );
    assert!(html.contains("How far from the origin each configuration holds"));
}

#[test]
fn report_names_a_bad_tradeoff_file() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("tradeoff.csv");
    std::fs::write(&bad, "level,scenario\nflat,walk\n").unwrap();
    let out = report_on_flat_seams(dir.path(), &["--tradeoff".as_ref(), bad.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("tradeoff.csv"), "{err}");
    assert!(
        !dir.path().join("report/report.html").exists(),
        "nothing written"
    );
}

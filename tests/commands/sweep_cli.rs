//! `platbench sweep` as a user runs it: the error score is the user's (`--score`), the front is
//! drawn per behaviour, and docs/speed.md's claim about the front is read from the CSV the
//! documented command wrote.
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
use platbench::tradeoff::{grid, scored_behaviours, TradeoffRow, ALL};

const LEVEL: &str = "map = \"\"\"\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"walk\"\nspawn = [1.5, 1.0]\nduration = 0.5\ninputs = [ { t = 0.0, right = true } ]\n";

fn read_rows(path: &std::path::Path) -> Vec<TradeoffRow> {
    csv::Reader::from_path(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .deserialize()
        .collect::<Result<_, _>>()
        .expect("tradeoff.csv parses")
}

#[test]
fn sweep_takes_a_score_and_draws_a_front_per_behaviour() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("walk.toml");
    std::fs::write(&level, LEVEL).unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["sweep", "--out"])
        .arg(&out_dir)
        .args(["--score", "rest_gap_declared=2,tunneled"])
        .arg(&level)
        .output()
        .unwrap();
    assert_success(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("error score: rest_gap_declared=2,tunneled=1"),
        "{err}"
    );
    let rows = read_rows(&out_dir.join("tradeoff.csv"));
    let settings = grid().len();
    assert!(settings > 0);
    // One row per setting for the whole score, and one per behaviour.
    assert_eq!(rows.iter().filter(|r| r.scope == ALL).count(), settings);
    for b in scored_behaviours() {
        assert_eq!(
            rows.iter().filter(|r| r.scope == b.key()).count(),
            settings,
            "{}",
            b.key()
        );
        assert!(out_dir.join(format!("tradeoff.{}.svg", b.key())).exists());
        // Every behaviour's front has a member (the cheapest setting cannot be dominated on
        // cost, so a front always exists).
        assert!(rows.iter().any(|r| r.scope == b.key() && r.pareto));
    }
}

#[test]
fn a_bad_score_is_refused_with_its_reason() {
    let dir = tempfile::tempdir().unwrap();
    for (score, says) in [
        ("no_such_metric", "unknown metric"),
        ("rest_gap=-1", "not a finite number"),
        ("rest_gap=0", "no metric above 0"),
    ] {
        let out = platbench()
            .args(["sweep", "--out"])
            .arg(dir.path())
            .args(["--score", score])
            .output()
            .unwrap();
        // An error is exit status 2 (1 is diff's "worse").
        assert_eq!(out.status.code(), Some(2), "{score}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{score}: {err}");
    }
    for ppt in ["0", "-16", "inf", "sixteen"] {
        let out = platbench()
            .args(["sweep", "--out"])
            .arg(dir.path())
            .arg(format!("--pixels-per-tile={ppt}"))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{ppt}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("is not a finite number > 0"), "{ppt}: {err}");
    }
}

#[test]
fn sweep_charges_at_the_game_s_pixels_per_tile() {
    // A walk scored on progress alone at 4 pixels per tile: the score says its resolution on
    // stderr (docs/metrics.md, "The error score and the game's pixel").
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("walk.toml");
    std::fs::write(&level, LEVEL).unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["sweep", "--backend", "sweep", "--out"])
        .arg(&out_dir)
        .args(["--score", "progress_ratio", "--pixels-per-tile", "4"])
        .arg(&level)
        .output()
        .unwrap();
    assert_success(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("error score: progress_ratio=1 at 4 pixels per tile"),
        "{err}"
    );
    assert!(out_dir.join("tradeoff.csv").exists());
}

#[test]
fn every_setting_on_the_committed_front_is_a_sweep_setting() {
    // compare/tradeoff/tradeoff.csv is what `platbench sweep --out compare/tradeoff` wrote (one
    // run on the built-in set, default score; docs/speed.md, "Speed versus accuracy"). The page
    // says every setting on the front is a sweep setting, because each Rapier setting is
    // beaten on both cost and error by some sweep setting: check that claim on the numbers.
    let rows = read_rows(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compare/tradeoff/tradeoff.csv"),
    );
    let all: Vec<&TradeoffRow> = rows.iter().filter(|r| r.scope == ALL).collect();
    assert_eq!(all.len(), grid().len(), "every setting of the grid");
    // docs/speed.md says the same of every Box2D setting.
    let rapier: Vec<&&TradeoffRow> = all
        .iter()
        .filter(|r| r.backend == "rapier" || r.backend == "box2d")
        .collect();
    let sweep: Vec<&&TradeoffRow> = all.iter().filter(|r| r.backend == "sweep").collect();
    assert!(!rapier.is_empty() && !sweep.is_empty());
    assert!(rapier.iter().any(|r| r.backend == "box2d"));
    for r in &rapier {
        assert!(
            sweep
                .iter()
                .any(|s| s.cost_us < r.cost_us && s.error < r.error),
            "{} is beaten by no sweep setting",
            r.setting
        );
        assert!(!r.pareto, "{} marked on the front", r.setting);
    }
    assert!(all.iter().any(|r| r.pareto));
}

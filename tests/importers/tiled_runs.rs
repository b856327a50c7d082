//! Tiled maps run end to end: the showcase map on every configuration of both backends, in a
//! report beside the built-in levels, and mixed with TOML levels in one run.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{assert_success, platbench};

use platbench::level::load_tiled_map;

use super::tiled::shipped;

#[test]
fn the_showcase_runs_on_every_configuration_of_both_backends() {
    use platbench::metrics::evaluate;
    let (level, _) = load_tiled_map(&shipped("showcase.tmx")).unwrap();
    let configs = platbench::registry::Registry::builtin().builtin_configs();
    assert!(configs.iter().any(|c| c.backend.backend() == "sweep"));
    assert!(configs.iter().any(|c| c.backend.backend() == "rapier"));
    for run in &configs {
        let who = format!("{}/{}", run.backend.backend(), run.label);
        for spec in &level.scenarios {
            let e = match evaluate(&level, spec, run) {
                // The sweep's integer mode refuses the showcase's ramp and platform by name
                // (tests/behaviour/integer.rs); every other configuration must run it.
                Err(platbench::scenario::RunError::Controller(
                    platbench::backend::BackendError::Unsupported { feature, .. },
                )) if run.label.starts_with("positions=integer") => {
                    assert!(feature.contains("slopes") || feature.contains("moving"));
                    continue;
                }
                e => e.unwrap(),
            };
            let rows = &e.trace.rows;
            assert!(
                rows.iter().all(|r| r.x.is_finite() && r.y.is_finite()),
                "{who} {}: a position is not finite",
                spec.name
            );
            assert!(
                e.metrics.iter().all(|m| !m.value.is_nan()),
                "{who} {}: a metric is NaN",
                spec.name
            );
            if spec.name.ends_with("-ride") {
                // The ride probe measures carrying on every configuration.
                assert!(
                    e.metrics.iter().any(|m| m.metric == "carry_drift"),
                    "{who} {}: no carry_drift",
                    spec.name
                );
            }
            if run.backend.backend() != "sweep"
                || run.label != platbench::sweep::kind::run_default().label
            {
                continue;
            }
            let last = rows.last().unwrap();
            let metric = |name: &str| {
                e.metrics
                    .iter()
                    .find(|m| m.metric == name)
                    .unwrap_or_else(|| panic!("{} has no {name}", spec.name))
                    .value
            };
            match spec.name.as_str() {
                "start-walk_right" => {
                    // Up the collision-editor ramp at i = 8 onto the plateau (top at y = 2,
                    // i = 9..13), down its mirror at i = 13 and on: past x = 14, the mirror's
                    // right edge, back on the floor (y = 1). Heights within the sweep's epsilon,
                    // 1e-3.
                    let top = rows.iter().map(|r| r.y).fold(f32::MIN, f32::max);
                    assert!((top - 2.0).abs() < 1e-3, "plateau top 2, got {top}");
                    assert!(last.x > 14.0, "ended at x = {}", last.x);
                    assert!((last.y - 1.0).abs() < 1e-3, "ended at y = {}", last.y);
                }
                "start-jump" => {
                    // A 3-tile jump from the floor (y = 1) passes up through the one-way row at
                    // j = 2 and lands on its top, y = 3 (within the sweep's epsilon, 1e-3).
                    assert!((last.y - 3.0).abs() < 1e-3, "ended at y = {}", last.y);
                    assert!(last.is_grounded(), "not grounded on the one-way top");
                }
                "start-ride" => {
                    // The carry bound for the sweep on horizontal rides, 1e-4 tiles: the float
                    // carry's rounding over a ride (tests/behaviour/platforms.rs).
                    assert!(metric("carry_drift") <= 1e-4, "{}", metric("carry_drift"));
                    assert_eq!(metric("carry_airborne_frames"), 0.0);
                    assert_eq!(last.platform, Some(0));
                }
                "start-drop" => {
                    // Spawned on the floor: at rest on it, no gap (the sweep's rest bound, 1e-4
                    // tiles, as in tests/behaviour/sweep_builtin.rs).
                    assert!(metric("rest_gap").abs() <= 1e-4, "{}", metric("rest_gap"));
                }
                _ => {}
            }
        }
    }
}

#[test]
fn report_on_a_tiled_map_shows_it_like_a_built_in_level() {
    let dir = tempfile::tempdir().unwrap();
    let out = platbench()
        .arg("report")
        .arg(shipped("showcase.tmx"))
        .arg("--out")
        .arg(dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    for f in ["report.md", "report.html"] {
        let text = std::fs::read_to_string(dir.path().join(f)).unwrap();
        assert!(
            text.contains("showcase"),
            "{f} does not name the map's level"
        );
    }
}

#[test]
fn run_mixes_toml_and_tiled_files_and_prints_warnings() {
    let dir = tempfile::tempdir().unwrap();
    // The showcase with one map property platbench does not read: one warning.
    let tmx = std::fs::read_to_string(shipped("showcase.tmx"))
        .unwrap()
        .replace(
            "<properties>",
            "<properties>\n  <property name=\"music\" value=\"theme.ogg\"/>",
        );
    std::fs::write(dir.path().join("mine.tmx"), tmx).unwrap();
    std::fs::copy(shipped("terrain.tsx"), dir.path().join("terrain.tsx")).unwrap();
    std::fs::write(
        dir.path().join("small.toml"),
        "map = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"drop\"\nspawn = [1.5, 2.0]\nduration = 1.0\n",
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = platbench()
        .args(["run", "--backend", "sweep", "--out"])
        .arg(&out_dir)
        .arg(dir.path().join("small.toml"))
        .arg(dir.path().join("mine.tmx"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: ") && stderr.contains("mine.tmx: map: property \"music\""),
        "{stderr}"
    );
    let metrics = std::fs::read_to_string(out_dir.join("metrics.csv")).unwrap();
    assert!(metrics.contains("\nsmall,drop,sweep,"), "{metrics}");
    assert!(metrics.contains("\nmine,start-ride,sweep,"), "{metrics}");
    assert!(out_dir
        .join("traces/mine.start-walk_right.sweep.csv")
        .exists());
    // A map that marks no spawn (rules.tmx without its side file) runs from the fallback
    // spawn, and says so.
    let bare = dir.path().join("bare.tmx");
    std::fs::copy(shipped("rules.tmx"), &bare).unwrap();
    let out = platbench()
        .arg("run")
        .arg(&bare)
        .args(["--backend", "sweep", "--out"])
        .arg(dir.path().join("bare-out"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("bare.tmx: map: no spawn point found")
            && stderr.contains("class \"spawn\""),
        "{stderr}"
    );
    // The shipped map runs on its own, through its side file rules.toml.
    let rules_out = dir.path().join("rules-out");
    let out = platbench()
        .arg("run")
        .arg(shipped("rules.tmx"))
        .args(["--backend", "sweep", "--out"])
        .arg(&rules_out)
        .output()
        .unwrap();
    assert_success(&out);
    assert!(rules_out
        .join("traces/rules.walk_over_the_rules.sweep.csv")
        .exists());
}

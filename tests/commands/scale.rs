//! The harness at scale (docs/scale.md): which traces a run writes, and the same output on one
//! thread as on several.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use std::collections::BTreeSet;
use std::path::Path;

use common::{assert_success, platbench};
use platbench::metrics::registry;

/// Every file under `dir` (relative path) with its bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().display().to_string();
                out.push((rel, std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// The trace file names under `dir/traces`.
fn trace_names(dir: &Path) -> BTreeSet<String> {
    match std::fs::read_dir(dir.join("traces")) {
        Ok(d) => d
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect(),
        Err(_) => BTreeSet::new(),
    }
}

#[test]
fn the_built_in_run_is_byte_identical_on_one_thread_and_on_two() {
    let dir = tempfile::tempdir().unwrap();
    let (one, two) = (dir.path().join("one"), dir.path().join("two"));
    for (jobs, out_dir) in [("1", &one), ("2", &two)] {
        let out = platbench()
            .args(["run", "--jobs", jobs, "--detail", "--out"])
            .arg(out_dir)
            .output()
            .unwrap();
        assert_success(&out);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(&format!("on {jobs} thread")),
            "--jobs {jobs} not used:\n{stderr}"
        );
    }
    let (a, b) = (files(&one), files(&two));
    // Every trace of the built-in set and metrics.csv (and the marker).
    assert!(a.len() > 100, "only {} files", a.len());
    assert_eq!(
        a.iter().map(|(n, _)| n).collect::<Vec<_>>(),
        b.iter().map(|(n, _)| n).collect::<Vec<_>>()
    );
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{name} differs between --jobs 1 and --jobs 2");
    }
}

#[test]
fn run_without_out_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = platbench()
        .current_dir(dir.path())
        .args(["run", "--backend", "sweep"])
        .output()
        .unwrap();
    assert_success(&out);
    assert!(!String::from_utf8_lossy(&out.stdout).is_empty());
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "run without --out wrote {left:?}");
    // --traces only means something with --out.
    let out = platbench()
        .current_dir(dir.path())
        .args(["run", "--traces", "all"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn traces_none_failing_and_all() {
    let dir = tempfile::tempdir().unwrap();
    let run = |which: &str| {
        let out_dir = dir.path().join(which);
        let out = platbench()
            .args(["run", "--traces", which, "--out"])
            .arg(&out_dir)
            .output()
            .unwrap();
        assert_success(&out);
        out_dir
    };
    let all = run("all");
    let none = run("none");
    let failing = run("failing");
    // The same metrics whichever traces are kept.
    let metrics = std::fs::read(all.join("metrics.csv")).unwrap();
    assert_eq!(metrics, std::fs::read(none.join("metrics.csv")).unwrap());
    assert_eq!(metrics, std::fs::read(failing.join("metrics.csv")).unwrap());
    assert!(trace_names(&none).is_empty());
    let every = trace_names(&all);
    // The failing runs, worked out here from metrics.csv and the registry (--help's definition):
    // a metric of non-zero default weight off its reference by more than its scale beyond the
    // one-pixel allowance of a 16-pixel tile (charged above 1), or NaN.
    let mut want = BTreeSet::new();
    let mut rd = csv::Reader::from_reader(&metrics[..]);
    for r in rd.records() {
        let r = r.unwrap();
        let def = registry::get(&r[4]).expect("a registered metric");
        let error: f64 = r[8].parse().unwrap();
        if def.weight > 0.0 && def.charged(error, registry::DEFAULT_PIXELS_PER_TILE) > 1.0 {
            let name = if &r[3] == "default" {
                format!("{}.{}.{}.csv", &r[0], &r[1], &r[2])
            } else {
                let config: String = r[3]
                    .chars()
                    .map(|c| {
                        if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                            c
                        } else {
                            '_'
                        }
                    })
                    .collect();
                format!("{}.{}.{}.{config}.csv", &r[0], &r[1], &r[2])
            };
            want.insert(name);
        }
    }
    let got = trace_names(&failing);
    assert_eq!(got, want);
    // Neither empty nor everything on the built-in set, so the test can tell the modes apart.
    assert!(!got.is_empty() && got.len() < every.len(), "{got:?}");
    assert!(got.is_subset(&every));
    // A failing run's trace is the one --traces all writes.
    for name in &got {
        assert_eq!(
            std::fs::read(failing.join("traces").join(name)).unwrap(),
            std::fs::read(all.join("traces").join(name)).unwrap()
        );
    }
}

#[test]
fn stress_and_sweep_rows_are_the_same_on_one_thread_and_on_two() {
    use platbench::registry::Registry;
    use platbench::stress::stress_matrix_on;
    let runs = vec![platbench::sweep::kind::run_default()];
    let one = stress_matrix_on(&runs, 1, |_| {}).unwrap();
    let two = stress_matrix_on(&runs, 2, |_| {}).unwrap();
    assert!(!one.is_empty());
    assert_eq!(one, two);

    // The sweep's error scores (its costs are timings, which differ run to run) on a few
    // settings of each backend over two levels.
    let levels: Vec<_> = common::builtin_levels().into_iter().take(2).collect();
    let mut settings = Vec::new();
    for k in Registry::builtin().kinds() {
        settings.extend(k.tradeoff_settings().into_iter().take(2));
    }
    let score = platbench::metrics::score::Score::default();
    let key =
        |rows: Vec<platbench::tradeoff::TradeoffRow>| -> Vec<(String, String, String, u64, usize)> {
            rows.into_iter()
                .map(|r| {
                    (
                        r.backend,
                        r.setting,
                        r.scope,
                        r.error.to_bits(),
                        r.scenarios,
                    )
                })
                .collect()
        };
    let a =
        platbench::tradeoff::run_tradeoff_on(&levels, &settings, &score, 1, |_, _, _| {}).unwrap();
    let b =
        platbench::tradeoff::run_tradeoff_on(&levels, &settings, &score, 2, |_, _, _| {}).unwrap();
    assert!(!a.is_empty());
    assert_eq!(key(a), key(b));
}

#[test]
fn the_summary_of_the_kept_rows_is_the_summary_of_every_row_on_the_built_in_set() {
    use platbench::registry::Registry;
    use platbench::report::summary_rows::SummaryRows;
    use platbench::report::{summary_table, summary_table_in};
    let registry = Registry::builtin();
    let configs = registry.builtin_configs();
    let levels = common::builtin_levels();
    let mut all = Vec::new();
    let mut kept = SummaryRows::default();
    let mut notes = platbench::report::notes::RunNotes::new();
    let mut groups: Vec<Vec<bool>> = Vec::new();
    let mut runs = 0;
    for level in &levels {
        let set: Vec<bool> = configs.iter().map(|c| c.backend.supports(level)).collect();
        if !groups.contains(&set) {
            groups.push(set);
        }
        for spec in &level.scenarios {
            for run in configs.iter().filter(|c| c.backend.supports(level)) {
                let e = platbench::metrics::evaluate(level, spec, run).unwrap();
                all.extend(e.metrics.iter().cloned());
                notes.push_run(&e.metrics);
                kept.push_run(e.metrics);
                runs += 1;
            }
        }
    }
    // Levels that only some configurations model (groups of their own) are exercised by the
    // unit test in src/report/summary_rows.rs: on the built-in set every configuration may
    // model every level.
    assert!(!groups.is_empty());
    let (kept, coverage) = kept.into_parts();
    // Rows that do not grow with the runs: at most the first row of each metric and three per
    // group, metric and configuration (fewer than one per run here).
    let metrics = platbench::metrics::METRICS.len();
    assert!(kept.len() <= metrics * (1 + 3 * groups.len() * configs.len()));
    assert!(kept.len() < all.len() && runs > 0);
    assert_eq!(summary_table_in(&kept, &coverage), summary_table(&all));
    assert_eq!(notes.notes(), platbench::report::notes::notes(&all));
    assert!(!notes.notes().is_empty());
}

/// A run's rows spilled to a temporary file measure exactly as rows held in memory: every
/// built-in scenario on every sweep configuration and the first Rapier and Box2D ones, spilled
/// after its first row and read back three rows at a time (so every metric reads across block
/// boundaries and evicts), gives the same metric rows bit for bit and the same trace CSV as the
/// in-memory run. `platbench run` measures a run of more than `SPILL_ROWS` rows this way.
#[test]
fn a_spilled_run_measures_bit_for_bit_as_one_held_in_memory() {
    use platbench::config::RunConfig;
    use platbench::metrics::{evaluate_recorded, evaluate_with};
    use platbench::scenario::Runner;
    use platbench::trace::RowStore;

    let mut configs: Vec<RunConfig> = Vec::new();
    for c in platbench::registry::Registry::builtin().builtin_configs() {
        let kind = c.backend.backend();
        if kind == "sweep" || !configs.iter().any(|k| k.backend.backend() == kind) {
            configs.push(c);
        }
    }
    // The built-in set's sweep configurations (float, jump=continuous, integer) and one Rapier
    // and one Box2D: five; at least two sweeps beside the two peers.
    assert!(configs.len() >= 4, "{} configurations", configs.len());
    let bits = |rows: &[platbench::metrics::MetricRow]| -> Vec<(String, u64, u64)> {
        rows.iter()
            .map(|r| {
                (
                    r.metric.to_string(),
                    r.value.to_bits(),
                    r.reference.to_bits(),
                )
            })
            .collect()
    };
    let (mut runs, mut spilled) = (0, 0);
    for level in common::builtin_levels() {
        let mut runner = Runner::new(&level);
        for spec in &level.scenarios {
            for run in &configs {
                let held = match evaluate_with(&mut runner, spec, run) {
                    // A level the configuration does not model.
                    Err(e) if e.is_unsupported() => continue,
                    e => e.unwrap(),
                };
                let store = RowStore::with_limits(1, 3);
                let rec = evaluate_recorded(&mut runner, spec, run, store).unwrap();
                let what = format!("{}.{} on {}", level.name, spec.name, run.label);
                assert_eq!(bits(&rec.metrics), bits(&held.metrics), "{what}");
                assert_eq!(rec.trace.file_name(), held.trace.file_name());
                let (mut a, mut b) = (Vec::new(), Vec::new());
                rec.write_csv(&mut a).unwrap();
                held.trace.write_csv(&mut b).unwrap();
                assert!(a == b, "{what}: trace CSV differs");
                runs += 1;
                spilled += rec.rows.spilled() as usize;
            }
        }
    }
    // Every run spilled (each has more than one row); the built-in set has 64 scenarios.
    assert!(runs >= 64 * 3, "{runs} runs");
    assert_eq!(spilled, runs);
}

/// A run long enough to spill (more than `SPILL_ROWS` rows) writes the same directory on one
/// thread and on two, byte for byte, and its trace has every row.
#[test]
fn a_run_that_spills_is_byte_identical_on_one_thread_and_on_two() {
    let dir = tempfile::tempdir().unwrap();
    // 1,100 s at 60 Hz: 66,001 rows, past the 65,536 a run holds in memory.
    let map = format!("#{}#\n", ".".repeat(18)).repeat(3) + &"#".repeat(20);
    let level = format!(
        "name = \"soak\"\nmap = \"\"\"\n{map}\n\"\"\"\n\n[[scenario]]\nname = \"walk\"\n\
         spawn = [10.5, 1.0]\nduration = 1100.0\n\
         inputs = [ {{ t = 1.0, right = true }}, {{ t = 2.0, right = false, left = true }}, {{ t = 3.0, left = false }} ]\n"
    );
    let file = dir.path().join("soak.toml");
    std::fs::write(&file, level).unwrap();
    let (one, two) = (dir.path().join("one"), dir.path().join("two"));
    for (jobs, out_dir) in [("1", &one), ("2", &two)] {
        let out = platbench()
            .args(["run", "--backend", "sweep", "--jobs", jobs, "--out"])
            .arg(out_dir)
            .arg(&file)
            .output()
            .unwrap();
        assert_success(&out);
    }
    let (a, b) = (files(&one), files(&two));
    let trace = a
        .iter()
        .find(|(name, _)| name.ends_with("soak.walk.sweep.csv"))
        .expect("the default sweep's trace");
    // A header and one row per frame.
    assert_eq!(trace.1.iter().filter(|&&c| c == b'\n').count(), 1 + 66_001);
    assert_eq!(a.len(), b.len());
    for ((na, da), (nb, db)) in a.iter().zip(&b) {
        assert_eq!(na, nb);
        assert!(da == db, "{na} differs");
    }
}

//! `platbench review --accept`: one accepted run changes that run's part of the baseline, and
//! nothing else, byte for byte.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::ExitCode;

use super::toy::{cli, harness, path, setup, statuses};

/// Every file under `dir` (relative path to bytes).
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().display().to_string();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// The lines of a metrics.csv of run `prefix` (`level,scenario,backend,config,`) and the others.
fn split_lines(bytes: &[u8], prefix: &str) -> (Vec<String>, Vec<String>) {
    String::from_utf8(bytes.to_vec())
        .unwrap()
        .lines()
        .map(str::to_string)
        .partition(|l| l.starts_with(prefix))
}

#[test]
fn accepting_one_run_leaves_the_rest_of_the_baseline_byte_identical() {
    let (dir, level) = setup();
    let bl = dir.path().join("baseline");
    let (before, after) = (harness(false, &bl), harness(true, &bl));
    assert_eq!(cli(&before, &["baseline", path(&level)]), ExitCode::SUCCESS);
    let ck = dir.path().join("check");
    assert_eq!(
        cli(&after, &["check", "--out", path(&ck)]),
        ExitCode::from(1)
    );
    let old = files(&bl);
    assert_eq!(
        cli(
            &after,
            &["review", path(&ck), "--accept", "plain.drop/toy flush"]
        ),
        ExitCode::SUCCESS
    );
    let new = files(&bl);
    let accepted_trace = "traces/plain.drop.toy.flush.csv";
    assert_eq!(
        old.keys().collect::<Vec<_>>(),
        new.keys().collect::<Vec<_>>()
    );
    for (name, bytes) in &old {
        if name == "metrics.csv" || name == accepted_trace {
            continue;
        }
        assert!(new[name] == *bytes, "{name} changed");
    }
    // The accepted trace is the check's, byte for byte.
    assert_ne!(new[accepted_trace], old[accepted_trace]);
    assert_eq!(
        new[accepted_trace],
        std::fs::read(ck.join(accepted_trace)).unwrap()
    );
    // metrics.csv: the accepted run's rows are the check's, every other line the baseline's,
    // in its order.
    let run = "plain,drop,toy,flush,";
    let (old_run, old_rest) = split_lines(&old["metrics.csv"], run);
    let (new_run, new_rest) = split_lines(&new["metrics.csv"], run);
    assert_eq!(old_rest, new_rest);
    assert_ne!(old_run, new_run);
    let (check_run, _) = split_lines(&std::fs::read(ck.join("metrics.csv")).unwrap(), run);
    assert_eq!(new_run, check_run);
    // The page replaying both traces was written, self-contained.
    let page = std::fs::read_to_string(ck.join("review/plain.drop.toy.flush.html")).unwrap();
    assert!(page.contains("flush (baseline)") && page.contains("flush (new)"));
    assert!(!page.contains("src=\"http"));
    // A check now fails on the rejected run only.
    let again = dir.path().join("again");
    assert_eq!(
        cli(&after, &["check", "--out", path(&again)]),
        ExitCode::from(1)
    );
    for (scenario, config, status) in statuses(&again) {
        let rejected = scenario == "plain.drop" && config == "toy hover";
        assert_eq!(status != "pass", rejected, "{scenario} {config}: {status}");
    }
    // Rejecting everything changes nothing.
    let now = files(&bl);
    assert_eq!(
        cli(&after, &["review", path(&again), "--reject-all"]),
        ExitCode::SUCCESS
    );
    assert!(files(&bl) == now);
}

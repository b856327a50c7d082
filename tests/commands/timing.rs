//! `run --timing` and `diff --fail-on-timing` as a detector: two runs of the same code pass,
//! a controller made twice as slow is caught. Performance itself is never asserted here (the
//! house rule): these tests assert what the diff concludes from its own measured noise, read
//! from the run directories' `metrics.csv` and from the exit status, as CI would see them.

use std::path::Path;
use std::process::ExitCode;

use glam::Vec2;

use platbench::backend::{BackendError, CharacterId, CharacterState};
use platbench::cli::{run_cli, Harness};
use platbench::config::RunConfig;
use platbench::controller::{Controller, Setup};
use platbench::level::Features;
use platbench::motion::{Contacts, Input, MotionParams, MotionState};
use platbench::registry::Registry;

/// A toy controller whose step does `WORK` rounds of a dependent arithmetic chain before the
/// shared motion over a flat floor at the level's highest solid top: its cost is that chain
/// (no memory traffic, so the cache other tests disturb hardly matters), twice as much with
/// twice the `WORK`. Every `WORK` is named `spin` with one configuration, `default`: runs of two
/// of them compare as the same configuration, as a change to a controller's code does.
#[derive(Clone, Debug, Default, PartialEq)]
struct Spin<const WORK: u32>;

struct SpinMover {
    floor: f32,
    params: MotionParams,
    chars: Vec<(Vec2, MotionState)>,
}

impl<const WORK: u32> Controller for Spin<WORK> {
    type Mover = SpinMover;
    const NAME: &'static str = "spin";

    fn features(&self) -> Features {
        Features::NONE
    }

    fn build(&self, setup: Setup<'_>) -> Result<SpinMover, BackendError> {
        Ok(SpinMover {
            floor: setup
                .level
                .solid_boxes()
                .map(|b| b.maxs.y)
                .fold(f32::MIN, f32::max),
            params: setup.params.clone(),
            chars: setup
                .characters
                .iter()
                .map(|c| (c.spawn, MotionState::with_velocity(c.velocity)))
                .collect(),
        })
    }

    fn step(&self, m: &mut SpinMover, inputs: &[Input], dt: f32) {
        // The work: a chain of WORK multiply-adds, each depending on the last.
        let mut x = std::hint::black_box(1.000_001_f64);
        for _ in 0..WORK {
            x = x.mul_add(std::hint::black_box(0.999_999), 1e-9);
        }
        std::hint::black_box(x);
        for (k, (pos, motion)) in m.chars.iter_mut().enumerate() {
            let input = inputs.get(k).copied().unwrap_or_default();
            *pos += motion.integrate(&m.params, &input, dt);
            let ground = pos.y <= m.floor;
            if ground {
                pos.y = m.floor;
            }
            motion.apply_contacts(
                &m.params,
                &input,
                Contacts {
                    ground,
                    ..Default::default()
                },
            );
        }
    }

    fn state(&self, m: &SpinMover, id: CharacterId) -> CharacterState {
        let (pos, motion) = &m.chars[id];
        CharacterState {
            pos: *pos,
            vel: motion.vel,
            grounded: motion.grounded,
            ground_normal: if motion.grounded { Vec2::Y } else { Vec2::ZERO },
            ..Default::default()
        }
    }

    fn configs() -> Vec<RunConfig> {
        vec![RunConfig::new("default", Spin::<WORK>)]
    }
}

/// The chain's length for the toy as it is: a few microseconds a step in release (about a
/// nanosecond a link), far above the clock's resolution and the shared motion's cost.
const BASE: u32 = 3000;

/// Two scenarios of one second (60 steps): each timed 11 times, a fraction of a second in all.
/// Few rows, few chances for a noisy one; two, so that the diff compares more than one.
const LEVEL: &str = "name = \"plain\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"drop\"\nspawn = [2.5, 2.5]\nduration = 1.0\n[[scenario]]\nname = \"walk\"\nspawn = [1.5, 1.0]\nduration = 1.0\ninputs = [ { t = 0.0, right = true } ]\n";

fn cli(h: &Harness, args: &[&str]) -> ExitCode {
    let mut all = vec!["platbench"];
    all.extend_from_slice(args);
    run_cli(h, all)
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// Runs the toy of `registry` on the test level with --timing into `out`, and returns the
/// timing rows of its metrics.csv as (median, q1, q3).
fn timed_run(registry: Registry, dir: &Path, out: &Path) -> Vec<(f64, f64, f64)> {
    let level = dir.join("plain.toml");
    std::fs::write(&level, LEVEL).unwrap();
    let h = Harness {
        registry,
        baseline: dir.join("baseline"),
    };
    assert_eq!(
        cli(
            &h,
            &[
                "run",
                path(&level),
                "--timing",
                "--traces",
                "none",
                "--out",
                path(out)
            ]
        ),
        ExitCode::SUCCESS
    );
    let metrics = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    let header: Vec<&str> = metrics.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (value, q1, q3) = (col("value"), col("q1"), col("q3"));
    let rows: Vec<(f64, f64, f64)> = metrics
        .lines()
        .filter(|l| l.contains(",ns_per_character_step,"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f[i].parse::<f64>().unwrap();
            (num(value), num(q1), num(q3))
        })
        .collect();
    assert_eq!(rows.len(), 2, "{metrics}");
    for &(m, lo, hi) in &rows {
        assert!(0.0 < lo && lo <= m && m <= hi, "{metrics}");
    }
    rows
}

/// `diff BASE NEW --fail-on-timing` on a harness that knows the toy (the diff reads files only).
fn diff_fails_on_timing(dir: &Path, base: &Path, new: &Path) -> ExitCode {
    let h = Harness {
        registry: Registry::new().with::<Spin<BASE>>(),
        baseline: dir.join("baseline"),
    };
    cli(&h, &["diff", path(base), path(new), "--fail-on-timing"])
}

#[test]
fn two_timed_runs_of_the_same_controller_pass_diff_fail_on_timing() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    timed_run(Registry::new().with::<Spin<BASE>>(), dir.path(), &a);
    timed_run(Registry::new().with::<Spin<BASE>>(), dir.path(), &b);
    // Both ways: neither run may call the other slower. The diff calls a timing worse only
    // when the two runs' interquartile ranges do not overlap and the median moved by more than
    // 1 ns + 60% (docs/speed.md): two runs of the same code stay within that on a loaded
    // machine (the largest move measured between identical runs of the built-in set was 72%,
    // with overlapping ranges; none beyond 60% had its ranges apart).
    assert_eq!(diff_fails_on_timing(dir.path(), &a, &b), ExitCode::SUCCESS);
    assert_eq!(diff_fails_on_timing(dir.path(), &b, &a), ExitCode::SUCCESS);
}

#[test]
fn a_controller_made_at_least_twice_as_slow_is_reported_worse() {
    let dir = tempfile::tempdir().unwrap();
    let (fast, slow) = (dir.path().join("fast"), dir.path().join("slow"));
    let before = timed_run(Registry::new().with::<Spin<BASE>>(), dir.path(), &fast);
    // Four times the work: at least twice the step's cost in any build. In release the chain is
    // nearly all of the step, and four times it is about four times the step; in a debug build
    // (what `cargo test` runs) the step has a fixed part too, measured on this machine at about
    // 30 of the 53 microseconds of the toy as it is (twice the work gave only 1.45 times the
    // step, which the diff rightly does not call beyond its 60%), and four times the work gives
    // about 2.3 times. Twice the step's cost, +100%, is beyond the diff's 60% with room for the
    // noise of a loaded machine, and the toy's quartiles lie a few percent apart.
    let after = timed_run(
        Registry::new().with::<Spin<{ 4 * BASE }>>(),
        dir.path(),
        &slow,
    );
    // The diff says the new run is slower: --fail-on-timing fails (exit 1) ...
    assert_eq!(
        diff_fails_on_timing(dir.path(), &fast, &slow),
        ExitCode::from(1),
        "medians and quartiles before {before:?}, after {after:?}"
    );
    // ... and only timings changed: without it the diff passes (a timing never fails alone).
    let h = Harness {
        registry: Registry::new().with::<Spin<BASE>>(),
        baseline: dir.path().join("baseline"),
    };
    assert_eq!(
        cli(&h, &["diff", path(&fast), path(&slow)]),
        ExitCode::SUCCESS
    );
}

#[test]
#[cfg(all(feature = "rapier", feature = "box2d"))]
fn timing_adds_a_cost_row_per_scenario_and_configuration() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("t.toml");
    std::fs::write(
        &level,
        "name = \"t\"\nmap = \"\"\"\n....\n####\n\"\"\"\n[[scenario]]\nname = \"stand\"\nspawn = [1.5, 1.0]\nduration = 0.5\n",
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = crate::common::platbench()
        .args(["run", "--timing", "--out"])
        .arg(&out_dir)
        .arg(&level)
        .output()
        .unwrap();
    crate::common::assert_success(&out);
    let metrics = std::fs::read_to_string(out_dir.join("metrics.csv")).unwrap();
    let timing: Vec<&str> = metrics
        .lines()
        .filter(|l| l.contains(",ns_per_character_step,"))
        .collect();
    // One scenario on the 23 configurations of the built-in comparison: 3 sweep, 4 Rapier
    // shapes on 2 collider buildings fed gravity every step and again fed as Rapier's examples
    // feed them, and Box2D's capsule on 2 collider buildings with its advised and
    // grid-best-spring rows (`Box2dKind::builtin_configs`).
    assert_eq!(
        timing.len(),
        platbench::registry::Registry::builtin()
            .builtin_configs()
            .len(),
        "{metrics}"
    );
    assert_eq!(timing.len(), 23);
    // The value is the median of the samples, between their quartiles (the last two columns,
    // after the empty frame).
    assert!(metrics.starts_with(
        "level,scenario,backend,config,metric,value,unit,reference,error,frame,q1,q3\n"
    ));
    for l in timing {
        let f: Vec<&str> = l.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let (value, q1, q3) = (num(5), num(10), num(11));
        assert!(value.is_finite() && value > 0.0, "{l}");
        assert!(q1 <= value && value <= q3, "{l}");
    }
    // The closing lines: the cheapest configuration against each of the 22 others, over the
    // one scenario.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let closing: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains(" × cheaper than ") || l.contains(" × what "))
        .collect();
    assert_eq!(closing.len(), 22, "{stdout}");
    assert!(
        closing
            .iter()
            .all(|l| l.ends_with("(median over 1 scenario)")),
        "{stdout}"
    );
}

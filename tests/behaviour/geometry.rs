//! The geometric metrics (`max_penetration`, `rest_gap`, `slope_gap_max`, `slope_overlap`)
//! measure every controller's real shape against the real level surface, slopes included
//! (nothing is left out for slopes, docs/metrics.md): the sweep's box overhanging a ramp by design
//! is measured as what it is, and feet moved below a slope's surface are seen.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{evaluate_all, level, rows};
use platbench::metrics::{compute, Context, DeclaredContact, MetricRow};
use platbench::motion::MotionParams;
use platbench::scenario::effective_params;
use platbench::shape::CharacterShape;
use platbench::trace::Trace;

/// The straight ramps of the built-in set and their gradients (the `line` heights of their
/// legend rise by this much per tile).
const RAMPS: [(&str, f64); 4] = [
    ("slope_22_5", 0.41421),
    ("slope_26_6", 0.5),
    ("slope_45", 1.0),
    ("slope_63_4", 2.0),
];

#[test]
fn the_sweeps_box_overlaps_each_ramp_by_its_designed_overhang() {
    for (name, gradient) in RAMPS {
        let evals = evaluate_all(&[level(name)], &platbench::sweep::kind::run_default());
        let overlaps = rows(&evals, "slope_overlap");
        assert!(!overlaps.is_empty(), "{name}: slope_overlap measured");
        // The seed's centre-column rule stands the box's centre on the surface: its uphill
        // corner is half the width (0.4) times the gradient below the surface, which is
        // 0.4 sin(angle) along the ramp's normal (parry's penetration depth). Every scenario
        // that stands on the ramp reaches it, none exceeds it (1e-4: f32 positions of a few
        // tiles).
        let designed = 0.4 * gradient.atan().sin();
        let worst = overlaps.iter().map(|r| r.value).fold(0.0, f64::max);
        assert!(
            (worst - designed).abs() < 1e-4,
            "{name}: overlap {worst}, designed {designed}"
        );
    }
}

#[test]
fn the_sweeps_box_at_the_foot_of_a_too_steep_slope_is_charged_beyond_its_design() {
    // The centre-column climb limit stops the box with its centre at the foot of the 63.4-degree
    // ramp and its leading half inside it: 0.4 sin(63.4) = 0.358 deep, deeper than the design
    // allows on any walkable ramp (0.4 sin(45), the climb limit). The excess, less the epsilon
    // (0.001 tiles, the sweep's default), is charged; the walkable ramps charge nothing.
    let evals = evaluate_all(
        &RAMPS.map(|(n, _)| level(n)),
        &platbench::sweep::kind::run_default(),
    );
    let beyond = rows(&evals, "penetration_beyond_declared");
    assert!(!beyond.is_empty());
    // The allowance keeps 1e-4 tiles of slack for f32 noise on a ramp at the limit itself.
    let excess = 0.4 * 2f64.atan().sin() - 0.4 * std::f64::consts::FRAC_PI_4.sin() - 0.001 - 1e-4;
    for (scenario, e) in &evals {
        let v = value(&e.metrics, "penetration_beyond_declared");
        let expected = if scenario.starts_with("slope_63_4.walk_into_steep") {
            excess
        } else {
            0.0
        };
        // 1e-5: f32 positions of a few tiles (measured within 1e-7).
        assert!(
            (v - expected).abs() < 1e-5,
            "{scenario}: penetration_beyond_declared {v}, expected {expected}"
        );
    }
}

/// The metrics of `t` on `spec`, recomputed for the sweep's box.
fn metrics_of(name: &str, scenario: &str, t: &Trace, declared: DeclaredContact) -> Vec<MetricRow> {
    metrics_with(name, scenario, t, declared, CharacterShape::Cuboid)
}

/// The metrics of `t` on `spec`, recomputed for a character of `shape`.
fn metrics_with(
    name: &str,
    scenario: &str,
    t: &Trace,
    declared: DeclaredContact,
    shape: CharacterShape,
) -> Vec<MetricRow> {
    let level = level(name);
    let spec = level
        .scenarios
        .iter()
        .find(|s| s.name == scenario)
        .expect("scenario exists");
    let params = effective_params(&MotionParams::default(), spec);
    compute(&Context {
        shape,
        level: &level,
        spec,
        params: &params,
        trace: t,
        declared,
    })
}

fn value(rows: &[MetricRow], m: &str) -> f64 {
    rows.iter()
        .find(|r| r.metric == m)
        .unwrap_or_else(|| panic!("{m} measured"))
        .value
}

#[test]
fn feet_moved_below_a_slope_are_seen() {
    // Take the sweep's own traces on the 45-degree ramp and move its feet 0.2 tiles down
    // wherever it stands over the ramp: every geometric metric must move by the depth that
    // adds. A box against a 45-degree line that moves down by d goes d cos 45 deeper along the
    // line's normal (its deepest corner stays the same), so the depth grows by 0.2 cos 45 =
    // 0.1414; 1e-3 allows the f32 positions.
    let deeper = 0.2 * std::f64::consts::FRAC_PI_4.cos() - 1e-3;
    let hill = level("slope_45");
    for scenario in ["rest_on_slope", "walk_right"] {
        let evals = evaluate_all(
            std::slice::from_ref(&hill),
            &platbench::sweep::kind::run_default(),
        );
        let (_, e) = evals
            .iter()
            .find(|(n, _)| n.ends_with(&format!(".{scenario}")))
            .expect("scenario ran");
        let sweep = platbench::sweep::kind::run_default()
            .backend
            .declared_contact(glam::Vec2::new(0.8, 0.9), std::f32::consts::FRAC_PI_4);
        let before = metrics_of("slope_45", scenario, &e.trace, sweep);
        let mut sunk = e.trace.clone();
        let mut moved = 0;
        for r in &mut sunk.rows {
            let over_ramp = matches!(hill.surface_at(r.x, r.y + 0.5, 1.5), Some((_, Some(_))));
            if over_ramp {
                r.y -= 0.2;
                moved += 1;
            }
        }
        assert!(moved > 10, "{scenario}: {moved} frames over the ramp");
        let after = metrics_of("slope_45", scenario, &sunk, sweep);
        for m in ["slope_overlap", "max_penetration"] {
            let (b, a) = (value(&before, m), value(&after, m));
            assert!(a >= b + deeper, "{scenario} {m}: {b} -> {a}");
        }
        let (b, a) = (
            value(&before, "slope_gap_max"),
            value(&after, "slope_gap_max"),
        );
        assert!(a <= b - deeper, "{scenario} slope_gap_max: {b} -> {a}");
        // Against the sweep's own promise (its box standing on the surface under its centre,
        // overlapping the ramp by 0.4 sin 45 along the normal, plus epsilon): kept before (0),
        // broken after by the whole sinking: 0.2 cos 45 - 0.001 = 0.1404 along the normal
        // (1e-3: f32).
        let (b, a) = (
            value(&before, "penetration_beyond_declared"),
            value(&after, "penetration_beyond_declared"),
        );
        assert_eq!(b, 0.0, "{scenario}");
        assert!(
            a >= 0.1404 - 1e-3,
            "{scenario} penetration_beyond_declared {a}"
        );
        if scenario == "rest_on_slope" {
            let (b, a) = (value(&before, "rest_gap"), value(&after, "rest_gap"));
            assert!(a <= b - deeper, "rest_gap: {b} -> {a}");
        }
    }
}

#[test]
fn a_bounce_after_landing_is_charged() {
    // The sweep's drop_3 lands and stays down (bounce_frames 0). Lift its trace off the
    // floor for 12 frames right after it first touched ground, as a bouncing controller
    // would: bounce_frames counts exactly those frames, while land_frame_error (first grounded
    // frame) and rest_jitter (the settled last 0.5 s) do not see them.
    let evals = evaluate_all(&[level("drops")], &platbench::sweep::kind::run_default());
    let (_, e) = evals
        .iter()
        .find(|(n, _)| n.ends_with(".drop_3"))
        .expect("drop_3 ran");
    let declared = DeclaredContact::default();
    let value = |m: &[MetricRow], name: &str| {
        m.iter()
            .find(|r| r.metric == name)
            .unwrap_or_else(|| panic!("{name}"))
            .value
    };
    let before = metrics_of("drops", "drop_3", &e.trace, declared);
    assert_eq!(value(&before, "bounce_frames"), 0.0);
    let mut bounced = e.trace.clone();
    let landed = bounced
        .rows
        .iter()
        .position(|r| r.grounded != 0)
        .expect("it lands");
    for r in &mut bounced.rows[landed + 1..landed + 13] {
        r.grounded = 0;
        r.y += 0.5;
    }
    let after = metrics_of("drops", "drop_3", &bounced, declared);
    assert_eq!(value(&after, "bounce_frames"), 12.0);
    assert_eq!(
        value(&after, "land_frame_error"),
        value(&before, "land_frame_error")
    );
}

#[test]
fn feet_moved_below_a_one_way_top_are_seen() {
    // The real geometry, for one-way tops (docs/metrics.md: the depth below a one-way top a shape
    // stands on is an overlap): take a controller's own trace landing on the one-way platform (top
    // at y = 4) and move its feet 0.2 tiles down on every grounded frame there. A one-way top
    // resists only downward motion, so the depth is vertical: max_penetration must reach 0.2 and
    // rest_gap fall by 0.2 (1e-3: f32 positions), and the promise metric must see the sinking
    // beyond the declared overlap tolerance. The same frames untouched read nothing: passing up
    // through the platform (jump_through_from_below) is inside it by right.
    let oneway = level("oneway");
    let size = glam::Vec2::new(0.8, 0.9);
    let sweep = platbench::sweep::kind::run_default();
    let rapier = platbench::rapier::kind::run(
        platbench::rapier::ColliderBuilding::PerTile,
        CharacterShape::Capsule,
    );
    for (run, shape) in [
        (&sweep, CharacterShape::Cuboid),
        (&rapier, CharacterShape::Capsule),
    ] {
        let declared = run
            .backend
            .declared_contact(size, std::f32::consts::FRAC_PI_4);
        let evals = evaluate_all(std::slice::from_ref(&oneway), run);
        let trace = |s: &str| {
            &evals
                .iter()
                .find(|(n, _)| n.ends_with(&format!(".{s}")))
                .expect("scenario ran")
                .1
                .trace
        };
        let through = metrics_with(
            "oneway",
            "jump_through_from_below",
            trace("jump_through_from_below"),
            declared,
            shape,
        );
        assert!(
            value(&through, "max_penetration") < 1e-3,
            "{}: jumping up through the platform is no penetration",
            run.label
        );
        let before = metrics_with(
            "oneway",
            "land_on_top",
            trace("land_on_top"),
            declared,
            shape,
        );
        let mut sunk = trace("land_on_top").clone();
        let mut moved = 0;
        for r in &mut sunk.rows {
            if r.grounded != 0 && r.y > 3.5 {
                r.y -= 0.2;
                moved += 1;
            }
        }
        assert!(moved > 10, "{}: {moved} frames on the platform", run.label);
        let after = metrics_with("oneway", "land_on_top", &sunk, declared, shape);
        let (b, a) = (value(&before, "rest_gap"), value(&after, "rest_gap"));
        assert!(
            (a - (b - 0.2)).abs() < 1e-3,
            "{}: rest_gap {b} -> {a}",
            run.label
        );
        // A controller that kept a gap above the top (Rapier's offset) sinks 0.2 minus it.
        let kept = b.max(0.0);
        let (b, a) = (
            value(&before, "max_penetration"),
            value(&after, "max_penetration"),
        );
        assert!(
            a >= 0.2 - kept - 1e-3 && b < 1e-2,
            "{}: {b} -> {a}",
            run.label
        );
        let a = value(&after, "penetration_beyond_declared");
        assert!(
            a >= 0.2 - kept - declared.overlap_tolerance as f64 - 1e-3,
            "{}: penetration_beyond_declared {a}",
            run.label
        );
    }
}

/// A still trace of `n` steps standing grounded at feet `(x, y)` (the spawn row too).
fn still_trace(scenario: &str, x: f32, y: f32, n: u32) -> Trace {
    Trace {
        level: "l".into(),
        scenario: scenario.into(),
        backend: "x".into(),
        config: "y".into(),
        rows: (0..=n)
            .map(|k| platbench::trace::TraceRow {
                frame: k,
                t: k as f32 / 60.0,
                character: 0,
                x,
                y,
                vx: 0.0,
                vy: 0.0,
                grounded: (k > 0) as u8,
                ground_nx: 0.0,
                ground_ny: 1.0,
                platform: None,
                ladder: 0,
                crushed: 0,
            })
            .collect(),
    }
}

fn sweep_declared() -> DeclaredContact {
    platbench::sweep::kind::run_default()
        .backend
        .declared_contact(glam::Vec2::new(0.8, 0.9), std::f32::consts::FRAC_PI_4)
}

#[test]
fn a_box_pushed_into_a_wall_breaks_every_promise() {
    // Found by review: the allowance of the sweep's centre-column stance was taken at the
    // feet's x, where a wall beside the box overlaps it as much as it does the box, so a box
    // 0.2 inside a wall read 0 for the sweep and 0.2 for Rapier. Now a tile beside the body is
    // never allowed: the box's side 0.2 into the wall (x = 6) is charged 0.2 less each
    // controller's overlap tolerance, for both (1e-4: f32).
    let wall =
        "name = \"w\"\nmap = \"\"\"\n..........\n......#...\n......#...\n##########\n\"\"\"\n\
                [[scenario]]\nname = \"stand\"\nspawn = [5.6, 1.0]\nduration = 1.0\n";
    let level = platbench::level::parse_level(wall, "w.toml").unwrap();
    let rapier = platbench::rapier::kind::run(
        platbench::rapier::ColliderBuilding::PerTile,
        CharacterShape::Cuboid,
    )
    .backend
    .declared_contact(glam::Vec2::new(0.8, 0.9), std::f32::consts::FRAC_PI_4);
    // Box2D declares its pogo's sag (0.0338 at 60 Hz): found by the second review, the sag was
    // allowed into every tile, so a push of up to the sag into a wall read 0. It is allowed
    // only into the ground under the feet: standing sunk by the sag, the floor reads nothing and
    // the wall its 0.2.
    let box2d = platbench::box2d::kind::run_with(platbench::box2d::Box2dConfig::default())
        .backend
        .declared_contact_in(
            glam::Vec2::new(0.8, 0.9),
            &MotionParams::default(),
            1.0 / 60.0,
        );
    assert!(box2d.stance_sink > 0.03, "{box2d:?}");
    for d in [sweep_declared(), rapier, box2d] {
        let t = still_trace("stand", 5.8, 1.0 - d.stance_sink, 60);
        let spec = &level.scenarios[0];
        let params = effective_params(&MotionParams::default(), spec);
        let m = compute(&Context {
            shape: CharacterShape::Cuboid,
            level: &level,
            spec,
            params: &params,
            trace: &t,
            declared: d,
        });
        let beyond = value(&m, "penetration_beyond_declared");
        // The sink is no overlap tolerance: the wall's 0.2 less Box2D's linear slop (its
        // collision tolerance), not less the sag.
        let expected = if d.stance_sink > 0.0 {
            0.2 - platbench::box2d::LINEAR_SLOP as f64
        } else {
            0.2 - d.overlap_tolerance as f64
        };
        assert!((beyond - expected).abs() < 1e-4, "{d:?}: {beyond}");
    }
}

#[test]
fn feet_sunk_deep_below_a_ramp_are_seen_at_every_depth() {
    // Found by review: the stance was looked for within the overhang of the feet, so a box sunk
    // deeper than that found the ramp's solid mass below and was allowed more overlap than it
    // had (0 at sinks of 0.45, 0.5, 0.8). The surface is now found from mid-body down.
    // Every sink from 0.2 tiles down is charged at least what the 0.2 sink is charged on the
    // ramp (0.2 cos 45 less the 0.001 epsilon = 0.1404 along the normal, as in
    // feet_moved_below_a_slope_are_seen; 1e-3 for f32): measured 0.140 to 0.499 at x = 7.5 and
    // 7.9 and sinks 0.2 to 0.8. Standing on the surface is charged nothing.
    let floor = 0.2 * std::f64::consts::FRAC_PI_4.cos() - 0.001 - 1e-3;
    for x in [7.5f32, 7.9] {
        for sink in [0.0f32, 0.2, 0.45, 0.5, 0.6, 0.8] {
            // slope_45's ramp surface is y = x - 5 over x in [6, 10].
            let t = still_trace("rest_on_slope", x, x - 5.0 - sink, 90);
            let m = metrics_of("slope_45", "rest_on_slope", &t, sweep_declared());
            let beyond = value(&m, "penetration_beyond_declared");
            if sink == 0.0 {
                assert_eq!(beyond, 0.0, "x {x}");
            } else {
                assert!(beyond >= floor, "x {x} sink {sink}: {beyond}");
            }
        }
    }
}

/// The sweep's own run of `walk_right` on `hill`.
fn sweep_walk_right(hill: &platbench::level::Level) -> platbench::metrics::Evaluation {
    let spec = hill
        .scenarios
        .iter()
        .find(|s| s.name == "walk_right")
        .expect("walk_right exists");
    platbench::metrics::evaluate(hill, spec, &platbench::sweep::kind::run_default())
        .expect("walk_right runs")
}

#[test]
fn a_sweep_hovering_over_a_ramp_while_it_walks_is_seen() {
    // Found by review: lifting the sweep's feet 0.09 tiles on every grounded frame over the ramp
    // of its own walk_right moved only slope_gap_max. slope_gap_declared measures the gap
    // against the declared stance: the lift, less the landing frames it leaves out (1e-3: f32).
    let hill = level("slope_45");
    let e = sweep_walk_right(&hill);
    let before = metrics_of("slope_45", "walk_right", &e.trace, sweep_declared());
    assert_eq!(value(&before, "slope_gap_declared"), 0.0);
    let mut lifted = e.trace.clone();
    for r in &mut lifted.rows {
        let over_ramp = matches!(hill.surface_at(r.x, r.y + 0.5, 1.5), Some((_, Some(_))));
        if over_ramp && r.grounded != 0 {
            r.y += 0.09;
        }
    }
    let after = metrics_of("slope_45", "walk_right", &lifted, sweep_declared());
    let hover = value(&after, "slope_gap_declared");
    assert!(hover >= 0.09 - 1e-3, "{hover}");
}

/// The sweep's `slope_45.walk_right` with the feet lifted by `lift` on the grounded frames
/// whose centre and both box edges are over the ramp, but every `keep`-th of them (0: all).
fn lift_mid_ramp(hill: &platbench::level::Level, t: &Trace, lift: f32, keep: usize) -> Trace {
    let on = |x: f32, y: f32| matches!(hill.surface_at(x, y + 0.5, 1.5), Some((_, Some(_))));
    let mut lifted = t.clone();
    let mut n = 0;
    for r in &mut lifted.rows {
        if r.grounded != 0 && on(r.x, r.y) && on(r.x - 0.45, r.y) && on(r.x + 0.45, r.y) {
            if keep == 0 || n % keep != keep - 1 {
                r.y += lift;
            }
            n += 1;
        }
    }
    assert!(n > 30, "{n} mid-ramp frames");
    lifted
}

#[test]
fn a_hover_on_some_frames_only_is_charged_and_judged_like_any_shape_s() {
    // Found by review: a three-frame window let a sweep hovering 0.3 tiles on two frames of
    // every three read 0; and the sweep's gap was a depth along the ramp's normal where its box
    // overlaps the ramp, so a lift read cos(angle) smaller than a drop measured for another
    // shape, and its corners inside the ramp read "supported" while it hovered. Every frame
    // counts now, vertically, and a sweep hovering beyond its stance is not supported.
    let hill = level("slope_45");
    let e = sweep_walk_right(&hill);
    for (lift, keep) in [(0.09f32, 3usize), (0.3, 3), (0.09, 0)] {
        let m = metrics_of(
            "slope_45",
            "walk_right",
            &lift_mid_ramp(&hill, &e.trace, lift, keep),
            sweep_declared(),
        );
        let hover = value(&m, "slope_gap_declared");
        // The lift itself, vertically, less the epsilon's tolerance (0.001) and f32 (1e-4).
        assert!(
            (hover - (lift as f64 - 0.001)).abs() < 1e-3,
            "lift {lift} keep {keep}: {hover}"
        );
        // Hovering 0.3 (beyond FLICKER_SUPPORT_TOLERANCE, 0.1) while reporting grounded is
        // standing on air, for the sweep as for any shape.
        let false_grounded = value(&m, "false_grounded");
        if lift > 0.1 {
            assert!(false_grounded > 30.0, "lift {lift}: {false_grounded}");
        } else {
            assert_eq!(false_grounded, 0.0, "lift {lift}");
        }
    }
}

#[test]
fn a_standing_character_that_reports_its_drift_is_still_charged() {
    // Found by review: idle_drift anchored only once the reported velocity had stopped, so a
    // standing character sliding at 0.5 tiles/s that reports vx = 0.5 read 0. It is anchored at
    // the latest REST_WINDOW (0.5 s) after the commanded glide ended: of the 2 s stand, 1.5 s of
    // drift (0.75 tiles) less the frame it anchors on (1e-2: one frame of 0.5 tiles/s).
    let lvl = level("flat_seams");
    let spec = lvl
        .scenarios
        .iter()
        .find(|s| s.name == "stand")
        .expect("stand exists");
    let e = platbench::metrics::evaluate(&lvl, spec, &platbench::sweep::kind::run_default())
        .expect("stand runs");
    let before = metrics_of("flat_seams", "stand", &e.trace, sweep_declared());
    assert_eq!(value(&before, "idle_drift"), 0.0);
    for reported in [false, true] {
        let mut t = e.trace.clone();
        for r in t.rows.iter_mut().skip(1) {
            r.x += 0.5 * r.t;
            if reported {
                r.vx = 0.5;
            }
        }
        let m = metrics_of("flat_seams", "stand", &t, sweep_declared());
        let drift = value(&m, "idle_drift");
        assert!(drift >= 0.75 - 1e-2, "reported {reported}: {drift}");
    }
}

//! The sweep's stability envelope, pinned at its edges (`platbench stress`): a change that
//! shrinks it fails here.

use platbench::stress::{stress_matrix, StressRow};

fn sweep_rows() -> Vec<StressRow> {
    stress_matrix(&[platbench::sweep::kind::run_default()], |_| {}).unwrap()
}

/// Whether every invariant (but those in `except`) held at `dim = v`.
fn holds(rows: &[StressRow], dim: &str, v: f64, except: &[&str]) -> bool {
    let mut seen = false;
    let all = rows
        .iter()
        .filter(|r| r.dimension == dim && r.value == v && !except.contains(&r.invariant.as_str()))
        .inspect(|_| seen = true)
        .all(|r| r.holds);
    assert!(seen, "no rows for {dim} = {v}");
    all
}

fn invariant_holds(rows: &[StressRow], dim: &str, v: f64, invariant: &str) -> bool {
    let r = rows
        .iter()
        .find(|r| r.dimension == dim && r.value == v && r.invariant == invariant)
        .unwrap_or_else(|| panic!("no {invariant} row for {dim} = {v}"));
    r.holds
}

#[test]
fn sweep_envelope_holds_to_1e6_tiles_and_across_every_other_extreme() {
    let rows = sweep_rows();
    // Offsets: every invariant holds up to 1e6 tiles from the origin (f32 spacing 1/16 tile
    // there): the sweep snaps onto exact tile faces, and the rider follows every move of the
    // elevator (Celeste's rule, the default since issue 23), so the elevator's drops in 0 or
    // 1/16-tile steps carry it exactly. Under the gravity rule (issue 5's) those steps left it
    // in the air at 1e6. At 1e7 (spacing 1 tile) it sinks 0.4 into the floor and cannot rest.
    for v in [0.0, 1e3, 1e4, 1e5, 1e6] {
        assert!(holds(&rows, "offset", v, &[]), "offset {v}");
    }
    assert!(
        !invariant_holds(&rows, "offset", 1e7, "stable_rest"),
        "offset 1e7 was expected to break the rest"
    );
    // Every other dimension of the matrix, at its extremes: dt 1e-4 to 0.2 s, speeds up to 1000
    // tiles/s, widths 0.01 to 10 tiles, epsilon 1e-1 down to 1e-9; every invariant, the carry on
    // both moving platforms included.
    for (dim, vs) in [
        ("dt", vec![1e-4, 0.2]),
        ("speed", vec![10.0, 1000.0]),
        ("width", vec![0.01, 10.0]),
        ("epsilon", vec![1e-1, 1e-9]),
    ] {
        for v in vs {
            assert!(holds(&rows, dim, v, &[]), "{dim} {v}");
        }
    }
}

#[test]
fn the_sweep_carries_its_riders_at_the_base_case_far_inside_the_allowance() {
    let rows = sweep_rows();
    let carry = rows
        .iter()
        .find(|r| r.dimension == "offset" && r.value == 0.0 && r.invariant == "carry_no_drift")
        .unwrap();
    // The sweep carries by the platform's displacement in the same step, so it has no lag: its
    // drift is f32 rounding of positions near 20 tiles (a few ulps of 2e-6), far below the
    // allowance for a controller that lags a step (at least 2 x 3.1 tiles/s x 1/60 s = 0.105, the
    // slower platform's).
    assert!(carry.measured < 1e-4, "drift {}", carry.measured);
    assert!(carry.tolerance > 0.1, "allowance {}", carry.tolerance);
}

#[test]
fn the_integer_mode_keeps_every_invariant_up_to_1e7_tiles_and_carries_with_no_drift_at_all() {
    let rows = stress_matrix(&[platbench::sweep::kind::run_integer(32)], |_| {}).unwrap();
    // Issue 12: offsets up to 1e7 tiles (3.2e8 subpixels: an i64 holds 2.9e17 tiles at 32 per
    // tile; the bound is the broadphase's f32 tile boxes, exact to 2^24 = 1.7e7 tiles), where
    // the float mode breaks (the test above). Every dimension at its extremes too.
    for v in [0.0, 1e3, 1e4, 1e5, 1e6, 1e7] {
        assert!(holds(&rows, "offset", v, &[]), "offset {v}");
    }
    for (dim, vs) in [
        ("dt", vec![1e-4, 0.2]),
        ("speed", vec![10.0, 1000.0]),
        ("width", vec![0.01, 10.0]),
    ] {
        for v in vs {
            assert!(holds(&rows, dim, v, &[]), "{dim} {v}");
        }
    }
    // Issue 23: the carry is measured at every value of every dimension (offset, dt, speed,
    // width: 19 values), and its drift over the 10 s rides is exactly 0, not within a tolerance:
    // the platforms move in whole subpixels along their path rounded to the grid, the rider is
    // moved by the same whole subpixels, and the drift is read against that rounded platform
    // (the one the mode moves), so any lost or extra subpixel would show as 1/32 tile.
    let carry: Vec<_> = rows
        .iter()
        .filter(|r| r.invariant == "carry_no_drift")
        .collect();
    assert_eq!(carry.len(), 6 + 5 + 3 + 5, "carry rows");
    for r in carry {
        assert_eq!(
            r.measured, 0.0,
            "{} = {}: carry drift",
            r.dimension, r.value
        );
    }
    assert!(rows.iter().all(|r| r.dimension != "epsilon"));
}

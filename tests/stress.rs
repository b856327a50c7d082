//! The sweep's stability envelope, pinned at its edges (`platbench stress`): a change that
//! shrinks it fails here.

use platbench::scenario::RunConfig;
use platbench::stress::stress_matrix;

#[test]
fn sweep_envelope_holds_to_1e6_tiles_and_across_every_other_extreme() {
    let rows = stress_matrix(&[RunConfig::sweep_default()], |_| {}).unwrap();
    let holds = |dim: &str, v: f64| {
        rows.iter()
            .filter(|r| r.dimension == dim && r.value == v)
            .all(|r| r.holds)
    };
    // Offsets: every invariant holds up to 1e6 tiles from the origin (f32 spacing 0.0625 there;
    // the sweep snaps onto exact tile faces) and breaks at 1e7 (spacing 1 tile: it sinks 0.4 into
    // the floor and cannot rest).
    for v in [0.0, 1e3, 1e4, 1e5, 1e6] {
        assert!(holds("offset", v), "offset {v}");
    }
    assert!(!holds("offset", 1e7), "offset 1e7 was expected to break");
    // Every other dimension of the matrix, at its extremes: dt 1e-4 to 0.2 s, speeds up to 1000
    // tiles/s, widths 0.01 to 10 tiles, epsilon 1e-1 down to 1e-9.
    for (dim, vs) in [
        ("dt", vec![1e-4, 0.2]),
        ("speed", vec![10.0, 1000.0]),
        ("width", vec![0.01, 10.0]),
        ("epsilon", vec![1e-1, 1e-9]),
    ] {
        for v in vs {
            assert!(holds(dim, v), "{dim} {v}");
        }
    }
}

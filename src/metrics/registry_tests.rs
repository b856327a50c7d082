//! The registry's unit tests: names, units, weights and the charge of an error.

use super::*;

#[test]
fn names_are_unique_and_units_known() {
    for (i, d) in METRICS.iter().enumerate() {
        assert!(
            METRICS[i + 1..].iter().all(|e| e.name != d.name),
            "{} twice",
            d.name
        );
        assert!(
            ["tiles", "ratio", "tiles/s", "frames", "count", "bool", "ns"].contains(&d.unit),
            "{}: {}",
            d.name,
            d.unit
        );
        assert!(d.weight >= 0.0 && d.weight.is_finite());
    }
}

#[test]
fn errors_under_a_pixel_are_not_charged() {
    let d = |name| get(name).unwrap();
    // At 16 px per tile one pixel is 0.0625 tiles: a 0.16-pixel hover (0.01 tiles, the
    // issue's example) is free; a pixel and a clearly-wrong size (0.0625 + 0.01) is 1.
    assert_eq!(d("rest_gap_declared").charged(0.01, 16.0), 0.0);
    assert_eq!(d("rest_gap_declared").charged(-0.0625, 16.0), 0.0);
    assert!((d("rest_gap_declared").charged(0.0725, 16.0) - 1.0).abs() < 1e-9);
    // At 32 px per tile the same 0.0725 is 1.15 pixels beyond the pixel (0.04125 tiles).
    assert!((d("rest_gap_declared").charged(0.0725, 32.0) - 4.125).abs() < 1e-9);
    // Speeds: one pixel per second (1/16 tiles/s) is free.
    assert_eq!(d("ladder_speed_error").charged(0.06, 16.0), 0.0);
    // Ratios, frames, counts and booleans have no pixel allowance.
    assert_eq!(d("progress_ratio").charged(0.02, 16.0), 2.0);
    assert_eq!(d("bounce_frames").charged(1.0, 16.0), 1.0);
    assert_eq!(d("tunneled").charged(1.0, 16.0), 1.0);
    assert_eq!(d("apex_error").charged(f64::NAN, 16.0), f64::INFINITY);
}

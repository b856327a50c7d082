//! The per-tile slope polygons Rapier collides with are the tiles cut by their slope lines, on
//! every built-in level and every test map. A hull that spanned a bottom corner the line never
//! reaches (what `Slope::outline` produced before) puts a false step into a ramp: tile `d` of
//! `slope_22_5` became (8,2)(9,2)(9,2.243) instead of (8.414,2)(9,2)(9,2.243), and every Rapier
//! shape stuck on it.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use glam::{DVec2, Vec2};
use platbench::level::{load_tiled_map, Level, Slope, Tile};
use platbench::rapier::{ColliderBuilding, StaticWorld};

/// How far a corner may sit off its tile's edges or slope line: 1e-6 tiles, far below the 0.17-tile
/// false step the old hull put into a ramp. Tile-local coordinates are computed here in f64 from
/// the f32 world points; the levels' slope corners sit at whole or line-crossing coordinates below
/// 100 tiles.
const TOL: f64 = 1e-6;

/// Every level to check: the built-in set and the Tiled test maps.
fn all_levels() -> Vec<Level> {
    let mut levels = common::builtin_levels();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/maps");
    for entry in std::fs::read_dir(&dir).expect("tests/maps") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "tmx") {
            let (level, _) =
                load_tiled_map(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            levels.push(level);
        }
    }
    levels
}

/// The polygon's area (shoelace formula).
fn area(pts: &[DVec2]) -> f64 {
    let n = pts.len();
    (0..n)
        .map(|k| pts[k].perp_dot(pts[(k + 1) % n]))
        .sum::<f64>()
        .abs()
        * 0.5
}

/// The area under the clamped line over the tile, by a fine midpoint sum (the clamped line is
/// piecewise linear with at most 3 pieces, so 10,000 samples are exact to about 1e-8).
fn area_under(left: f64, right: f64) -> f64 {
    let n = 10_000;
    (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) / n as f64;
            (left + (right - left) * u).clamp(0.0, 1.0)
        })
        .sum::<f64>()
        / n as f64
}

#[test]
fn per_tile_slope_polygons_are_the_tile_cut_by_the_line() {
    let mut checked = 0;
    for level in all_levels() {
        if !level.features.slopes {
            continue;
        }
        let world = StaticWorld::new(&level, ColliderBuilding::PerTile);
        for (_, collider) in world.colliders.iter() {
            let Some(poly) = collider.shape().as_convex_polygon() else {
                continue;
            };
            let pose = collider.position();
            let pts: Vec<Vec2> = poly
                .points()
                .iter()
                .map(|p| pose.transform_point(*p) - level.origin_f32())
                .collect();
            let centroid = pts.iter().copied().sum::<Vec2>() / pts.len() as f32;
            let (i, j) = (centroid.x.floor() as i64, centroid.y.floor() as i64);
            let Tile::Slope(Slope::Line { left, right }) = level.tile(i, j) else {
                panic!("{}: polygon {pts:?} is not on a line slope", level.name);
            };
            let local: Vec<DVec2> = pts
                .iter()
                .map(|p| p.as_dvec2() - DVec2::new(i as f64, j as f64))
                .collect();
            let (left, right) = (left as f64, right as f64);
            let line = |u: f64| left + (right - left) * u;
            let on_border = |p: DVec2| {
                p.y.abs() < TOL
                    || (p.y - 1.0).abs() < TOL
                    || p.x.abs() < TOL
                    || (p.x - 1.0).abs() < TOL
            };
            let what = format!(
                "{} tile ({i},{j}) line {left}..{right}: {local:?}",
                level.name
            );
            for p in &local {
                assert!(
                    (-TOL..=1.0 + TOL).contains(&p.x) && (-TOL..=1.0 + TOL).contains(&p.y),
                    "{what}: vertex outside the tile"
                );
                assert!(
                    p.y <= line(p.x).clamp(0.0, 1.0) + TOL,
                    "{what}: vertex above the line"
                );
                // No vertex on the bottom edge where the line runs below it (left of where a
                // rising line crosses the bottom, right of where a falling one does).
                assert!(
                    !(p.y.abs() < TOL && line(p.x) < -TOL),
                    "{what}: vertex on the bottom edge where the line is below the tile"
                );
            }
            // The top edge: every edge that is not on the tile's border lies on the line at
            // both ends.
            let n = local.len();
            for k in 0..n {
                let (a, b) = (local[k], local[(k + 1) % n]);
                let along_border = on_border(a)
                    && on_border(b)
                    && ((a.x - b.x).abs() < TOL || (a.y - b.y).abs() < TOL);
                if !along_border {
                    for p in [a, b] {
                        assert!(
                            (p.y - line(p.x)).abs() < TOL,
                            "{what}: top edge end {p:?} off the line"
                        );
                    }
                }
            }
            // All vertices under the line and the same area as the region under it: the
            // polygon is that region.
            let expected = area_under(left, right);
            assert!(
                (area(&local) - expected).abs() < 1e-4,
                "{what}: area {} against {expected}",
                area(&local)
            );
            checked += 1;
        }
    }
    // The built-in set alone has dozens of line-slope tiles; zero would mean nothing was read.
    assert!(checked >= 20, "only {checked} polygons checked");
}

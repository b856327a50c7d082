//! The level's static geometry as every collider-building controller gets it (Rapier's
//! colliders, Box2D's shapes, the move-and-slide example's parry2d shapes), written once: solid
//! boxes per tile or merged, one-way boxes, and slope outlines per tile or merged into seamless
//! ramps. Each controller turns these into its own shapes.

use glam::Vec2;

use crate::level::Level;
#[cfg(doc)]
use crate::level::Slope;

/// How solid tiles become colliders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColliderBuilding {
    /// One collider per tile: a cuboid per solid tile, a convex polygon per line slope, a
    /// polyline per height-array slope. What a naive tile-map import does; every tile edge is a
    /// seam a sliding shape can catch on.
    PerTile,
    /// Adjacent solid tiles merged into rectangles (row runs grown upward), and line slopes that
    /// continue one another merged into one polyline per straight ramp: far fewer colliders and
    /// no seams inside a merged floor or ramp.
    Merged,
}

impl ColliderBuilding {
    /// Label used in configs and CSV files.
    pub fn label(self) -> &'static str {
        match self {
            ColliderBuilding::PerTile => "per-tile",
            ColliderBuilding::Merged => "merged",
        }
    }
}

/// Solid tiles as boxes: one per tile, or adjacent tiles merged into rectangles.
pub fn solid_rects(
    level: &Level,
    building: ColliderBuilding,
) -> Vec<parry2d::bounding_volume::Aabb> {
    match building {
        ColliderBuilding::PerTile => level.solid_boxes().collect(),
        ColliderBuilding::Merged => level.merged_solid_rects(),
    }
}

/// One-way tiles (and ladder tops) as boxes: one per tile, or merged along each row. None for a
/// level without one-way tiles or ladders.
pub fn one_way_rects(
    level: &Level,
    building: ColliderBuilding,
) -> Vec<parry2d::bounding_volume::Aabb> {
    let mut out: Vec<parry2d::bounding_volume::Aabb> = Vec::new();
    if !(level.features.one_way || level.features.ladders) {
        return out;
    }
    for b in level.one_way_boxes() {
        match out.last_mut() {
            Some(last)
                if building == ColliderBuilding::Merged
                    && last.maxs.x == b.mins.x
                    && last.mins.y == b.mins.y =>
            {
                last.maxs.x = b.maxs.x
            }
            _ => out.push(b),
        }
    }
    out
}

/// The outlines of the level's slopes, in level coordinates, as Rapier gets them. Per tile:
/// each slope tile's solid part, [`Slope::outline`] (a convex polygon for a line: the tile cut
/// by the line; the surface polyline closed down both sides for a height array). Merged: one polyline per run of adjacent columns holding
/// slopes, following the ground's top surface across the run (slopes and the solids between
/// them), closed down both ends, with collinear points removed, so a ramp is one seamless
/// surface whatever rows it crosses.
pub fn slope_outlines(level: &Level, building: ColliderBuilding) -> Vec<Vec<Vec2>> {
    if building == ColliderBuilding::PerTile {
        return level
            .slopes()
            .map(|(i, j, s)| {
                let o = Vec2::new(i as f32, j as f32);
                s.outline().into_iter().map(|p| p + o).collect::<Vec<_>>()
            })
            .filter(|outline| !outline.is_empty())
            .collect();
    }
    let mut columns: Vec<i64> = level.slopes().map(|(i, _, _)| i).collect();
    columns.sort_unstable();
    columns.dedup();
    let mut out = Vec::new();
    let mut k = 0;
    while k < columns.len() {
        let mut end = k;
        while end + 1 < columns.len() && columns[end + 1] == columns[end] + 1 {
            end += 1;
        }
        out.push(ramp_outline(level, columns[k], columns[end]));
        k = end + 1;
    }
    out
}

/// The ground's top surface over columns `a..=b`, closed down to the lowest slope tile's
/// bottom at both ends.
fn ramp_outline(level: &Level, a: i64, b: i64) -> Vec<Vec2> {
    // The ground's top at x, probed just inside [x0, x1] and evaluated exactly on the tile
    // found there (a slope's own line, or a solid's top), walking down from the column's
    // highest slope tile, not from the map's top: a ceiling or a block above the ramp is its
    // own collider, not the ramp's surface.
    // `left`: the limit from the left, which differs at a height array's column boundary.
    let ground = |x: f32, probe: f32, left: bool| {
        let i = probe.floor() as i64;
        let highest = level
            .slopes()
            .filter(|(c, _, _)| *c == i)
            .map(|(_, j, _)| j)
            .max()
            .unwrap_or(-1);
        for j in (0..=highest).rev() {
            match level.tile(i, j) {
                crate::level::Tile::Slope(s) if s.height_at(probe - i as f32) > 0.0 => {
                    let u = x - i as f32;
                    return j as f32
                        + if left {
                            s.height_left_of(u)
                        } else {
                            s.height_at(u)
                        };
                }
                crate::level::Tile::Solid => return j as f32 + 1.0,
                _ => {}
            }
        }
        0.0
    };
    let base = |i: i64| {
        level
            .slopes()
            .filter(|(c, _, _)| *c == i)
            .map(|(_, j, _)| j as f32)
            .fold(f32::INFINITY, f32::min)
    };
    let mut xs: Vec<f32> = Vec::new();
    for (i, _, s) in level.slopes().filter(|(i, _, _)| (a..=b).contains(i)) {
        xs.extend(s.surface_points().iter().map(|p| i as f32 + p.x));
    }
    xs.sort_by(f32::total_cmp);
    xs.dedup_by(|p, q| (*p - *q).abs() < 1e-6);
    let (x0, x1) = (a as f32, b as f32 + 1.0);
    let nudge = 1e-4;
    let mut pts = vec![Vec2::new(x0, base(a))];
    for x in xs {
        let probe = x.clamp(x0 + nudge, x1 - nudge);
        let at = ground(x, probe, false);
        // A step of a height array (or between tiles): the riser, from the left's height.
        let from_left = ground(x, (x - nudge).clamp(x0 + nudge, x1 - nudge), true);
        if (from_left - at).abs() > 1e-6 {
            pts.push(Vec2::new(x, from_left));
        }
        pts.push(Vec2::new(x, at));
    }
    pts.push(Vec2::new(x1, base(b)));
    // Drop points in the middle of straight runs.
    let mut simple: Vec<Vec2> = Vec::with_capacity(pts.len());
    for p in pts {
        if simple.len() >= 2 {
            let (u, v) = (simple[simple.len() - 2], simple[simple.len() - 1]);
            if (v - u).perp_dot(p - v).abs() < 1e-5 && (v - u).dot(p - v) > 0.0 {
                simple.pop();
            }
        }
        simple.push(p);
    }
    simple
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::parse_level;

    #[test]
    fn straight_ramps_merge_and_per_tile_stays_per_tile() {
        // A 45-degree ramp of three '/' tiles climbing diagonally, on solids.
        let level = parse_level(
            "map = \"\"\"\n..../\n.../#\n../##\n#####\n\"\"\"\n",
            "r.toml",
        )
        .unwrap();
        let merged = slope_outlines(&level, ColliderBuilding::Merged);
        assert_eq!(merged.len(), 1, "{merged:?}");
        // Base, the foot of the ramp, its top, and down the far side: one straight surface.
        assert_eq!(
            merged[0],
            vec![
                Vec2::new(2.0, 1.0),
                Vec2::new(2.0, 1.0),
                Vec2::new(5.0, 4.0),
                Vec2::new(5.0, 3.0)
            ]
        );
        let per_tile = slope_outlines(&level, ColliderBuilding::PerTile);
        assert_eq!(per_tile.len(), 3);
        // A '/' tile is a triangle.
        assert_eq!(per_tile[0].len(), 3, "{:?}", per_tile[0]);
    }

    #[test]
    fn a_ceiling_above_a_ramp_is_not_its_surface() {
        // The same ramp under a ceiling: the merged outline still follows the ramp (it traced
        // the ceiling's top when probed from the map's top, and the ramp had no collider).
        let open = "map = \"\"\"\n.....\n..../\n.../#\n../##\n#####\n\"\"\"\n";
        let roofed = "map = \"\"\"\n#####\n..../\n.../#\n../##\n#####\n\"\"\"\n";
        let outline = |text: &str| {
            slope_outlines(
                &parse_level(text, "r.toml").unwrap(),
                ColliderBuilding::Merged,
            )
        };
        assert_eq!(outline(roofed), outline(open));
    }
}

//! What one grid cell holds ([`Tile`]) and the surface of a sloped one ([`Slope`]): its
//! heights across the tile, its outline and the polyline every controller collides with.

use glam::Vec2;

/// What one grid cell holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tile {
    /// Nothing: characters pass.
    Empty,
    /// A full solid square.
    Solid,
    /// A platform that blocks only from above (`=`).
    OneWay,
    /// A ladder (`H`).
    Ladder,
    /// A sloped tile.
    Slope(Slope),
}

/// The surface of a sloped tile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slope {
    /// The seed's integer height array: 16 heights in sixteenths of a tile, left to right.
    Heights([u8; 16]),
    /// The seed's line slope: surface heights at the tile's left and right edge, in tiles.
    /// Heights outside 0..=1 describe a line that leaves the tile through its top or bottom;
    /// the surface is clamped into the tile, so a straight ramp of any angle spans rows exactly.
    Line {
        /// Height of the line at the tile's left edge, in tiles.
        left: f32,
        /// Height of the line at the tile's right edge, in tiles.
        right: f32,
    },
}

impl Slope {
    /// The tile's solid part as an outline in tile-local coordinates, counter-clockwise from
    /// the bottom: the tile cut by its surface. Where the surface lies on the tile's bottom (a
    /// line that enters through the bottom edge, or zero heights), the outline starts or ends
    /// where the surface leaves the bottom, so that a convex hull of these points is exactly
    /// the solid part (a hull spanning a bottom corner the surface never reaches would add a
    /// false step to a ramp). Empty when the tile holds no solid area.
    pub fn outline(&self) -> Vec<Vec2> {
        let mut pts = vec![Vec2::ZERO];
        pts.extend(self.surface_points());
        pts.push(Vec2::X);
        pts.dedup_by(|a, b| (*a - *b).length() < 1e-6);
        // Drop bottom points whose neighbours both lie on the bottom too: collinear points
        // along the bottom edge and spurs back to a corner the surface does not reach.
        let on_bottom = |p: Vec2| p.y.abs() < 1e-6;
        let mut i = 0;
        while i < pts.len() && pts.len() >= 3 {
            let n = pts.len();
            let (prev, next) = (pts[(i + n - 1) % n], pts[(i + 1) % n]);
            if on_bottom(prev) && on_bottom(pts[i]) && on_bottom(next) {
                pts.remove(i);
                i = i.saturating_sub(1);
            } else {
                i += 1;
            }
        }
        if pts.len() < 3 || pts.iter().all(|p| on_bottom(*p)) {
            pts.clear();
        }
        pts
    }

    /// Surface height above the tile's bottom, in tiles, at `u` (0..=1 across the tile).
    ///
    /// Height arrays are the seed's step function: the entry under `u` (sixteenths of a tile).
    /// Line slopes interpolate from `left` at u = 0 to `right` at u = 1. (The seed's slide writes
    /// `Lerp(a, b, alpha) = a * alpha + b * (1 - alpha)` with `a` the left height, which would
    /// put the right height at the left edge; the surface here runs the intended way.)
    pub fn height_at(&self, u: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Slope::Heights(h) => h[((u * 16.0) as usize).min(15)] as f32 / 16.0,
            Slope::Line { left, right } => (left + (right - left) * u).clamp(0.0, 1.0),
        }
    }

    /// Surface height just left of `u`, in tiles: the same as [`Slope::height_at`] except at a
    /// column boundary of a height array, where it is the column to the left's.
    pub fn height_left_of(&self, u: f32) -> f32 {
        match self {
            Slope::Heights(h) => {
                let k = (u.clamp(0.0, 1.0) * 16.0).ceil() as usize;
                h[k.clamp(1, 16) - 1] as f32 / 16.0
            }
            Slope::Line { .. } => self.height_at(u),
        }
    }

    /// Heights at the tile's left and right edges, in tiles.
    pub fn edges(&self) -> (f32, f32) {
        (self.height_at(0.0), self.height_at(1.0))
    }

    /// The surface as a polyline in tile-local coordinates (x and y in 0..=1), left to right:
    /// the line itself, or for a height array its 16 columns as steps (the flat top of each
    /// column, with a vertical riser where two columns differ), the very surface the sweep
    /// stands on and the metrics measure, so that every controller collides with the same
    /// geometry.
    pub fn surface_points(&self) -> Vec<Vec2> {
        match self {
            Slope::Line { left, right } => {
                // The clamped line: its ends, and where it crosses the tile's bottom or top.
                let mut us = vec![0.0, 1.0];
                for level in [0.0f32, 1.0] {
                    if right != left {
                        let u = (level - left) / (right - left);
                        if u > 0.0 && u < 1.0 {
                            us.push(u);
                        }
                    }
                }
                us.sort_by(f32::total_cmp);
                us.into_iter()
                    .map(|u| Vec2::new(u, self.height_at(u)))
                    .collect()
            }
            Slope::Heights(h) => {
                let mut pts: Vec<Vec2> = Vec::with_capacity(32);
                for (i, v) in h.iter().enumerate() {
                    let y = *v as f32 / 16.0;
                    let (x0, x1) = (i as f32 / 16.0, (i + 1) as f32 / 16.0);
                    // Extend the previous column's top when this one is as high.
                    match pts.last_mut() {
                        Some(last) if last.y == y => last.x = x1,
                        _ => pts.extend([Vec2::new(x0, y), Vec2::new(x1, y)]),
                    }
                }
                pts
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_surfaces_run_left_to_right() {
        let up = Slope::Line {
            left: 0.0,
            right: 0.5,
        };
        assert_eq!(up.height_at(0.0), 0.0);
        assert_eq!(up.height_at(1.0), 0.5);
        assert_eq!(up.height_at(0.5), 0.25);
        let seed = Slope::Heights([12, 11, 10, 8, 7, 6, 5, 5, 5, 5, 5, 4, 3, 2, 1, 1]);
        assert_eq!(seed.height_at(0.0), 12.0 / 16.0);
        assert_eq!(seed.height_at(3.5 / 16.0), 8.0 / 16.0);
        assert_eq!(seed.height_at(1.0), 1.0 / 16.0);
        // 11 runs of equal heights (12, 11, 10, 8, 7, 6, 5 x5, 4, 3, 2, 1 x2), two points each.
        assert_eq!(seed.surface_points().len(), 22);
        assert_eq!(seed.height_left_of(3.0 / 16.0), 10.0 / 16.0);
        assert_eq!(seed.height_at(3.0 / 16.0), 8.0 / 16.0);
    }
}

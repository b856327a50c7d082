//! Queries on a level's tiles, the geometry every backend and metric reads: tile boxes, solid
//! rectangles merged for colliders, overlaps, the support and surface under a point, slope
//! normals, one-way tiles and ladders; and the character's box and the rounding of heights to
//! a grid.

use glam::Vec2;
use parry2d::bounding_volume::Aabb;

use super::{Level, Slope, Tile};
use crate::rounding::{ceil64, floor_to_i64, round64};

impl Level {
    /// The box of tile `(i, j)`.
    pub fn tile_box(i: i64, j: i64) -> Aabb {
        Aabb::new(
            Vec2::new(i as f32, j as f32),
            Vec2::new(i as f32 + 1.0, j as f32 + 1.0),
        )
    }

    /// Every solid tile's box, in row order.
    pub fn solid_boxes(&self) -> impl Iterator<Item = Aabb> + '_ {
        let w = self.width as usize;
        self.tiles
            .iter()
            .enumerate()
            .filter(|(_, t)| *t == Tile::Solid)
            .map(move |(k, _)| Self::tile_box((k % w) as i64, (k / w) as i64))
    }

    /// Solid tiles merged into rectangles: each row's runs of solid tiles, grown upward while
    /// the rows above hold the same run. Every solid tile is in exactly one rectangle.
    pub fn merged_solid_rects(&self) -> Vec<Aabb> {
        let (w, h) = (self.width as usize, self.height as usize);
        let solid = |i: usize, j: usize| self.tiles.get(j * w + i) == Tile::Solid;
        let mut used = vec![false; w * h];
        let mut out = Vec::new();
        for j in 0..h {
            let mut i = 0;
            while i < w {
                if !solid(i, j) || used[j * w + i] {
                    i += 1;
                    continue;
                }
                let mut i1 = i + 1;
                while i1 < w && solid(i1, j) && !used[j * w + i1] {
                    i1 += 1;
                }
                let mut j1 = j + 1;
                while j1 < h && (i..i1).all(|k| solid(k, j1) && !used[j1 * w + k]) {
                    j1 += 1;
                }
                for jj in j..j1 {
                    for k in i..i1 {
                        used[jj * w + k] = true;
                    }
                }
                out.push(Aabb::new(
                    Vec2::new(i as f32, j as f32),
                    Vec2::new(i1 as f32, j1 as f32),
                ));
                i = i1;
            }
        }
        out
    }

    /// The columns `i0..=i1` that lie within the map (an empty range, `i0 > i1`, if none do):
    /// outside the map every cell is empty, so a walk over cells that only looks for what the
    /// map holds costs the map's cells, not the area asked about.
    pub(crate) fn clip_columns(&self, i0: i64, i1: i64) -> (i64, i64) {
        (i0.max(0), i1.min(self.width as i64 - 1))
    }

    /// The rows `j0..=j1` that lie within the map (an empty range if none do); see
    /// [`Level::clip_columns`].
    pub(crate) fn clip_rows(&self, j0: i64, j1: i64) -> (i64, i64) {
        (j0.max(0), j1.min(self.height as i64 - 1))
    }

    /// Solid tiles whose boxes overlap `area` with positive area (touching does not count).
    /// Only the part of `area` inside the map is walked (outside is empty), so the work is
    /// bounded by the map however large or non-finite the area is.
    pub fn solids_overlapping(&self, area: &Aabb) -> impl Iterator<Item = Aabb> + '_ {
        let (w, h) = (self.width as i64, self.height as i64);
        let i0 = (area.mins.x.floor() as i64).clamp(0, w);
        let i1 = (area.maxs.x.ceil() as i64).clamp(0, w);
        let j0 = (area.mins.y.floor() as i64).clamp(0, h);
        let j1 = (area.maxs.y.ceil() as i64).clamp(0, h);
        let a = *area;
        (j0..j1)
            .flat_map(move |j| (i0..i1).map(move |i| (i, j)))
            .filter(move |&(i, j)| self.tile(i, j) == Tile::Solid)
            .map(|(i, j)| Self::tile_box(i, j))
            .filter(move |b| {
                b.mins.x < a.maxs.x
                    && a.mins.x < b.maxs.x
                    && b.mins.y < a.maxs.y
                    && a.mins.y < b.maxs.y
            })
    }

    /// The highest solid or one-way top at or below `y + tolerance` under the horizontal span
    /// `[x0, x1]` (open at both ends), or `None` if nothing is below.
    pub fn support_below(&self, x0: f32, x1: f32, y: f32, tolerance: f32) -> Option<f32> {
        // Columns outside the map hold nothing: the walk stays within it.
        let i0 = (x0.floor() as i64).clamp(0, self.width as i64);
        let i1 = (x1.ceil() as i64).clamp(0, self.width as i64);
        let top_row = ((y + tolerance).floor() as i64 - 1).min(self.height as i64 - 1);
        let mut best: Option<f32> = None;
        for i in i0..i1 {
            if (i as f32 + 1.0) <= x0 || i as f32 >= x1 {
                continue;
            }
            let mut j = top_row;
            while j >= 0 {
                if self.tile(i, j) == Tile::Solid || self.is_one_way(i, j) {
                    let top = j as f32 + 1.0;
                    best = Some(best.map_or(top, |b: f32| b.max(top)));
                    break;
                }
                j -= 1;
            }
        }
        best
    }
}

impl Level {
    /// The highest ground surface in column `floor(x)` at or below `top`, looking down at most
    /// `depth` tiles: a solid tile's top or a slope's surface at `x`. Returns the height and, for
    /// a slope, its tile.
    pub fn surface_at(&self, x: f32, top: f32, depth: f32) -> Option<(f32, Option<(i64, i64)>)> {
        let i = floor_to_i64(x);
        surface_walk(self.height, i, top, depth, |j| self.surface_cell(i, j, x))
    }

    /// What cell `(i, j)` offers [`Level::surface_at`]'s walk at `x` (in column `i`).
    #[inline]
    pub(crate) fn surface_cell(&self, i: i64, j: i64, x: f32) -> SurfaceCell {
        match self.tile(i, j) {
            Tile::Solid => SurfaceCell::Solid,
            Tile::Slope(s) => {
                // Where the surface is at the tile's bottom, this tile holds nothing at x.
                let local = s.height_at(x - i as f32);
                if local > 0.0 {
                    SurfaceCell::Slope(local)
                } else {
                    SurfaceCell::Open
                }
            }
            _ => SurfaceCell::Open,
        }
    }

    /// The slope surface's normal at `x` in slope tile `(i, j)`, from the gradient over a
    /// sixteenth of a tile around `x` (the width of one height-array column).
    pub fn slope_normal(&self, i: i64, j: i64, x: f32) -> Vec2 {
        let Tile::Slope(s) = self.tile(i, j) else {
            return Vec2::Y;
        };
        let u = x - i as f32;
        let (a, b) = ((u - 1.0 / 32.0).max(0.0), (u + 1.0 / 32.0).min(1.0));
        let grad = (s.height_at(b) - s.height_at(a)) / (b - a).max(1e-6);
        Vec2::new(-grad, 1.0).normalize()
    }

    /// Whether tile `(i, j)` is a solid tile carrying a slope tile: part of a ramp's mass, which
    /// the centre-column slope rules govern rather than the box sweep.
    pub fn supports_slope(&self, i: i64, j: i64) -> bool {
        self.tile(i, j) == Tile::Solid && matches!(self.tile(i, j + 1), Tile::Slope(_))
    }

    /// Whether tile `(i, j)` can be stood on from above only: a one-way platform, or the top
    /// tile of a ladder (which the seed makes walkable like a one-way platform).
    pub fn is_one_way(&self, i: i64, j: i64) -> bool {
        match self.tile(i, j) {
            Tile::OneWay => true,
            Tile::Ladder => self.tile(i, j + 1) != Tile::Ladder,
            _ => false,
        }
    }

    /// The run of ladder tiles in column `i` that contains row `j`, as (bottom, top) heights.
    pub fn ladder_extent(&self, i: i64, j: i64) -> Option<(f32, f32)> {
        let top = self.ladder_top(i, j)?;
        let mut lo = j;
        while self.tile(i, lo - 1) == Tile::Ladder {
            lo -= 1;
        }
        Some((lo as f32, top))
    }

    /// The top height of the run of ladder tiles in column `i` that contains row `j`
    /// ([`Level::ladder_extent`]'s top, without walking down to its bottom), read from the
    /// table of run tops the level keeps when it has ladders.
    #[inline]
    pub(crate) fn ladder_top(&self, i: i64, j: i64) -> Option<f32> {
        let hi = self.tiles.ladder_top(self.cell(i, j)?)?;
        Some(hi as f32 + 1.0)
    }

    /// Boxes of every one-way tile (see [`Level::is_one_way`]), in row order.
    pub fn one_way_boxes(&self) -> impl Iterator<Item = Aabb> + '_ {
        (0..self.height as i64)
            .flat_map(move |j| (0..self.width as i64).map(move |i| (i, j)))
            .filter(move |&(i, j)| self.is_one_way(i, j))
            .map(|(i, j)| Self::tile_box(i, j))
    }

    /// Every slope tile with its column and row.
    pub fn slopes(&self) -> impl Iterator<Item = (i64, i64, Slope)> + '_ {
        let w = self.width as usize;
        // A level without slope tiles has none to look for (most levels): no walk over its cells.
        let any = self.tiles.any_distinct(|t| matches!(t, Tile::Slope(_)));
        self.tiles
            .iter()
            .take(if any { usize::MAX } else { 0 })
            .enumerate()
            .filter_map(move |(k, t)| match t {
                Tile::Slope(s) => Some(((k % w) as i64, (k / w) as i64, s)),
                _ => None,
            })
    }
}

/// What one cell of a column offers the walk of [`Level::surface_at`] at a given x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SurfaceCell {
    /// Nothing to stand on at x: empty, one-way, ladder, or a slope whose surface is at the
    /// cell's bottom there.
    Open,
    /// A solid tile: its top.
    Solid,
    /// A slope tile whose surface at x is this far (above 0) over the cell's bottom.
    Slope(f32),
}

/// [`Level::surface_at`]'s walk down column `i` of a map `height` rows tall, reading each row's
/// cell from `cell` (the level's own, or cells kept from an earlier walk at the same x): the
/// highest surface at or below `top`, looking down at most `depth` tiles.
#[inline]
pub(crate) fn surface_walk(
    height: u32,
    i: i64,
    top: f32,
    depth: f32,
    mut cell: impl FnMut(i64) -> SurfaceCell,
) -> Option<(f32, Option<(i64, i64)>)> {
    let lowest = top - depth;
    // Rows above the map hold nothing: the walk starts at most at its top row.
    let mut j = floor_to_i64(top).min(height as i64 - 1);
    while j as f32 + 1.0 > lowest && j >= 0 {
        match cell(j) {
            SurfaceCell::Solid => {
                let h = j as f32 + 1.0;
                return (h <= top && h >= lowest).then_some((h, None));
            }
            SurfaceCell::Slope(local) => {
                let h = j as f32 + local;
                if h <= top {
                    return (h >= lowest).then_some((h, Some((i, j))));
                }
            }
            SurfaceCell::Open => {}
        }
        j -= 1;
    }
    None
}

/// A height `h` (tiles, from the level's corner) on a grid of `per_tile` steps per tile, as
/// whole steps: the one rounding of surface heights that integer positions use (the sweep's
/// `Grid::round_height`, and the metrics' declared stance for it). A height within 1e-4 of a
/// step (f32 noise of a surface already on the grid) is that step; any other is rounded *up*,
/// so feet put on a surface are never below it and at most one step above it.
pub fn round_height_up(h: f32, per_tile: i64) -> i64 {
    let v = h as f64 * per_tile as f64;
    if v.abs() < 4_503_599_627_370_496.0 {
        // Below 2^52 (and not NaN), in integers: `t` truncates `v`, `d = v - t` is exact, `t + k`
        // is `round64(v)` and `d - k` is exactly `v - round64(v)`; `ceil64(v)` is `t + 1` for a
        // positive fraction, else `t`. The same answers as the float roundings below, with two
        // conversions instead of four (this runs a few times per step on the grid's slopes).
        let t = v as i64;
        let d = v - t as f64;
        let k = (d >= 0.5) as i64 - (d <= -0.5) as i64;
        return if (d - k as f64).abs() < 1e-4 {
            t + k
        } else {
            t + (d > 0.0) as i64
        };
    }
    let r = round64(v);
    if (v - r).abs() < 1e-4 {
        r as i64
    } else {
        ceil64(v) as i64
    }
}

/// The box of a character whose feet (bottom centre) are at `pos`.
pub fn character_box(pos: Vec2, size: Vec2) -> Aabb {
    Aabb::new(
        Vec2::new(pos.x - size.x * 0.5, pos.y),
        Vec2::new(pos.x + size.x * 0.5, pos.y + size.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::Features;

    fn small() -> Level {
        // Row 0: solid floor of 4 tiles; row 1: one solid at i = 3.
        let mut t = vec![Tile::Solid; 4];
        t.extend([Tile::Empty, Tile::Empty, Tile::Empty, Tile::Solid]);
        t.extend([Tile::Empty; 4]);
        Level::from_tiles("small", 4, 3, t)
    }

    #[test]
    fn tile_lookup_and_bounds() {
        let l = small();
        assert_eq!(l.tile(0, 0), Tile::Solid);
        assert_eq!(l.tile(3, 1), Tile::Solid);
        assert_eq!(l.tile(-1, 0), Tile::Empty);
        assert_eq!(l.tile(0, 3), Tile::Empty);
        assert_eq!(l.solid_boxes().count(), 5);
        assert_eq!(l.features, Features::default());
    }

    #[test]
    fn support_below_finds_the_highest_top() {
        let l = small();
        assert_eq!(l.support_below(0.5, 1.5, 1.0, 0.0), Some(1.0));
        assert_eq!(l.support_below(2.5, 3.5, 2.0, 0.0), Some(2.0));
        assert_eq!(l.support_below(2.5, 3.5, 1.5, 0.0), Some(1.0));
        assert_eq!(l.support_below(5.0, 6.0, 1.0, 0.0), None);
    }

    #[test]
    fn heights_round_up_to_the_grid_unless_on_it() {
        // On the grid (up to f32 noise): that step. Off it: the next step up, never down.
        assert_eq!(round_height_up(0.75, 32), 24);
        assert_eq!(round_height_up(0.75 + 1e-7, 32), 24);
        assert_eq!(round_height_up(0.414_213_57, 32), 14); // 13.25 subpixels
        assert_eq!(round_height_up(-0.414_213_57, 32), -13);
    }

    #[test]
    fn heights_round_up_as_the_float_roundings_do() {
        // The integer path against the float roundings it replaced, over every magnitude (each
        // of 2^32 f32 bit patterns stepped by a prime), the grid's steps and their neighbours.
        let reference = |h: f32, n: i64| {
            let v = h as f64 * n as f64;
            let r = v.round();
            if (v - r).abs() < 1e-4 {
                r as i64
            } else {
                v.ceil() as i64
            }
        };
        let spread = (0..100_000u64).map(|k| f32::from_bits((k * 42_947) as u32));
        let steps = (-2000..2000).flat_map(|k| {
            let h = k as f32 / 32.0;
            [
                h,
                h.next_up(),
                h.next_down(),
                h + 1e-5,
                h - 1e-5,
                h + 0.5 / 32.0,
            ]
        });
        for h in spread
            .chain(steps)
            .chain([f32::NAN, f32::INFINITY, -1e30, 1e30])
        {
            for n in [1, 16, 32, 65_536] {
                assert_eq!(round_height_up(h, n), reference(h, n), "{h:e} x {n}");
            }
        }
    }

    #[test]
    fn surface_at_finds_solids_and_slopes() {
        // Row 0 solid; row 1: a '/' at i = 1.
        let mut t = vec![Tile::Solid; 3];
        t.extend([
            Tile::Empty,
            Tile::Slope(Slope::Line {
                left: 0.0,
                right: 1.0,
            }),
            Tile::Empty,
        ]);
        t.extend([Tile::Empty; 3]);
        let l = Level::from_tiles("s", 3, 3, t);
        assert_eq!(l.surface_at(0.5, 2.5, 2.0), Some((1.0, None)));
        assert_eq!(l.surface_at(1.25, 2.5, 2.0), Some((1.25, Some((1, 1)))));
        // Below the slope surface the slope is not "at or below": the solid under it is found.
        assert_eq!(l.surface_at(1.75, 1.5, 2.0), Some((1.0, None)));
        assert_eq!(l.surface_at(1.75, 1.5, 0.2), None);
        let n = l.slope_normal(1, 1, 1.5);
        assert!((n - Vec2::new(-1.0, 1.0).normalize()).length() < 1e-5);
    }

    #[test]
    fn merged_rects_cover_every_solid_tile_once() {
        let l = small();
        let rects = l.merged_solid_rects();
        // The floor row is one run; the single tile above it at i = 3 is its own rectangle.
        assert_eq!(rects.len(), 2, "{rects:?}");
        let area: f32 = rects.iter().map(|r| r.extents().x * r.extents().y).sum();
        assert_eq!(area, l.solid_boxes().count() as f32);
        // A solid 3 x 2 block becomes one rectangle.
        let block = Level::from_tiles("b", 3, 2, vec![Tile::Solid; 6]);
        assert_eq!(block.merged_solid_rects().len(), 1);
    }

    #[test]
    fn walks_over_tiles_stay_within_the_map() {
        // An area of 1e30 tiles (once a hang: `size = [1e30, 1e30]`) or a non-finite one
        // visits only the map's 12 tiles, and finds its 5 solids.
        let l = small();
        let huge = Aabb::new(Vec2::splat(-1e30), Vec2::splat(1e30));
        assert_eq!(l.solids_overlapping(&huge).count(), 5);
        let inf = Aabb::new(Vec2::splat(f32::NEG_INFINITY), Vec2::splat(f32::INFINITY));
        assert_eq!(l.solids_overlapping(&inf).count(), 5);
        let nan = Aabb::new(Vec2::splat(f32::NAN), Vec2::splat(f32::NAN));
        assert_eq!(l.solids_overlapping(&nan).count(), 0);
        assert_eq!(l.surface_at(0.5, 1e30, f32::INFINITY), Some((1.0, None)));
        assert_eq!(l.support_below(-1e30, 1e30, 1e30, 0.0), Some(2.0));
    }

    #[test]
    fn overlap_ignores_touching() {
        let l = small();
        let b = character_box(Vec2::new(1.0, 1.0), Vec2::new(0.8, 0.9));
        assert_eq!(l.solids_overlapping(&b).count(), 0);
        let sunk = character_box(Vec2::new(1.0, 0.99), Vec2::new(0.8, 0.9));
        assert_eq!(l.solids_overlapping(&sunk).count(), 2);
    }
}

//! Where the ground is under a character, for every shape, and how deep the shape is inside the
//! level: the same geometry for every backend. Solid tiles are squares, slope tiles their true
//! solid part (the convex polygon under a line, the seed's 16 columns of a height array), and
//! one-way platforms and ladder tops are ground for a shape above them, and for a shape that
//! stands on one sunk below its top ([`Ground::one_way_sink`]). Nothing is left out:
//! the sweep's box, which the seed's centre-column rule stands on a slope by its centre so that
//! it overhangs the ramp by up to half its width times the gradient, reads as inside the ramp
//! by that much (negative gap, positive penetration), as any other shape inside it would; the
//! part of an overlap that is with a slope is also reported on its own
//! ([`Ground::slope_penetration`], the `slope_overlap` metric).

use std::collections::HashMap;

use glam::Vec2;

use crate::oneway::OneWayCheck;
use parry2d::math::Pose;
use parry2d::query::{cast_shapes, contact, ShapeCastHit, ShapeCastOptions};
use parry2d::shape::{Cuboid, SharedShape};

use super::landing::FLICKER_SUPPORT_TOLERANCE;
use crate::level::{Level, Slope, SlopeKey, Tile};
use crate::shape::CharacterShape;

/// How far below the feet the ground is looked for, in tiles.
pub const GROUND_SEARCH: f32 = 2.0;

/// How far below a one-way top a shape's feet may be and still stand on it, for the ground
/// the metrics find: f32 rounding of a position of a few tiles, no more.
const ONE_WAY_ROUNDING: f32 = 1e-3;

/// The level's ground geometry for one character shape.
pub struct Ground<'a> {
    level: &'a Level,
    shape: SharedShape,
    size: Vec2,
    /// The solid part of each distinct slope the level holds (`None`: it has none), built once
    /// per slope rather than per slope tile (a map of a million slope tiles held a million
    /// shapes, 320 bytes a tile, where it has a handful of slopes).
    slopes: HashMap<SlopeKey, Option<SharedShape>>,
    tile: Cuboid,
}

/// A slope tile's solid part as a parry shape, in tile-local coordinates: the convex polygon
/// under a line, or for a height array the seed's 16 columns exactly.
fn slope_shape(s: &Slope) -> Option<SharedShape> {
    match s {
        Slope::Line { .. } => {
            // A line that never rises above the tile's bottom leaves no solid part.
            let outline = s.outline();
            (outline.len() >= 3)
                .then(|| SharedShape::convex_hull(&outline))
                .flatten()
        }
        Slope::Heights(h) => {
            let parts: Vec<(Pose, SharedShape)> = h
                .iter()
                .enumerate()
                .filter(|(_, v)| **v > 0)
                .map(|(i, v)| {
                    let (w, ht) = (1.0 / 16.0, *v as f32 / 16.0);
                    (
                        Pose::from_translation(Vec2::new((i as f32 + 0.5) * w, ht * 0.5)),
                        SharedShape::cuboid(w * 0.5, ht * 0.5),
                    )
                })
                .collect();
            (!parts.is_empty()).then(|| SharedShape::compound(parts))
        }
    }
}

/// Casts `shape` at `pose` straight down onto `target` at `target_pose`, at most `max_toi`
/// tiles: parry's time of impact, with the normal at the touch.
///
/// parry 0.31's cast between two support-map shapes, when its time of impact is under 1e-4,
/// replaces the cast's normal with that of a contact query, and returns no hit when that query
/// finds none: it finds none for two boxes face to face 1e-5 to 1e-4 apart (and for a capsule
/// 1e-7 above a box), so a box hovering there over a floor or a platform read as having no
/// ground within reach (a rider 4e-5 above a platform placed far out read as false_grounded).
/// Such a miss is cast again without that replacement, which keeps the cast's own time of
/// impact and normal; a cast that hits the first time is kept as it was.
fn cast_down_onto(
    pose: &Pose,
    shape: &dyn parry2d::shape::Shape,
    target_pose: &Pose,
    target: &dyn parry2d::shape::Shape,
    max_toi: f32,
) -> Option<ShapeCastHit> {
    let cast = |options| {
        cast_shapes(
            pose,
            Vec2::NEG_Y,
            shape,
            target_pose,
            Vec2::ZERO,
            target,
            options,
        )
        .ok()
        .flatten()
    };
    let options = ShapeCastOptions::with_max_time_of_impact(max_toi);
    cast(options).or_else(|| {
        cast(ShapeCastOptions {
            compute_impact_geometry_on_penetration: false,
            ..options
        })
    })
}

impl<'a> Ground<'a> {
    /// The ground of `level` for a character of `shape` and outer `size` (tiles).
    pub fn new(level: &'a Level, shape: CharacterShape, size: Vec2) -> Self {
        let slopes = level
            .distinct_tiles()
            .filter_map(|t| match t {
                Tile::Slope(s) => Some((SlopeKey::of(&s), slope_shape(&s))),
                _ => None,
            })
            .collect();
        Ground {
            level,
            shape: shape.build(size),
            size,
            slopes,
            tile: Cuboid::new(Vec2::splat(0.5)),
        }
    }

    /// The solid part of slope `s` (a slope of the level), if it has one.
    fn slope(&self, s: &Slope) -> Option<&SharedShape> {
        self.slopes.get(&SlopeKey::of(s)).and_then(Option::as_ref)
    }

    /// The columns `i0..=i1` that lie within the map (an empty range, `i0 > i1`, if none do):
    /// every walk over cells goes through this or [`Ground::rows`], so its cost is bounded by
    /// the map whatever the character's size.
    fn columns(&self, i0: i64, i1: i64) -> (i64, i64) {
        self.level.clip_columns(i0, i1)
    }

    /// The rows `j0..=j1` that lie within the map (an empty range if none do).
    fn rows(&self, j0: i64, j1: i64) -> (i64, i64) {
        self.level.clip_rows(j0, j1)
    }

    /// Deepest overlap of the shape with the level's solid geometry (solid tiles and slopes'
    /// solid parts), in tiles (0 if none): parry's penetration depth, the shortest move that
    /// separates them.
    pub fn solid_penetration(&self, feet: Vec2) -> f32 {
        self.deepest(feet, true, true)
    }

    /// Deepest overlap of the shape with a solid tile's square, in tiles (0 if none).
    pub fn square_penetration(&self, feet: Vec2) -> f32 {
        self.deepest(feet, true, false)
    }

    /// Deepest overlap of the shape with a slope tile's solid part, in tiles (0 if none).
    pub fn slope_penetration(&self, feet: Vec2) -> f32 {
        self.deepest(feet, false, true)
    }

    /// Deepest overlap with solid tiles (`squares`) and slope tiles (`slopes`) under the
    /// shape's bounding box.
    fn deepest(&self, feet: Vec2, squares: bool, slopes: bool) -> f32 {
        let mut worst = 0.0f32;
        self.each_overlap(feet, squares, slopes, |_, depth| worst = worst.max(depth));
        worst
    }

    /// Calls `f((i, j), depth)` for each solid tile (`squares`) and slope tile (`slopes`) the
    /// shape at `feet` overlaps, with parry's penetration depth.
    pub fn each_overlap(
        &self,
        feet: Vec2,
        squares: bool,
        slopes: bool,
        mut f: impl FnMut((i64, i64), f32),
    ) {
        let pose = CharacterShape::pose(feet, self.size);
        let bb = self.shape.compute_aabb(&pose);
        // Only the map's cells: outside it every cell is empty and overlaps nothing, so the
        // walk costs what the map holds under the box, not the box's area.
        let (i0, i1) = self.columns(
            bb.mins.x.floor() as i64,
            (bb.maxs.x.ceil() as i64).saturating_sub(1),
        );
        let (j0, j1) = self.rows(
            bb.mins.y.floor() as i64,
            (bb.maxs.y.ceil() as i64).saturating_sub(1),
        );
        for j in j0..=j1 {
            for i in i0..=i1 {
                let is_square = matches!(self.level.tile(i, j), Tile::Solid);
                if (is_square && !squares) || (!is_square && !slopes) {
                    continue;
                }
                let depth = self.tile_overlap(feet, i, j);
                if depth > 0.0 {
                    f((i, j), depth);
                }
            }
        }
    }

    /// Overlap of the shape at `feet` with tile `(i, j)`'s solid part (a solid tile's square or
    /// a slope's solid part), in tiles: parry's penetration depth, 0 if apart or the tile is empty.
    pub fn tile_overlap(&self, feet: Vec2, i: i64, j: i64) -> f32 {
        let pose = CharacterShape::pose(feet, self.size);
        let origin = Vec2::new(i as f32, j as f32);
        let (tile_pose, tile_shape): (Pose, &dyn parry2d::shape::Shape) =
            match self.level.tile(i, j) {
                Tile::Solid => (
                    Pose::from_translation(origin + Vec2::splat(0.5)),
                    &self.tile,
                ),
                Tile::Slope(s) => match self.slope(&s) {
                    Some(s) => (Pose::from_translation(origin), &**s),
                    None => return 0.0,
                },
                _ => return 0.0,
            };
        match contact(&pose, &*self.shape, &tile_pose, tile_shape, 0.0) {
            Ok(Some(c)) if c.dist < 0.0 => -c.dist,
            _ => 0.0,
        }
    }

    /// How far the shape stands sunk below the top of a one-way tile (a one-way platform or a
    /// ladder top) that it is over, in tiles, measured vertically (a one-way top resists only
    /// downward motion): the drop from half its height above `feet` to its first touch of the
    /// tile, subtracted from that half height; 0 if no one-way top lies between its feet and half
    /// its height above them. A shape passing up or down through a one-way tile is inside it by
    /// right (as is a climber passing through a ladder top), so this counts only where the
    /// character stands on it: frames reported grounded, not on a ladder, with no other support
    /// ([`Ground::penetration`]).
    pub fn one_way_sink(&self, feet: Vec2) -> f32 {
        // Half the height: deeper than that, the tile is beside the body (as for platforms in
        // [`Ground::support_gap`]), not under the feet.
        let band = self.size.y * 0.5;
        let pose = CharacterShape::pose(feet, self.size);
        let half = self.shape.compute_aabb(&pose).half_extents().x;
        // Within the map: outside it no cell is one-way.
        let (i0, i1) = self.columns(
            (feet.x - half + 1e-4).floor() as i64,
            (feet.x + half - 1e-4).floor() as i64,
        );
        // Tops j + 1 in (feet.y, feet.y + band].
        let (j0, j1) = self.rows(
            feet.y.floor() as i64,
            ((feet.y + band).floor() as i64).saturating_sub(1),
        );
        let above = CharacterShape::pose(feet + Vec2::Y * band, self.size);
        let mut worst = 0.0f32;
        for i in i0..=i1 {
            for j in j0..=j1 {
                if !self.level.is_one_way(i, j) || (j + 1) as f32 <= feet.y {
                    continue;
                }
                let tile = Pose::from_translation(Vec2::new(i as f32, j as f32) + Vec2::splat(0.5));
                if let Some(hit) = cast_down_onto(&above, &*self.shape, &tile, &self.tile, band) {
                    worst = worst.max(band - hit.time_of_impact);
                }
            }
        }
        worst
    }

    /// The depth of the shape inside the level on a frame at time `t`, in tiles: its overlap
    /// with the solid geometry ([`Ground::solid_penetration`]), and, on a frame where it is
    /// `standing` (reported grounded, not in the ladder state) with no other ground within
    /// [`FLICKER_SUPPORT_TOLERANCE`] below it, how far it is sunk below the one-way top it stands
    /// on ([`Ground::one_way_sink`]).
    pub fn penetration(&self, feet: Vec2, t: f64, standing: bool) -> f32 {
        let solid = self.solid_penetration(feet);
        solid.max(self.sunk_on_one_way(feet, t, standing))
    }

    /// [`Ground::one_way_sink`] where the character stands on the one-way top: a `standing` frame
    /// with no other ground (tiles, slopes, one-way tops below the feet, moving platforms) within
    /// [`FLICKER_SUPPORT_TOLERANCE`]; 0 elsewhere.
    pub fn sunk_on_one_way(&self, feet: Vec2, t: f64, standing: bool) -> f32 {
        if !standing {
            return 0.0;
        }
        let sink = self.one_way_sink(feet);
        if sink > 0.0 && self.support_gap(feet, t) > FLICKER_SUPPORT_TOLERANCE {
            sink
        } else {
            0.0
        }
    }

    /// Signed gap from the shape down to the ground at time `t` (moving platforms included), in
    /// tiles: the distance it can drop before touching (0 when touching), or minus the depth it
    /// is inside the level (tiles and slopes alike, and on a `standing` frame the one-way top it
    /// stands on, see [`Ground::penetration`]). Infinite if no ground is within [`GROUND_SEARCH`].
    pub fn gap_at(&self, feet: Vec2, t: f64, standing: bool) -> f32 {
        let gap = self.support_gap(feet, t);
        let sink = if gap > FLICKER_SUPPORT_TOLERANCE {
            self.sunk_on_one_way(feet, t, standing)
        } else {
            0.0
        };
        if sink > 0.0 {
            -sink
        } else {
            gap
        }
    }

    /// Signed gap from the shape down to what can hold it at time `t`: the static ground
    /// ([`Ground::gap`]) and moving platforms under it.
    fn support_gap(&self, feet: Vec2, t: f64) -> f32 {
        let best = self.gap(feet);
        if best <= 0.0 {
            return best;
        }
        best.min(self.platform_gap(feet, t))
    }

    /// Gap from the shape down to the nearest moving platform under it at time `t`, in tiles
    /// (infinite if none is within [`GROUND_SEARCH`]).
    pub(crate) fn platform_gap(&self, feet: Vec2, t: f64) -> f32 {
        let mut best = f32::INFINITY;
        let pose = CharacterShape::pose(feet, self.size);
        // The shape's own half-width (a ball is as wide as it is tall).
        let half = self.shape.compute_aabb(&pose).half_extents().x;
        for p in &self.level.platforms {
            let b = p.aabb(t);
            // Under the shape: its top at most half the character's height above the feet (a
            // rider that sank into it stands on it; one whose middle it reaches is beside it).
            let top_limit = feet.y + self.size.y * 0.5;
            if b.maxs.x <= feet.x - half || b.mins.x >= feet.x + half || b.maxs.y > top_limit {
                continue;
            }
            let half_extents = b.half_extents();
            if let Some(hit) = cast_down_onto(
                &pose,
                &*self.shape,
                &Pose::from_translation(b.center()),
                &Cuboid::new(half_extents),
                GROUND_SEARCH,
            ) {
                best = best.min(hit.time_of_impact);
            }
        }
        best
    }

    /// Overlap of the shape with a box `b` (a moving platform where it is placed), in tiles (0 if
    /// none): parry's penetration depth, so a capsule or a ball is measured by its own outline,
    /// not by its bounding box.
    pub fn box_penetration(&self, feet: Vec2, b: &parry2d::bounding_volume::Aabb) -> f32 {
        let pose = CharacterShape::pose(feet, self.size);
        let platform = Pose::from_translation(b.center());
        match contact(
            &pose,
            &*self.shape,
            &platform,
            &Cuboid::new(b.half_extents()),
            0.0,
        ) {
            Ok(Some(c)) => (-c.dist).max(0.0),
            _ => 0.0,
        }
    }

    /// Signed gap from the shape down to the level's static ground (see [`Ground::gap_at`]).
    pub fn gap(&self, feet: Vec2) -> f32 {
        let sunk = self.solid_penetration(feet);
        if sunk > 0.0 {
            return -sunk;
        }
        self.cast_down(feet).0
    }

    /// The normal of the ground the shape would touch dropping straight down from `feet` (the
    /// surface's outward normal at the first contact), if any is within [`GROUND_SEARCH`].
    pub fn ground_normal(&self, feet: Vec2) -> Option<Vec2> {
        let (toi, n) = self.cast_down(feet);
        toi.is_finite().then_some(n)
    }

    /// The distance the shape can drop from `feet` before it touches the static ground, and the
    /// ground's outward normal there (infinite and up if nothing is within reach).
    fn cast_down(&self, feet: Vec2) -> (f32, Vec2) {
        let pose = CharacterShape::pose(feet, self.size);
        // The shape's own half-width (a ball is as wide as it is tall).
        let half = self.shape.compute_aabb(&pose).half_extents().x;
        // Columns the shape spans (a wall touching its side is not under it), rows from mid-body
        // down to the search depth.
        // Within the map: outside it every cell is empty and holds no ground.
        let (i0, i1) = self.columns(
            (feet.x - half + 1e-4).floor() as i64,
            (feet.x + half - 1e-4).floor() as i64,
        );
        let (j_low, j_top) = self.rows(
            (feet.y - GROUND_SEARCH).floor() as i64,
            (feet.y + self.size.y * 0.5).floor() as i64,
        );
        let mut best = (f32::INFINITY, Vec2::Y);
        for i in i0..=i1 {
            for j in (j_low..=j_top).rev() {
                let origin = Vec2::new(i as f32, j as f32);
                // One-way tops (platforms, ladder tops) are ground for a shape above them: the
                // shared one-way rule, with rounding's tolerance.
                let above = OneWayCheck {
                    feet: feet.y,
                    tolerance: ONE_WAY_ROUNDING,
                    passes_all: false,
                    dropping_through: None,
                };
                let one_way_below = self.level.is_one_way(i, j) && above.blocks(j as f32 + 1.0);
                let (tile_pose, tile_shape): (Pose, &dyn parry2d::shape::Shape) =
                    match self.level.tile(i, j) {
                        _ if one_way_below => (
                            Pose::from_translation(origin + Vec2::splat(0.5)),
                            &self.tile,
                        ),
                        Tile::Solid => (
                            Pose::from_translation(origin + Vec2::splat(0.5)),
                            &self.tile,
                        ),
                        Tile::Slope(s) => match self.slope(&s) {
                            Some(s) => (Pose::from_translation(origin), &**s),
                            None => continue,
                        },
                        _ => continue,
                    };
                if let Some(hit) =
                    cast_down_onto(&pose, &*self.shape, &tile_pose, tile_shape, GROUND_SEARCH)
                {
                    if hit.time_of_impact < best.0 {
                        // Tiles are posed by translation only: the local normal is the world's.
                        best = (hit.time_of_impact, hit.normal2);
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::parse_level;

    #[test]
    fn a_line_leaving_through_the_bottom_is_solid_only_where_it_is_above_it() {
        // The 22.5-degree ramp's tile 'y' (slope_22_5.toml): its line falls from 0.071 to
        // -0.343, crossing the bottom at u = 0.0711 / 0.4142 = 0.1716. Its solid part is the
        // triangle left of that; at u = 0.5 the tile is empty.
        let s = Slope::Line {
            left: 0.07107,
            right: -0.34315,
        };
        let shape = slope_shape(&s).unwrap();
        let inside = |p: Vec2| shape.contains_point(&Pose::IDENTITY, p);
        assert!(inside(Vec2::new(0.05, 0.02)));
        assert!(!inside(Vec2::new(0.5, 0.01)));
        assert!(!inside(Vec2::new(0.9, 0.001)));
    }

    #[test]
    fn standing_sunk_below_a_one_way_top_is_seen_and_passing_through_is_not() {
        // A one-way platform (row 2, top at y = 3) over a floor (top at y = 1).
        let level = parse_level(
            "map = \"\"\"\n.....\n.===.\n.....\n#####\n\"\"\"\n",
            "o.toml",
        )
        .unwrap();
        let size = Vec2::new(0.8, 0.9);
        for shape in [
            CharacterShape::Cuboid,
            CharacterShape::Capsule,
            CharacterShape::Ball,
        ] {
            let g = Ground::new(&level, shape, size);
            // Standing on the top: nothing.
            assert_eq!(g.penetration(Vec2::new(2.5, 3.0), 0.0, true), 0.0);
            assert!(g.gap_at(Vec2::new(2.5, 3.0), 0.0, true).abs() < 1e-4);
            // Sunk 0.2 below it while grounded: 0.2 deep, gap -0.2 (1e-4: f32 casts).
            let sunk = Vec2::new(2.5, 2.8);
            assert!(
                (g.penetration(sunk, 0.0, true) - 0.2).abs() < 1e-4,
                "{shape:?}"
            );
            assert!((g.gap_at(sunk, 0.0, true) + 0.2).abs() < 1e-4, "{shape:?}");
            // The same place airborne (jumping up through it): inside it by right.
            assert_eq!(g.penetration(sunk, 0.0, false), 0.0);
            assert!(g.gap_at(sunk, 0.0, false) > 1.0);
            // Grounded on the floor with the platform above the head: the floor holds it.
            assert_eq!(g.penetration(Vec2::new(2.5, 1.0), 0.0, true), 0.0);
            // Beside the platform (left of x = 1 by the half-width): not over it.
            assert_eq!(g.one_way_sink(Vec2::new(0.55, 2.8)), 0.0);
        }
    }

    #[test]
    fn box_penetration_is_the_shapes_own() {
        // A still 2 x 1 platform at x 2..4, y 2..3 (sine of amplitude 0 keeps it put).
        let level = parse_level(
            "map = \"\"\"\n......\n......\n......\n......\n######\n\"\"\"\n\
             [[platform]]\nrect = [2.0, 2.0, 2.0, 1.0]\nsine = { amplitude = [0.0, 0.0], period = 1.0 }\n",
            "p.toml",
        )
        .unwrap();
        let size = Vec2::new(0.8, 0.9);
        let boxy = Ground::new(&level, CharacterShape::Cuboid, size);
        let ball = Ground::new(&level, CharacterShape::Ball, size);
        let b = level.platforms[0].aabb(0.0);
        // Feet 0.1 into its top, centred over it: 0.1 deep for both (1e-4: f32).
        let on = Vec2::new(3.0, 2.9);
        assert!((boxy.box_penetration(on, &b) - 0.1).abs() < 1e-4);
        assert!((ball.box_penetration(on, &b) - 0.1).abs() < 1e-4);
        // Feet 0.35 left of the platform's top-left corner and 0.1 below its top: the box
        // (x 1.25..2.05) overlaps the corner by 0.05 across and 0.1 down, 0.05 deep; the ball's
        // round outline (radius 0.45, centre 0.35 left of the corner and 0.35 above it, 0.495
        // away) is clear of it. A box-for-every-shape measure would charge the ball 0.05.
        let corner = Vec2::new(2.0 - 0.35, 3.0 - 0.1);
        assert!((boxy.box_penetration(corner, &b) - 0.05).abs() < 1e-4);
        assert_eq!(ball.box_penetration(corner, &b), 0.0);
    }

    #[test]
    fn gap_is_shape_aware_on_floors_and_slopes() {
        let level = parse_level("map = \"\"\"\n.....\n../##\n#####\n\"\"\"\n", "g.toml").unwrap();
        let size = Vec2::new(0.8, 0.9);
        let boxy = Ground::new(&level, CharacterShape::Cuboid, size);
        assert!((boxy.gap(Vec2::new(0.5, 1.25)) - 0.25).abs() < 1e-4);
        assert!((boxy.gap(Vec2::new(0.5, 0.97)) + 0.03).abs() < 1e-4);
        // The box's centre on the '/' surface at x = 2.5 (height 1.5), as the seed stands it:
        // its right corner is 0.4 tiles (half the width times the gradient 1) below the
        // surface, inside the ramp; the shortest way out is along the ramp's normal, 0.4 cos 45
        // (the corner's distance to the 45-degree line), so that is the depth.
        let depth = 0.4 * std::f32::consts::FRAC_1_SQRT_2;
        assert!((boxy.gap(Vec2::new(2.5, 1.5)) + depth).abs() < 1e-4);
        assert!((boxy.slope_penetration(Vec2::new(2.5, 1.5)) - depth).abs() < 1e-4);
        // Lifted by 0.4 the corner touches the surface: no overlap, gap 0.
        assert!(boxy.gap(Vec2::new(2.5, 1.9)).abs() < 1e-4);
        // A ball of radius 0.45 above the 45-degree surface rests where its bottom point is
        // r (sqrt 2 - 1) above the surface under its centre.
        let ball = Ground::new(&level, CharacterShape::Ball, size);
        let lift = 0.45 * (2f32.sqrt() - 1.0);
        assert!(ball.gap(Vec2::new(2.5, 1.5 + lift + 0.1)) - 0.1 < 1e-3);
        assert!(boxy.gap(Vec2::new(0.5, 5.0)).is_infinite());
    }
    #[test]
    fn a_box_hovering_under_1e_4_over_a_platform_has_it_below() {
        // The diagonal ride of platforms.toml at 1e12 tiles out, frame 8 of the f64 sweep, in
        // level coordinates: the platform's box (placed from f64, rounded to f32) and the
        // rider 4.5e-5 right of its middle and 4.4e-5 above its top (the f64 spacing there,
        // 2^-13, rounds the rider's place). parry's cast found no hit for the box 1e-5 to
        // 1e-4 above it there, so the gap read as infinite (nothing else within reach).
        let level = parse_level(
            "map = \"\"\"\n......\n######\n\"\"\"\n\
             [[platform]]\nrect = [26.623735, 5.623735, 3.0, 0.5]\n\
             sine = { amplitude = [0.0, 0.0], period = 1.0 }\n",
            "p.toml",
        )
        .unwrap();
        let size = Vec2::new(0.8, 0.9);
        for shape in [
            CharacterShape::Cuboid,
            CharacterShape::Capsule,
            CharacterShape::Ball,
        ] {
            let g = Ground::new(&level, shape, size);
            for lift in [1e-5f32, 4.4e-5, 9e-5] {
                let gap = g.gap_at(Vec2::new(28.12378, 6.123735 + lift), 0.0, true);
                // The gap is the lift, to 1e-6: the f32 spacing at y = 6 is 4.8e-7, and the
                // casts converge within it here (measured 1.2e-7 for the box).
                assert!((gap - lift).abs() < 1e-6, "{shape:?} {lift}: {gap}");
            }
        }
    }
}

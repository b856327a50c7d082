//! Collision resolution, the seed's "collision avoidance": move along one axis, find the
//! closest obstacle the move would reach, snap the box flush against it, and report the hit.
//!
//! The seed moves x first, then y. Each axis move sweeps the box over the whole displacement,
//! so a fast mover cannot tunnel through a thin wall whatever its speed.
//!
//! Snapping flush involves a subtraction, and in floating point the result can still overlap
//! the obstacle by a rounding error. The seed's fix is an overlap tolerance: an overlap smaller
//! than `epsilon` is not a collision. Here that tolerance appears twice: a box counts as beside
//! the mover only if the two overlap by more than `epsilon` across the move, and a box that the
//! mover already overlaps by less than `epsilon` along the move still counts as ahead of it (so
//! the next snap puts it back flush rather than letting it sink further). Symmetrically, a move
//! that ends less than `epsilon` short of an obstacle counts as reaching it and snaps flush, so
//! a fall that arrives on the floor exactly (within rounding) is a landing on that frame.

use glam::Vec2;
use parry2d::bounding_volume::{Aabb, BoundingVolume};

use super::broadphase::{BoxKind, NearCache, StaticTiles};
use super::oneway;
use super::space::{Rect, Space};
use super::{Character, World};

/// The axis of a move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Horizontal.
    X,
    /// Vertical.
    Y,
}

impl Axis {
    /// The axis's index in a vector (x 0, y 1).
    pub(crate) fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
        }
    }
}

/// Moves the box whose feet are at `pos` by `delta` along `axis`, stopping flush at the
/// closest obstacle among the static tiles (found through the mover's `near` cache) and the
/// `extra` boxes (moving platforms at their current place). `skip` tells which boxes are not obstacles for this move (it gets the box
/// and its kind). Returns the kind of the obstacle that stopped the move, if one did.
#[allow(clippy::too_many_arguments)]
pub fn move_axis(
    tiles: &StaticTiles,
    near: &mut NearCache,
    extra: &[(Aabb, BoxKind)],
    pos: &mut Vec2,
    size: Vec2,
    axis: Axis,
    delta: f32,
    epsilon: f32,
    skip: impl Fn(&Aabb, BoxKind) -> bool,
) -> Option<BoxKind> {
    if delta == 0.0 {
        return None;
    }
    let a = axis.index();
    let o = 1 - a;
    let b = crate::level::character_box(*pos, size);
    let (lo, hi) = (b.mins[a], b.maxs[a]);
    // The box swept over the whole move (and epsilon beyond it), shrunk by epsilon across it:
    // boxes that only touch (or overlap by less than epsilon) on the other axis are not
    // obstacles.
    let mut swept = b;
    if delta > 0.0 {
        swept.maxs[a] = hi + delta + epsilon;
    } else {
        swept.mins[a] = lo + delta - epsilon;
    }
    swept.mins[o] += epsilon;
    swept.maxs[o] -= epsilon;

    let mut closest: Option<(f32, BoxKind)> = None;
    let moving = extra
        .iter()
        .filter(|(t, _)| t.intersects(&swept))
        .map(|(t, k)| (t, *k));
    for (t, kind) in near.query(tiles, &swept).chain(moving) {
        if skip(t, kind) || !overlaps_across(&b, t, o, epsilon) {
            continue;
        }
        if delta > 0.0 {
            let face = t.mins[a];
            // Ahead of the mover (allowing an overlap below epsilon) and within reach.
            if face >= hi - epsilon
                && face <= hi + delta + epsilon
                && closest.is_none_or(|(c, _)| face < c)
            {
                closest = Some((face, kind));
            }
        } else {
            let face = t.maxs[a];
            if face <= lo + epsilon
                && face >= lo + delta - epsilon
                && closest.is_none_or(|(c, _)| face > c)
            {
                closest = Some((face, kind));
            }
        }
    }
    match closest {
        None => {
            pos[a] += delta;
            None
        }
        Some((face, kind)) => {
            // Snap flush: the box's leading side goes onto the face.
            pos[a] = if delta > 0.0 {
                face - (hi - pos[a])
            } else {
                face + (pos[a] - lo)
            };
            Some(kind)
        }
    }
}

/// [`move_axis`] with the position in f64 world coordinates (the sweep's f64 mode): the same
/// sweep, snap and epsilon fudge, every comparison and the snap in f64. The static boxes are
/// kept in the level's own coordinates (`tiles` built at origin 0, where f32 is exact for tile
/// faces) and placed at `origin` in f64; the broadphase is asked in f32 level coordinates with a
/// margin of [`F64_QUERY_MARGIN`] so that its rounding never hides a box, and the boxes it
/// returns are filtered again in f64. The `extra` boxes (moving platforms at their current
/// place) are f64 world boxes already. `skip` gets a box's top (f64 world tiles) and its kind.
#[allow(clippy::too_many_arguments)]
pub fn move_axis_f64(
    tiles: &StaticTiles,
    near: &mut NearCache,
    extra: &[(Rect<f64>, BoxKind)],
    origin: glam::DVec2,
    pos: &mut glam::DVec2,
    size: Vec2,
    axis: Axis,
    delta: f64,
    epsilon: f32,
    skip: impl Fn(f64, BoxKind) -> bool,
) -> Option<BoxKind> {
    use glam::DVec2;
    if delta == 0.0 {
        return None;
    }
    let epsilon = epsilon as f64;
    let a = axis.index();
    let o = 1 - a;
    let half = size.x as f64 * 0.5;
    let bmin = DVec2::new(pos.x - half, pos.y);
    let bmax = DVec2::new(pos.x + half, pos.y + size.y as f64);
    let (lo, hi) = (bmin[a], bmax[a]);
    let (mut smin, mut smax) = (bmin, bmax);
    if delta > 0.0 {
        smax[a] = hi + delta + epsilon;
    } else {
        smin[a] = lo + delta - epsilon;
    }
    smin[o] += epsilon;
    smax[o] -= epsilon;
    let area = Aabb::new(
        (smin - origin).as_vec2() - Vec2::splat(F64_QUERY_MARGIN),
        (smax - origin).as_vec2() + Vec2::splat(F64_QUERY_MARGIN),
    );
    let placed = near
        .query(tiles, &area)
        .map(|(t, kind)| (t.mins.as_dvec2() + origin, t.maxs.as_dvec2() + origin, kind));
    let moving = extra
        .iter()
        .map(|(t, kind)| (DVec2::from_array(t.min), DVec2::from_array(t.max), *kind));
    let mut closest: Option<(f64, BoxKind)> = None;
    for (tmin, tmax, kind) in placed.chain(moving) {
        // The f64 box must touch the swept box (the f32 query's inclusive test, in f64).
        let touches = (0..2).all(|k| tmin[k] <= smax[k] && tmax[k] >= smin[k]);
        let across = bmax[o].min(tmax[o]) - bmin[o].max(tmin[o]) > epsilon;
        if !touches || skip(tmax.y, kind) || !across {
            continue;
        }
        if delta > 0.0 {
            let face = tmin[a];
            if face >= hi - epsilon
                && face <= hi + delta + epsilon
                && closest.is_none_or(|(c, _)| face < c)
            {
                closest = Some((face, kind));
            }
        } else {
            let face = tmax[a];
            if face <= lo + epsilon
                && face >= lo + delta - epsilon
                && closest.is_none_or(|(c, _)| face > c)
            {
                closest = Some((face, kind));
            }
        }
    }
    match closest {
        None => {
            pos[a] += delta;
            None
        }
        Some((face, kind)) => {
            pos[a] = if delta > 0.0 {
                face - (hi - pos[a])
            } else {
                face + (pos[a] - lo)
            };
            Some(kind)
        }
    }
}

/// How far beyond the swept box (tiles) the f64 mode asks the f32 broadphase: level coordinates
/// within a few thousand tiles of the level's corner round by under 1e-3 tile in f32.
pub const F64_QUERY_MARGIN: f32 = 1e-2;

/// Step 3, the x move ("integrate x one step forward, x before y"): sweeps the box along x and
/// snaps it flush to the closest obstacle. One-way boxes never block it (the seed: "don't
/// collide x axis step"), nor does the mass under a ramp: solids carrying a slope, and solids
/// whose top is at most `ramp_top` (the overhang above the slope under the centre, see
/// [`super::slopes::ramp_top_for_x`]). Returns whether a wall stopped it.
pub(super) fn move_x<S: Space>(
    s: &S,
    w: &World,
    c: &mut Character,
    dx: f32,
    ramp_top: Option<S::Coord>,
) -> bool {
    s.move_axis(w, c, Axis::X, dx, false, |top, kind| match kind {
        BoxKind::UnderSlope => true,
        BoxKind::Solid => ramp_top.is_some_and(|l| top <= l),
        k => oneway::is_one_way(k),
    })
    .is_some()
}

/// Step 5, the y move ("repeat for y"): sweeps the box along y and snaps it flush. One-way
/// boxes block only as [`oneway::Fall`] says; moving platforms always block; solids with their
/// top inside `ramp_band` (above its low end, at most its high end) belong to the slope rules.
/// A drop through a one-way platform falls at least one storage unit. Returns what stopped it.
pub(super) fn move_y<S: Space>(
    s: &S,
    w: &World,
    c: &mut Character,
    dy: f32,
    fall: &oneway::Fall<S::Coord>,
    ramp_band: Option<(S::Coord, S::Coord)>,
) -> Option<BoxKind> {
    let min_fall = c.motion.drop_through;
    s.move_axis(w, c, Axis::Y, dy, min_fall, |top, kind| {
        if oneway::is_one_way(kind) {
            fall.passes(top)
        } else if matches!(kind, BoxKind::Platform { .. }) {
            false
        } else {
            ramp_band.is_some_and(|(lo, hi)| top > lo && top <= hi)
        }
    })
}

/// Whether `b` and `t` overlap by more than `epsilon` on axis `o`.
fn overlaps_across(b: &Aabb, t: &Aabb, o: usize, epsilon: f32) -> bool {
    b.maxs[o].min(t.maxs[o]) - b.mins[o].max(t.mins[o]) > epsilon
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{Level, Tile};

    /// A floor row at j = 0 and a wall column at i = 10 (rows 1..4), 20 x 5 tiles.
    fn room() -> StaticTiles {
        let (w, h) = (20u32, 5u32);
        let mut t = vec![Tile::Empty; (w * h) as usize];
        for i in 0..w {
            t[i as usize] = Tile::Solid;
        }
        for j in 1..h {
            t[(j * w + 10) as usize] = Tile::Solid;
        }
        StaticTiles::new(&Level::from_tiles("room", w, h, t))
    }

    const SIZE: Vec2 = Vec2::new(0.8, 0.9);

    fn hits(
        tiles: &StaticTiles,
        p: &mut Vec2,
        size: Vec2,
        axis: Axis,
        delta: f32,
        eps: f32,
        skip: impl Fn(&Aabb, BoxKind) -> bool,
    ) -> bool {
        move_axis(
            tiles,
            &mut NearCache::default(),
            &[],
            p,
            size,
            axis,
            delta,
            eps,
            skip,
        )
        .is_some()
    }
    const EPS: f32 = 0.001;

    #[test]
    fn falls_and_snaps_flush_onto_the_floor() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 3.0);
        assert!(hits(&tiles, &mut p, SIZE, Axis::Y, -5.0, EPS, |_, _| false));
        assert_eq!(p.y, 1.0);
    }

    #[test]
    fn walks_over_seams_without_snagging() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.0);
        for _ in 0..60 {
            assert!(!hits(&tiles, &mut p, SIZE, Axis::X, 0.1, EPS, |_, _| false));
        }
        assert!((p.x - 8.5).abs() < 1e-4);
    }

    #[test]
    fn stops_flush_at_a_wall_even_at_huge_speed() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.0);
        assert!(hits(&tiles, &mut p, SIZE, Axis::X, 1000.0, EPS, |_, _| {
            false
        }));
        assert!((p.x + SIZE.x / 2.0 - 10.0).abs() < 1e-5, "{p}");
        // Flush now: a further push is still stopped and does not sink in.
        assert!(hits(&tiles, &mut p, SIZE, Axis::X, 0.5, EPS, |_, _| false));
        assert!(p.x + SIZE.x / 2.0 <= 10.0 + EPS);
    }

    #[test]
    fn ending_within_epsilon_of_the_floor_is_a_landing() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.5);
        // Stops 0.0005 short of the floor: a contact, snapped flush.
        assert!(hits(&tiles, &mut p, SIZE, Axis::Y, -0.4995, EPS, |_, _| {
            false
        }));
        assert_eq!(p.y, 1.0);
        // Stops 0.01 short: no contact.
        let mut q = Vec2::new(2.5, 1.5);
        assert!(!hits(&tiles, &mut q, SIZE, Axis::Y, -0.49, EPS, |_, _| {
            false
        }));
        assert!((q.y - 1.01).abs() < 1e-6);
    }

    #[test]
    fn overlap_below_epsilon_is_not_a_side_collision() {
        let tiles = room();
        // Feet 0.0005 inside the floor: less than epsilon, so the floor does not block x.
        let mut p = Vec2::new(2.5, 1.0 - 0.0005);
        assert!(!hits(&tiles, &mut p, SIZE, Axis::X, 1.0, EPS, |_, _| false));
        // 0.01 inside: a real overlap, so the floor tile ahead blocks.
        let mut q = Vec2::new(2.5, 1.0 - 0.01);
        assert!(hits(&tiles, &mut q, SIZE, Axis::X, 1.0, EPS, |_, _| false));
    }
}

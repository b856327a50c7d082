//! Collision resolution, the seed's "collision avoidance": move along one axis, find the
//! closest obstacle the move would reach, snap the box flush against it, and report the hit.
//! Written once ([`move_axis`]), generic over the coordinate the positions are stored in: f32 or
//! f64 tiles, or whole subpixels (`space.rs`).
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
//! a fall that arrives on the floor exactly (within rounding) is a landing on that frame. On the
//! integer grid the tolerance is 0 and the snap exact: the same rules with nothing to absorb.

use super::broadphase::{BoxKind, NearCache, StaticTiles};
use super::oneway;
use super::platforms::Platforms;
use super::space::{Body, Coord, Rect, Space};
use super::{Character, World};
use crate::oneway::OneWayCheck;

/// The axis of a move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Axis {
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

/// What a move runs into, in one space: the static tiles (asked through the mover's near
/// cache) and the moving platforms where they are now (each placed only when the move comes
/// within its reach), with the space's overlap tolerance `eps`.
pub(crate) struct Obstacles<'a, S: Space> {
    /// How positions are stored, and how the broadphase is asked in them.
    pub space: &'a S,
    /// The level's static boxes.
    pub tiles: &'a StaticTiles,
    /// The moving platforms (none for a move against the static level only).
    pub moving: Option<&'a Platforms<S::Coord>>,
    /// The overlap tolerance: the seed's epsilon in float, 0 on the grid.
    pub eps: S::Coord,
}

/// The seed's sweep and snap: moves `body` by `delta` along `axis`, stopping flush at the
/// closest obstacle the box swept over the whole move reaches, and returns the kind of what
/// stopped it. `skip` tells which boxes are not obstacles for this move (it gets a box's top
/// and its kind). The tolerance `eps` counts as the module says; the snap moves the anchor
/// (`body.at`) alone, so the box keeps its size.
#[inline(always)]
pub(crate) fn move_axis<S: Space>(
    o: &Obstacles<'_, S>,
    near: &mut NearCache<S::Coord>,
    body: &mut Body<S::Coord>,
    axis: Axis,
    delta: S::Coord,
    skip: impl Fn(S::Coord, BoxKind) -> bool,
) -> Option<BoxKind> {
    let zero = S::Coord::default();
    if delta == zero {
        return None;
    }
    let (a, across) = (axis.index(), 1 - axis.index());
    let eps = o.eps;
    let b = body.rect();
    let (lo, hi) = (b.min[a], b.max[a]);
    // The box swept over the whole move (and eps beyond it), shrunk by eps across it: boxes
    // that only touch (or overlap by less than eps) on the other axis are not obstacles.
    let mut swept = b;
    if delta > zero {
        swept.max[a] = hi + delta + eps;
    } else {
        swept.min[a] = lo + delta - eps;
    }
    swept.min[across] = swept.min[across] + eps;
    swept.max[across] = swept.max[across] - eps;

    let mut sweep = Sweep {
        b,
        swept,
        a,
        across,
        delta,
        eps,
        closest: None,
    };
    // The static boxes, then the moving platforms, each in its own order (two plain loops: the
    // one chained iterator they replaced cost more instructions than the tests themselves).
    for &(t, kind) in o.space.statics(o.tiles, near, swept) {
        sweep.consider(t, kind, &skip);
    }
    if let Some(m) = o.moving {
        m.near(o.space, swept, |t, kind| sweep.consider(t, kind, &skip));
    }
    let closest = sweep.closest;
    let at = body.at[a];
    match closest {
        None => {
            body.at[a] = at + delta;
            None
        }
        Some((face, kind)) => {
            // Snap flush: the box's leading side goes onto the face.
            body.at[a] = if delta > zero {
                face - (hi - at)
            } else {
                face + (at - lo)
            };
            Some(kind)
        }
    }
}

/// One axis move's sweep: the mover's box `b`, the box swept over the move `swept`, and the
/// closest face found so far ([`move_axis`]).
struct Sweep<C> {
    b: Rect<C>,
    swept: Rect<C>,
    /// The axis of the move and the other one (indices).
    a: usize,
    across: usize,
    delta: C,
    eps: C,
    closest: Option<(C, BoxKind)>,
}

impl<C: Coord> Sweep<C> {
    /// Tests box `t` of `kind` against the move: keeps its face if it is the closest obstacle
    /// so far. Inlined into both loops of [`move_axis`] (as a closure it was a call per box).
    #[inline(always)]
    fn consider(&mut self, t: Rect<C>, kind: BoxKind, skip: &impl Fn(C, BoxKind) -> bool) {
        let (a, across, eps, delta) = (self.a, self.across, self.eps, self.delta);
        let zero = C::default();
        // Only a box that touches the swept box (the broadphase's inclusive test, here in the
        // storage's coordinate) can be in the way.
        if !t.touches(&self.swept) || skip(t.max[1], kind) {
            return;
        }
        let b = &self.b;
        let beside = b.max[across].min(t.max[across]) - b.min[across].max(t.min[across]) > eps;
        if !beside {
            return;
        }
        let (lo, hi) = (b.min[a], b.max[a]);
        if delta > zero {
            let face = t.min[a];
            if face >= hi - eps
                && face <= hi + delta + eps
                && self.closest.is_none_or(|(c, _)| face < c)
            {
                self.closest = Some((face, kind));
            }
        } else {
            let face = t.max[a];
            if face <= lo + eps
                && face >= lo + delta - eps
                && self.closest.is_none_or(|(c, _)| face > c)
            {
                self.closest = Some((face, kind));
            }
        }
    }
}

/// What the box's side facing `toward` (one storage unit along `axis`, signed) rests against:
/// [`move_axis`] by it, undone unless the box stayed where it was (flush against what stopped
/// it). The grid's "collide check one pixel down". Inlined, so that the probe of each axis
/// move is specialised for its axis and its one-unit move (as a call it cost a step on the
/// grid more than the x move itself).
#[inline(always)]
pub(crate) fn touching<S: Space>(
    o: &Obstacles<'_, S>,
    near: &mut NearCache<S::Coord>,
    body: &mut Body<S::Coord>,
    axis: Axis,
    toward: S::Coord,
    skip: impl Fn(S::Coord, BoxKind) -> bool,
) -> Option<BoxKind> {
    let before = body.at;
    let hit = move_axis(o, near, body, axis, toward, skip);
    if body.at == before {
        hit
    } else {
        body.at = before;
        None
    }
}

/// One step's move of `c` by `delta` tiles along `axis` against the level and the moving
/// platforms, in the storage's units ([`Space::whole_move`]). On the grid a fall too small to
/// move a subpixel reports the ground the box rests on, and a move that hits drops the axis's
/// carried fraction.
#[inline(always)]
fn step_move<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    axis: Axis,
    delta: f32,
    min_fall: bool,
    skip: impl Fn(S::Coord, BoxKind) -> bool,
) -> Option<BoxKind> {
    let o = w.obstacles();
    let d = w.space.whole_move(&mut c.body, axis, delta, min_fall);
    let mut hit = move_axis(&o, &mut c.near, &mut c.body, axis, d, &skip);
    let zero = S::Coord::default();
    if S::Coord::UNIT != zero && axis == Axis::Y && d == zero && delta < 0.0 {
        // A fall of less than a subpixel this step moves nothing (only on the grid, whose
        // `UNIT` is not 0: in float a nonzero move always moves, and the test folds away): the
        // ground is there if the box rests on it (Celeste's "collide check one pixel down"). A
        // move of a subpixel or more that ends on a face has already reported it.
        hit = touching(&o, &mut c.near, &mut c.body, axis, -S::Coord::UNIT, &skip);
    }
    if hit.is_some() {
        c.body.remainder[axis.index()] = 0.0;
    }
    hit
}

/// Moves `c` by `delta` (x, then y) against the static level only, as a moving platform
/// carries or pushes it; returns whether the level stopped any part of the move (by more than
/// the tolerance).
pub(crate) fn shove<S: Space>(
    o: &Obstacles<'_, S>,
    c: &mut Character<S::Coord>,
    delta: [S::Coord; 2],
) -> bool {
    let skip = |_, k: BoxKind| matches!(k, BoxKind::OneWay | BoxKind::Platform { .. });
    let start = c.body.at;
    for (axis, d) in [(Axis::X, delta[0]), (Axis::Y, delta[1])] {
        move_axis(o, &mut c.near, &mut c.body, axis, d, skip);
    }
    let off = [0, 1].map(|k| c.body.at[k] - start[k] - delta[k]);
    S::Coord::longer_than(off, o.eps)
}

/// Step 3, the x move ("integrate x one step forward, x before y"): sweeps the box along x and
/// snaps it flush to the closest obstacle. One-way boxes never block it (the seed: "don't
/// collide x axis step"), nor does the mass under a ramp: solids carrying a slope, and solids
/// whose top is at most `ramp_top` (the overhang above the slope under the centre, see
/// [`super::slopes::ramp_top_for_x`]). Returns whether a wall stopped it.
pub(super) fn move_x<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    dx: f32,
    ramp_top: Option<S::Coord>,
) -> bool {
    step_move(w, c, Axis::X, dx, false, |top, kind| match kind {
        BoxKind::UnderSlope => true,
        BoxKind::Solid => ramp_top.is_some_and(|l| top <= l),
        k => oneway::is_one_way(k),
    })
    .is_some()
}

/// Step 5, the y move ("repeat for y"): sweeps the box along y and snaps it flush. One-way
/// boxes block only as [`OneWayCheck::blocks`] says; moving platforms always block; solids with their
/// top inside `ramp_band` (above its low end, at most its high end) belong to the slope rules.
/// A drop through a one-way platform falls at least one storage unit. Returns what stopped it.
pub(super) fn move_y<S: Space>(
    w: &World<S>,
    c: &mut Character<S::Coord>,
    dy: f32,
    fall: &OneWayCheck<S::Coord>,
    ramp_band: Option<(S::Coord, S::Coord)>,
) -> Option<BoxKind> {
    let min_fall = c.motion.drop_through;
    step_move(w, c, Axis::Y, dy, min_fall, |top, kind| {
        if oneway::is_one_way(kind) {
            !fall.blocks(top)
        } else if matches!(kind, BoxKind::Platform { .. }) {
            false
        } else {
            ramp_band.is_some_and(|(lo, hi)| top > lo && top <= hi)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{Level, Tile};
    use crate::sweep::space::FloatSpace;
    use glam::Vec2;

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

    /// Moves the feet `p` of a box of `size` by `delta` along `axis` in float with tolerance
    /// `eps`; returns whether an obstacle stopped it.
    fn hits(
        tiles: &StaticTiles,
        p: &mut Vec2,
        size: Vec2,
        axis: Axis,
        delta: f32,
        eps: f32,
    ) -> bool {
        let space = FloatSpace {
            eps,
            origin: Vec2::ZERO,
        };
        let o = Obstacles {
            space: &space,
            tiles,
            moving: None,
            eps,
        };
        let mut body = space.spawn(*p, size);
        let mut near = NearCache::default();
        let hit = move_axis(&o, &mut near, &mut body, axis, delta, |_, _| false);
        *p = space.feet(&body);
        hit.is_some()
    }
    const EPS: f32 = 0.001;

    #[test]
    fn falls_and_snaps_flush_onto_the_floor() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 3.0);
        assert!(hits(&tiles, &mut p, SIZE, Axis::Y, -5.0, EPS));
        assert_eq!(p.y, 1.0);
    }

    #[test]
    fn walks_over_seams_without_snagging() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.0);
        for _ in 0..60 {
            assert!(!hits(&tiles, &mut p, SIZE, Axis::X, 0.1, EPS));
        }
        assert!((p.x - 8.5).abs() < 1e-4);
    }

    #[test]
    fn stops_flush_at_a_wall_even_at_huge_speed() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.0);
        assert!(hits(&tiles, &mut p, SIZE, Axis::X, 1000.0, EPS));
        assert!((p.x + SIZE.x / 2.0 - 10.0).abs() < 1e-5, "{p}");
        // Flush now: a further push is still stopped and does not sink in.
        assert!(hits(&tiles, &mut p, SIZE, Axis::X, 0.5, EPS));
        assert!(p.x + SIZE.x / 2.0 <= 10.0 + EPS);
    }

    #[test]
    fn ending_within_epsilon_of_the_floor_is_a_landing() {
        let tiles = room();
        let mut p = Vec2::new(2.5, 1.5);
        // Stops 0.0005 short of the floor: a contact, snapped flush.
        assert!(hits(&tiles, &mut p, SIZE, Axis::Y, -0.4995, EPS));
        assert_eq!(p.y, 1.0);
        // Stops 0.01 short: no contact.
        let mut q = Vec2::new(2.5, 1.5);
        assert!(!hits(&tiles, &mut q, SIZE, Axis::Y, -0.49, EPS));
        assert!((q.y - 1.01).abs() < 1e-6);
    }

    #[test]
    fn overlap_below_epsilon_is_not_a_side_collision() {
        let tiles = room();
        // Feet 0.0005 inside the floor: less than epsilon, so the floor does not block x.
        let mut p = Vec2::new(2.5, 1.0 - 0.0005);
        assert!(!hits(&tiles, &mut p, SIZE, Axis::X, 1.0, EPS));
        // 0.01 inside: a real overlap, so the floor tile ahead blocks.
        let mut q = Vec2::new(2.5, 1.0 - 0.01);
        assert!(hits(&tiles, &mut q, SIZE, Axis::X, 1.0, EPS));
    }
}

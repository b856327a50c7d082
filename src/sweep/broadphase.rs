//! Broadphase of the sweep controller: the level's static solid tiles in a parry2d [`Bvh`].
//!
//! A step asks for the tiles that touch the box swept along one axis; the narrow test is the
//! seed's AABB-vs-AABB, done by the resolve stage on the boxes returned here.

use glam::Vec2;
use parry2d::bounding_volume::{Aabb, BoundingVolume};
use parry2d::partitioning::{Bvh, BvhBuildStrategy};

use super::space::{Coord, Rect};
use crate::level::Level;

/// What a box in the broadphase is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BoxKind {
    /// A solid tile.
    Solid,
    /// A solid tile carrying a slope: part of a ramp's mass, which the x sweep skips.
    UnderSlope,
    /// A one-way platform (or a ladder's top): blocks only a character coming from above.
    OneWay,
    /// Moving platform `index`, one-way or solid.
    Platform {
        /// Index in the level's platforms.
        index: u32,
        /// Whether it blocks only from above.
        one_way: bool,
    },
}

/// How far beyond a query the near cache reaches on each side, in tiles, on average over the
/// two sides of an axis: the scan over it stays a dozen boxes for a one-tile character.
const NEAR_MARGIN: f32 = 1.0;

/// The share of [`NEAR_MARGIN`] a refill moves from behind a mover to ahead of it, on each axis
/// it moved along since the last refill: 1.75 tiles of travel ahead before the next refill
/// instead of 1, with the same number of boxes kept. On `flat_seams.walk_right_10s`, 688 to 656
/// instructions a float step and 950 to 894 an integer one (callgrind, docs/speed.md); 0.9
/// gave 654 and 887, too close to be worth a lag of a tenth of a tile.
const LEAD: f32 = 0.75;

/// The static boxes around one character, kept between steps (temporal coherence): a query
/// inside the cached region scans the few boxes kept here instead of descending the BVH from its
/// root, so a step's cost does not grow with the level's size. The region is refilled, from one
/// BVH query reaching `NEAR_MARGIN` beyond the asked area (more ahead of a mover than behind
/// it, [`LEAD`]), only when a query leaves it. The region's shape changes no answer, only how
/// often the BVH is asked: the region always holds the asked area.
///
/// A query answers every box of the region, in the BVH's (depth-first) order: the boxes the
/// BVH would give for the asked area are among them, in the same order, and the others are
/// near it. The caller tests each box against its own swept box anyway (in its storage's
/// coordinate, [`super::resolve::move_axis`]), so a box outside the area costs that one test and
/// changes no answer; testing it here as well would test every box twice.
///
/// Each box is kept only as its place in the mover's storage `C` (f32 or f64 tiles, or whole
/// subpixels), converted once when the region is refilled rather than at every query.
///
/// Where a query comes in the storage's coordinate and its broadphase area takes converting
/// (f64, the subpixel grid: [`NearCache::query_rect`]), the cache also keeps `inner`, a box in
/// that coordinate whose area the region holds: a query inside it is answered from the cache
/// with no conversion, exactly as the region would answer it (the area of a box inside `inner`
/// lies inside `inner`'s area, so the region holds it).
#[derive(Clone, Debug)]
pub(crate) struct NearCache<C> {
    region: Aabb,
    /// The centre of the area the last refill was asked for (the way the mover went).
    last: Vec2,
    /// A box in the storage's coordinate whose broadphase area `region` holds (checked when
    /// it was set), if one is known.
    inner: Option<Rect<C>>,
    items: Vec<(Rect<C>, BoxKind)>,
}

impl<C> Default for NearCache<C> {
    fn default() -> Self {
        NearCache {
            region: Aabb::new_invalid(),
            last: Vec2::NAN,
            inner: None,
            // Room for the neighbourhood of a character a few tiles tall; it grows (once) only
            // for bigger characters or very fast moves.
            items: Vec::with_capacity(64),
        }
    }
}

impl<C: Copy> NearCache<C> {
    /// The static boxes near `area`, each as `place` puts it in the storage, with their kind,
    /// in the BVH's order: every box touching `area` (inclusive) and maybe others near it, which
    /// the caller's own test leaves out (see the type's note).
    #[inline(always)]
    pub(crate) fn query(
        &mut self,
        tiles: &StaticTiles,
        area: Aabb,
        place: impl Fn(&Aabb) -> Rect<C>,
    ) -> &[(Rect<C>, BoxKind)] {
        if !self.region.contains(&area) {
            self.refill(tiles, &area, place);
        }
        &self.items
    }

    /// Keeps the boxes touching `area` grown by [`NEAR_MARGIN`], leaning ahead by [`LEAD`] (the
    /// rare path of a query).
    #[cold]
    fn refill(&mut self, tiles: &StaticTiles, area: &Aabb, place: impl Fn(&Aabb) -> Rect<C>) {
        // Twice the margin on each axis, most of it ahead of the way the mover went since
        // the last refill (the same margin on both sides when it did not move on that axis).
        // (The first refill has no way: its `last` is NaN, and so is the difference.)
        let centre = area.center();
        let way = centre - self.last;
        let (lead, lag) = (NEAR_MARGIN * (1.0 + LEAD), NEAR_MARGIN * (1.0 - LEAD));
        let ahead = |d: f32| match d {
            d if d > 0.0 => lead,
            d if d < 0.0 => lag,
            _ => NEAR_MARGIN,
        };
        self.region = Aabb::new(
            area.mins - Vec2::new(ahead(-way.x), ahead(-way.y)),
            area.maxs + Vec2::new(ahead(way.x), ahead(way.y)),
        );
        self.last = centre;
        self.inner = None;
        self.items.clear();
        let region = self.region;
        self.items
            .extend(tiles.query(&region).map(|(b, k)| (place(b), k)));
    }
}

impl<C: Coord> NearCache<C> {
    /// [`NearCache::query`] for the box `swept` in the storage's coordinate, whose broadphase
    /// area is `area_of(swept)`: the same answer and the same refills, but a query inside the
    /// box kept as `inner` costs four comparisons instead of converting `swept` to its area.
    /// `area_of` must be monotone (the area of a box inside another lies inside the other's),
    /// as rounding each corner to f32 and widening by the corners' magnitude is; `inside`
    /// gives a box in the storage's coordinate meant to lie within a region, which is checked.
    #[inline(always)]
    pub(crate) fn query_rect(
        &mut self,
        tiles: &StaticTiles,
        swept: Rect<C>,
        area_of: impl Fn(&Rect<C>) -> Aabb,
        inside: impl Fn(&Aabb) -> Rect<C>,
        place: impl Fn(&Aabb) -> Rect<C>,
    ) -> &[(Rect<C>, BoxKind)] {
        if !self.inner.is_some_and(|r| r.contains(&swept)) {
            self.outside_inner(tiles, swept, area_of, inside, place);
        }
        &self.items
    }

    /// A query outside `inner`: [`NearCache::query`]'s test on its area; a refill sets
    /// `inner` to `inside(region)` if the region holds that box's area (else to none, and
    /// every query takes this test).
    fn outside_inner(
        &mut self,
        tiles: &StaticTiles,
        swept: Rect<C>,
        area_of: impl Fn(&Rect<C>) -> Aabb,
        inside: impl Fn(&Aabb) -> Rect<C>,
        place: impl Fn(&Aabb) -> Rect<C>,
    ) {
        let area = area_of(&swept);
        if !self.region.contains(&area) {
            self.refill(tiles, &area, place);
            let inner = inside(&self.region);
            let valid = (0..2).all(|k| inner.min[k] <= inner.max[k]);
            self.inner = (valid && self.region.contains(&area_of(&inner))).then_some(inner);
        }
    }
}

/// Static boxes (solid tiles, and one-way tiles when the level has them) and a BVH over them.
pub(crate) struct StaticTiles {
    boxes: Vec<Aabb>,
    kinds: Vec<BoxKind>,
    bvh: Bvh,
}

impl StaticTiles {
    /// Collects the level's solid tiles (one box per tile, placed at the level's origin in the
    /// world) and builds the BVH.
    pub(crate) fn new(level: &Level) -> Self {
        let mut boxes = Vec::new();
        let mut kinds = Vec::new();
        for b in level.solid_boxes() {
            let under = level.supports_slope(b.mins.x as i64, b.mins.y as i64);
            boxes.push(b.translated(level.origin_f32()));
            kinds.push(if under {
                BoxKind::UnderSlope
            } else {
                BoxKind::Solid
            });
        }
        if level.features.one_way || level.features.ladders {
            for b in level.one_way_boxes() {
                boxes.push(b.translated(level.origin_f32()));
                kinds.push(BoxKind::OneWay);
            }
        }
        let bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes);
        StaticTiles { boxes, kinds, bvh }
    }

    /// Boxes whose AABB intersects `area` (inclusive of touching; the caller filters), with
    /// their kind.
    pub(crate) fn query<'a>(
        &'a self,
        area: &'a Aabb,
    ) -> impl Iterator<Item = (&'a Aabb, BoxKind)> + 'a {
        self.bvh
            .intersect_aabb(area)
            .map(move |leaf| (&self.boxes[leaf as usize], self.kinds[leaf as usize]))
    }

    /// Number of static boxes.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.boxes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::Tile;
    use glam::Vec2;

    #[test]
    fn query_returns_only_nearby_tiles() {
        let level = Level::from_tiles("row", 100, 1, vec![Tile::Solid; 100]);
        let tiles = StaticTiles::new(&level);
        assert_eq!(tiles.len(), 100);
        let area = Aabb::new(Vec2::new(10.2, 0.5), Vec2::new(11.8, 2.0));
        let mut found: Vec<f32> = tiles.query(&area).map(|(b, _)| b.mins.x).collect();
        found.sort_by(f32::total_cmp);
        assert_eq!(found, vec![10.0, 11.0]);
    }

    type Answer = Vec<(Aabb, BoxKind)>;

    /// The near cache's answer for `area`, picked out by the caller's own test (inclusive
    /// touching), beside the BVH's direct answer.
    fn cached_and_direct(
        tiles: &StaticTiles,
        near: &mut NearCache<f32>,
        area: Aabb,
    ) -> (Answer, Answer) {
        let cached = near
            .query(tiles, area, |b| Rect::from(*b))
            .iter()
            .map(|(b, k)| (Aabb::new(b.min.into(), b.max.into()), *k))
            .filter(|(b, _)| b.intersects(&area))
            .collect();
        let direct = tiles.query(&area).map(|(b, k)| (*b, k)).collect();
        (cached, direct)
    }

    #[test]
    fn near_cache_answers_as_the_bvh_does() {
        // A floor with gaps and a wall, queried along a walk: every answer, refilled or cached,
        // is the BVH's own, in its order.
        let mut t = vec![Tile::Empty; 200 * 4];
        for i in 0..200 {
            if i % 7 != 3 {
                t[i] = Tile::Solid;
            }
            if i % 13 == 0 {
                t[200 * 2 + i] = Tile::Solid;
            }
        }
        let tiles = StaticTiles::new(&Level::from_tiles("walk", 200, 4, t));
        let mut near = NearCache::<f32>::default();
        let mut refills = 0;
        for k in 0..2000 {
            let x = k as f32 * 0.093;
            let area = Aabb::new(Vec2::new(x, 0.9), Vec2::new(x + 0.8, 2.05));
            let before = near.region;
            let (cached, direct) = cached_and_direct(&tiles, &mut near, area);
            refills += (near.region != before) as usize;
            assert_eq!(cached, direct, "at x = {x}");
        }
        // 186 tiles walked with a one-tile margin: a refill about every tile, not every query.
        assert!(refills < 300, "{refills} refills for 2000 queries");
    }

    #[test]
    fn near_cache_answers_as_the_bvh_does_whichever_way_the_mover_turns() {
        // A staircase of solids, queried along a path that turns on both axes every few
        // steps (the region leans ahead of the way the mover went): every answer is the BVH's.
        let (w, h) = (60, 40);
        let t: Vec<Tile> = (0..w * h)
            .map(|i| {
                if (i % w + i / w) % 5 == 0 || (i * 7) % 11 == 0 {
                    Tile::Solid
                } else {
                    Tile::Empty
                }
            })
            .collect();
        let tiles = StaticTiles::new(&Level::from_tiles("turns", w as u32, h as u32, t));
        let mut near = NearCache::<f32>::default();
        let mut p = Vec2::new(30.0, 20.0);
        for k in 0..3000 {
            let turn = (k / 37) % 4;
            let v = [(0.13, 0.05), (-0.21, 0.0), (0.0, -0.17), (0.08, 0.31)][turn];
            p += Vec2::new(v.0, v.1);
            p = p.clamp(Vec2::splat(2.0), Vec2::new(w as f32 - 3.0, h as f32 - 3.0));
            let area = Aabb::new(p, p + Vec2::new(0.8, 0.9) + Vec2::new(v.0, v.1).abs());
            let (cached, direct) = cached_and_direct(&tiles, &mut near, area);
            assert_eq!(cached, direct, "step {k} at {p}");
            assert!(near.region.contains(&area), "step {k}");
        }
    }
}

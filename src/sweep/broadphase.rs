//! Broadphase of the sweep controller: the level's static solid tiles in a parry2d [`Bvh`].
//!
//! A step asks for the tiles that touch the box swept along one axis; the narrow test is the
//! seed's AABB-vs-AABB, done by the resolve stage on the boxes returned here.

use parry2d::bounding_volume::Aabb;
use parry2d::partitioning::{Bvh, BvhBuildStrategy};

use crate::level::Level;

/// What a box in the broadphase is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxKind {
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

/// Static boxes (solid tiles, and one-way tiles when the level has them) and a BVH over them.
pub struct StaticTiles {
    boxes: Vec<Aabb>,
    kinds: Vec<BoxKind>,
    bvh: Bvh,
}

impl StaticTiles {
    /// Collects the level's solid tiles (one box per tile, placed at the level's origin in the
    /// world) and builds the BVH.
    pub fn new(level: &Level) -> Self {
        let mut boxes = Vec::new();
        let mut kinds = Vec::new();
        for b in level.solid_boxes() {
            let under = level.supports_slope(b.mins.x as i64, b.mins.y as i64);
            boxes.push(b.translated(level.origin));
            kinds.push(if under {
                BoxKind::UnderSlope
            } else {
                BoxKind::Solid
            });
        }
        if level.features.one_way || level.features.ladders {
            for b in level.one_way_boxes() {
                boxes.push(b.translated(level.origin));
                kinds.push(BoxKind::OneWay);
            }
        }
        let bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes);
        StaticTiles { boxes, kinds, bvh }
    }

    /// Boxes whose AABB intersects `area` (inclusive of touching; the caller filters), with
    /// their kind.
    pub fn query<'a>(&'a self, area: &'a Aabb) -> impl Iterator<Item = (&'a Aabb, BoxKind)> + 'a {
        self.bvh
            .intersect_aabb(area)
            .map(move |leaf| (&self.boxes[leaf as usize], self.kinds[leaf as usize]))
    }

    /// Number of solid boxes.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// Whether the level has no solid tile.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
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
}

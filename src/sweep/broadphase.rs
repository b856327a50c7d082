//! Broadphase of the sweep controller: the level's static solid tiles in a parry2d [`Bvh`].
//!
//! A step asks for the tiles that touch the box swept along one axis; the narrow test is the
//! seed's AABB-vs-AABB, done by the resolve stage on the boxes returned here.

use parry2d::bounding_volume::Aabb;
use parry2d::partitioning::{Bvh, BvhBuildStrategy};

use crate::level::Level;

/// Static solid boxes and a BVH over them.
pub struct StaticTiles {
    boxes: Vec<Aabb>,
    /// Per box: a solid tile carrying a slope (part of a ramp's mass), which the x sweep skips.
    under_slope: Vec<bool>,
    bvh: Bvh,
}

impl StaticTiles {
    /// Collects the level's solid tiles (one box per tile, placed at the level's origin in the
    /// world) and builds the BVH.
    pub fn new(level: &Level) -> Self {
        let solid: Vec<Aabb> = level.solid_boxes().collect();
        let under_slope = solid
            .iter()
            .map(|b| level.supports_slope(b.mins.x as i64, b.mins.y as i64))
            .collect();
        let boxes: Vec<Aabb> = solid.iter().map(|b| b.translated(level.origin)).collect();
        let bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes);
        StaticTiles {
            boxes,
            under_slope,
            bvh,
        }
    }

    /// Boxes whose AABB intersects `area` (inclusive of touching; the caller filters), with
    /// whether each carries a slope.
    pub fn query<'a>(&'a self, area: &'a Aabb) -> impl Iterator<Item = (&'a Aabb, bool)> + 'a {
        self.bvh
            .intersect_aabb(area)
            .map(move |leaf| (&self.boxes[leaf as usize], self.under_slope[leaf as usize]))
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

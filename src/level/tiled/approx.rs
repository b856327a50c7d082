//! Tile collision shapes that are neither one full-tile rectangle nor one ramp polygon: a
//! rectangle over part of the tile, several rectangles, a polyline, a polygon that is almost a
//! ramp. Games use them for half tiles, ledges and hand-drawn ground; a level's tile is whole,
//! a ramp or empty, so each is approximated by the nearest of those, and the note says how.

use glam::Vec2;
use tiled::{ObjectData, ObjectShape};

use crate::level::{Slope, Tile};

/// The shapes must span at least this fraction of the tile's width to be ground: narrower, a
/// character's box (0.8 tile wide) would not rest on them alone.
const MIN_WIDTH: f32 = 0.5;
/// Shapes whose top is this close to the tile's top (fraction of its height) make it solid.
const TOP_SNAP: f32 = 0.25;
/// Below this height (tiles) the shapes are a sliver on the floor: the tile is empty.
const MIN_HEIGHT: f32 = 1.0 / 16.0;

/// An object's points in tile pixels, y down, clipped to the tile; empty for shapes with no
/// extent (points, text).
fn points(o: &ObjectData, tw: f32, th: f32) -> Vec<Vec2> {
    let at = Vec2::new(o.x, o.y);
    let pts: Vec<Vec2> = match &o.shape {
        ObjectShape::Rect { width, height }
        | ObjectShape::Ellipse { width, height }
        | ObjectShape::Capsule { width, height } => vec![at, at + Vec2::new(*width, *height)],
        ObjectShape::Polygon { points } | ObjectShape::Polyline { points } => {
            points.iter().map(|&(x, y)| at + Vec2::new(x, y)).collect()
        }
        ObjectShape::Point(..) | ObjectShape::Text { .. } => Vec::new(),
    };
    pts.into_iter()
        .filter(|p| p.is_finite())
        .map(|p| p.clamp(Vec2::ZERO, Vec2::new(tw, th)))
        .collect()
}

/// The nearest whole tile, ramp or empty tile to `objects` (the tile's collision shapes, none
/// rotated), and a note that says what was read and how it was approximated. A single polygon
/// becomes a ramp through its highest points at its left and right ends; other shapes become
/// a flat box from the tile's bottom to their highest point, or a solid tile when that point is
/// within a quarter tile of the top.
pub(crate) fn approximate(objects: &[ObjectData], tw: f32, th: f32) -> (Tile, String) {
    let shapes: Vec<Vec<Vec2>> = objects
        .iter()
        .map(|o| points(o, tw, th))
        .filter(|p| !p.is_empty())
        .collect();
    let what = match objects {
        [o] => super::shape_name(&o.shape).to_string(),
        many => format!("{} objects", many.len()),
    };
    let all = shapes.iter().flatten();
    let lo = all
        .clone()
        .fold(Vec2::splat(f32::INFINITY), |a, p| a.min(*p));
    let hi = all.fold(Vec2::splat(f32::NEG_INFINITY), |a, p| a.max(*p));
    if shapes.is_empty() || hi.x - lo.x < MIN_WIDTH * tw {
        return (
            Tile::Empty,
            format!("its collision shape ({what}) spans less than half the tile's width inside it, so nothing rests on it; approximated as empty"),
        );
    }
    let within = format!(
        "({what}, within ({}, {}) to ({}, {}) px of the {tw} x {th} tile)",
        lo.x, lo.y, hi.x, hi.y
    );
    // Heights in tiles above the tile's bottom.
    let height = |y: f32| 1.0 - y / th;
    if let [poly] = objects {
        if matches!(poly.shape, ObjectShape::Polygon { .. }) {
            let pts = &shapes[0];
            let tol = super::SHAPE_TOLERANCE_PX;
            let top_at = |x: f32| {
                pts.iter()
                    .filter(|p| (p.x - x).abs() <= tol)
                    .map(|p| height(p.y))
                    .fold(0.0f32, f32::max)
            };
            let (left, right) = (top_at(lo.x), top_at(hi.x));
            if (left - right).abs() > MIN_HEIGHT {
                return (
                    Tile::Slope(Slope::Line { left, right }),
                    format!("its collision shape is not one full-tile rectangle or ramp {within}; approximated as a ramp from height {left} to {right} tile across the tile"),
                );
            }
        }
    }
    let top = height(lo.y);
    if top >= 1.0 - TOP_SNAP {
        (
            Tile::Solid,
            format!("its collision shape is not one full-tile rectangle or ramp {within}; its top is within a quarter tile of the tile's top, so approximated as a solid tile"),
        )
    } else if top < MIN_HEIGHT {
        (
            Tile::Empty,
            format!("its collision shape is not one full-tile rectangle or ramp {within}; it lies on the tile's bottom, less than 1/16 tile high, so approximated as empty"),
        )
    } else {
        (
            Tile::Slope(Slope::Line {
                left: top,
                right: top,
            }),
            format!("its collision shape is not one full-tile rectangle or ramp {within}; approximated as a flat box {top} tile high from the tile's bottom"),
        )
    }
}

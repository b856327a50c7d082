//! What one tileset tile is: its properties (platbench's own `collision` string, the bool
//! properties games use, slope properties), its class, else its collision shape; and how a flip
//! changes it.

use std::collections::BTreeMap;

use glam::Vec2;
use tiled::{ObjectShape, PropertyValue};

use super::error::{FlipError, HeightsError, ShapeError, TileKindError};
use super::{approx, kind_of, names, number, SHAPE_TOLERANCE_PX};
use crate::level::import::parse_tile_kind;
use crate::level::{Slope, Tile};

/// Bool tile properties games mark collision with (compared in lower case): true makes the tile
/// solid, false empty.
pub(crate) const SOLID_BOOLS: &[&str] = &[
    "collision",
    "collidable",
    "issolid",
    "solid",
    "collides",
    "blocked",
    "wall",
    "collide",
    "estsolide",
];
/// Bool tile properties that make a tile a one-way platform when true.
pub(crate) const ONE_WAY_BOOLS: &[&str] = &[
    "one_way",
    "oneway",
    "isoneway",
    "jumpthrough",
    "jumpthru",
    "platform",
    "unisolid",
    "semisolid",
    "passthrough",
];
/// Bool tile properties that mark a hazard (spikes, lava, a kill zone): not solid when true,
/// unless a solid mark of the same tile says otherwise.
pub(crate) const HAZARD_BOOLS: &[&str] = &[
    "hazard", "kill", "kills", "deadly", "lethal", "death", "damage", "spike", "spikes",
];
/// String tile properties a game may name a tile's kind with, as Tiled's own class does
/// (`class = one_way`); read when the value is a kind.
const KIND_STRINGS: &[&str] = &["class", "type", "kind"];
/// Bool tile properties that make a tile a ladder when true.
pub(crate) const LADDER_BOOLS: &[&str] = &["ladder", "isladder", "climbable"];

/// Whether a property marks collision with a bool (see [`SOLID_BOOLS`], [`ONE_WAY_BOOLS`],
/// [`LADDER_BOOLS`]).
pub(crate) fn is_bool_mark(key: &str, value: &PropertyValue) -> bool {
    let k = key.to_lowercase();
    matches!(value, PropertyValue::BoolValue(_))
        && (SOLID_BOOLS.contains(&k.as_str())
            || ONE_WAY_BOOLS.contains(&k.as_str())
            || LADDER_BOOLS.contains(&k.as_str()))
}

/// A tileset tile's meaning from its properties, else its class (`solid`, `one_way`, `ladder`,
/// `empty`), else its collision shape; `None` when it says nothing (the caller's default then
/// holds: solid, or empty in a tileset that marks its solid tiles with a bool property).
/// Properties take precedence over a collision shape, which is then not read (a warning says
/// so). Returns the tile and the warnings about it; `Err` says why the tile is unsupported.
/// `tw` x `th` is the tile's own size in pixels (its image's, in an image collection).
pub(crate) fn tile_kind(
    props: &tiled::Properties,
    class: &str,
    shape: Option<&tiled::ObjectLayerData>,
    tw: f32,
    th: f32,
) -> Result<(Option<Tile>, Vec<String>), TileKindError> {
    let mut notes = Vec::new();
    let mut collision = None;
    let mut marked: Option<(String, Tile)> = None;
    let mut left = None;
    let mut right = None;
    let mut heights = None;
    let sorted: BTreeMap<_, _> = props.iter().collect();
    for (key, value) in sorted {
        let lower = key.to_lowercase();
        if let PropertyValue::BoolValue(b) = value {
            let t = if SOLID_BOOLS.contains(&lower.as_str()) {
                Some(if *b { Tile::Solid } else { Tile::Empty })
            } else if ONE_WAY_BOOLS.contains(&lower.as_str()) {
                b.then_some(Tile::OneWay)
            } else if LADDER_BOOLS.contains(&lower.as_str()) {
                b.then_some(Tile::Ladder)
            } else if HAZARD_BOOLS.contains(&lower.as_str()) {
                b.then_some(Tile::Empty)
            } else {
                None
            };
            let known = SOLID_BOOLS.contains(&lower.as_str())
                || ONE_WAY_BOOLS.contains(&lower.as_str())
                || LADDER_BOOLS.contains(&lower.as_str())
                || HAZARD_BOOLS.contains(&lower.as_str());
            if known {
                match (&marked, t) {
                    (_, None) => {}
                    (None, Some(t)) => marked = Some((key.clone(), t)),
                    (Some((_, Tile::Empty)), Some(t)) => marked = Some((key.clone(), t)),
                    (Some(_), Some(Tile::Empty)) => {}
                    (Some((k0, t0)), Some(t)) if *t0 != t => {
                        return Err(TileKindError::ConflictingBools {
                            first: k0.clone(),
                            first_tile: *t0,
                            second: key.clone(),
                            second_tile: t,
                        })
                    }
                    _ => {}
                }
                continue;
            }
        }
        if let PropertyValue::StringValue(v) = value {
            if KIND_STRINGS.contains(&lower.as_str()) && parse_tile_kind(v).is_some() {
                if collision.is_none() {
                    collision = Some(v.clone());
                }
                continue;
            }
        }
        match key.as_str() {
            names::COLLISION => match value {
                PropertyValue::StringValue(s) => collision = Some(s.clone()),
                other => return Err(TileKindError::CollisionType { kind: kind_of(other) }),
            },
            names::SLOPE_LEFT | names::SLOPE_RIGHT => {
                let v = number(value).ok_or_else(|| TileKindError::SlopeType {
                    key: key.clone(),
                    kind: kind_of(value),
                })?;
                if !(v.is_finite() && v.abs() <= 16.0) {
                    return Err(TileKindError::SlopeRange {
                        key: key.clone(),
                        value: v,
                    });
                }
                if key == names::SLOPE_LEFT {
                    left = Some(v);
                } else {
                    right = Some(v);
                }
            }
            names::HEIGHTS => match value {
                PropertyValue::StringValue(s) => heights = Some(parse_heights(s)?),
                other => return Err(TileKindError::HeightsType { kind: kind_of(other) }),
            },
            _ => notes.push(format!(
                "property {key:?} is not one platbench reads (it reads collision, slope_left, slope_right, heights, class = solid/one_way/ladder/empty, and bools such as collidable, isSolid, solid, collides, blocked, one_way, unisolid, ladder, hazard; docs/formats.md lists them); ignored"
            )),
        }
    }
    let slope = match (left, right, heights) {
        (None, None, None) => None,
        (Some(l), Some(r), None) => Some(Slope::Line { left: l, right: r }),
        (None, None, Some(h)) => Some(Slope::Heights(h)),
        (Some(_), None, None) | (None, Some(_), None) => return Err(TileKindError::HalfLineSlope),
        _ => return Err(TileKindError::TwoSlopes),
    };
    let from_string = match collision.as_deref() {
        None => None,
        Some(c) => match parse_tile_kind(c) {
            Some(t) => Some(t),
            None => {
                return Err(TileKindError::CollisionValue {
                    value: c.to_string(),
                })
            }
        },
    };
    let from_props = match (from_string, slope, &marked) {
        (Some(_), Some(_), _) => {
            return Err(TileKindError::CollisionAndSlope {
                collision: collision.unwrap_or_default(),
            })
        }
        (None, Some(s), _) => Some(Tile::Slope(s)),
        // A generic collision mark (`collidable = true`) says only that the tile collides; a
        // kind (`class = one_way`) beside it says how (remyroez/love-platformer's tiles).
        (Some(t), None, Some((k, Tile::Solid)))
            if SOLID_BOOLS.contains(&k.to_lowercase().as_str())
                && matches!(t, Tile::OneWay | Tile::Ladder) =>
        {
            Some(t)
        }
        (Some(t), None, Some((k, m))) if t != *m => {
            return Err(TileKindError::CollisionAndBool {
                collision: collision.unwrap_or_default(),
                key: k.clone(),
                tile: *m,
            })
        }
        (Some(t), None, _) => Some(t),
        (None, None, Some((_, m))) => Some(*m),
        (None, None, None) => None,
    };
    let objects = shape.map_or(&[][..], |s| s.object_data());
    if let Some(t) = from_props {
        if !objects.is_empty() {
            notes.push("its properties say what it is, so its collision shape is not read".into());
        }
        return Ok((Some(t), notes));
    }
    if !class.is_empty() {
        if let Some(t) = parse_tile_kind(class) {
            return Ok((Some(t), notes));
        }
    }
    if let Some(o) = objects.iter().find(|o| o.rotation != 0.0) {
        return Err(ShapeError::Rotated {
            degrees: o.rotation,
        }
        .into());
    }
    let t = match objects {
        [] => None,
        [o] => match exact_kind(o, tw, th) {
            Some(t) => Some(t),
            None => Some(approximated(objects, tw, th, &mut notes)),
        },
        many => Some(approximated(many, tw, th, &mut notes)),
    };
    Ok((t, notes))
}

fn parse_heights(s: &str) -> Result<[u8; 16], HeightsError> {
    let vals: Vec<&str> = s.split(',').map(str::trim).collect();
    if vals.len() != 16 {
        return Err(HeightsError::Count {
            text: s.to_string(),
            count: vals.len(),
        });
    }
    let mut out = [0u8; 16];
    for (k, v) in vals.iter().enumerate() {
        match v.parse::<u8>() {
            Ok(h) if h <= 16 => out[k] = h,
            _ => {
                return Err(HeightsError::Entry {
                    text: s.to_string(),
                    entry: k + 1,
                    value: v.to_string(),
                })
            }
        }
    }
    Ok(out)
}

/// A partial or compound collision shape's nearest tile ([`approx::approximate`]), its note
/// added to the tile's.
fn approximated(objects: &[tiled::ObjectData], tw: f32, th: f32, notes: &mut Vec<String>) -> Tile {
    let (t, note) = approx::approximate(objects, tw, th);
    notes.push(note);
    t
}

/// The meaning of a tile's single, unrotated collision object when it is exact: a rectangle
/// over the whole tile is solid, a ramp polygon is a line slope; `None` for anything else.
fn exact_kind(o: &tiled::ObjectData, tw: f32, th: f32) -> Option<Tile> {
    let tol = SHAPE_TOLERANCE_PX;
    match &o.shape {
        ObjectShape::Rect { width, height } => {
            let full = o.x.abs() <= tol
                && o.y.abs() <= tol
                && (o.x + width - tw).abs() <= tol
                && (o.y + height - th).abs() <= tol;
            full.then_some(Tile::Solid)
        }
        ObjectShape::Polygon { points } => {
            let pts: Vec<Vec2> = points
                .iter()
                .map(|&(x, y)| Vec2::new(o.x + x, o.y + y))
                .collect();
            ramp(&pts, tw, th).map(Tile::Slope)
        }
        _ => None,
    }
}

/// Recognises a ramp: a polygon (tile pixels, y down) whose corners, once points on a straight
/// edge are dropped, are the tile's two bottom corners, next to each other, and one point on
/// each side (or on one side only, for a triangle), all within [`SHAPE_TOLERANCE_PX`]. Returns
/// the line slope through the top points, heights in tiles.
pub(crate) fn ramp(pts: &[Vec2], tw: f32, th: f32) -> Option<Slope> {
    // Tile-local, y up, in tiles; tolerances in the same units.
    let tol = Vec2::new(SHAPE_TOLERANCE_PX / tw, SHAPE_TOLERANCE_PX / th);
    let p: Vec<Vec2> = pts
        .iter()
        .map(|q| Vec2::new(q.x / tw, 1.0 - q.y / th))
        .collect();
    if p.iter().any(|q| !q.is_finite()) {
        return None;
    }
    let near = |a: Vec2, b: Vec2| (a.x - b.x).abs() <= tol.x && (a.y - b.y).abs() <= tol.y;
    // Drop repeated points and points on the straight line between their neighbours.
    let p = drop_straight(p, |a, b, c| {
        let ac = c - a;
        let off = if ac.length() < 1e-9 {
            (b - a).length()
        } else {
            (ac.perp_dot(b - a) / ac.length()).abs()
        };
        near(a, b) || off <= tol.min_element() * 0.5
    });
    if !(3..=4).contains(&p.len()) {
        return None;
    }
    let n = p.len();
    let bl = p.iter().position(|q| near(*q, Vec2::ZERO))?;
    let br = p.iter().position(|q| near(*q, Vec2::X))?;
    // The bottom edge is one edge of the polygon.
    if (bl + 1) % n != br && (br + 1) % n != bl {
        return None;
    }
    let mut left = 0.0f32;
    let mut right = 0.0f32;
    for (k, q) in p.iter().enumerate() {
        if k == bl || k == br {
            continue;
        }
        if q.y < -tol.y || q.y > 1.0 + tol.y {
            return None;
        }
        let h = q.y.clamp(0.0, 1.0);
        if q.x.abs() <= tol.x {
            left = h;
        } else if (q.x - 1.0).abs() <= tol.x {
            right = h;
        } else {
            return None;
        }
    }
    let snap = |h: f32, t: f32| {
        if h <= t {
            0.0
        } else if h >= 1.0 - t {
            1.0
        } else {
            h
        }
    };
    let (left, right) = (snap(left, tol.y), snap(right, tol.y));
    (left > 0.0 || right > 0.0).then_some(Slope::Line { left, right })
}

/// The polygon `p` with its points dropped one at a time while one can be: always the first
/// point (in the polygon's order) that `drop(previous, point, next)` says goes, until none does
/// or fewer than 3 are left. A point's neighbours change only when a neighbour is dropped, so
/// only those two are looked at again: O(n log n), where rescanning the polygon after each
/// drop was O(n²) (a 1,000,000-point polygon took 58 s).
fn drop_straight(p: Vec<Vec2>, drop: impl Fn(Vec2, Vec2, Vec2) -> bool) -> Vec<Vec2> {
    let n = p.len();
    if n < 3 {
        return p;
    }
    let mut prev: Vec<usize> = (0..n).map(|k| (k + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|k| (k + 1) % n).collect();
    let mut alive = vec![true; n];
    let mut left = n;
    // The points that may go: every point not in it was kept by its present neighbours.
    let mut todo: std::collections::BTreeSet<usize> = (0..n).collect();
    while left >= 3 {
        let Some(k) = todo.pop_first() else {
            break;
        };
        let (a, c) = (prev[k], next[k]);
        if drop(p[a], p[k], p[c]) {
            next[a] = c;
            prev[c] = a;
            alive[k] = false;
            left -= 1;
            todo.insert(a);
            todo.insert(c);
        }
    }
    p.into_iter()
        .zip(alive)
        .filter_map(|(q, keep)| keep.then_some(q))
        .collect()
}

/// A tile's meaning once flipped: mirroring a slope mirrors its surface; flips that turn a
/// slope upside down or sideways (vertical, diagonal) are not representable; solids, ladders,
/// empty and one-way tiles keep their meaning under any flip (a one-way cell blocks from above
/// however its art is turned).
pub(crate) fn apply_flips(t: Tile, h: bool, v: bool, d: bool) -> Result<Tile, FlipError> {
    match t {
        // A one-way tile blocks from above whichever way its art is drawn: games read the
        // cell's property, not the picture.
        Tile::Empty | Tile::Solid | Tile::Ladder | Tile::OneWay => Ok(t),
        Tile::Slope(_) if v || d => Err(FlipError::SlopeTurned),
        Tile::Slope(s) if h => Ok(Tile::Slope(match s {
            Slope::Line { left, right } => Slope::Line {
                left: right,
                right: left,
            },
            Slope::Heights(mut a) => {
                a.reverse();
                Slope::Heights(a)
            }
        })),
        Tile::Slope(_) => Ok(t),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_with_a_corner_drawn_a_thousand_times_is_the_ramp() {
        // (0,16) (16,16) (16,8), then its top-left corner (0,0) 1,000 times over.
        let corners = [(0.0, 16.0), (16.0, 16.0), (16.0, 8.0)].map(|(x, y)| Vec2::new(x, y));
        let pts: Vec<Vec2> = corners.into_iter().chain([Vec2::ZERO; 1000]).collect();
        let (left, right) = (1.0, 0.5);
        assert_eq!(ramp(&pts, 16.0, 16.0), Some(Slope::Line { left, right }));
    }

    #[test]
    fn a_kind_beside_a_generic_collision_mark_says_how_the_tile_collides() {
        let props = |pairs: &[(&str, PropertyValue)]| -> tiled::Properties {
            pairs
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect()
        };
        let one_way = props(&[
            ("class", PropertyValue::StringValue("one_way".into())),
            ("collidable", PropertyValue::BoolValue(true)),
        ]);
        let (t, _) = tile_kind(&one_way, "", None, 16.0, 16.0).unwrap();
        assert_eq!(t, Some(Tile::OneWay));
        // A mark that says the tile does not collide still contradicts a kind.
        let off = props(&[
            ("class", PropertyValue::StringValue("one_way".into())),
            ("collidable", PropertyValue::BoolValue(false)),
        ]);
        assert!(tile_kind(&off, "", None, 16.0, 16.0).is_err());
    }

    fn px(points: &[(f32, f32)]) -> Vec<Vec2> {
        points.iter().map(|&(x, y)| Vec2::new(x, y)).collect()
    }

    #[test]
    fn ramp_polygons_become_line_slopes_both_ways() {
        // 16 px tiles, y down: bottom-left (0, 16), bottom-right (16, 16).
        let up = ramp(&px(&[(0.0, 16.0), (16.0, 16.0), (16.0, 0.0)]), 16.0, 16.0);
        assert_eq!(
            up,
            Some(Slope::Line {
                left: 0.0,
                right: 1.0
            })
        );
        let down = ramp(&px(&[(0.0, 0.0), (0.0, 16.0), (16.0, 16.0)]), 16.0, 16.0);
        assert_eq!(
            down,
            Some(Slope::Line {
                left: 1.0,
                right: 0.0
            })
        );
        // A trapezoid, the other winding, half a pixel off: 0.25 to 0.75 of the tile.
        let trap = ramp(
            &px(&[(0.0, 12.0), (16.0, 4.0), (16.0, 16.0), (0.3, 15.6)]),
            16.0,
            16.0,
        );
        assert_eq!(
            trap,
            Some(Slope::Line {
                left: 0.25,
                right: 0.75
            })
        );
        // A point in the middle of the bottom edge is dropped.
        let mid = ramp(
            &px(&[(0.0, 16.0), (8.0, 16.0), (16.0, 16.0), (16.0, 0.0)]),
            16.0,
            16.0,
        );
        assert_eq!(
            mid,
            Some(Slope::Line {
                left: 0.0,
                right: 1.0
            })
        );
    }

    #[test]
    fn polygons_that_are_not_ramps_are_refused() {
        // A triangle hanging from the top (a ceiling slope).
        assert_eq!(
            ramp(&px(&[(0.0, 0.0), (16.0, 0.0), (16.0, 16.0)]), 16.0, 16.0),
            None
        );
        // A bow tie over the four corners.
        assert_eq!(
            ramp(
                &px(&[(0.0, 16.0), (16.0, 0.0), (16.0, 16.0), (0.0, 0.0)]),
                16.0,
                16.0
            ),
            None
        );
        // A bump in the middle of the top.
        assert_eq!(
            ramp(
                &px(&[
                    (0.0, 16.0),
                    (16.0, 16.0),
                    (16.0, 8.0),
                    (8.0, 2.0),
                    (0.0, 8.0)
                ]),
                16.0,
                16.0
            ),
            None
        );
        // A peak that leaves the tile.
        assert_eq!(
            ramp(&px(&[(0.0, 16.0), (16.0, 16.0), (16.0, -4.0)]), 16.0, 16.0),
            None
        );
        // Flat along the bottom: no surface.
        assert_eq!(
            ramp(&px(&[(0.0, 16.0), (16.0, 16.0), (16.0, 15.9)]), 16.0, 16.0),
            None
        );
    }

    #[test]
    fn a_mirrored_ramp_is_the_mirror_and_other_flips_are_refused() {
        let up = Tile::Slope(Slope::Line {
            left: 0.0,
            right: 0.5,
        });
        assert_eq!(
            apply_flips(up, true, false, false),
            Ok(Tile::Slope(Slope::Line {
                left: 0.5,
                right: 0.0
            }))
        );
        assert_eq!(
            apply_flips(up, false, true, false),
            Err(FlipError::SlopeTurned)
        );
        assert_eq!(
            apply_flips(up, false, false, true),
            Err(FlipError::SlopeTurned)
        );
        let mut h = [0u8; 16];
        h[0] = 16;
        let mut r = [0u8; 16];
        r[15] = 16;
        assert_eq!(
            apply_flips(Tile::Slope(Slope::Heights(h)), true, false, false),
            Ok(Tile::Slope(Slope::Heights(r)))
        );
        assert_eq!(apply_flips(Tile::Solid, true, true, true), Ok(Tile::Solid));
        // A rotated one-way tile is still one-way (it was refused without need).
        assert_eq!(
            apply_flips(Tile::OneWay, false, true, true),
            Ok(Tile::OneWay)
        );
        assert_eq!(
            apply_flips(Tile::OneWay, true, false, false),
            Ok(Tile::OneWay)
        );
    }

    #[test]
    fn height_strings_need_sixteen_sixteenths() {
        assert_eq!(
            parse_heights("0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,16").map(|h| h[15]),
            Ok(16)
        );
        assert_eq!(
            parse_heights("1,2").unwrap_err().to_string(),
            "heights = \"1,2\" has 2 entries; expected 16 comma-separated integers 0..16 (sixteenths of a tile, left to right)"
        );
        assert!(parse_heights("0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,17")
            .unwrap_err()
            .to_string()
            .contains("entry 16 is \"17\""));
    }
}

//! Where the map itself overrules a layer's name: a tile layer named like art where the player
//! is (`Foreground`, `Details`; not `Background`, `Water` or `Coins`) whose tiles carry a
//! collision mark (`collide = true`) is collision, as the game that marks its tiles reads them; a tile layer named like ground (`Ground`, `World`) beside an object layer
//! named for collision that holds the collision shapes is that layer's art, not a second
//! collision source; when no layer is named for collision, an object layer of plain boxes
//! (rectangles and polygons, most with neither name nor class) is the collision source, as the games that
//! build their colliders from `geom` or `Object Layer 1` read it; a tile layer named
//! `platforms` beside one named `collision` is one-way. The user's `--layer` and side file
//! still decide over all of these.

use tiled::{LayerType, PropertyValue, TileLayer};

use super::layers::Entry;
use super::tiles::is_bool_mark;
use super::Importer;
use crate::level::import::names::{
    is_spawn_name, role_from_name, says, ART_WORDS, STRONG_COLLISION_WORDS,
};
use crate::level::import::LayerRole;

/// The first collision mark (a solid or one-way bool property set true, `key = true`) on a tile
/// the layer draws, if any.
fn marked(t: &TileLayer) -> Option<String> {
    let mark = |lt: tiled::LayerTile| -> Option<String> {
        let tile = lt.get_tile()?;
        // The properties are a hash map: the least name, so the message is the same each run.
        let marks = tile
            .properties
            .iter()
            .filter(|(k, v)| is_bool_mark(k, v) && **v == PropertyValue::BoolValue(true));
        marks.map(|(k, _)| k).min().map(|k| format!("{k} = true"))
    };
    match t {
        TileLayer::Finite(f) => (0..f.height() as i32)
            .flat_map(|y| (0..f.width() as i32).map(move |x| (x, y)))
            .find_map(|(x, y)| f.get_tile(x, y).and_then(mark)),
        // The chunks are a hash map: read top row first, as a finite layer is.
        TileLayer::Infinite(inf) => {
            let mut chunks: Vec<_> = inf.chunks().collect();
            chunks.sort_by_key(|&((x, y), _)| (y, x));
            chunks.into_iter().find_map(|(_, chunk)| {
                let w = tiled::ChunkData::WIDTH as i32;
                let h = tiled::ChunkData::HEIGHT as i32;
                (0..h)
                    .flat_map(|y| (0..w).map(move |x| (x, y)))
                    .find_map(|(x, y)| chunk.get_tile(x, y).and_then(mark))
            })
        }
    }
}

/// Why an object layer no rule marks is evidently collision: at least two objects, every one an
/// unrotated rectangle or polygon, no tile object and no moving platform, none named like a
/// spawn or decoration, and at least half with neither name nor class (a trigger, a coin or a
/// camera bound carries one). Games build their collision boxes from such layers whatever
/// their name (`geom`, `Unmovable`, `Object Layer 1`).
fn plain_boxes(objects: &[tiled::Object]) -> Option<String> {
    let shaped = |o: &tiled::Object| {
        matches!(
            o.shape,
            tiled::ObjectShape::Rect { .. } | tiled::ObjectShape::Polygon { .. }
        ) && o.rotation == 0.0
            && !o.properties.contains_key(super::names::PATH)
            && o.tile_data().is_none()
    };
    let named_away = |s: &str| {
        !s.is_empty()
            && (is_spawn_name(s)
                || matches!(role_from_name(s), Some((r, _)) if r != LayerRole::Collision))
    };
    let plain = objects
        .iter()
        .filter(|o| o.name.is_empty() && o.user_type.is_empty())
        .count();
    (objects.len() >= 2
        && objects.iter().all(shaped)
        && !objects.iter().any(|o| named_away(&o.name) || named_away(&o.user_type))
        && plain * 2 >= objects.len())
    .then(|| {
        format!(
            "no rule marks it, and its {} objects are plain rectangles or polygons ({plain} with neither name nor class), which games build collision boxes from (--layer NAME=objects leaves them out)",
            objects.len()
        )
    })
}

impl<'m> Importer<'m> {
    /// The entries with the roles their names gave corrected where the map says otherwise
    /// (see the module's comment). Roles from flags, properties and groups are kept.
    pub(super) fn evident_roles(&self, mut entries: Vec<Entry<'m>>) -> Vec<Entry<'m>> {
        // Object layers of plain boxes are collision when no layer is certainly one: marked by
        // the user or a property, or named with a word only collision layers use (a layer
        // named `Terrain` or `Ground` may be art).
        let any_named = entries.iter().any(|e| match &e.role {
            Some((LayerRole::Collision | LayerRole::Solid | LayerRole::OneWay, why)) => {
                !why.starts_with("its name says") || says(&e.layer.name, STRONG_COLLISION_WORDS)
            }
            _ => false,
        });
        let mut evident = None;
        for e in entries.iter_mut().filter(|_| !any_named) {
            let LayerType::Objects(o) = e.layer.layer_type() else {
                continue;
            };
            if e.role.is_some() || is_spawn_name(&e.layer.name) {
                continue;
            }
            let objects: Vec<tiled::Object> = o.objects().collect();
            if let Some(why) = plain_boxes(&objects) {
                e.role = Some((LayerRole::Collision, why));
                evident.get_or_insert_with(|| e.path.clone());
            }
        }
        let named_objects = evident.or_else(|| {
            entries
                .iter()
                .find_map(|e| match (e.layer.layer_type(), &e.role) {
                    (LayerType::Objects(o), Some((r, _)))
                        if says(&e.layer.name, STRONG_COLLISION_WORDS)
                            && o.objects().any(|ob| Self::is_collision_shape(&ob, *r)) =>
                    {
                        Some(e.path.clone())
                    }
                    _ => None,
                })
        });
        for e in &mut entries {
            let LayerType::Tiles(t) = e.layer.layer_type() else {
                continue;
            };
            let Some((role, why)) = &e.role else {
                continue;
            };
            if !why.starts_with("its name says") {
                continue;
            }
            let strong = says(&e.layer.name, STRONG_COLLISION_WORDS);
            let new = match (role, marked(&t)) {
                (LayerRole::Decoration, Some(mark)) if says(&e.layer.name, ART_WORDS) => Some((
                    LayerRole::Collision,
                    format!("{why}, but its tiles carry {mark}, a collision mark, which wins over the name (--layer NAME=decoration leaves it out)"),
                )),
                (LayerRole::Collision, None) if !strong => named_objects.as_ref().map(|o| {
                    (
                        LayerRole::Decoration,
                        format!("{why}, but object layer {o:?}, named for collision or made of plain boxes, holds the collision shapes, so this layer is their art (--layer NAME=collision reads it too)"),
                    )
                }),
                _ => None,
            };
            if new.is_some() {
                e.role = new;
            }
        }
        self.separate_platforms(&mut entries);
        Self::unmarked_collide(&mut entries);
        entries
    }

    /// When the map marks some tile layer `nocollide`, the tile layers it leaves unmarked and
    /// that no other property or the user decides are collision, whatever their names say: the
    /// author marked the ones that do not collide (HaxeFlixel's Tiled demo collides with its
    /// `Foreground`).
    fn unmarked_collide(entries: &mut [Entry<'m>]) {
        let is_tiles = |e: &Entry| matches!(e.layer.layer_type(), LayerType::Tiles(_));
        let Some(marked) = entries
            .iter()
            .find(|e| {
                is_tiles(e)
                    && matches!(&e.role, Some((LayerRole::Decoration, why)) if why.starts_with("its property"))
                    && e.layer.properties.iter().any(|(k, v)| super::names::is_no_collide(k, v))
            })
            .map(|e| e.path.clone())
        else {
            return;
        };
        for e in entries.iter_mut().filter(|e| is_tiles(e)) {
            let by_name = e
                .role
                .as_ref()
                .is_none_or(|(_, why)| why.starts_with("its name says"));
            if by_name {
                e.role = Some((
                    LayerRole::Collision,
                    format!("the map marks tile layer {marked:?} nocollide and not this one, so this one collides (--layer NAME=decoration leaves it out)"),
                ));
            }
        }
    }

    /// A tile layer named just `platform` or `platforms` beside a tile layer named only for
    /// collision (`collision`, `solid`, …) is one-way: a game that keeps its platforms apart from
    /// its collision layer does so because they differ, and the difference platformers make is
    /// that a platform is jumped through from below. Beside a `Ground` or `Walls` layer, or
    /// alone, `platforms` stays solid, as most games mean it.
    fn separate_platforms(&self, entries: &mut [Entry<'m>]) {
        let is_tiles = |e: &Entry| matches!(e.layer.layer_type(), LayerType::Tiles(_));
        let Some(walls) = entries
            .iter()
            .find(|e| {
                is_tiles(e)
                    && matches!(e.role, Some((LayerRole::Collision | LayerRole::Solid, _)))
                    && says(&e.layer.name, STRONG_COLLISION_WORDS)
            })
            .map(|e| e.layer.name.clone())
        else {
            return;
        };
        for e in entries.iter_mut().filter(|e| is_tiles(e)) {
            let n = crate::level::import::normalize(&e.layer.name);
            let by_name = matches!(&e.role, Some((LayerRole::Collision, why)) if why.starts_with("its name says"));
            if by_name && (n == "platform" || n == "platforms") {
                e.role = Some((
                    LayerRole::OneWay,
                    format!("its name says \"{n}\", and tile layer {walls:?} holds the walls: platforms kept apart from the collision layer are one-way (--layer NAME=collision reads them solid)"),
                ));
            }
        }
    }
}

//! Where the map itself overrules a layer's name: a tile layer named like art where the player
//! is (`Foreground`, `Details`; not `Background`, `Water` or `Coins`) whose tiles carry a
//! collision mark (`collide = true`) is collision, as the game that marks its tiles reads them; a tile layer named like ground (`Ground`, `World`) beside an object layer
//! named for collision that holds the collision shapes is that layer's art, not a second
//! collision source. The user's `--layer` and side file still decide over both.

use tiled::{LayerType, PropertyValue, TileLayer};

use super::layers::Entry;
use super::tiles::is_bool_mark;
use super::Importer;
use crate::level::import::names::{says, ART_WORDS, STRONG_COLLISION_WORDS};
use crate::level::import::LayerRole;

/// The first collision mark (a solid or one-way bool property set true, `key = true`) on a tile
/// the layer draws, if any.
fn marked(t: &TileLayer) -> Option<String> {
    let mark = |lt: tiled::LayerTile| -> Option<String> {
        let tile = lt.get_tile()?;
        tile.properties.iter().find_map(|(k, v)| {
            (is_bool_mark(k, v) && *v == PropertyValue::BoolValue(true))
                .then(|| format!("{k} = true"))
        })
    };
    match t {
        TileLayer::Finite(f) => (0..f.height() as i32)
            .flat_map(|y| (0..f.width() as i32).map(move |x| (x, y)))
            .find_map(|(x, y)| f.get_tile(x, y).and_then(mark)),
        TileLayer::Infinite(inf) => inf.chunks().find_map(|(_, chunk)| {
            let w = tiled::ChunkData::WIDTH as i32;
            let h = tiled::ChunkData::HEIGHT as i32;
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .find_map(|(x, y)| chunk.get_tile(x, y).and_then(mark))
        }),
    }
}

impl<'m> Importer<'m> {
    /// The entries with the roles their names gave corrected where the map says otherwise
    /// (see the module's comment). Roles from flags, properties and groups are kept.
    pub(super) fn evident_roles(&self, mut entries: Vec<Entry<'m>>) -> Vec<Entry<'m>> {
        let named_objects = entries
            .iter()
            .find_map(|e| match (e.layer.layer_type(), &e.role) {
                (LayerType::Objects(o), Some((r, _)))
                    if says(&e.layer.name, STRONG_COLLISION_WORDS)
                        && o.objects().any(|ob| Self::is_collision_shape(&ob, *r)) =>
                {
                    Some(e.path.clone())
                }
                _ => None,
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
                        format!("{why}, but object layer {o:?}, named for collision, holds the collision shapes, so this layer is their art (--layer NAME=collision reads it too)"),
                    )
                }),
                _ => None,
            };
            if new.is_some() {
                e.role = new;
            }
        }
        entries
    }
}

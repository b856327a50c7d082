//! Which layer is what, and the tile layers' cells. A layer's role comes from, in order: the
//! command line (`--layer NAME=ROLE`), the layer's own property (`collision`: a bool, or a role
//! name; a bool `one_way`), its name (see [`crate::level::import::names::role_from_name`]), its group's
//! role, and last the default for tile layers no rule marks: collision, unless an object layer
//! holds collision shapes or another tile layer is named for collision (then decoration), or
//! as the map property `tile_layers` or `--tile-layers` say.

use crate::level::import::given;
use std::collections::{BTreeMap, HashMap};

use glam::Vec2;
use tiled::{LayerType, PropertyValue, TileLayer};

use super::objects::ObjectLayer;
use super::tiles::{apply_flips, is_bool_mark, tile_kind, SOLID_BOOLS};
use super::{kind_of, names, Importer, TiledError};
use crate::level::import::names::{is_spawn_name, role_from_name};
use crate::level::import::{LayerReport, LayerRole};
use crate::level::Tile;

/// A Tiled cell (column, row; y down).
type Cell = (i64, i64);

/// One layer of the map, flattened out of its groups.
pub(super) struct Entry<'m> {
    pub(super) layer: tiled::Layer<'m>,
    /// `group/child` path of names.
    pub(super) path: String,
    /// The role a flag, property, name or group gives it, and why.
    pub(super) role: Option<(LayerRole, String)>,
    /// Offset in pixels, its groups' included.
    offset: Vec2,
}

/// The smallest and largest chunk corners (Tiled cells, y down) of an infinite map's tile
/// layers, groups included.
pub(super) fn chunk_bounds<'m>(
    layers: impl Iterator<Item = tiled::Layer<'m>>,
) -> (Option<Cell>, Option<Cell>) {
    let mut lo: Option<(i64, i64)> = None;
    let mut hi: Option<(i64, i64)> = None;
    for l in layers {
        match l.layer_type() {
            LayerType::Tiles(TileLayer::Infinite(t)) => {
                for ((cx, cy), _) in t.chunks() {
                    let (w, h) = (
                        tiled::ChunkData::WIDTH as i64,
                        tiled::ChunkData::HEIGHT as i64,
                    );
                    let (x, y) = (cx as i64 * w, cy as i64 * h);
                    lo = Some(lo.map_or((x, y), |(a, b)| (a.min(x), b.min(y))));
                    hi = Some(hi.map_or((x + w, y + h), |(a, b)| (a.max(x + w), b.max(y + h))));
                }
            }
            LayerType::Group(g) => {
                let (l2, h2) = chunk_bounds(g.layers());
                if let Some((x, y)) = l2 {
                    lo = Some(lo.map_or((x, y), |(a, b)| (a.min(x), b.min(y))));
                }
                if let Some((x, y)) = h2 {
                    hi = Some(hi.map_or((x, y), |(a, b)| (a.max(x), b.max(y))));
                }
            }
            _ => {}
        }
    }
    (lo, hi)
}

/// A Tiled cell as Tiled's `i32` coordinates (a level's cells lie within them).
fn tiled_i32((x, y): Cell) -> (i32, i32) {
    let c = |v: i64| v.clamp(i32::MIN.into(), i32::MAX.into()) as i32;
    (c(x), c(y))
}

fn kind_name(l: &tiled::Layer) -> &'static str {
    match l.layer_type() {
        LayerType::Tiles(_) => "tiles",
        LayerType::Objects(_) => "objects",
        LayerType::Group(_) => "group",
        LayerType::Image(_) => "image",
    }
}

/// Whether a tile layer draws no tile at all.
fn no_tiles(t: &TileLayer) -> bool {
    match t {
        TileLayer::Finite(f) => (0..f.height() as i32)
            .all(|y| (0..f.width() as i32).all(|x| f.get_tile(x, y).is_none())),
        TileLayer::Infinite(inf) => inf.chunks().all(|(_, chunk)| {
            let (w, h) = (
                tiled::ChunkData::WIDTH as i32,
                tiled::ChunkData::HEIGHT as i32,
            );
            (0..h).all(|y| (0..w).all(|x| chunk.get_tile(x, y).is_none()))
        }),
    }
}

impl<'m> Importer<'m> {
    /// Every layer, groups flattened, each with the role a flag, property, name or group gives.
    pub(super) fn collect_layers(&mut self) -> Result<Vec<Entry<'m>>, TiledError> {
        let mut out = Vec::new();
        for l in self.map.layers() {
            self.collect(l, "", None, Vec2::ZERO, &mut out)?;
        }
        Ok(out)
    }

    fn collect(
        &mut self,
        layer: tiled::Layer<'m>,
        parent: &str,
        inherited: Option<(LayerRole, String)>,
        offset: Vec2,
        out: &mut Vec<Entry<'m>>,
    ) -> Result<(), TiledError> {
        let path = if parent.is_empty() {
            layer.name.clone()
        } else {
            format!("{parent}/{}", layer.name)
        };
        let file = self.file.clone();
        let layer_err = |message: String| TiledError::Layer {
            file: file.clone(),
            layer: path.clone(),
            message,
        };
        let mut from_prop = None;
        let props: BTreeMap<_, _> = layer.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::COLLISION, PropertyValue::BoolValue(b)) => {
                    let r = if *b {
                        LayerRole::Collision
                    } else {
                        LayerRole::Decoration
                    };
                    from_prop = Some((r, format!("its property collision = {b}")));
                }
                (names::COLLISION, PropertyValue::StringValue(s)) => match LayerRole::parse(s) {
                    Some(r) => from_prop = Some((r, format!("its property collision = {s:?}"))),
                    None => return Err(layer_err(format!("property \"collision\" = {s:?}; expected a bool, or one of collision, solid, one_way, ladder, objects, decoration"))),
                },
                (names::COLLISION, other) => {
                    return Err(layer_err(format!(
                        "property \"collision\" is {}; expected a bool (false leaves the layer out) or a role (solid, one_way, ladder, decoration)",
                        kind_of(other)
                    )))
                }
                (k, PropertyValue::BoolValue(true)) if is_bool_mark(k, value) => {
                    let r = if super::tiles::ONE_WAY_BOOLS.contains(&k.to_lowercase().as_str()) {
                        LayerRole::OneWay
                    } else if super::tiles::LADDER_BOOLS.contains(&k.to_lowercase().as_str()) {
                        LayerRole::Ladder
                    } else {
                        LayerRole::Collision
                    };
                    from_prop = Some((r, format!("its property {k} = true")));
                }
                // HaxeFlixel's Tiled demo marks the tile layers that do not collide.
                (k, v) if names::is_no_collide(k, v) => {
                    from_prop = Some((LayerRole::Decoration, format!("its property {k} = true")));
                }
                (k, PropertyValue::BoolValue(false)) if is_bool_mark(k, value) => {
                    from_prop = Some((LayerRole::Decoration, format!("its property {k} = false")));
                }
                _ => self.warn(
                    format!("layer {path:?}"),
                    format!("property {key:?} is not one platbench reads (it reads \"collision\", the bools one_way, ladder, collidable, solid and nocollide on layers); ignored"),
                ),
            }
        }
        let role = if let Some(r) = self.opts.role_of(&layer.name) {
            Some((r, given(&layer.name, r)))
        } else if let Some(r) = from_prop {
            Some(r)
        } else if matches!(inherited, Some((LayerRole::Decoration, _))) {
            inherited.clone()
        } else if let Some((r, w)) = role_from_name(&layer.name) {
            Some((r, format!("its name says {w:?}")))
        } else {
            inherited
                .clone()
                .map(|(r, why)| (r, format!("its group's role ({why})")))
        };
        let offset = offset + Vec2::new(layer.offset_x, layer.offset_y);
        if let LayerType::Group(g) = layer.layer_type() {
            self.reports.push(LayerReport {
                name: path.clone(),
                kind: "group".into(),
                role: role.as_ref().map_or(LayerRole::Objects, |r| r.0),
                why: role
                    .as_ref()
                    .map_or("its layers decide for themselves".into(), |r| {
                        format!("{}; its layers inherit it unless they say otherwise", r.1)
                    }),
                empty: g.layers().next().is_none(),
            });
            for child in g.layers() {
                self.collect(child, &path, role.clone(), offset, out)?;
            }
            return Ok(());
        }
        out.push(Entry {
            layer,
            path,
            role,
            offset,
        });
        Ok(())
    }

    /// Whether an object is a collision shape in a layer of `role` (see
    /// [`Importer::is_collision_object`]).
    pub(super) fn is_collision_shape(o: &tiled::Object, role: LayerRole) -> bool {
        role.collides() && Self::is_collision_object(o)
    }

    /// Gives each layer its role, reads the tile layers, and keeps the object layers for later.
    pub(super) fn read_layers(
        &mut self,
        entries: Vec<Entry<'m>>,
        tile_default: Option<(LayerRole, String)>,
    ) -> Result<(), TiledError> {
        let entries = self.evident_roles(entries);
        // Object layers that hold collision shapes, and tile layers a rule names: these make
        // the unmarked tile layers decoration.
        let object_collision = entries
            .iter()
            .find_map(|e| match (e.layer.layer_type(), &e.role) {
                (LayerType::Objects(o), Some((r, _)))
                    if o.objects().any(|ob| Self::is_collision_shape(&ob, *r)) =>
                {
                    Some(e.path.clone())
                }
                _ => None,
            });
        let named_tiles = entries
            .iter()
            .find_map(|e| match (e.layer.layer_type(), &e.role) {
                (
                    LayerType::Tiles(_),
                    Some((
                        LayerRole::Collision
                        | LayerRole::Solid
                        | LayerRole::OneWay
                        | LayerRole::Ladder,
                        _,
                    )),
                ) => Some(e.path.clone()),
                _ => None,
            });
        let default = match (tile_default, object_collision, named_tiles) {
            (Some(d), _, _) => d,
            (None, Some(o), _) => (
                LayerRole::Decoration,
                format!("no rule marks it, and object layer {o:?} holds the collision shapes (tile layers then default to decoration; --layer NAME=collision or the property collision = true reads it)"),
            ),
            (None, None, Some(t)) => (
                LayerRole::Decoration,
                format!("no rule marks it, and tile layer {t:?} is named for collision (--layer NAME=collision or the property collision = true reads it too)"),
            ),
            (None, None, None) => (
                LayerRole::Collision,
                "no layer is named for collision, so every tile layer is (a name like \"background\" or the property collision = false leaves one out)".into(),
            ),
        };
        for e in entries {
            let kind = kind_name(&e.layer);
            match e.layer.layer_type() {
                LayerType::Tiles(t) => {
                    let (role, why) = e.role.clone().unwrap_or_else(|| default.clone());
                    self.reports.push(LayerReport {
                        name: e.path.clone(),
                        kind: kind.into(),
                        role,
                        why,
                        empty: no_tiles(&t),
                    });
                    if role == LayerRole::Decoration || role == LayerRole::Objects {
                        continue;
                    }
                    self.tile_layer(&e.path, &t, role, e.offset)?;
                }
                LayerType::Objects(o) => {
                    let spawn_layer = is_spawn_name(&e.layer.name);
                    let (role, why) = match (&e.role, spawn_layer) {
                        (Some(r), _) => r.clone(),
                        (None, true) => (
                            LayerRole::Objects,
                            "its name says spawn: each of its points, rectangles and tile objects is a spawn".into(),
                        ),
                        (None, false) => (
                            LayerRole::Objects,
                            "no rule marks it: spawns and moving platforms by their class or name, other shapes ignored".into(),
                        ),
                    };
                    self.reports.push(LayerReport {
                        name: e.path.clone(),
                        kind: kind.into(),
                        role,
                        why,
                        empty: o.objects().next().is_none(),
                    });
                    self.objects.push(ObjectLayer {
                        name: e.path.clone(),
                        role,
                        spawn_layer: spawn_layer && role == LayerRole::Objects,
                        offset: e.offset,
                        excluded: role == LayerRole::Decoration
                            && e.role
                                .as_ref()
                                .is_some_and(|r| !r.1.starts_with("its name")),
                        objects: o.objects().collect(),
                    });
                }
                LayerType::Image(_) => {
                    self.reports.push(LayerReport {
                        name: e.path.clone(),
                        kind: kind.into(),
                        role: LayerRole::Decoration,
                        why: "an image layer holds no collision".into(),
                        empty: false,
                    });
                }
                LayerType::Group(_) => {}
            }
        }
        Ok(())
    }

    /// One tile layer's cells into the level: each tile by its meaning, or the one the role
    /// forces; the layer's offset moves its cells by whole tiles.
    fn tile_layer(
        &mut self,
        lname: &str,
        t: &TileLayer<'m>,
        role: LayerRole,
        offset: Vec2,
    ) -> Result<(), TiledError> {
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let (dx, dy) = ((offset.x / tw).round(), (offset.y / th).round());
        if offset != Vec2::ZERO {
            let exact = (offset.x - dx * tw).abs() < 0.5 && (offset.y - dy * th).abs() < 0.5;
            self.warn(
                format!("layer {lname:?}"),
                if exact {
                    format!("offset by ({}, {}) pixels: its cells move by ({dx}, {dy}) tiles", offset.x, offset.y)
                } else {
                    format!("offset by ({}, {}) pixels, not whole tiles: its cells move by the nearest whole tiles, ({dx}, {dy})", offset.x, offset.y)
                },
            );
        }
        let (dx, dy) = (dx as i64, dy as i64);
        let g = self.grid;
        let file = self.file.clone();
        if let TileLayer::Finite(f) = t {
            if !self.map.infinite()
                && (f.width() != self.map.width || f.height() != self.map.height)
            {
                return Err(TiledError::Layer {
                    file,
                    layer: lname.into(),
                    message: format!(
                        "the layer is {} x {} tiles but the map is {} x {}; expected the map's size",
                        f.width(),
                        f.height(),
                        self.map.width,
                        self.map.height
                    ),
                });
            }
        }
        let mut dropped = 0u64;
        // Each tile's source, interned once for the layer.
        let mut sources: HashMap<(usize, u32), u32> = HashMap::new();
        // Every cell of the level, read from the layer's cell it shows (the tiled crate indexes
        // a finite layer's cells without a bounds check; a layer whose data holds fewer cells
        // than width x height was refused by `scan::scan_map` before loading).
        for y in 0..g.h as i64 {
            for x in 0..g.w as i64 {
                let (sx, sy) = (x + g.x0 as i64 - dx, y + g.y0 as i64 - dy);
                let lt = match t {
                    TileLayer::Finite(f) => {
                        if sx < 0 || sy < 0 || sx >= f.width() as i64 || sy >= f.height() as i64 {
                            continue;
                        }
                        f.get_tile(sx as i32, sy as i32)
                    }
                    TileLayer::Infinite(inf) => {
                        if sx < i32::MIN as i64
                            || sy < i32::MIN as i64
                            || sx > i32::MAX as i64
                            || sy > i32::MAX as i64
                        {
                            continue;
                        }
                        inf.get_tile(sx as i32, sy as i32)
                    }
                };
                let Some(lt) = lt else { continue };
                let (i, j) = (x as u32, (g.h as i64 - 1 - y) as u32);
                let tile = match role.forced_tile() {
                    Some(f) => f,
                    None => {
                        let key = (lt.tileset_index(), lt.id(), lt.flip_h, lt.flip_v, lt.flip_d);
                        match self.kinds.get(&key) {
                            Some(t) => *t,
                            None => {
                                self.check_gid(lname, &lt, (sx, sy))?;
                                let t = self.classify(&lt, (sx, sy))?;
                                self.kinds.insert(key, t);
                                t
                            }
                        }
                    }
                };
                let k = j as usize * g.w as usize + i as usize;
                let key = (lt.tileset_index(), lt.id());
                let this = match sources.get(&key) {
                    Some(&id) => id,
                    None => {
                        let what = format!("tileset {:?} tile {}", lt.get_tileset().name, lt.id());
                        let id = self.cells.source(what, lname);
                        sources.insert(key, id);
                        id
                    }
                };
                if let Err(e) = self.cells.set(k, tile, this) {
                    return Err(TiledError::Tile {
                        file: self.file.clone(),
                        tileset: lt.get_tileset().name.clone(),
                        tile: lt.id(),
                        cell: Some(tiled_i32(g.tiled_cell(i.into(), j.into()))),
                        message: e.to_string(),
                    });
                }
            }
        }
        // Cells an offset moved out of the level.
        if dx != 0 || dy != 0 {
            if let TileLayer::Finite(f) = t {
                for sy in 0..f.height() as i64 {
                    for sx in 0..f.width() as i64 {
                        let (x, y) = (sx + dx - g.x0 as i64, sy + dy - g.y0 as i64);
                        let outside = x < 0 || y < 0 || x >= g.w as i64 || y >= g.h as i64;
                        if outside && f.get_tile(sx as i32, sy as i32).is_some() {
                            dropped += 1;
                        }
                    }
                }
            }
        }
        if dropped > 0 {
            self.warn(
                format!("layer {lname:?}"),
                format!("its offset moves {dropped} drawn cell(s) outside the map; left out"),
            );
        }
        Ok(())
    }

    /// What a tile of the map means, flips included; `cell` is the Tiled cell it is drawn at.
    fn classify(
        &mut self,
        lt: &tiled::LayerTile<'m>,
        cell: (i64, i64),
    ) -> Result<Tile, TiledError> {
        let ts = lt.get_tileset();
        let id = lt.id();
        let file = self.file.clone();
        let err = |message: String| TiledError::Tile {
            file: file.clone(),
            tileset: ts.name.clone(),
            tile: id,
            cell: Some(tiled_i32(cell)),
            message,
        };
        let data = ts.get_tile(id);
        if data.is_none() && (ts.image.is_none() || id >= ts.tilecount) {
            return Err(err(format!(
                "the map uses tile id {id} but the tileset has no such tile ({} tiles)",
                ts.tilecount
            )));
        }
        // A tile's own size: its image's in an image collection, else the tileset's. Art larger
        // (or smaller) than the map's cells is one cell, anchored at its bottom-left as Tiled
        // draws it.
        let (tw, th) = match data.as_ref().and_then(|d| d.image.as_ref()) {
            Some(img) if ts.image.is_none() => (img.width.max(1) as f32, img.height.max(1) as f32),
            _ => (ts.tile_width.max(1) as f32, ts.tile_height.max(1) as f32),
        };
        let ti = lt.tileset_index();
        if (tw as u32, th as u32) != (self.map.tile_width, self.map.tile_height)
            && !self.noted_tilesets.contains(&ti)
        {
            self.noted_tilesets.push(ti);
            self.warn(
                format!("tileset {:?}", ts.name),
                format!(
                    "its tiles ({tw} x {th} pixels for tile {id}) are not the map's {} x {}: each is read as the one cell it stands on (its collision shape in its own pixels)",
                    self.map.tile_width, self.map.tile_height
                ),
            );
        }
        // A tileset that marks its solid tiles with a bool property leaves unmarked tiles empty
        // (a one-way or ladder bool marks those tiles only: the unmarked ones stay solid).
        let marks = ts.tiles().any(|(_, t)| {
            t.properties.iter().any(|(k, v)| {
                SOLID_BOOLS.contains(&k.to_lowercase().as_str())
                    && matches!(v, PropertyValue::BoolValue(true))
            })
        });
        // A tile property the side file (or a library caller) gives a kind decides first.
        let given = data.as_ref().and_then(|d| {
            self.opts
                .tile_properties
                .iter()
                .rev()
                .find_map(|(name, t)| {
                    d.properties
                        .iter()
                        .any(|(k, v)| {
                            k.eq_ignore_ascii_case(name)
                                && !matches!(v, PropertyValue::BoolValue(false))
                        })
                        .then_some(*t)
                })
        });
        let (base, notes) = match &data {
            _ if given.is_some() => (given, Vec::new()),
            None => (None, Vec::new()),
            Some(d) => tile_kind(&d.properties, &d.user_type, d.collision.as_ref(), tw, th)
                .map_err(|e| err(e.to_string()))?,
        };
        let base = base.unwrap_or(if marks { Tile::Empty } else { Tile::Solid });
        let subject = format!("tileset {:?} tile {id}", ts.name);
        if !self.warned.contains(&(ti, id)) {
            self.warned.push((ti, id));
            for n in notes {
                self.warn(subject.clone(), n);
            }
        }
        apply_flips(base, lt.flip_h, lt.flip_v, lt.flip_d).map_err(|e| err(e.to_string()))
    }
}

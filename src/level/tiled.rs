//! Import of maps made with the Tiled editor (`.tmx`, tilesets inline or in `.tsx` files):
//! tile layers become the level's tiles, tile properties or collision shapes say what a tile
//! is, and object layers give moving platforms and spawn points. The README's "Tiled maps"
//! section is the user's side of the mapping; this module is its one implementation.
//!
//! Nothing here panics on a map's content: every construct platbench cannot represent is a
//! [`TiledError`] or a [`TiledWarning`] that names the tile (tileset and local id, and a map
//! cell where one is involved) or the object (id and name).

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::path::Path;

use glam::Vec2;
use tiled::{LayerType, ObjectShape, PropertyValue, TileLayer};

mod scan;

use super::probes::{probe_scenarios, ProbeConfig, SpawnPoint};
use super::{character_box, parse_scenarios, Level, LevelError, Platform, PlatformMotion};
use super::{valid_name, Slope, Tile, DEFAULT_CHARACTER_SIZE};

/// How far a collision-shape point may be from the tile edge or corner it stands for, in
/// pixels: the editor snaps to whole pixels, so a hand-drawn ramp is exact to about one.
pub const SHAPE_TOLERANCE_PX: f32 = 1.0;

/// The map property, tile properties and layer property names platbench reads.
mod names {
    /// Tile property: what the tile is (`solid`, `one_way`, `ladder`, `empty`).
    pub const COLLISION: &str = "collision";
    /// Tile property: height of a line slope at the tile's left edge, in tiles.
    pub const SLOPE_LEFT: &str = "slope_left";
    /// Tile property: height of a line slope at the tile's right edge, in tiles.
    pub const SLOPE_RIGHT: &str = "slope_right";
    /// Tile property: 16 comma-separated heights in sixteenths of a tile.
    pub const HEIGHTS: &str = "heights";
    /// Object class (or type) of a spawn point.
    pub const SPAWN: &str = "spawn";
    /// Object class (or type) of a moving platform (optional: a `path` property suffices).
    pub const PLATFORM: &str = "platform";
    /// Object property: the polyline a platform follows (an object reference).
    pub const PATH: &str = "path";
    /// Object property: a platform's speed along its path, in tiles/s.
    pub const SPEED: &str = "speed";
    /// Object property: whether a platform blocks from above only.
    pub const ONE_WAY: &str = "one_way";
    /// Map property: the level's name.
    pub const NAME: &str = "name";
    /// Map property: the level's description.
    pub const DESCRIPTION: &str = "description";
}

/// A Tiled map that platbench cannot run as it is, with what was found and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum TiledError {
    /// The file could not be read or is not a well-formed Tiled map (the `tiled` crate's error).
    #[error("{file}: cannot load the Tiled map: {message}")]
    Load {
        /// The map file.
        file: String,
        /// The loader's message.
        message: String,
    },
    /// A property of the whole map (orientation, size, infinite) that platbench cannot use.
    #[error("{file}: {message}")]
    Map {
        /// The map file.
        file: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A layer that cannot be imported (offset, size, an unexpected property value).
    #[error("{file}: layer {layer:?}: {message}")]
    Layer {
        /// The map file.
        file: String,
        /// The layer's name.
        layer: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A tile whose properties or collision shape platbench cannot represent.
    #[error("{file}: tileset {tileset:?} tile {tile}{}: {message}", cell_text(.cell))]
    Tile {
        /// The map file.
        file: String,
        /// The tileset's name.
        tileset: String,
        /// The tile's id, local to its tileset (as Tiled's tileset editor shows it).
        tile: u32,
        /// The map cell (i, j) where it is used, in platbench's coordinates (j = 0 is the bottom
        /// row), when one cell is involved.
        cell: Option<(u32, u32)>,
        /// What was found and what was expected.
        message: String,
    },
    /// An object (platform, spawn, path) that cannot be imported.
    #[error("{file}: object {id} {name:?}: {message}")]
    Object {
        /// The map file.
        file: String,
        /// The object's id (unique in the map, as Tiled shows it).
        id: u32,
        /// The object's name (may be empty).
        name: String,
        /// What was found and what was expected.
        message: String,
    },
    /// The map has neither spawn points nor a side file, so nothing can run on it.
    #[error("{file}: the map has no spawn points (objects of class \"spawn\") and no side file {side} with [[scenario]] entries, so nothing can run on it; add a point object of class \"spawn\" in an object layer in Tiled (where the character's feet start), or write {side} with [[scenario]] entries (README, \"Tiled maps\")")]
    NoScenarios {
        /// The map file.
        file: String,
        /// Where the side file was looked for.
        side: String,
    },
    /// The side file's scenarios are invalid (file, line and column inside).
    #[error(transparent)]
    SideFile(#[from] LevelError),
    /// The side file exists but cannot be read.
    #[error("{file}: cannot read the side file: {message}")]
    SideFileRead {
        /// The side file.
        file: String,
        /// The system's message.
        message: String,
    },
}

fn cell_text(cell: &Option<(u32, u32)>) -> String {
    match cell {
        Some((i, j)) => format!(" (at cell i = {i}, j = {j})"),
        None => String::new(),
    }
}

/// Something in a map that platbench does not use, said aloud rather than dropped in silence.
#[derive(Clone, Debug, PartialEq)]
pub struct TiledWarning {
    /// The map (or tileset) file.
    pub file: String,
    /// What it is about: `tileset "NAME" tile ID`, `object ID "NAME"`, `layer "NAME"` or `map`.
    pub subject: String,
    /// What was found and what platbench does with it.
    pub message: String,
}

impl fmt::Display for TiledWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}: {}", self.file, self.subject, self.message)
    }
}

/// A map imported without its scenarios: the level (geometry and platforms), its spawn points
/// and the warnings raised on the way.
#[derive(Clone, Debug)]
pub struct TiledImport {
    /// The level, with no scenarios yet.
    pub level: Level,
    /// The map's spawn points, in the order of the file.
    pub spawns: Vec<SpawnPoint>,
    /// Everything that was ignored, each naming its tile, object or layer.
    pub warnings: Vec<TiledWarning>,
}

/// Loads a Tiled map as a runnable level: its geometry, platforms and scenarios — those of the
/// side file `MAP.toml` next to it when there is one, else the standard probes at each spawn
/// point ([`super::probes`]). Returns the warnings too, for the caller to show.
pub fn load_tiled_map(path: &Path) -> Result<(Level, Vec<TiledWarning>), TiledError> {
    let TiledImport {
        mut level,
        spawns,
        mut warnings,
    } = import_tiled_map(path)?;
    let side = path.with_extension("toml");
    if side.is_file() {
        let text =
            crate::limits::read_text_capped(&side).map_err(|e| TiledError::SideFileRead {
                file: side.display().to_string(),
                message: e.to_string(),
            })?;
        level.scenarios = parse_scenarios(&text, &side.display().to_string(), &level)?;
        if level.scenarios.is_empty() {
            return Err(TiledError::NoScenarios {
                file: path.display().to_string(),
                side: side.display().to_string(),
            });
        }
        if !spawns.is_empty() {
            warnings.push(TiledWarning {
                file: path.display().to_string(),
                subject: "map".into(),
                message: format!(
                    "the side file {} replaces the probes at its {} spawn point(s)",
                    side.display(),
                    spawns.len()
                ),
            });
        }
        return Ok((level, warnings));
    }
    if spawns.is_empty() {
        return Err(TiledError::NoScenarios {
            file: path.display().to_string(),
            side: side.display().to_string(),
        });
    }
    let (scenarios, probe_warnings) = probe_scenarios(&level, &spawns, &ProbeConfig::default());
    level.scenarios = scenarios;
    let file = path.display().to_string();
    warnings.extend(
        probe_warnings
            .into_iter()
            .map(|(subject, message)| TiledWarning {
                file: file.clone(),
                subject,
                message,
            }),
    );
    Ok((level, warnings))
}

/// Reads a Tiled map's geometry, platforms and spawn points (no scenarios).
pub fn import_tiled_map(path: &Path) -> Result<TiledImport, TiledError> {
    let file = path.display().to_string();
    // Read once, within the input cap, and look at what the tiled crate would allocate or
    // index before it does.
    let text = crate::limits::read_text_capped(path).map_err(|e| TiledError::Load {
        file: file.clone(),
        message: e.to_string(),
    })?;
    scan::scan_map(&text).map_err(|e| TiledError::Map {
        file: format!("{file}:{}", e.line),
        message: e.message,
    })?;
    let map_path = path.to_path_buf();
    let bytes = text.into_bytes();
    // The map as read above; tilesets and templates through the same cap.
    let reader = move |p: &Path| -> std::io::Result<std::io::Cursor<Vec<u8>>> {
        if p == map_path {
            Ok(std::io::Cursor::new(bytes.clone()))
        } else {
            crate::limits::read_capped(p).map(std::io::Cursor::new)
        }
    };
    let map = tiled::Loader::with_reader(reader)
        .load_tmx_map(path)
        .map_err(|e| TiledError::Load {
            file: file.clone(),
            message: e.to_string(),
        })?;
    let mut im = Importer {
        file: file.clone(),
        map: &map,
        tiles: Vec::new(),
        kinds: HashMap::new(),
        warned: Vec::new(),
        warnings: Vec::new(),
        objects: Vec::new(),
    };
    // The size is checked before the cells are allocated.
    im.check_map()?;
    im.tiles = vec![None; (map.width as usize) * (map.height as usize)];
    let (name, description) = im.map_properties(path)?;
    for layer in map.layers() {
        im.layer(layer, true)?;
    }
    let tiles = im
        .tiles
        .iter()
        .map(|t| t.as_ref().map_or(Tile::Empty, |(t, _)| *t))
        .collect();
    let mut level = Level::from_tiles(&name, map.width, map.height, tiles);
    level.description = description;
    level.source = file.clone();
    let spawns = im.objects(&mut level)?;
    level.features.moving_platforms = !level.platforms.is_empty();
    Ok(TiledImport {
        level,
        spawns,
        warnings: im.warnings,
    })
}

/// A tile as the map uses it: tileset index, local id and flips.
type TileKey = (usize, u32, bool, bool, bool);

/// The state of one import.
struct Importer<'m> {
    file: String,
    map: &'m tiled::Map,
    /// The level's cells so far (row 0 at the bottom), with the tile that set each.
    tiles: Vec<Option<(Tile, String)>>,
    /// Each used tile's meaning, computed once.
    kinds: HashMap<TileKey, Tile>,
    /// Tiles already warned about, so a tile used many times warns once.
    warned: Vec<(usize, u32)>,
    warnings: Vec<TiledWarning>,
    /// Object layers to read once the tiles are known: (layer name, objects).
    objects: Vec<(String, Vec<tiled::Object<'m>>)>,
}

impl<'m> Importer<'m> {
    fn map_err(&self, message: String) -> TiledError {
        TiledError::Map {
            file: self.file.clone(),
            message,
        }
    }

    fn warn(&mut self, subject: String, message: String) {
        self.warnings.push(TiledWarning {
            file: self.file.clone(),
            subject,
            message,
        });
    }

    /// Orientation, infinite maps, tile size.
    fn check_map(&self) -> Result<(), TiledError> {
        let m = self.map;
        if m.orientation != tiled::Orientation::Orthogonal {
            return Err(self.map_err(format!(
                "the map's orientation is {}; platbench imports orthogonal maps only",
                m.orientation
            )));
        }
        if m.infinite() {
            return Err(self.map_err(
                "the map is infinite; platbench imports fixed-size maps only (untick \"Infinite\" in the map properties)".into(),
            ));
        }
        if m.tile_width == 0 || m.tile_height == 0 || m.width == 0 || m.height == 0 {
            return Err(self.map_err(format!(
                "the map is {} x {} tiles of {} x {} pixels; expected a positive size",
                m.width, m.height, m.tile_width, m.tile_height
            )));
        }
        if (m.width as u64) * (m.height as u64) > crate::limits::MAX_TILES {
            return Err(self.map_err(format!(
                "the map is {} x {} tiles; expected at most {} tiles",
                m.width,
                m.height,
                crate::limits::MAX_TILES
            )));
        }
        Ok(())
    }

    /// The level's name (map property `name`, else the file stem made safe) and description.
    fn map_properties(&mut self, path: &Path) -> Result<(String, String), TiledError> {
        let mut name = None;
        let mut description = String::new();
        let props: BTreeMap<_, _> = self.map.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::NAME, PropertyValue::StringValue(s)) => name = Some(s.clone()),
                (names::DESCRIPTION, PropertyValue::StringValue(s)) => description = s.clone(),
                (names::NAME | names::DESCRIPTION, other) => {
                    return Err(self.map_err(format!(
                        "map property {key:?} is {}; expected a string",
                        kind_of(other)
                    )))
                }
                _ => self.warn(
                    "map".into(),
                    format!("property {key:?} is not one platbench reads (it reads \"name\" and \"description\"); ignored"),
                ),
            }
        }
        let name = match name {
            Some(n) => {
                if !valid_name(&n) {
                    return Err(self.map_err(format!("map property name = {n:?}: expected non-empty ASCII letters, digits, '_' or '-' (it names output files)")));
                }
                n
            }
            None => {
                let stem = path
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                let safe: String = stem
                    .chars()
                    .map(|c| {
                        if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                            c
                        } else {
                            '_'
                        }
                    })
                    .collect();
                if safe.is_empty() {
                    "map".to_string()
                } else {
                    safe
                }
            }
        };
        Ok((name, description))
    }

    /// One layer: tiles go into the grid, objects are kept for later, groups recurse. `include`
    /// is false inside a group whose `collision` property is false.
    fn layer(&mut self, layer: tiled::Layer<'m>, include: bool) -> Result<(), TiledError> {
        let lname = layer.name.clone();
        let file = self.file.clone();
        let layer_err = |message: String| TiledError::Layer {
            file: file.clone(),
            layer: lname.clone(),
            message,
        };
        let mut collides = include;
        let props: BTreeMap<_, _> = layer.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::COLLISION, PropertyValue::BoolValue(b)) => collides &= *b,
                (names::COLLISION, other) => {
                    return Err(layer_err(format!(
                        "property \"collision\" is {}; expected a bool (false leaves the layer out)",
                        kind_of(other)
                    )))
                }
                _ => self.warn(
                    format!("layer {lname:?}"),
                    format!("property {key:?} is not one platbench reads (it reads \"collision\" on layers); ignored"),
                ),
            }
        }
        if !collides {
            return Ok(());
        }
        if layer.offset_x != 0.0 || layer.offset_y != 0.0 {
            return Err(layer_err(format!(
                "the layer is offset by ({}, {}) pixels; expected no offset (platbench places tiles on the map's grid)",
                layer.offset_x, layer.offset_y
            )));
        }
        match layer.layer_type() {
            LayerType::Tiles(TileLayer::Finite(t)) => {
                if t.width() != self.map.width || t.height() != self.map.height {
                    return Err(layer_err(format!(
                        "the layer is {} x {} tiles but the map is {} x {}; expected the map's size",
                        t.width(),
                        t.height(),
                        self.map.width,
                        self.map.height
                    )));
                }
                self.tile_layer(&lname, &t)
            }
            LayerType::Tiles(TileLayer::Infinite(_)) => Err(layer_err(
                "the layer is infinite; platbench imports fixed-size maps only".into(),
            )),
            LayerType::Objects(o) => {
                self.objects.push((lname, o.objects().collect()));
                Ok(())
            }
            LayerType::Group(g) => {
                for child in g.layers() {
                    self.layer(child, collides)?;
                }
                Ok(())
            }
            LayerType::Image(_) => {
                self.warn(
                    format!("layer {lname:?}"),
                    "an image layer holds no collision; ignored".into(),
                );
                Ok(())
            }
        }
    }

    fn tile_layer(
        &mut self,
        lname: &str,
        t: &tiled::FiniteTileLayer<'m>,
    ) -> Result<(), TiledError> {
        let (w, h) = (self.map.width, self.map.height);
        // The tiled crate indexes its cell list without a bounds check; a layer whose data holds
        // fewer cells than width x height was refused by `scan::scan_map` before loading.
        for y in 0..h {
            for x in 0..w {
                let Some(lt) = t.get_tile(x as i32, y as i32) else {
                    continue;
                };
                let (i, j) = (x, h - 1 - y);
                let key = (lt.tileset_index(), lt.id(), lt.flip_h, lt.flip_v, lt.flip_d);
                let tile = match self.kinds.get(&key) {
                    Some(t) => *t,
                    None => {
                        let t = self.classify(&lt, (i, j))?;
                        self.kinds.insert(key, t);
                        t
                    }
                };
                let k = j as usize * w as usize + i as usize;
                let this = format!(
                    "tileset {:?} tile {} in layer {lname:?}",
                    lt.get_tileset().name,
                    lt.id()
                );
                match &self.tiles[k] {
                    None => self.tiles[k] = Some((tile, this)),
                    Some((prev, _)) if *prev == tile || tile == Tile::Empty => {}
                    Some((Tile::Empty, _)) => self.tiles[k] = Some((tile, this)),
                    Some((prev, by)) => {
                        return Err(TiledError::Tile {
                            file: self.file.clone(),
                            tileset: lt.get_tileset().name.clone(),
                            tile: lt.id(),
                            cell: Some((i, j)),
                            message: format!(
                                "it is {} but the cell already holds {} from {by}; expected one kind of tile per cell across the collision layers",
                                tile_name(&tile),
                                tile_name(prev)
                            ),
                        })
                    }
                }
            }
        }
        Ok(())
    }

    /// What a tile of the map means, flips included.
    fn classify(
        &mut self,
        lt: &tiled::LayerTile<'m>,
        cell: (u32, u32),
    ) -> Result<Tile, TiledError> {
        let ts = lt.get_tileset();
        let id = lt.id();
        let file = self.file.clone();
        let err = |message: String| TiledError::Tile {
            file: file.clone(),
            tileset: ts.name.clone(),
            tile: id,
            cell: Some(cell),
            message,
        };
        if ts.tile_width != self.map.tile_width || ts.tile_height != self.map.tile_height {
            return Err(err(format!(
                "its tileset's tiles are {} x {} pixels but the map's are {} x {}; expected the map's tile size",
                ts.tile_width, ts.tile_height, self.map.tile_width, self.map.tile_height
            )));
        }
        let data = ts.get_tile(id);
        if data.is_none() && (ts.image.is_none() || id >= ts.tilecount) {
            return Err(err(format!(
                "the map uses tile id {id} but the tileset has no such tile ({} tiles)",
                ts.tilecount
            )));
        }
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let (base, notes) = match &data {
            None => (Tile::Solid, Vec::new()),
            Some(d) => tile_kind(&d.properties, d.collision.as_ref(), tw, th).map_err(&err)?,
        };
        let subject = format!("tileset {:?} tile {id}", ts.name);
        if !self.warned.contains(&(lt.tileset_index(), id)) {
            self.warned.push((lt.tileset_index(), id));
            for n in notes {
                self.warn(subject.clone(), n);
            }
        }
        apply_flips(base, lt.flip_h, lt.flip_v, lt.flip_d).map_err(err)
    }

    /// Platforms and spawn points from the object layers; everything else is warned about.
    fn objects(&mut self, level: &mut Level) -> Result<Vec<SpawnPoint>, TiledError> {
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let map_h = self.map.height as f32;
        let layers = std::mem::take(&mut self.objects);
        let all: HashMap<u32, &tiled::Object<'m>> = layers
            .iter()
            .flat_map(|(_, objs)| objs.iter())
            .map(|o| (o.id(), o))
            .collect();
        let file = self.file.clone();
        let obj_err = |o: &tiled::Object, message: String| TiledError::Object {
            file: file.clone(),
            id: o.id(),
            name: o.name.clone(),
            message,
        };
        // Tiled's pixel position (y down, from the map's top) to level tiles (y up).
        let to_level = |x: f32, y: f32| Vec2::new(x / tw, map_h - y / th);
        let mut used_paths: Vec<u32> = Vec::new();
        let mut spawns: Vec<(SpawnPoint, u32)> = Vec::new();
        let mut polylines: Vec<&tiled::Object<'m>> = Vec::new();
        for (_, objs) in &layers {
            for o in objs {
                let subject = format!("object {} {:?}", o.id(), o.name);
                let class = o.user_type.as_str();
                if o.tile_data().is_some() {
                    self.warn(subject, "a tile object (a placed sprite) holds no collision platbench reads; ignored".into());
                    continue;
                }
                let is_platform =
                    class == names::PLATFORM || o.properties.contains_key(names::PATH);
                if class == names::SPAWN {
                    if o.rotation != 0.0 {
                        return Err(obj_err(
                            o,
                            format!(
                                "a spawn point is rotated by {} degrees; expected no rotation",
                                o.rotation
                            ),
                        ));
                    }
                    let feet = match &o.shape {
                        ObjectShape::Point(..) => to_level(o.x, o.y),
                        ObjectShape::Rect { width, height } => {
                            to_level(o.x + width * 0.5, o.y + height)
                        }
                        other => {
                            return Err(obj_err(
                                o,
                                format!("a spawn point is {}; expected a point (the feet) or a rectangle (feet at its bottom centre)", shape_name(other)),
                            ))
                        }
                    };
                    if !(feet.x.is_finite() && feet.y.is_finite()) {
                        return Err(obj_err(o, "its position is not finite".into()));
                    }
                    let (w, h) = (level.width as f32, level.height as f32);
                    if !(feet.x >= 0.0 && feet.x <= w && feet.y >= 0.0 && feet.y <= h) {
                        return Err(obj_err(o, format!(
                            "the spawn point's feet are at ({}, {}) tiles, outside the map (0 <= x <= {w}, 0 <= y <= {h}); expected a spawn inside the map, on or above open space",
                            feet.x, feet.y
                        )));
                    }
                    for key in o.properties.keys() {
                        self.warn(subject.clone(), format!("property {key:?} is not one platbench reads on a spawn point; ignored"));
                    }
                    let b = character_box(feet, DEFAULT_CHARACTER_SIZE);
                    if let Some(t) = level.solids_overlapping(&b).next() {
                        return Err(obj_err(o, format!(
                            "the spawn point at ({}, {}) puts the {} x {} character inside the solid tile at ({}, {}); expected empty space (the point is the feet)",
                            feet.x, feet.y, DEFAULT_CHARACTER_SIZE.x, DEFAULT_CHARACTER_SIZE.y, t.mins.x, t.mins.y
                        )));
                    }
                    let name = if valid_name(&o.name) {
                        o.name.clone()
                    } else {
                        format!("spawn{}", o.id())
                    };
                    if let Some((_, other)) = spawns.iter().find(|(s, _)| s.name == name) {
                        return Err(obj_err(o, format!("spawn name {name:?} is also the name of object {other}; expected unique spawn names (they name the scenarios)")));
                    }
                    spawns.push((
                        SpawnPoint {
                            name,
                            position: feet,
                        },
                        o.id(),
                    ));
                } else if is_platform {
                    let p = self.platform(o, &all, &obj_err, &to_level, &mut used_paths)?;
                    level.platforms.push(p);
                } else {
                    match &o.shape {
                        ObjectShape::Polyline { .. } => polylines.push(o),
                        other => {
                            let class_text = if class.is_empty() {
                                "no class".to_string()
                            } else {
                                format!("class {class:?}")
                            };
                            self.warn(subject, format!(
                                "a {} with {class_text} is neither a spawn point (class \"spawn\") nor a moving platform (a rectangle with a \"path\" property); ignored",
                                shape_name(other)
                            ));
                        }
                    }
                }
            }
        }
        for o in polylines {
            if !used_paths.contains(&o.id()) {
                self.warn(
                    format!("object {} {:?}", o.id(), o.name),
                    "a polyline that no platform's \"path\" property names; ignored".into(),
                );
            }
        }
        Ok(spawns.into_iter().map(|(s, _)| s).collect())
    }

    /// A moving platform from a rectangle with `path` and `speed`.
    fn platform(
        &mut self,
        o: &tiled::Object<'m>,
        all: &HashMap<u32, &tiled::Object<'m>>,
        obj_err: &dyn Fn(&tiled::Object, String) -> TiledError,
        to_level: &dyn Fn(f32, f32) -> Vec2,
        used_paths: &mut Vec<u32>,
    ) -> Result<Platform, TiledError> {
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let subject = format!("object {} {:?}", o.id(), o.name);
        let ObjectShape::Rect { width, height } = o.shape else {
            return Err(obj_err(
                o,
                format!(
                    "a moving platform is {}; expected a rectangle",
                    shape_name(&o.shape)
                ),
            ));
        };
        if o.rotation != 0.0 {
            return Err(obj_err(
                o,
                format!(
                    "the platform is rotated by {} degrees; expected no rotation",
                    o.rotation
                ),
            ));
        }
        if !(width > 0.0 && height > 0.0 && width.is_finite() && height.is_finite()) {
            return Err(obj_err(
                o,
                format!("the platform is {width} x {height} pixels; expected a positive size"),
            ));
        }
        let start = to_level(o.x, o.y + height);
        let size = Vec2::new(width / tw, height / th);
        let mut speed = None;
        let mut path = None;
        let mut one_way = false;
        let props: BTreeMap<_, _> = o.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::PATH, PropertyValue::ObjectValue(id)) => path = Some(*id),
                (names::SPEED, PropertyValue::FloatValue(v)) => speed = Some(*v),
                (names::SPEED, PropertyValue::IntValue(v)) => speed = Some(*v as f32),
                (names::ONE_WAY, PropertyValue::BoolValue(b)) => one_way = *b,
                (names::PATH, other) => return Err(obj_err(o, format!("property \"path\" is {}; expected an object reference to a polyline", kind_of(other)))),
                (names::SPEED, other) => return Err(obj_err(o, format!("property \"speed\" is {}; expected a float (tiles/s)", kind_of(other)))),
                (names::ONE_WAY, other) => return Err(obj_err(o, format!("property \"one_way\" is {}; expected a bool", kind_of(other)))),
                _ => self.warn(subject.clone(), format!("property {key:?} is not one platbench reads on a platform (it reads \"path\", \"speed\", \"one_way\"); ignored")),
            }
        }
        let path_id = match path {
            Some(id) if id != 0 => id,
            _ => return Err(obj_err(o, "a moving platform needs a \"path\" property (an object reference to a polyline); none is set".into())),
        };
        let speed = match speed {
            Some(s) if s.is_finite() && s > 0.0 && s as f64 <= crate::limits::MAX_SPEED => s,
            Some(s) => {
                return Err(obj_err(
                    o,
                    format!(
                        "speed = {s}; expected 0 < speed <= {} (tiles/s)",
                        crate::limits::MAX_SPEED
                    ),
                ))
            }
            None => {
                return Err(obj_err(
                    o,
                    "a moving platform needs a \"speed\" property (float, tiles/s)".into(),
                ))
            }
        };
        let Some(p) = all.get(&path_id) else {
            return Err(obj_err(o, format!("its path names object {path_id}, which is not in any object layer platbench reads")));
        };
        let ObjectShape::Polyline { points } = &p.shape else {
            return Err(obj_err(
                o,
                format!(
                    "its path names object {path_id} {:?}, which is {}; expected a polyline",
                    p.name,
                    shape_name(&p.shape)
                ),
            ));
        };
        if p.rotation != 0.0 {
            return Err(obj_err(
                o,
                format!(
                    "its path, object {path_id} {:?}, is rotated; expected no rotation",
                    p.name
                ),
            ));
        }
        let Some(&(x0, y0)) = points.first() else {
            return Err(obj_err(
                o,
                format!("its path, object {path_id} {:?}, has no points", p.name),
            ));
        };
        // The path's shape, moved so that its first point is the platform's start: where the
        // polyline is drawn does not matter, only its legs.
        let waypoints: Vec<Vec2> = points
            .iter()
            .map(|&(x, y)| start + Vec2::new((x - x0) / tw, -(y - y0) / th))
            .collect();
        let far =
            |v: Vec2| v.abs().max_element() as f64 > crate::limits::MAX_COORD || !v.is_finite();
        if far(start) || far(size) || waypoints.iter().any(|w| far(*w)) {
            return Err(obj_err(
                o,
                format!(
                    "the platform or its path reaches beyond {} tiles from the map's corner; expected a platform near the map",
                    crate::limits::MAX_COORD
                ),
            ));
        }
        if waypoints.iter().any(|w| !w.is_finite()) {
            return Err(obj_err(
                o,
                format!(
                    "its path, object {path_id} {:?}, has a point that is not finite",
                    p.name
                ),
            ));
        }
        if waypoints.len() < 2 || waypoints.windows(2).all(|w| w[0] == w[1]) {
            return Err(obj_err(o, format!("its path, object {path_id} {:?}, has zero length; expected at least 2 different points", p.name)));
        }
        used_paths.push(path_id);
        Ok(Platform {
            start,
            size,
            motion: PlatformMotion::Waypoints {
                points: waypoints,
                speed,
            },
            one_way,
        })
    }
}

fn kind_of(v: &PropertyValue) -> &'static str {
    match v {
        PropertyValue::BoolValue(_) => "a bool",
        PropertyValue::FloatValue(_) => "a float",
        PropertyValue::IntValue(_) => "an int",
        PropertyValue::ColorValue(_) => "a color",
        PropertyValue::StringValue(_) => "a string",
        PropertyValue::FileValue(_) => "a file",
        PropertyValue::ObjectValue(_) => "an object reference",
        PropertyValue::ListValue(_) => "a list",
        PropertyValue::ClassValue { .. } => "a class value",
    }
}

fn shape_name(s: &ObjectShape) -> &'static str {
    match s {
        ObjectShape::Rect { .. } => "a rectangle",
        ObjectShape::Ellipse { .. } => "an ellipse",
        ObjectShape::Capsule { .. } => "a capsule",
        ObjectShape::Polyline { .. } => "a polyline",
        ObjectShape::Polygon { .. } => "a polygon",
        ObjectShape::Point(..) => "a point",
        ObjectShape::Text { .. } => "a text",
    }
}

fn tile_name(t: &Tile) -> String {
    match t {
        Tile::Empty => "empty".into(),
        Tile::Solid => "solid".into(),
        Tile::OneWay => "one-way".into(),
        Tile::Ladder => "a ladder".into(),
        Tile::Slope(Slope::Line { left, right }) => format!("a line slope ({left}, {right})"),
        Tile::Slope(Slope::Heights(_)) => "a height-array slope".into(),
    }
}

fn number(v: &PropertyValue) -> Option<f32> {
    match v {
        PropertyValue::FloatValue(f) => Some(*f),
        PropertyValue::IntValue(i) => Some(*i as f32),
        _ => None,
    }
}

/// A tileset tile's meaning from its properties, else its collision shape, else solid (a tile
/// drawn in a collision layer is a wall unless it says otherwise). Properties take precedence
/// over a collision shape, which is then not read (a warning says so). Returns the tile and the
/// warnings about it; `Err` is the message for an unsupported tile.
pub(crate) fn tile_kind(
    props: &tiled::Properties,
    shape: Option<&tiled::ObjectLayerData>,
    tw: f32,
    th: f32,
) -> Result<(Tile, Vec<String>), String> {
    let mut notes = Vec::new();
    let mut collision = None;
    let mut left = None;
    let mut right = None;
    let mut heights = None;
    let sorted: BTreeMap<_, _> = props.iter().collect();
    for (key, value) in sorted {
        match key.as_str() {
            names::COLLISION => match value {
                PropertyValue::StringValue(s) => collision = Some(s.clone()),
                other => return Err(format!("property \"collision\" is {}; expected a string: solid, one_way, ladder or empty", kind_of(other))),
            },
            names::SLOPE_LEFT | names::SLOPE_RIGHT => {
                let v = number(value).ok_or_else(|| {
                    format!("property {key:?} is {}; expected a float (height in tiles)", kind_of(value))
                })?;
                if !(v.is_finite() && v.abs() <= 16.0) {
                    return Err(format!("property {key:?} = {v}; expected a height between -16 and 16 tiles"));
                }
                if key == names::SLOPE_LEFT {
                    left = Some(v);
                } else {
                    right = Some(v);
                }
            }
            names::HEIGHTS => match value {
                PropertyValue::StringValue(s) => heights = Some(parse_heights(s)?),
                other => return Err(format!("property \"heights\" is {}; expected a string of 16 comma-separated integers 0..16", kind_of(other))),
            },
            _ => notes.push(format!(
                "property {key:?} is not one platbench reads (it reads collision, slope_left, slope_right, heights); ignored"
            )),
        }
    }
    let slope = match (left, right, heights) {
        (None, None, None) => None,
        (Some(l), Some(r), None) => Some(Slope::Line { left: l, right: r }),
        (None, None, Some(h)) => Some(Slope::Heights(h)),
        (Some(_), None, None) | (None, Some(_), None) => {
            return Err("it has only one of slope_left and slope_right; expected both (a line slope)".into())
        }
        _ => return Err("it has both a height array (heights) and a line slope (slope_left/slope_right); expected one".into()),
    };
    let from_props = match (collision.as_deref(), slope) {
        (Some(c), Some(_)) => {
            return Err(format!("it has collision = {c:?} and slope properties; expected one of them (a slope needs no collision property)"))
        }
        (None, Some(s)) => Some(Tile::Slope(s)),
        (Some("solid"), None) => Some(Tile::Solid),
        (Some("one_way" | "oneway"), None) => Some(Tile::OneWay),
        (Some("ladder"), None) => Some(Tile::Ladder),
        (Some("empty"), None) => Some(Tile::Empty),
        (Some(other), None) => {
            return Err(format!("collision = {other:?}; expected solid, one_way, ladder or empty"))
        }
        (None, None) => None,
    };
    let objects = shape.map_or(&[][..], |s| s.object_data());
    if let Some(t) = from_props {
        if !objects.is_empty() {
            notes.push("its properties say what it is, so its collision shape is not read".into());
        }
        return Ok((t, notes));
    }
    let t = match objects {
        [] => Tile::Solid,
        [o] => shape_kind(o, tw, th)?,
        many => {
            return Err(format!(
                "its collision shape has {} objects; expected one: a rectangle covering the tile (solid) or a ramp polygon (slope)",
                many.len()
            ))
        }
    };
    Ok((t, notes))
}

fn parse_heights(s: &str) -> Result<[u8; 16], String> {
    let expected =
        "expected 16 comma-separated integers 0..16 (sixteenths of a tile, left to right)";
    let vals: Vec<&str> = s.split(',').map(str::trim).collect();
    if vals.len() != 16 {
        return Err(format!(
            "heights = {s:?} has {} entries; {expected}",
            vals.len()
        ));
    }
    let mut out = [0u8; 16];
    for (k, v) in vals.iter().enumerate() {
        match v.parse::<u8>() {
            Ok(h) if h <= 16 => out[k] = h,
            _ => {
                return Err(format!(
                    "heights = {s:?}: entry {} is {v:?}; {expected}",
                    k + 1
                ))
            }
        }
    }
    Ok(out)
}

/// The meaning of a tile's single collision object: a rectangle over the whole tile is solid,
/// a ramp polygon is a line slope.
fn shape_kind(o: &tiled::ObjectData, tw: f32, th: f32) -> Result<Tile, String> {
    if o.rotation != 0.0 {
        return Err(format!(
            "its collision shape is rotated by {} degrees; expected no rotation",
            o.rotation
        ));
    }
    let (tol_x, tol_y) = (SHAPE_TOLERANCE_PX, SHAPE_TOLERANCE_PX);
    match &o.shape {
        ObjectShape::Rect { width, height } => {
            let full = o.x.abs() <= tol_x
                && o.y.abs() <= tol_y
                && (o.x + width - tw).abs() <= tol_x
                && (o.y + height - th).abs() <= tol_y;
            if full {
                Ok(Tile::Solid)
            } else {
                Err(format!(
                    "its collision shape is a rectangle at ({}, {}) of {} x {} pixels, which does not cover the {tw} x {th} tile; expected a full-tile rectangle (solid) or a ramp polygon (slope)",
                    o.x, o.y, width, height
                ))
            }
        }
        ObjectShape::Polygon { points } => {
            let pts: Vec<Vec2> = points
                .iter()
                .map(|&(x, y)| Vec2::new(o.x + x, o.y + y))
                .collect();
            ramp(&pts, tw, th).map(Tile::Slope).ok_or_else(|| {
                format!(
                    "its collision shape is a polygon {} that is not a ramp; expected the tile's bottom edge, its two sides and one straight top line from the left side to the right side (within {SHAPE_TOLERANCE_PX} pixel)",
                    points_text(&pts)
                )
            })
        }
        other => Err(format!(
            "its collision shape is {}; expected a full-tile rectangle (solid) or a ramp polygon (slope)",
            shape_name(other)
        )),
    }
}

fn points_text(pts: &[Vec2]) -> String {
    let p: Vec<String> = pts.iter().map(|p| format!("({}, {})", p.x, p.y)).collect();
    format!("[{}]", p.join(", "))
}

/// Recognises a ramp: a polygon (tile pixels, y down) whose corners, once points on a straight
/// edge are dropped, are the tile's two bottom corners, next to each other, and one point on
/// each side (or on one side only, for a triangle), all within [`SHAPE_TOLERANCE_PX`]. Returns
/// the line slope through the top points, heights in tiles.
pub(crate) fn ramp(pts: &[Vec2], tw: f32, th: f32) -> Option<Slope> {
    // Tile-local, y up, in tiles; tolerances in the same units.
    let tol = Vec2::new(SHAPE_TOLERANCE_PX / tw, SHAPE_TOLERANCE_PX / th);
    let mut p: Vec<Vec2> = pts
        .iter()
        .map(|q| Vec2::new(q.x / tw, 1.0 - q.y / th))
        .collect();
    if p.iter().any(|q| !q.is_finite()) {
        return None;
    }
    let near = |a: Vec2, b: Vec2| (a.x - b.x).abs() <= tol.x && (a.y - b.y).abs() <= tol.y;
    // Drop repeated points and points on the straight line between their neighbours.
    let mut changed = true;
    while changed && p.len() >= 3 {
        changed = false;
        for k in 0..p.len() {
            let n = p.len();
            let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
            let ac = c - a;
            let off = if ac.length() < 1e-9 {
                (b - a).length()
            } else {
                (ac.perp_dot(b - a) / ac.length()).abs()
            };
            if near(a, b) || off <= tol.min_element() * 0.5 {
                p.remove(k);
                changed = true;
                break;
            }
        }
    }
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

/// A tile's meaning once flipped: mirroring a slope mirrors its surface; flips that turn a
/// surface upside down or sideways (vertical, diagonal) are not representable for slopes and
/// one-way tiles, which block from above only; solids, ladders and empty tiles are symmetric.
pub(crate) fn apply_flips(t: Tile, h: bool, v: bool, d: bool) -> Result<Tile, String> {
    match t {
        Tile::Empty | Tile::Solid | Tile::Ladder => Ok(t),
        Tile::OneWay if v || d => Err(
            "it is a one-way tile drawn flipped vertically or rotated; a one-way tile blocks from above only, expected it unflipped or flipped horizontally".into(),
        ),
        Tile::OneWay => Ok(t),
        Tile::Slope(_) if v || d => Err(
            "it is a slope drawn flipped vertically or rotated, which makes a ceiling or wall slope; expected it unflipped or flipped horizontally (the mirrored ramp)".into(),
        ),
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
        assert!(apply_flips(up, false, true, false).is_err());
        assert!(apply_flips(up, false, false, true).is_err());
        let mut h = [0u8; 16];
        h[0] = 16;
        let mut r = [0u8; 16];
        r[15] = 16;
        assert_eq!(
            apply_flips(Tile::Slope(Slope::Heights(h)), true, false, false),
            Ok(Tile::Slope(Slope::Heights(r)))
        );
        assert_eq!(apply_flips(Tile::Solid, true, true, true), Ok(Tile::Solid));
        assert!(apply_flips(Tile::OneWay, false, true, false).is_err());
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
        assert!(parse_heights("1,2").unwrap_err().contains("has 2 entries"));
        assert!(parse_heights("0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,17")
            .unwrap_err()
            .contains("entry 16"));
    }
}

//! Import of maps made with the Tiled editor (`.tmx`; tilesets inline, in `.tsx` files or in
//! JSON `.tsj` files): tile layers become the level's tiles, object layers give collision
//! rectangles and ramps, moving platforms and spawn points, read the way games mark them (layer
//! names, object names and classes, bool tile properties). The README's "Tiled maps" section is
//! the user's side of the mapping; this module is its one implementation, split by concern:
//! `layers` (which layer is what, and the tile layers), `tiles` (what one tile is),
//! `objects` (spawns, collision objects, platforms), `normalize` (what the `tiled` crate
//! cannot read as Tiled writes it) and `scan` (what it would allocate without bound).
//!
//! Nothing here panics on a map's content: every construct platbench cannot represent is a
//! [`TiledError`] or a [`TiledWarning`] that names the tile (tileset and local id, and a map
//! cell where one is involved), the object (id and name) or the layer.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::rc::Rc;

use tiled::{ObjectShape, PropertyValue};

mod layers;
mod normalize;
mod objects;
mod scan;
mod tiles;

pub(crate) use tiles::ramp;

use super::import::{
    fallback_spawn_point, no_solids_warning, ImportFailure, ImportOptions, ImportWarning,
    LayerReport, LayerRole,
};
use super::probes::{probe_scenarios, ProbeConfig, SpawnPoint};
use super::{parse_scenarios, Level, LevelError};
use super::{valid_name, Slope, Tile};

/// How far a collision-shape point may be from the tile edge or corner it stands for, in
/// pixels: the editor snaps to whole pixels, so a hand-drawn ramp is exact to about one.
pub const SHAPE_TOLERANCE_PX: f32 = 1.0;

/// A warning of the Tiled import (the shared [`ImportWarning`]).
pub type TiledWarning = ImportWarning;

/// The map property, tile properties and layer property names platbench reads.
mod names {
    /// Tile property: what the tile is (`solid`, `one_way`, `ladder`, `empty`); on a layer, a
    /// bool or a role.
    pub const COLLISION: &str = "collision";
    /// Tile property: height of a line slope at the tile's left edge, in tiles.
    pub const SLOPE_LEFT: &str = "slope_left";
    /// Tile property: height of a line slope at the tile's right edge, in tiles.
    pub const SLOPE_RIGHT: &str = "slope_right";
    /// Tile property: 16 comma-separated heights in sixteenths of a tile.
    pub const HEIGHTS: &str = "heights";
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
    /// Map property: the role of tile layers no name or property marks.
    pub const TILE_LAYERS: &str = "tile_layers";
}

/// How to mark a spawn in Tiled, for the messages that need one.
const HOW_TO_SPAWN: &str = "mark one with a point object named or of class \"spawn\" (or \"player\", \"start\") in an object layer";
/// How to mark collision in Tiled, for the messages that need one.
const HOW_TO_COLLIDE: &str = "name the collision layer (\"collision\", \"ground\", \"walls\", \"platforms\"), give it the property collision = true, or pass --layer NAME=collision";

/// A Tiled map that platbench cannot run as it is, with what was found and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum TiledError {
    /// The file could not be read or is not a well-formed Tiled map (the `tiled` crate's error,
    /// with the file it was reading).
    #[error("{file}: cannot load the Tiled map: {message}")]
    Load {
        /// The map, tileset or template file at fault (with its line when known).
        file: String,
        /// What was wrong.
        message: String,
    },
    /// A property of the whole map (orientation, size) that platbench cannot use.
    #[error("{file}: {message}")]
    Map {
        /// The map file.
        file: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A layer that cannot be imported (size, an unexpected property value).
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
    /// An object (platform, spawn, path, collision shape) that cannot be imported.
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
    /// The map has no spawn point, no cell to stand on and no side file, so nothing can run.
    #[error("{file}: the map has no spawn points, no cell a character can stand on, and no side file {side} with [[scenario]] entries, so nothing can run on it; mark a spawn with a point object named or of class \"spawn\" in an object layer (where the character's feet start), pass --spawn X,Y, or write {side} with [[scenario]] entries (README, \"Tiled maps\")")]
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

/// A map imported without its scenarios: the level (geometry and platforms), its spawn points,
/// what each layer was read as, and the warnings raised on the way.
#[derive(Clone, Debug)]
pub struct TiledImport {
    /// The level, with no scenarios yet.
    pub level: Level,
    /// The map's spawn points, in the order of the file (or the fallback spawn `auto`).
    pub spawns: Vec<SpawnPoint>,
    /// Where each spawn point came from (the object, the rule), one per spawn.
    pub spawn_sources: Vec<String>,
    /// Each layer with the role it was given and why, in the file's order.
    pub layers: Vec<LayerReport>,
    /// Everything that was ignored or assumed, each naming its tile, object or layer.
    pub warnings: Vec<TiledWarning>,
}

/// Loads a Tiled map as a runnable level with the default rules; see [`load_tiled_map_with`].
pub fn load_tiled_map(path: &Path) -> Result<(Level, Vec<TiledWarning>), TiledError> {
    load_tiled_map_with(path, &ImportOptions::default()).map_err(|f| f.error)
}

/// Loads a Tiled map as a runnable level: its geometry, platforms and scenarios — those of the
/// side file `MAP.toml` next to it when there is one, else the standard probes at each spawn
/// point ([`super::probes`]). Returns the warnings too, for the caller to show; on failure, the
/// warnings gathered so far come with the error.
pub fn load_tiled_map_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<(Level, Vec<TiledWarning>), ImportFailure<TiledError>> {
    let TiledImport {
        mut level,
        spawns,
        mut warnings,
        ..
    } = import_tiled_map_with(path, opts)?;
    let fail = |error: TiledError, warnings: Vec<TiledWarning>| ImportFailure { error, warnings };
    let side = path.with_extension("toml");
    if side.is_file() {
        let text = match crate::limits::read_text_capped(&side) {
            Ok(t) => t,
            Err(e) => {
                return Err(fail(
                    TiledError::SideFileRead {
                        file: side.display().to_string(),
                        message: e.to_string(),
                    },
                    warnings,
                ))
            }
        };
        level.scenarios = match parse_scenarios(&text, &side.display().to_string(), &level) {
            Ok(s) => s,
            Err(e) => return Err(fail(e.into(), warnings)),
        };
        if level.scenarios.is_empty() {
            return Err(fail(
                TiledError::NoScenarios {
                    file: path.display().to_string(),
                    side: side.display().to_string(),
                },
                warnings,
            ));
        }
        // The fallback spawn's warning is moot when a side file gives the scenarios.
        warnings.retain(|w| !w.message.starts_with("no spawn point found"));
        if !spawns.is_empty() && spawns[0].name != "auto" {
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
        return Err(fail(
            TiledError::NoScenarios {
                file: path.display().to_string(),
                side: side.display().to_string(),
            },
            warnings,
        ));
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

/// Reads a Tiled map's geometry, platforms and spawn points (no scenarios) with the default
/// rules; see [`import_tiled_map_with`].
pub fn import_tiled_map(path: &Path) -> Result<TiledImport, TiledError> {
    import_tiled_map_with(path, &ImportOptions::default()).map_err(|f| f.error)
}

/// The file a map refers to, found as the `tiled` crate finds it: relative to the map's folder.
fn sibling(map: &Path, source: &str) -> PathBuf {
    map.parent()
        .map_or_else(|| PathBuf::from(source), |d| d.join(source))
}

/// Reads a Tiled map's geometry, platforms and spawn points (no scenarios), with the command
/// line's overrides. On failure the warnings gathered so far come with the error.
pub fn import_tiled_map_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<TiledImport, ImportFailure<TiledError>> {
    let file = path.display().to_string();
    let notes: Rc<RefCell<Vec<TiledWarning>>> = Rc::new(RefCell::new(Vec::new()));
    let failed = |error: TiledError, notes: &Rc<RefCell<Vec<TiledWarning>>>| ImportFailure {
        error,
        warnings: notes.borrow().clone(),
    };
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tmj") || e.eq_ignore_ascii_case("json"))
    {
        return Err(failed(
            TiledError::Map {
                file,
                message: "a JSON map (.tmj/.json): the tiled crate platbench reads maps with reads TMX only; save it as .tmx in Tiled (File > Save As, \"Tiled map files (*.tmx)\"); JSON tilesets (.tsj) are read".into(),
            },
            &notes,
        ));
    }
    // Read once, within the input cap, made readable by the crate where Tiled is tolerant and
    // the crate is not, and looked at for what the crate would allocate or index before it does.
    let text = crate::limits::read_text_capped(path).map_err(|e| {
        failed(
            TiledError::Load {
                file: file.clone(),
                message: e.to_string(),
            },
            &notes,
        )
    })?;
    let norm = normalize::normalize_xml(&text).map_err(|e| {
        failed(
            TiledError::Map {
                file: format!("{file}:{}", e.line),
                message: e.message,
            },
            &notes,
        )
    })?;
    for n in norm.notes {
        notes.borrow_mut().push(TiledWarning {
            file: file.clone(),
            subject: "map".into(),
            message: n,
        });
    }
    let text = norm.text;
    let sources = scan::scan_map(&text).map_err(|e| {
        failed(
            TiledError::Map {
                file: format!("{file}:{}", e.line),
                message: e.message,
            },
            &notes,
        )
    })?;
    let map_path = path.to_path_buf();
    let bytes = text.clone().into_bytes();
    // The map as read above; tilesets and templates through the same cap, made readable too.
    // The failure of a file the crate reads names that file.
    let reader_notes = notes.clone();
    let reader = move |p: &Path| -> std::io::Result<std::io::Cursor<Vec<u8>>> {
        if p == map_path {
            return Ok(std::io::Cursor::new(bytes.clone()));
        }
        let shown = p.display().to_string();
        let data = crate::limits::read_capped(p)?;
        let ext = p
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        let bad = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
        let text = String::from_utf8(data.clone());
        let out = match (ext.as_str(), text) {
            ("tsj" | "json", Ok(t)) => {
                let n = normalize::json_tileset_to_tsx(&t).map_err(bad)?;
                (n.text, n.notes)
            }
            ("tsx", Ok(t)) => {
                let n = normalize::normalize_xml(&t)
                    .map_err(|e| bad(format!("line {}: {}", e.line, e.message)))?;
                (n.text, n.notes)
            }
            _ => return Ok(std::io::Cursor::new(data)),
        };
        for n in out.1 {
            reader_notes.borrow_mut().push(TiledWarning {
                file: shown.clone(),
                subject: "tileset".into(),
                message: n,
            });
        }
        Ok(std::io::Cursor::new(out.0.into_bytes()))
    };
    let map = match tiled::Loader::with_reader(reader).load_tmx_map(path) {
        Ok(m) => m,
        Err(e) => {
            let error = load_error(path, &text, &sources, e, &notes);
            return Err(failed(error, &notes));
        }
    };
    let mut im = Importer::new(file.clone(), &map, opts);
    im.warnings = notes.borrow().clone();
    match im.run(path) {
        Ok(r) => Ok(r),
        Err(error) => Err(ImportFailure {
            error,
            warnings: im.warnings,
        }),
    }
}

/// The crate's error with the file it was reading: an external tileset or template that fails
/// on its own is named; otherwise the map, with the line of an XML syntax error.
fn load_error(
    path: &Path,
    text: &str,
    sources: &[String],
    e: tiled::Error,
    notes: &Rc<RefCell<Vec<TiledWarning>>>,
) -> TiledError {
    let file = path.display().to_string();
    if let tiled::Error::ResourceLoadingError { path: p, err } = &e {
        return TiledError::Load {
            file: p.display().to_string(),
            message: format!("cannot read it ({err}); the map {file} refers to it"),
        };
    }
    // An external tileset that fails to load on its own is the file at fault.
    for s in sources {
        let p = sibling(path, s);
        let reader = |q: &Path| -> std::io::Result<std::io::Cursor<Vec<u8>>> {
            let data = crate::limits::read_capped(q)?;
            let ext = q
                .extension()
                .map(|x| x.to_string_lossy().to_lowercase())
                .unwrap_or_default();
            let bad = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
            let t = String::from_utf8(data).map_err(|e| bad(e.to_string()))?;
            let t = match ext.as_str() {
                "tsj" | "json" => normalize::json_tileset_to_tsx(&t).map_err(bad)?.text,
                _ => {
                    normalize::normalize_xml(&t)
                        .map_err(|e| bad(format!("line {}: {}", e.line, e.message)))?
                        .text
                }
            };
            Ok(std::io::Cursor::new(t.into_bytes()))
        };
        if let Err(te) = tiled::Loader::with_reader(reader).load_tsx_tileset(&p) {
            let message = match te {
                tiled::Error::ResourceLoadingError { err, .. } => err.to_string(),
                other => explain(&other),
            };
            return TiledError::Load {
                file: p.display().to_string(),
                message: format!("{message} (a tileset the map {file} uses)"),
            };
        }
    }
    let _ = notes;
    let line = scan::xml_error_line(text)
        .map(|l| format!(":{l}"))
        .unwrap_or_default();
    TiledError::Load {
        file: format!("{file}{line}"),
        message: explain(&e),
    }
}

/// The crate's message, with what to do where platbench knows it.
fn explain(e: &tiled::Error) -> String {
    match e {
        tiled::Error::InvalidEncodingFormat { encoding, compression } => format!(
            "a tile layer's data is in {} encoding with {} compression, which the tiled crate does not read; save the map with CSV or Base64 (uncompressed, zlib or gzip) layer format",
            encoding.as_deref().unwrap_or("XML (no)"),
            compression.as_deref().unwrap_or("no")
        ),
        tiled::Error::MalformedAttributes(m) => {
            format!("{m} (an attribute the tiled crate requires is missing or not a number)")
        }
        other => other.to_string(),
    }
}

/// A role and why it was given.
type Reasoned = (LayerRole, String);

/// A tile as the map uses it: tileset index, local id and flips.
type TileKey = (usize, u32, bool, bool, bool);

/// Where the level's cells lie in Tiled's cell coordinates: the map itself, or the part of an
/// infinite map its chunks cover.
#[derive(Clone, Copy, Debug)]
struct Grid {
    /// Tiled column of the level's column 0.
    x0: i32,
    /// Tiled row of the level's top row.
    y0: i32,
    /// Width in tiles.
    w: u32,
    /// Height in tiles.
    h: u32,
}

/// The state of one import.
struct Importer<'m> {
    file: String,
    map: &'m tiled::Map,
    opts: &'m ImportOptions,
    grid: Grid,
    /// The level's cells so far (row 0 at the bottom), with what set each.
    tiles: Vec<Option<(Tile, String)>>,
    /// Each used tile's meaning, computed once.
    kinds: HashMap<TileKey, Tile>,
    /// Tiles already warned about, so a tile used many times warns once.
    warned: Vec<(usize, u32)>,
    /// Tilesets already noted (oversize art), by index.
    noted_tilesets: Vec<usize>,
    warnings: Vec<TiledWarning>,
    /// Each layer's role and why, in file order.
    reports: Vec<LayerReport>,
    /// Object layers to read once the tiles are known.
    objects: Vec<objects::ObjectLayer<'m>>,
}

impl<'m> Importer<'m> {
    fn new(file: String, map: &'m tiled::Map, opts: &'m ImportOptions) -> Self {
        Importer {
            file,
            map,
            opts,
            grid: Grid {
                x0: 0,
                y0: 0,
                w: map.width,
                h: map.height,
            },
            tiles: Vec::new(),
            kinds: HashMap::new(),
            warned: Vec::new(),
            noted_tilesets: Vec::new(),
            warnings: Vec::new(),
            reports: Vec::new(),
            objects: Vec::new(),
        }
    }

    fn run(&mut self, path: &Path) -> Result<TiledImport, TiledError> {
        let map = self.map;
        self.check_map()?;
        // The size is checked before the cells are allocated.
        self.tiles = vec![None; (self.grid.w as usize) * (self.grid.h as usize)];
        let (name, description, tile_default) = self.map_properties(path)?;
        let entries = self.collect_layers()?;
        self.read_layers(entries, tile_default)?;
        self.collision_objects()?;
        let tiles = self
            .tiles
            .iter()
            .map(|t| t.as_ref().map_or(Tile::Empty, |(t, _)| *t))
            .collect();
        let mut level = Level::from_tiles(&name, self.grid.w, self.grid.h, tiles);
        level.description = description;
        level.source = self.file.clone();
        let (mut spawns, mut sources) = self.objects(&mut level)?;
        level.features.moving_platforms = !level.platforms.is_empty();
        if let Some(w) = no_solids_warning(&level, &self.file, HOW_TO_COLLIDE) {
            self.warnings.push(w);
        }
        if !self.opts.spawns.is_empty() {
            spawns.clear();
            sources.clear();
            for (k, p) in self.opts.spawns.iter().enumerate() {
                spawns.push(SpawnPoint {
                    name: format!("spawn{}", k + 1),
                    position: *p,
                });
                sources.push("--spawn on the command line".into());
            }
        } else if spawns.is_empty() {
            let (s, w) = fallback_spawn_point(&level, &self.file, HOW_TO_SPAWN);
            self.warnings.push(w);
            if let Some(s) = s {
                spawns.push(s);
                sources.push(
                    "fallback: the lowest standable cell of the leftmost column that has one"
                        .into(),
                );
            }
        }
        let _ = map;
        Ok(TiledImport {
            level,
            spawns,
            spawn_sources: sources,
            layers: std::mem::take(&mut self.reports),
            warnings: std::mem::take(&mut self.warnings),
        })
    }

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

    /// Orientation, tile size, and the level's extent: the map, or an infinite map's chunks.
    fn check_map(&mut self) -> Result<(), TiledError> {
        let m = self.map;
        if m.orientation != tiled::Orientation::Orthogonal {
            return Err(self.map_err(format!(
                "the map's orientation is {}; platbench imports orthogonal maps only",
                m.orientation
            )));
        }
        if m.tile_width == 0 || m.tile_height == 0 {
            return Err(self.map_err(format!(
                "the map's tiles are {} x {} pixels; expected a positive size",
                m.tile_width, m.tile_height
            )));
        }
        if m.infinite() {
            let (lo, hi) = layers::chunk_bounds(m.layers());
            let (Some(lo), Some(hi)) = (lo, hi) else {
                return Err(self.map_err(
                    "the map is infinite and its tile layers hold no chunk, so it has no extent; draw some tiles, or untick \"Infinite\" in the map properties".into(),
                ));
            };
            let (w, h) = ((hi.0 - lo.0) as u64, (hi.1 - lo.1) as u64);
            if w * h > crate::limits::MAX_TILES {
                return Err(self.map_err(format!(
                    "the map is infinite and its chunks span {w} x {h} tiles; expected at most {} tiles",
                    crate::limits::MAX_TILES
                )));
            }
            self.grid = Grid {
                x0: lo.0 as i32,
                y0: lo.1 as i32,
                w: w as u32,
                h: h as u32,
            };
            self.warn(
                "map".into(),
                format!(
                    "the map is infinite; cropped to its chunks: {w} x {h} tiles from Tiled cell ({}, {})",
                    lo.0, lo.1
                ),
            );
            return Ok(());
        }
        if m.width == 0 || m.height == 0 {
            return Err(self.map_err(format!(
                "the map is {} x {} tiles; expected a positive size",
                m.width, m.height
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

    /// The level's name (map property `name`, else the file stem made safe), its description,
    /// and the role of unmarked tile layers (map property `tile_layers`).
    fn map_properties(
        &mut self,
        path: &Path,
    ) -> Result<(String, String, Option<Reasoned>), TiledError> {
        let mut name = None;
        let mut description = String::new();
        let mut tile_default = None;
        let props: BTreeMap<_, _> = self.map.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::NAME, PropertyValue::StringValue(s)) => name = Some(s.clone()),
                (names::DESCRIPTION, PropertyValue::StringValue(s)) => description = s.clone(),
                (names::TILE_LAYERS, PropertyValue::StringValue(s)) => match LayerRole::parse(s) {
                    Some(r) => tile_default = Some((r, format!("the map property tile_layers = {s:?}"))),
                    None => return Err(self.map_err(format!("map property tile_layers = {s:?}; expected collision, solid, one_way, ladder or decoration"))),
                },
                (names::NAME | names::DESCRIPTION | names::TILE_LAYERS, other) => {
                    return Err(self.map_err(format!(
                        "map property {key:?} is {}; expected a string",
                        kind_of(other)
                    )))
                }
                _ => self.warn(
                    "map".into(),
                    format!("property {key:?} is not one platbench reads (it reads \"name\", \"description\" and \"tile_layers\"); ignored"),
                ),
            }
        }
        if let Some(r) = self.opts.tile_layers {
            tile_default = Some((r, format!("--tile-layers {}", r.name())));
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
        Ok((name, description, tile_default))
    }

    /// Puts `tile` into level cell `k`, set by `by`: an empty tile gives way to any other, a
    /// ladder and a one-way platform make a ladder (whose top is walkable like a one-way
    /// platform); other differing kinds are the message of an error.
    fn set_cell(&mut self, k: usize, tile: Tile, by: String) -> Result<(), String> {
        match &self.tiles[k] {
            None => self.tiles[k] = Some((tile, by)),
            Some((prev, _)) if *prev == tile || tile == Tile::Empty => {}
            Some((Tile::Empty, _)) => self.tiles[k] = Some((tile, by)),
            Some((Tile::OneWay, _)) if tile == Tile::Ladder => self.tiles[k] = Some((tile, by)),
            Some((Tile::Ladder, _)) if tile == Tile::OneWay => {}
            Some((prev, prev_by)) => {
                return Err(format!(
                    "it is {} but the cell already holds {} from {prev_by}; expected one kind of tile per cell across the collision layers",
                    tile_name(&tile),
                    tile_name(prev)
                ))
            }
        }
        Ok(())
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

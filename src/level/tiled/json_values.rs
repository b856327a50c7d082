//! What Tiled's JSON format writes where, judged by the walk ([`super::json_walk`]) before
//! serde_json reads the file, so that a value Tiled never writes is refused at its line and
//! column rather than passed to the `tiled` crate, which names neither: an object at the top; a
//! number, never a string, under each key where Tiled writes one; sizes (a map's, a tile
//! layer's, a chunk's, a tileset's tile size) whole numbers within the limits, positive where
//! Tiled's are; a tile layer's cells tile ids. Floats stay floats where Tiled writes them (an
//! object's place and size, a layer's offset), and property values stay what they are.

use super::attrs::property_problem;
use super::error::JsonError;
use super::json_frame::{Frame, Key, Role};
use super::json_walk::{unescape, Pos, Walker};
use crate::limits;

/// The keys under which Tiled writes a number, by what the object holding them is. The top is
/// a map's header or (`.tsj`) a tileset's.
#[rustfmt::skip]
fn numeric_keys(role: Role) -> &'static [&'static str] {
    match role {
        Role::Top => &[
            "width", "height", "tilewidth", "tileheight", "nextlayerid", "nextobjectid",
            "hexsidelength", "compressionlevel", "parallaxoriginx", "parallaxoriginy",
            "firstgid", "tilecount", "columns", "spacing", "margin", "imagewidth", "imageheight",
        ],
        Role::Tileset => &[
            "firstgid", "tilewidth", "tileheight", "tilecount", "columns", "spacing", "margin",
            "imagewidth", "imageheight",
        ],
        Role::Layer => &[
            "id", "x", "y", "width", "height", "opacity", "offsetx", "offsety", "parallaxx",
            "parallaxy", "startx", "starty",
        ],
        Role::Chunk => &["x", "y", "width", "height"],
        Role::Object => &["id", "x", "y", "width", "height", "rotation", "gid"],
        Role::Tile => &[
            "id", "imagewidth", "imageheight", "probability", "x", "y", "width", "height",
        ],
        Role::Point => &["x", "y"],
        _ => &[],
    }
}

/// The name of member `name` (its text between the quotes) when Tiled writes a number there.
pub(super) fn numeric_key(role: Role, name: &[u8]) -> Option<&'static str> {
    numeric_keys(role)
        .iter()
        .copied()
        .find(|k| k.as_bytes() == name)
}

/// Largest size in tiles: a map, a tile layer or a chunk has at most [`limits::MAX_TILES`]
/// cells, so no side is longer.
const MAX_SIDE: u64 = limits::MAX_TILES;
/// Largest tile size in pixels: what a TMX attribute holds (`u32`, as the `tiled` crate reads it).
const MAX_TILE_PIXELS: u64 = u32::MAX as u64;

/// What a size under `key` must be, beyond a number, where Tiled writes a whole one: its least
/// as an error says it (a map's, layer's or chunk's 0 is refused at its close, where an infinite
/// map's is known to be allowed), its most, and its unit.
fn whole(role: Role, key: &str) -> Option<(u64, u64, &'static str)> {
    match (role, key) {
        (Role::Top | Role::Layer | Role::Chunk, "width" | "height") => Some((1, MAX_SIDE, "tiles")),
        (Role::Top, "tilewidth" | "tileheight") => Some((1, MAX_TILE_PIXELS, "pixels")),
        // An image collection's tile size may be 0; the importer reads it as 1.
        (Role::Tileset, "tilewidth" | "tileheight") => Some((0, MAX_TILE_PIXELS, "pixels")),
        _ => None,
    }
}

/// A value as an error shows it: `raw` is its text (a string with its quotes), `c` its first
/// byte; long text is cut.
fn describe(c: u8, raw: &[u8]) -> String {
    let cut = |t: &[u8]| {
        let t = String::from_utf8_lossy(t);
        match t.char_indices().nth(40) {
            Some((k, _)) => format!("{}...", &t[..k]),
            None => t.into_owned(),
        }
    };
    match c {
        b'{' => "an object".into(),
        b'[' => "an array".into(),
        b'"' => format!("the string {}", cut(raw)),
        _ => cut(raw),
    }
}

/// What Tiled writes under a key that holds no number, as an error says it.
const BOOL: &str = "true or false";
const ARRAY: &str = "an array";
const DATA: &str = "an array of tile ids or a base64 string";
const LAYER_TYPES: &str = "tilelayer, objectgroup, imagelayer or group";

/// The key's name and what Tiled writes under it, for the keys whose wrong type the `tiled`
/// crate would read as absent or describe as something else (issue 40, F11 and F12).
fn kind(role: Role, key: Key) -> Option<(&'static str, &'static str)> {
    match (role, key) {
        (Role::Top, Key::Infinite) => Some(("infinite", BOOL)),
        (Role::Top, Key::Tilesets) => Some(("tilesets", ARRAY)),
        (Role::Top | Role::Layer, Key::Layers) => Some(("layers", ARRAY)),
        (Role::Layer, Key::Objects) => Some(("objects", ARRAY)),
        (Role::Layer | Role::Chunk, Key::Data) => Some(("data", DATA)),
        (Role::Object, Key::Point) => Some(("point", BOOL)),
        (Role::Object, Key::Ellipse) => Some(("ellipse", BOOL)),
        (Role::Layer | Role::Object, Key::Visible) => Some(("visible", BOOL)),
        _ => None,
    }
}

/// The strings Tiled writes under a key that holds one of a few (with their quotes), and the
/// error's words for them: a layer's type, and the layer data's encoding and compression
/// that the `tiled` crate reads (Tiled also writes zstd, which it does not).
#[rustfmt::skip]
fn choices(role: Role, key: Key) -> Option<(&'static [&'static [u8]], &'static str)> {
    const ENCODINGS: &str = "csv, or base64 with no compression (\"\"), zlib or gzip, which the tiled crate reads (in Tiled: Map > Map Properties > Tile Layer Format)";
    match (role, key) {
        (Role::Layer, Key::Type) => Some((
            &[b"\"tilelayer\"", b"\"objectgroup\"", b"\"imagelayer\"", b"\"group\""],
            "tilelayer, objectgroup, imagelayer or group, as Tiled writes it",
        )),
        (Role::Layer, Key::Encoding) => Some((&[b"\"csv\"", b"\"base64\""], ENCODINGS)),
        (Role::Layer, Key::Compression) => {
            Some((&[b"\"\"", b"\"zlib\"", b"\"gzip\""], ENCODINGS))
        }
        _ => None,
    }
}

/// A property's value as the translation to TMX writes it in `value="..."`: a string
/// unescaped, another scalar as written; an array or object as a bracket, which no typed
/// property reads.
fn as_attribute(c: u8, raw: &[u8]) -> String {
    match c {
        b'"' => unescape(raw),
        b'{' | b'[' => char::from(c).to_string(),
        b'n' if raw == b"null" => String::new(),
        _ => String::from_utf8_lossy(raw).into_owned(),
    }
}

/// What a tile layer's cell must be.
const CELL_EXPECTED: &str = "expected a tile id, a whole number from 0 to 4294967295";

impl Walker<'_> {
    /// The top value, starting at `at` with byte `c` (`raw`, the token there): Tiled writes an
    /// object. `Ok` for what is not JSON at all, which serde_json reports.
    pub(super) fn check_top(&self, at: Pos, c: u8, raw: &[u8]) -> Result<(), JsonError> {
        let json = match c {
            b'[' | b'"' | b'-' | b'0'..=b'9' => true,
            _ => matches!(raw, b"null" | b"true" | b"false"),
        };
        if c == b'{' || !json {
            return Ok(());
        }
        Err(value_error(
            at,
            format!(
                "the file's top level is {}; expected a JSON object ({{ ... }}) holding {}",
                describe(c, raw),
                self.what
            ),
        ))
    }

    /// A file with no value at all.
    pub(super) fn empty(&self, at: Pos) -> JsonError {
        value_error(
            at,
            format!(
                "the file is empty; expected a JSON object ({{ ... }}) holding {}",
                self.what
            ),
        )
    }

    /// Judges the value starting at `at` with byte `c` (`raw`: its text, a string's with its
    /// quotes, nothing for an array or object) against what Tiled writes under its key, and
    /// notes the first that is wrong in the frame it belongs to, refused at that frame's close
    /// ([`Self::check_values`]), which knows the layer's or object's name.
    pub(super) fn judge(&mut self, at: Pos, c: u8, raw: &[u8]) {
        let n = self.stack.len();
        let Some(p) = self.stack.last_mut() else {
            return;
        };
        if p.array {
            if p.role() != Role::Cells {
                return;
            }
            let index = p.count.saturating_sub(1);
            let tile_id = c.is_ascii_digit()
                && raw.iter().all(u8::is_ascii_digit)
                && std::str::from_utf8(raw)
                    .ok()
                    .and_then(|t| t.parse::<u32>().ok())
                    .is_some();
            let layer = n.checked_sub(2).and_then(|k| self.stack.get_mut(k));
            if let Some(l) = layer.filter(|l| !tile_id && l.bad_cell.is_none()) {
                l.bad_cell = Some((at, index, describe(c, raw)));
            }
            return;
        }
        if p.bad.is_some() {
            return;
        }
        if let Some((allowed, expected)) = p.key.and_then(|k| choices(p.role(), k)) {
            if !allowed.contains(&raw) {
                let found = describe(c, raw);
                let key = match p.key {
                    Some(Key::Type) => "type",
                    Some(Key::Encoding) => "encoding",
                    _ => "compression",
                };
                p.bad = Some((at, format!("\"{key}\" is {found}; expected {expected}")));
            }
            return;
        }
        if p.role() == Role::Property && p.key == Some(Key::Value) {
            p.value = Some((at, describe(c, raw), as_attribute(c, raw)));
            return;
        }
        if let Some((key, expected)) = p.key.and_then(|k| kind(p.role(), k)) {
            let ok = match expected {
                BOOL => matches!(raw, b"true" | b"false"),
                ARRAY => c == b'[',
                _ => c == b'[' || c == b'"',
            };
            if !ok {
                let found = describe(c, raw);
                p.bad = Some((
                    at,
                    format!("{key:?} is {found}; expected {expected}, as Tiled writes it"),
                ));
            }
            return;
        }
        let Some(key) = p.number else {
            return;
        };
        let found = describe(c, raw);
        if !matches!(c, b'-' | b'0'..=b'9') {
            p.bad = Some((
                at,
                format!("{key:?} is {found}; expected a number, as Tiled writes it"),
            ));
            return;
        }
        let Some((min, max, unit)) = whole(p.role(), key) else {
            return;
        };
        let value = std::str::from_utf8(raw)
            .ok()
            .filter(|t| t.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|t| t.parse::<u64>().ok())
            .filter(|v| *v <= max);
        match value {
            None => {
                p.bad = Some((at, format!(
                    "{key:?} is {found}; expected a whole number of {unit} from {min} to {max}, as Tiled writes it"
                )));
            }
            Some(0) => p.zeros.push((at, key)),
            Some(_) => {}
        }
    }

    /// At the close of `f`, the first value it holds that Tiled does not write, named with what
    /// `f` is; a chunk's goes to its layer, which knows its name, a cell's is placed by the
    /// layer's or chunk's width.
    pub(super) fn check_values(&mut self, f: &Frame) -> Result<(), JsonError> {
        let name = f.name.as_deref().unwrap_or_default();
        let ty = f.ty.as_deref();
        let zero = |keys: &[&str]| f.zeros.iter().find(|z| keys.contains(&z.1));
        let (label, zero) = match f.role() {
            Role::Top if matches!(ty, Some("tileset" | "template")) => {
                (format!("the {}", ty.unwrap_or_default()), None)
            }
            Role::Top => {
                // A file without `type` may be an older tileset, whose tile size is 0 in an
                // image collection (and which has no width or height): only a map's is checked.
                let sides: &[&str] = match (f.chunked, ty.is_some()) {
                    (true, true) => &["tilewidth", "tileheight"],
                    (true, false) => &[],
                    (false, true) => &["width", "height", "tilewidth", "tileheight"],
                    (false, false) => &["width", "height"],
                };
                ("the map".to_string(), zero(sides))
            }
            Role::Layer => {
                if f.seen & Key::Type.bit() == 0 && f.bad.is_none() {
                    return Err(value_error(f.start, format!("layer {name:?} has no \"type\"; expected {LAYER_TYPES}, as Tiled writes it")));
                }
                let tiles = ty == Some("tilelayer") && !f.chunked;
                let zero = zero(&["width", "height"]).filter(|_| tiles);
                (format!("layer {name:?}"), zero)
            }
            Role::Chunk => {
                let bad = self.chunk_problem(f);
                let layer = self
                    .stack
                    .iter_mut()
                    .rev()
                    .find(|p| p.role() == Role::Layer);
                if let (Some((at, m)), Some(l)) = (bad, layer) {
                    if l.bad.is_none() {
                        let (x, y) = (f.x.unwrap_or(0), f.y.unwrap_or(0));
                        l.bad = Some((at, format!("chunk at x = {x}, y = {y}: {m}")));
                    }
                }
                return Ok(());
            }
            Role::Object => (
                format!("object {} {name:?}", f.id.as_deref().unwrap_or_default()),
                None,
            ),
            Role::Tile => (
                format!("tile {}", f.id.as_deref().unwrap_or_default()),
                None,
            ),
            Role::Tileset => {
                let label = format!("tileset {name:?}");
                if f.seen & Key::FirstGid.bit() == 0 && f.bad.is_none() {
                    return Err(value_error(f.start, format!("{label} has no \"firstgid\"; expected the gid of its first tile, a whole number from 1 to 4294967295, as Tiled writes it in every tileset of a map or template")));
                }
                (label, None)
            }
            Role::Property => return self.check_property(f),
            Role::Point => ("a point of a polygon or polyline".to_string(), None),
            _ => return Ok(()),
        };
        let bad = (f.bad.clone())
            .or_else(|| zero.map(zero_problem))
            .or_else(|| f.bad_cell.as_ref().map(|c| cell_problem(f, c, (0, 0))));
        match bad {
            Some((at, m)) => Err(value_error(at, format!("{label}: {m}"))),
            None => Ok(()),
        }
    }

    /// A property whose value its type does not read (`"type": "bool", "value": "yes"`), named
    /// with what holds it, at the value's place.
    fn check_property(&self, f: &Frame) -> Result<(), JsonError> {
        let name = f.name.as_deref().unwrap_or_default();
        let holder = self
            .stack
            .iter()
            .rev()
            .find(|p| !p.array && p.role() != Role::Properties);
        let of = match holder {
            Some(h) if h.role() == Role::Top => "the map: ".to_string(),
            Some(h) if h.role() == Role::Layer => {
                format!("layer {:?}: ", h.name.as_deref().unwrap_or_default())
            }
            Some(h) if h.role() == Role::Object => format!(
                "object {} {:?}: ",
                h.id.as_deref().unwrap_or_default(),
                h.name.as_deref().unwrap_or_default()
            ),
            Some(h) if h.role() == Role::Tile => {
                format!("tile {}: ", h.id.as_deref().unwrap_or_default())
            }
            Some(h) if h.role() == Role::Tileset => {
                format!("tileset {:?}: ", h.name.as_deref().unwrap_or_default())
            }
            _ => String::new(),
        };
        if let Some((at, m)) = &f.bad {
            return Err(value_error(*at, format!("{of}property {name:?}: {m}")));
        }
        let (Some(ty), Some((at, found, text))) = (f.ty.as_deref(), &f.value) else {
            return Ok(());
        };
        match property_problem(ty, text) {
            Some(expected) => Err(value_error(
                *at,
                format!(
                "{of}property {name:?} of type {ty:?}: \"value\" is {found}; expected {expected}"
            ),
            )),
            None => Ok(()),
        }
    }

    /// A chunk's first wrong value, size 0 or cell, without its layer's name.
    fn chunk_problem(&self, f: &Frame) -> Option<(Pos, String)> {
        let origin = (f.x.unwrap_or(0), f.y.unwrap_or(0));
        (f.bad.clone())
            .or_else(|| f.zeros.first().map(zero_problem))
            .or_else(|| f.bad_cell.as_ref().map(|c| cell_problem(f, c, origin)))
    }
}

/// A size of 0 where Tiled writes a positive one.
fn zero_problem((at, key): &(Pos, &'static str)) -> (Pos, String) {
    (
        *at,
        format!("{key:?} is 0; expected a positive whole number, as Tiled writes it"),
    )
}

/// A cell that is not a tile id, placed by the width of its layer or chunk `f` from `origin`
/// (a chunk's first cell, Tiled's column and row).
fn cell_problem(
    f: &Frame,
    (at, index, found): &(Pos, u64, String),
    origin: (i64, i64),
) -> (Pos, String) {
    let place = match f.width.filter(|w| *w > 0) {
        Some(w) => format!(
            "cell x = {}, y = {} (column and row from the map's top-left, as Tiled shows them; cell {index} of its data)",
            origin.0.saturating_add((index % w) as i64),
            origin.1.saturating_add((index / w) as i64)
        ),
        None => format!("cell {index} of its data"),
    };
    (*at, format!("{place} is {found}; {CELL_EXPECTED}"))
}

/// A value Tiled does not write where it is, at `at`.
fn value_error(at: Pos, message: String) -> JsonError {
    JsonError::Value {
        line: at.line,
        column: at.column,
        message,
    }
}

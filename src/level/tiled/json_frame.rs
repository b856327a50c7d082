//! What the walk of a Tiled JSON file ([`super::json_walk`]) knows of the value it is in: its
//! role, told by the key it is under (a layer, a chunk, an object, a tileset's tile, a layer's
//! cells, a shape's points, a property), the keys it reads, and what each open array or object
//! has said of itself so far.

use super::json_walk::{unescape, LayerPath, Pos};

/// What a value is to Tiled, told by the key it is under; an array's role says what its
/// elements are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    Other,
    /// The file's top object.
    Top,
    /// A layer: an element of the top's or a layer's (a group's) `layers`.
    Layer,
    /// A chunk of an infinite map's layer.
    Chunk,
    /// An object: of an object layer, of a tile's collision shapes, a template's.
    Object,
    /// A tileset's tile.
    Tile,
    /// A tileset: an element of a map's `tilesets`, or a template's `tileset`.
    Tileset,
    /// A point of a polygon or polyline.
    Point,
    /// `layers`, `chunks`, `objects`, `tilesets`: arrays of layers, chunks, objects, tilesets.
    Layers,
    Chunks,
    Objects,
    Tilesets,
    /// A tileset's `tiles`: an array of tiles, or (older Tiled) an object of them by id.
    Tiles,
    /// A layer's or chunk's `data` array: its cells.
    Cells,
    /// A `properties` value and everything in it: the user's own data (a class property may
    /// hold members named `tiles` or `objects`), never read as the map's structure.
    Properties,
    /// An element of a `properties` array, `{"name", "type", "value"}`: its value is judged by
    /// its type; what it holds is [`Role::Properties`].
    Property,
    /// An object's `polygon` or `polyline`: its points.
    Points,
}

/// The keys the walk reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Key {
    Other,
    Layers,
    Chunks,
    Objects,
    Object,
    Tiles,
    Data,
    Polygon,
    Polyline,
    Width,
    Height,
    X,
    Y,
    Id,
    Name,
    Type,
    Tilesets,
    Tileset,
    Infinite,
    Properties,
    Point,
    Ellipse,
    Visible,
    FirstGid,
    Value,
    Encoding,
    Compression,
}

#[rustfmt::skip]
const KEYS: &[(&str, Key)] = &[
    ("layers", Key::Layers), ("chunks", Key::Chunks), ("objects", Key::Objects),
    ("object", Key::Object), ("tiles", Key::Tiles), ("data", Key::Data),
    ("polygon", Key::Polygon), ("polyline", Key::Polyline), ("width", Key::Width),
    ("height", Key::Height), ("x", Key::X), ("y", Key::Y), ("id", Key::Id),
    ("name", Key::Name), ("type", Key::Type), ("tilesets", Key::Tilesets),
    ("tileset", Key::Tileset), ("infinite", Key::Infinite), ("properties", Key::Properties),
    ("point", Key::Point), ("ellipse", Key::Ellipse), ("visible", Key::Visible),
    ("firstgid", Key::FirstGid), ("value", Key::Value), ("encoding", Key::Encoding),
    ("compression", Key::Compression),
];

/// The key a member's name (with its quotes) is: a long escaped name is none of them.
pub(super) fn key_of(quoted: &[u8]) -> Key {
    let inner = quoted
        .get(1..quoted.len().saturating_sub(1))
        .unwrap_or_default();
    let find = |k: &[u8]| KEYS.iter().find(|(n, _)| n.as_bytes() == k).map(|e| e.1);
    let key = if !inner.contains(&b'\\') {
        find(inner)
    } else if inner.len() <= 128 {
        find(unescape(quoted).as_bytes())
    } else {
        None
    };
    key.unwrap_or(Key::Other)
}

/// An open array or object.
#[derive(Default)]
pub(super) struct Frame {
    pub role: Option<Role>,
    pub array: bool,
    pub start: Pos,
    /// The elements read so far (an array).
    pub count: u64,
    /// The member being read (an object), and its name when the object is `tiles` by id.
    pub key: Option<Key>,
    pub key_text: Option<String>,
    /// What the walk reads of a layer, chunk, object or tile.
    pub id: Option<String>,
    pub name: Option<String>,
    pub ty: Option<String>,
    pub width: Option<u64>,
    pub height: Option<u64>,
    pub x: Option<i64>,
    pub y: Option<i64>,
    /// The cells of a layer's (its chunks' included) or a chunk's data.
    pub cells: u64,
    /// Whether a layer has chunks, or the map (the top) is infinite.
    pub chunked: bool,
    /// The member being read when Tiled writes a number there (`json_values`).
    pub number: Option<&'static str>,
    /// The first value Tiled does not write where it is: its place and what is wrong.
    pub bad: Option<(Pos, String)>,
    /// The first cell of its data that is not a tile id: its place, index and text.
    pub bad_cell: Option<(Pos, u64, String)>,
    /// The sizes that are 0, where they are (positive where Tiled's are, checked at the close).
    pub zeros: Vec<(Pos, &'static str)>,
    /// A layer's first chunk past the limits: where it starts and what is wrong.
    pub bad_chunk: Option<(Pos, String)>,
    /// A layer's place in the map.
    pub path: LayerPath,
    /// The keys read so far (an object), one bit each, to find a member written twice.
    pub seen: u64,
    /// A property's value: where it starts, as an error says it, and its text as the
    /// translation to TMX writes it (a string unescaped, another scalar as written).
    pub value: Option<(Pos, String, String)>,
}

impl Key {
    /// The key's bit in [`Frame::seen`].
    pub(super) fn bit(self) -> u64 {
        1 << (self as u32)
    }
}

impl Frame {
    /// What the array or object is to Tiled.
    pub(super) fn role(&self) -> Role {
        self.role.unwrap_or(Role::Other)
    }
}

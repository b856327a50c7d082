//! The numbers the `tiled` crate parses from a TMX map's attributes, checked first with the
//! same parsers (`u32`, `i32`, `f32`, `bool`, its `Color`), so a bad one is named with its
//! element, line and column instead of the crate's bare "Error parsing attribute 'width'".

use quick_xml::events::{BytesStart, Event};

use super::scan::{attr, ScanError};

/// How the crate parses an attribute.
#[derive(Clone, Copy)]
enum Kind {
    U32,
    /// A tileset's `firstgid`: gid 0 is the empty cell, so a tileset's tiles start at 1.
    FirstGid,
    I32,
    F32,
    Bool,
    Color,
    /// A map's tile size: Tiled's is at least one pixel.
    Pixels,
    /// A `<data>`'s `encoding` and `compression`: what the crate reads.
    Encoding,
    Compression,
}

impl Kind {
    fn accepts(self, v: &str) -> bool {
        match self {
            Kind::U32 => v.parse::<u32>().is_ok(),
            Kind::FirstGid => v.parse::<u32>().is_ok_and(|g| g > 0),
            Kind::I32 => v.parse::<i32>().is_ok(),
            // The crate reads "1e39" and "inf" as infinity, which no place or size can be.
            Kind::F32 => v.parse::<f32>().is_ok_and(f32::is_finite),
            Kind::Bool => v.parse::<bool>().is_ok(),
            Kind::Color => v.parse::<tiled::Color>().is_ok(),
            Kind::Pixels => v.parse::<u32>().is_ok_and(|p| p > 0),
            Kind::Encoding => matches!(v, "csv" | "base64"),
            Kind::Compression => matches!(v, "zlib" | "gzip"),
        }
    }

    fn expected(self) -> &'static str {
        match self {
            Kind::U32 => "a whole number from 0 to 4294967295",
            Kind::FirstGid => "a whole number from 1 to 4294967295 (gid 0 is the empty cell; Tiled starts a map's first tileset at 1)",
            Kind::I32 => "a whole number from -2147483648 to 2147483647",
            Kind::F32 => "a number such as 16, -2.5 or 1e3, finite within f32's range (-3.4e38 to 3.4e38)",
            Kind::Bool => "true or false",
            Kind::Color => "a colour such as #ff8800 or #80ff8800",
            Kind::Pixels => "a whole number of pixels from 1 to 4294967295",
            Kind::Encoding | Kind::Compression => "csv, or base64 with no compression, zlib or gzip, which the tiled crate reads (in Tiled: Map > Map Properties > Tile Layer Format)",
        }
    }
}

use Kind::*;

/// Attributes every layer kind shares (the crate's `LayerData`).
const LAYER: &[(&str, Kind, bool)] = &[
    ("id", U32, false),
    ("opacity", F32, false),
    ("visible", I32, false),
    ("offsetx", F32, false),
    ("offsety", F32, false),
    ("parallaxx", F32, false),
    ("parallaxy", F32, false),
    ("tintcolor", Color, false),
];

/// The numeric attributes the crate parses on element `name` whose parent is `parent`: each
/// with its parser and whether the crate requires it (from tiled 0.16's `get_attrs!` calls).
fn table(name: &[u8], parent: &[u8]) -> (&'static [(&'static str, Kind, bool)], bool) {
    match (name, parent) {
        (b"map", _) => (
            &[
                ("width", U32, true),
                ("height", U32, true),
                ("tilewidth", Pixels, true),
                ("tileheight", Pixels, true),
                ("skewx", I32, false),
                ("skewy", I32, false),
                ("parallaxoriginx", F32, false),
                ("parallaxoriginy", F32, false),
                ("hexsidelength", I32, false),
                ("backgroundcolor", Color, false),
            ],
            false,
        ),
        (b"tileset", _) => (
            &[
                ("firstgid", FirstGid, true),
                ("tilewidth", U32, true),
                ("tileheight", U32, true),
                ("tilecount", U32, false),
                ("spacing", U32, false),
                ("margin", U32, false),
                ("columns", U32, false),
            ],
            false,
        ),
        (b"layer", _) => (&[("width", U32, true), ("height", U32, true)], true),
        (b"objectgroup", _) => (&[("color", Color, false)], true),
        (b"imagelayer" | b"group", _) => (&[], true),
        (b"object", _) => (
            &[
                ("id", U32, false),
                ("gid", U32, false),
                ("x", F32, false),
                ("y", F32, false),
                ("width", F32, false),
                ("height", F32, false),
                ("rotation", F32, false),
                ("opacity", F32, false),
                ("visible", I32, false),
            ],
            false,
        ),
        (b"chunk", _) => (
            &[
                ("x", I32, true),
                ("y", I32, true),
                ("width", U32, true),
                ("height", U32, true),
            ],
            false,
        ),
        (b"tile", b"data" | b"chunk") => (&[("gid", U32, false)], false),
        (b"data", _) => (
            &[
                ("encoding", Encoding, false),
                ("compression", Compression, false),
            ],
            false,
        ),
        (b"tile", b"tileset") => (
            &[
                ("id", U32, true),
                ("probability", F32, false),
                ("x", I32, false),
                ("y", I32, false),
                ("width", I32, false),
                ("height", I32, false),
            ],
            false,
        ),
        (b"image", _) => (
            &[
                ("width", I32, true),
                ("height", I32, true),
                ("trans", Color, false),
            ],
            false,
        ),
        (b"tileoffset", _) => (&[("x", I32, true), ("y", I32, true)], false),
        _ => (&[], false),
    }
}

/// The kind a `<property>`'s value is parsed as, by its `type`.
fn property_kind(e: &BytesStart) -> Option<Kind> {
    value_kind(attr(e, "type").as_deref(), attr(e, "value").as_deref())
}

/// The kind a property of type `ty` holding `value` is parsed as.
fn value_kind(ty: Option<&str>, value: Option<&str>) -> Option<Kind> {
    match ty {
        Some("int") => Some(I32),
        Some("float") => Some(F32),
        Some("bool") => Some(Bool),
        // The crate reads a colour of one character or none as empty.
        Some("color") if value.is_some_and(|v| v.len() > 1) => Some(Color),
        Some("object") => Some(U32),
        _ => None,
    }
}

/// What a property of type `ty` must hold when the crate would refuse `value` (its text as a
/// TMX attribute); `None` when it reads it.
pub(super) fn property_problem(ty: &str, value: &str) -> Option<&'static str> {
    value_kind(Some(ty), Some(value))
        .filter(|k| !k.accepts(value))
        .map(Kind::expected)
}

/// The value types Tiled writes in a `<property>`'s `type`; the crate refuses any other
/// ("Unknown property value type 'bogus'", with no line).
const PROPERTY_TYPES: [&str; 8] = [
    "string", "int", "float", "bool", "color", "file", "object", "class",
];

/// Refuses a `<property>` whose `type` is none of [`PROPERTY_TYPES`], at its column.
fn check_property_type(text: &str, pos: usize, e: &BytesStart) -> Result<(), ScanError> {
    match attr(e, "type") {
        Some(t) if !PROPERTY_TYPES.contains(&t.as_str()) => {
            let (line, column) = line_col(text, attr_offset(text, pos, e, "type"));
            Err(ScanError {
                line,
                column: Some(column),
                message: format!(
                    "{}: attribute \"type\" is {t:?}; expected one of {}",
                    element_name(e, b"property"),
                    PROPERTY_TYPES.join(", ")
                ),
            })
        }
        _ => Ok(()),
    }
}

/// How an element is named in an error: `<map>`, `layer "ground"`, `object 4 "start"`.
fn element_name(e: &BytesStart, name: &[u8]) -> String {
    let tag = String::from_utf8_lossy(name);
    match (attr(e, "id"), attr(e, "name")) {
        (Some(id), Some(n)) if name == b"object" => format!("object {id} {n:?}"),
        (_, Some(n)) if name != b"tile" => format!("{tag} {n:?}"),
        (Some(id), _) if name == b"object" || name == b"tile" => format!("{tag} {id}"),
        _ => format!("<{tag}>"),
    }
}

/// The 1-based line and column of byte offset `at` in `text`.
pub(super) fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text.as_bytes()[..at.min(text.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    (line, before.len() - start + 1)
}

/// The byte offset in `text` of attribute `key` of the element starting at `pos` (the
/// element's own offset if it is not found).
pub(super) fn attr_offset(text: &str, pos: usize, e: &BytesStart, key: &str) -> usize {
    let raw: &[u8] = e;
    let k = key.as_bytes();
    let found = (1..raw.len().saturating_sub(k.len())).find(|&i| {
        raw[i - 1].is_ascii_whitespace()
            && raw[i..].starts_with(k)
            && raw[i + k.len()..]
                .iter()
                .find(|b| !b.is_ascii_whitespace())
                .is_some_and(|&b| b == b'=')
    });
    // `raw` starts just after the element's `<`.
    found.map_or(pos, |i| (pos + 1 + i).min(text.len()))
}

/// Checks every attribute of a TMX map (or tileset) that the crate parses as a number, a
/// colour or a boolean, and that the ones it requires are there.
pub(super) fn check_attributes(text: &str) -> Result<(), ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut stack: Vec<Vec<u8>> = Vec::new();
    let mut layer = String::new();
    loop {
        let pos = reader.buffer_position();
        let (e, empty) = match reader.read_event() {
            // Malformed XML is the crate's to report, with xml_error_line.
            Err(_) | Ok(Event::Eof) => return Ok(()),
            Ok(Event::End(_)) => {
                stack.pop();
                continue;
            }
            Ok(Event::Start(e)) => (e, false),
            Ok(Event::Empty(e)) => (e, true),
            Ok(_) => continue,
        };
        let name = e.name().as_ref().to_vec();
        let parent = stack.last().map_or(&[][..], |p| &p[..]);
        let (attrs, is_layer) = table(&name, parent);
        if is_layer {
            layer = attr(&e, "name").unwrap_or_default();
        }
        if name == b"property" {
            check_property_type(text, pos, &e)?;
        }
        let property = (name == b"property")
            .then(|| property_kind(&e))
            .flatten()
            .map(|k| ("value", k, true));
        let layer_attrs = if is_layer { LAYER } else { &[] };
        // A tileset file's own `<tileset>` has no firstgid; the map's tilesets need one, and
        // one that names its file (`source`) has nothing else.
        let in_file = name == b"tileset" && parent != b"map";
        let by_source = name == b"tileset" && attr(&e, "source").is_some();
        let optional = |key: &str| match key {
            "firstgid" => in_file,
            _ => by_source,
        };
        for &(key, kind, required) in attrs.iter().chain(layer_attrs).chain(property.iter()) {
            let value = attr(&e, key);
            let bad = match &value {
                Some(v) => !kind.accepts(v),
                None => required && !optional(key),
            };
            if !bad {
                continue;
            }
            let (line, column) = line_col(text, attr_offset(text, pos, &e, key));
            let mut place = element_name(&e, &name);
            if matches!(name.as_slice(), b"tile" | b"chunk" | b"data") && !layer.is_empty() {
                place = format!("layer {layer:?}, {place}");
            }
            let found = value.map_or("missing".to_string(), |v| format!("{v:?}"));
            return Err(ScanError {
                line,
                column: Some(column),
                message: format!(
                    "{place}: attribute \"{key}\" is {found}; expected {}",
                    kind.expected()
                ),
            });
        }
        if matches!(name.as_slice(), b"polygon" | b"polyline") {
            check_points(text, pos, &e)?;
        }
        if !empty {
            stack.push(name);
        }
    }
}

/// A polygon's or polyline's `points` as the crate reads them: pairs `x,y` of numbers, one
/// space apart.
fn check_points(text: &str, pos: usize, e: &BytesStart) -> Result<(), ScanError> {
    let Some(points) = attr(e, "points") else {
        return Ok(());
    };
    let bad = points.split(' ').enumerate().find(|(_, p)| {
        let v: Vec<&str> = p.split(',').collect();
        !(v.len() == 2 && v.iter().all(|c| F32.accepts(c)))
    });
    let Some((k, point)) = bad else {
        return Ok(());
    };
    let (line, column) = line_col(text, attr_offset(text, pos, e, "points"));
    Err(ScanError {
        line,
        column: Some(column),
        message: format!(
            "<{}>: attribute \"points\" has point {} {point:?}; expected x,y pairs of finite numbers (within f32's range, -3.4e38 to 3.4e38) one space apart, such as \"0,0 16,0 16,16\"",
            String::from_utf8_lossy(e.name().as_ref()),
            k + 1
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> (usize, Option<usize>, String) {
        let e = check_attributes(text).err().unwrap();
        (e.line, e.column, e.message)
    }

    #[test]
    fn bad_numbers_are_named_where_they_are() {
        let map = |w: &str| {
            format!("<map width=\"{w}\" height=\"5\" tilewidth=\"16\" tileheight=\"16\">\n <layer name=\"g\" width=\"1\" height=\"1\"><data><tile gid=\"x\"/></data></layer></map>")
        };
        let (line, col, m) = err(&map("1O"));
        assert_eq!((line, col), (1, Some(6)), "{m}");
        assert!(m.contains("<map>: attribute \"width\" is \"1O\"; expected a whole number"));
        assert!(err(&map("")).2.contains("is \"\""));
        // The crate's parsers: no sign for u32 but '+', no spaces.
        assert!(check_attributes(&map("+10")).is_err_and(|e| e.line == 2));
        assert!(err(&map(" 10")).2.contains("\" 10\""));
        let (line, col, m) = err(&map("10"));
        assert_eq!((line, col), (2, Some(51)), "{m}");
        assert!(
            m.contains("layer \"g\", <tile>: attribute \"gid\" is \"x\""),
            "{m}"
        );
        let p = "<map width=\"1\" height=\"1\" tilewidth=\"1\" tileheight=\"1\"><properties><property name=\"n\" type=\"int\" value=\"zz\"/><property name=\"c\" type=\"color\" value=\"\"/></properties></map>";
        assert!(err(p)
            .2
            .contains("property \"n\": attribute \"value\" is \"zz\""));
        let o = "<map width=\"1\" height=\"1\" tilewidth=\"1\" tileheight=\"1\"><objectgroup name=\"o\" opacity=\"x\"/></map>";
        assert!(err(o)
            .2
            .contains("objectgroup \"o\": attribute \"opacity\""));
        let t = "<map width=\"1\" height=\"1\" tilewidth=\"1\" tileheight=\"1\"><tileset firstgid=\"1\" source=\"a.tsx\"/><tileset source=\"b.tsx\"/></map>";
        assert!(err(t).2.contains("\"firstgid\" is missing"));
        let p = "<map width=\"1\" height=\"1\" tilewidth=\"1\" tileheight=\"1\"><objectgroup><object id=\"2\"><polygon points=\"0,0 1,a 2,2\"/></object></objectgroup></map>";
        assert!(err(p).2.contains("has point 2 \"1,a\""));
    }
}

//! A look at a map's XML before the `tiled` crate reads it, for what that crate would turn into
//! a huge allocation or a panic: the map's declared size (checked against
//! [`limits::MAX_TILES`] before anything is allocated for it), and each tile layer's data,
//! and each chunk of an infinite map's layer, which must hold exactly one cell per cell (the
//! crate indexes a short layer out of bounds, and inflates a compressed layer without a bound),
//! each cell a tile id and base64 as the crate decodes it: what the crate would report with no
//! layer or line ("invalid digit found in string", "Invalid symbol 64, offset 0.",
//! "Invalid tile found in map being parsed") is named here with both.

use quick_xml::events::{BytesStart, Event};

use super::base64::{base64_decode, not_base64, read_cells};
use super::elements::count_element;
use super::gids::no_tileset;
use crate::limits;

/// What is wrong with the map, and the 1-based line where it is.
pub(super) struct ScanError {
    /// The line of the element at fault.
    pub line: usize,
    /// The 1-based column (in bytes) of the attribute at fault, where one is.
    pub column: Option<usize>,
    /// What was found and what was expected.
    pub message: String,
}

/// An attribute's value, unescaped (the first, should the name be repeated). Read without
/// quick-xml's duplicate check, which compares each attribute with every one before it.
pub(super) fn attr(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .with_checks(false)
        .filter_map(|a| a.ok())
        .find(|a| a.key.as_ref() == name.as_bytes())
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
}

/// The line of byte offset `pos` in `text`.
pub(super) fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// Lines of byte offsets asked for in increasing order, each counting only the newlines since
/// the one before (a scan asking every layer's and chunk's line from the file's start was
/// quadratic: 40,000 layers took more than 120 s).
struct Lines<'t> {
    text: &'t [u8],
    pos: usize,
    line: usize,
}

impl<'t> Lines<'t> {
    fn new(text: &'t str) -> Self {
        Lines {
            text: text.as_bytes(),
            pos: 0,
            line: 1,
        }
    }

    /// The line of byte offset `pos` (from the start again should `pos` go back).
    fn at(&mut self, pos: usize) -> usize {
        let pos = pos.min(self.text.len());
        if pos < self.pos {
            (self.pos, self.line) = (0, 1);
        }
        self.line += self.text[self.pos..pos]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = pos;
        self.line
    }
}

/// The tile layer whose `<data>` is being read, or one chunk of an infinite map's layer.
pub(super) struct Data {
    /// `layer "NAME"`, or `layer "NAME", chunk at x = X, y = Y`.
    pub(super) place: String,
    /// `layer` or `chunk`.
    unit: &'static str,
    cells: u64,
    /// The layer's or chunk's width, and the Tiled cell of its first cell, to place a cell.
    width: u64,
    origin: (i64, i64),
    encoding: Option<String>,
    compression: Option<String>,
    pub(super) line: usize,
    pub(super) text: String,
    chunked: bool,
    /// The lowest `firstgid` of the map's tilesets (`None`: the map has none).
    first_gid: Option<u32>,
}

/// The line of the first XML syntax error in `text`, if it has one.
pub(super) fn xml_error_line(text: &str) -> Option<usize> {
    let mut reader = quick_xml::Reader::from_str(text);
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => return None,
            Ok(_) => {}
            Err(_) => return Some(line_of(text, reader.buffer_position())),
        }
    }
}

/// The name of the document's root element and its byte offset (`None` if the XML is broken
/// before it, which the crate reports).
pub(super) fn root_element(text: &str) -> Option<(String, usize)> {
    let mut reader = quick_xml::Reader::from_str(text);
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e) | Event::Empty(e)) => {
                return Some((String::from_utf8_lossy(e.name().as_ref()).into_owned(), pos))
            }
            Ok(Event::Eof) | Err(_) => return None,
            Ok(_) => {}
        }
    }
}

/// Checks the map's size, every tile layer's data length and the points of every polygon and
/// polyline ([`super::points`]), and returns the `source` of each
/// external tileset. The XML's own errors are left to the `tiled` crate (and
/// [`xml_error_line`]).
pub(super) fn scan_map(text: &str) -> Result<Vec<String>, ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut layer: Option<(String, u64, u64)> = None;
    let mut data: Option<Data> = None;
    let mut chunk: Option<Data> = None;
    let mut sources = Vec::new();
    let mut shapes = super::points::Shapes::default();
    // Cells of every tile layer so far (width x height each), against MAX_LAYER_CELLS.
    let mut cells_read: u64 = 0;
    // Elements other than a layer's cells, against MAX_JSON_OBJECTS.
    let mut elements: u64 = 0;
    let mut lines = Lines::new(text);
    // The lowest firstgid of the map's tilesets: a gid below it is in no tileset.
    let mut first_gid: Option<u32> = None;
    let mut depth = 0usize;
    loop {
        let pos = reader.buffer_position();
        let event = match reader.read_event() {
            Ok(e) => e,
            // Malformed XML: the tiled crate reports it, and xml_error_line finds the line.
            Err(_) => return Ok(sources),
        };
        let empty = matches!(event, Event::Empty(_));
        match &event {
            Event::Start(e) if e.name().as_ref() != b"map" || depth > 0 => depth += 1,
            Event::End(_) => depth = depth.saturating_sub(1),
            _ => {}
        }
        match &event {
            Event::Start(e) | Event::Empty(e) => {
                count_element(&mut elements, e, data.is_some(), "the map", || {
                    line_of(text, pos)
                })?;
                shapes.element(e, empty, || line_of(text, pos))?;
            }
            Event::End(e) => shapes.end(e.name().as_ref()),
            _ => {}
        }
        match event {
            Event::Eof => return Ok(sources),
            Event::Start(e) | Event::Empty(e) => match e.name().as_ref() {
                b"tileset" => {
                    if let Some(s) = attr(&e, "source") {
                        sources.push(s);
                    }
                    // A map's own tileset (depth 1 once it is open), not a template's.
                    if depth == usize::from(!empty) {
                        let f = attr(&e, "firstgid").and_then(|v| v.parse::<u32>().ok());
                        first_gid = first_gid.min(f).or(first_gid).or(f);
                    }
                }
                b"object" => {
                    if let Some(g) = attr(&e, "gid").and_then(|v| v.parse::<u32>().ok()) {
                        if let Some(why) = no_tileset(g, first_gid) {
                            let id = attr(&e, "id").unwrap_or_default();
                            let name = attr(&e, "name").unwrap_or_default();
                            return Err(ScanError {
                                column: None,
                                line: line_of(text, pos),
                                message: format!("object {id} {name:?}: its tile is {why}"),
                            });
                        }
                    }
                }
                b"map" => {
                    let dim = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                    if let (Some(w), Some(h)) = (dim("width"), dim("height")) {
                        if w.saturating_mul(h) > limits::MAX_TILES {
                            return Err(ScanError {
                                column: None,
                                line: line_of(text, pos),
                                message: format!(
                                    "the map is {w} x {h} tiles; expected at most {} tiles (checked before reading its layers)",
                                    limits::MAX_TILES
                                ),
                            });
                        }
                    }
                }
                b"layer" => {
                    let dim = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                    let name = attr(&e, "name").unwrap_or_default();
                    let (w, h) = (dim("width").unwrap_or(0), dim("height").unwrap_or(0));
                    if w.saturating_mul(h) > limits::MAX_TILES {
                        return Err(ScanError {
                            column: None,
                            line: line_of(text, pos),
                            message: format!(
                                "layer {name:?} is {w} x {h} tiles; expected at most {} tiles",
                                limits::MAX_TILES
                            ),
                        });
                    }
                    cells_read = cells_read.saturating_add(w * h);
                    if cells_read > limits::MAX_LAYER_CELLS {
                        return Err(ScanError {
                            column: None,
                            line: line_of(text, pos),
                            message: format!(
                                "layer {name:?} ({w} x {h} tiles) brings the map's tile layers to {cells_read} cells together; expected at most {} (each layer's cells are held while the map is read)",
                                limits::MAX_LAYER_CELLS
                            ),
                        });
                    }
                    layer = Some((name, w * h, w));
                }
                b"data" => {
                    if let Some((name, cells, width)) = &layer {
                        data = Some(Data {
                            place: format!("layer {name:?}"),
                            unit: "layer",
                            cells: *cells,
                            width: *width,
                            origin: (0, 0),
                            encoding: attr(&e, "encoding"),
                            compression: attr(&e, "compression"),
                            line: lines.at(pos),
                            text: String::new(),
                            chunked: false,
                            first_gid,
                        });
                    }
                }
                b"chunk" => {
                    // An infinite map's chunk: checked on its own, as the crate reads it.
                    if let Some(d) = &mut data {
                        d.chunked = true;
                        let at = |key: &str| {
                            super::attrs::line_col(
                                text,
                                super::attrs::attr_offset(text, pos, &e, key),
                            )
                        };
                        let c = chunk_data(d, &e, lines.at(pos), at)?;
                        if empty {
                            check_data(&c)?;
                        } else {
                            chunk = Some(c);
                        }
                    }
                }
                b"tile" => {
                    // The old XML cell encoding: the crate checks it itself.
                    if let Some(d) = &mut data {
                        d.chunked = true;
                    }
                }
                _ => {}
            },
            Event::Text(t) => {
                if let Some(d) = chunk.as_mut().or(data.as_mut()) {
                    if let Ok(s) = t.unescape() {
                        d.text.push_str(&s);
                    }
                }
            }
            Event::CData(c) => {
                if let Some(d) = chunk.as_mut().or(data.as_mut()) {
                    d.text.push_str(&String::from_utf8_lossy(&c.into_inner()));
                }
            }
            Event::End(e) => match e.name().as_ref() {
                b"data" => {
                    if let Some(d) = data.take() {
                        check_data(&d)?;
                    }
                }
                b"chunk" => {
                    if let Some(c) = chunk.take() {
                        check_data(&c)?;
                    }
                }
                b"layer" => layer = None,
                _ => {}
            },
            _ => {}
        }
    }
}

/// A chunk of the layer whose data is `d`, from its `<chunk>` element at `line` (`at` gives
/// the line and column of one of its attributes): at most [`limits::MAX_TILES`] cells, so its
/// data is inflated no further than that.
fn chunk_data(
    d: &Data,
    e: &BytesStart,
    line: usize,
    at: impl Fn(&str) -> (usize, usize),
) -> Result<Data, ScanError> {
    let int = |n: &str| attr(e, n).and_then(|v| v.trim().parse::<i64>().ok());
    let (x, y) = (int("x").unwrap_or(0), int("y").unwrap_or(0));
    let place = format!("{}, chunk at x = {x}, y = {y}", d.place);
    let (w, h) = (int("width").unwrap_or(0), int("height").unwrap_or(0));
    if w < 1 || h < 1 {
        let (line, column) = at(if w < 1 { "width" } else { "height" });
        return Err(ScanError {
            column: Some(column),
            line,
            message: format!("{place}: the chunk is {w} x {h} tiles; expected a width and height of at least 1 (Tiled writes chunks of 16 x 16 tiles)"),
        });
    }
    let (w, h) = (w as u64, h as u64);
    // Tiled's cells are i32: a chunk reaching past them is dropped by the reader, which then
    // finds no chunk at all.
    let fits = |at: i64, len: u64| at >= i32::MIN as i64 && at + len as i64 <= i32::MAX as i64;
    if !(fits(x, w) && fits(y, h)) {
        let (line, column) = at(if fits(x, w) { "y" } else { "x" });
        return Err(ScanError {
            column: Some(column),
            line,
            message: format!(
                "{place}: the chunk ({w} x {h} tiles) reaches beyond Tiled's cell coordinates; expected chunks within -2147483648 to 2147483646"
            ),
        });
    }
    if w.saturating_mul(h) > limits::MAX_TILES {
        let (line, column) = at("width");
        return Err(ScanError {
            column: Some(column),
            line,
            message: format!(
                "{place}: the chunk is {w} x {h} tiles; expected at most {} tiles",
                limits::MAX_TILES
            ),
        });
    }
    Ok(Data {
        place,
        unit: "chunk",
        cells: w * h,
        width: w,
        origin: (x, y),
        encoding: d.encoding.clone(),
        compression: d.compression.clone(),
        line,
        text: String::new(),
        chunked: false,
        first_gid: d.first_gid,
    })
}

/// Whether a layer's (or chunk's) data holds one cell per cell of the layer.
fn check_data(d: &Data) -> Result<(), ScanError> {
    if d.chunked {
        return Ok(());
    }
    let err = |found: String| {
        ScanError {
        column: None,
        line: d.line,
        message: format!(
            "{}: its data holds {found}; expected exactly {} cells, one per cell of the {} (was the file cut short, or the {} resized by hand?)",
            d.place, d.cells, d.unit, d.unit
        ),
    }
    };
    match (d.encoding.as_deref(), d.compression.as_deref()) {
        (Some("csv"), None) => {
            // No text is no cells (a 0 x 0 layer of an infinite map, as Tiled writes it).
            let n = match d.text.trim() {
                "" => 0,
                t => t.split(',').count() as u64,
            };
            if n != d.cells {
                return Err(err(format!("{n} comma-separated cells")));
            }
            if n > 0 {
                csv_cells(d)?;
            }
        }
        (Some("base64"), compression) => {
            // The crate trims the data and reads no whitespace inside it.
            let inner_space = d.text.trim().contains(|c: char| c.is_ascii_whitespace());
            let Some(bytes) = base64_decode(&d.text).filter(|_| !inner_space) else {
                return Err(not_base64(d));
            };
            let expected = d.cells.saturating_mul(4);
            let bad = |gid| no_tileset(gid, d.first_gid);
            let (len, first_bad, broke) = match compression {
                None => read_cells(&bytes[..], expected, bad),
                Some("zlib") => {
                    read_cells(flate2::read::ZlibDecoder::new(&bytes[..]), expected, bad)
                }
                Some("gzip") => read_cells(flate2::read::GzDecoder::new(&bytes[..]), expected, bad),
                // zstd and unknown compressions: the crate refuses them.
                Some(_) => return Ok(()),
            };
            if let (Some(e), Some(c)) = (broke, compression) {
                return Err(ScanError {
                    column: None,
                    line: d.line,
                    message: format!(
                        "{}: its {c}-compressed data is corrupt: it inflates to {len} bytes, then {e}; expected {c} data that inflates to {} cells of 4 bytes (was the file cut short or edited by hand?)",
                        d.place, d.cells
                    ),
                });
            }
            if len != expected {
                let found = if len > expected {
                    format!("more than {expected} bytes ({} cells)", d.cells)
                } else {
                    format!("{len} bytes ({} cells of 4 bytes)", len / 4)
                };
                return Err(err(found));
            }
            if let Some((k, why)) = first_bad {
                let data = match compression {
                    Some(c) => format!("{c}-compressed base64 data"),
                    None => "base64 data".to_string(),
                };
                return Err(cell_error(d, d.line, k, &data, &why));
            }
        }
        _ => {}
    }
    Ok(())
}

/// What a CSV cell must be.
const TILE_ID: &str = "expected a tile id, a whole number from 0 (no tile) to 4294967295 (a global tile id with its flip bits)";

/// Checks that each cell of a CSV layer is a tile id, as the crate parses it (a `u32`), so a
/// bad cell is named with its layer, line and place instead of the crate's bare "invalid digit
/// found in string".
fn csv_cells(d: &Data) -> Result<(), ScanError> {
    // The data's text starts on the line of its `<data>` element.
    let mut line = d.line;
    for (k, cell) in d.text.split(',').enumerate() {
        let value = cell.trim();
        // Parsed once: a tile id the crate reads, in one of the map's tilesets.
        // A gid in no tileset is said of the layer's "data": a JSON map's array and the XML
        // cell encoding reach here as CSV too.
        let (what, why) = match value.parse::<u32>() {
            Ok(gid) => ("data", no_tileset(gid, d.first_gid)),
            Err(_) if value.is_empty() => ("CSV data", Some(format!("empty; {TILE_ID}"))),
            Err(_) if value.bytes().all(|b| b.is_ascii_digit()) => (
                "CSV data",
                Some(format!("{value}, more than 4294967295; {TILE_ID}")),
            ),
            Err(_) => ("CSV data", Some(format!("{value:?}; {TILE_ID}"))),
        };
        if let Some(why) = why {
            let lead = cell.len() - cell.trim_start().len();
            let line = line + cell[..lead].matches('\n').count();
            return Err(cell_error(d, line, k as u64, what, &why));
        }
        line += cell.matches('\n').count();
    }
    Ok(())
}

/// Cell `k` of `d`'s data (`what`: `CSV data`, `base64 data`, …) is wrong, as `why` says; the
/// cell is placed in Tiled's columns and rows.
fn cell_error(d: &Data, line: usize, k: u64, what: &str, why: &str) -> ScanError {
    ScanError {
        column: None,
        line,
        message: format!(
            "{}: cell {} (x = {}, y = {}) of its {what} is {why}",
            d.place,
            k + 1,
            d.origin.0 + (k % d.width.max(1)) as i64,
            d.origin.1 + (k / d.width.max(1)) as i64,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(w: u32, h: u32, data: &str, encoding: &str) -> String {
        format!(
            "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"{w}\" height=\"{h}\" tilewidth=\"16\" tileheight=\"16\"><tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\"/>\n<layer id=\"1\" name=\"ground\" width=\"{w}\" height=\"{h}\">\n<data {encoding}>{data}</data>\n</layer>\n</map>\n"
        )
    }

    #[test]
    fn short_and_oversized_layers_and_maps_are_found() {
        assert!(scan_map(&map(2, 2, "1,1,1,1", "encoding=\"csv\"")).is_ok());
        let e = scan_map(&map(2, 2, "1,1,1", "encoding=\"csv\""))
            .err()
            .unwrap();
        assert!(
            e.message.contains("3 comma-separated cells"),
            "{}",
            e.message
        );
        assert_eq!(e.line, 4);
        // 4 cells of 4 bytes: 16 bytes, "AQAAAAEAAAABAAAAAQAAAA==" in base64.
        let ok = map(2, 2, "AQAAAAEAAAABAAAAAQAAAA==", "encoding=\"base64\"");
        assert!(scan_map(&ok).is_ok());
        let short = map(2, 2, "AQAAAAEAAAABAAAA", "encoding=\"base64\"");
        assert!(scan_map(&short).is_err());
        // Cells the crate would refuse with a bare "invalid digit found in string", named.
        let e = scan_map(&map(2, 2, "1,\n1,x,1", "encoding=\"csv\""))
            .err()
            .unwrap();
        assert_eq!(e.line, 5, "{}", e.message);
        assert!(
            e.message
                .contains("cell 3 (x = 0, y = 1) of its CSV data is \"x\""),
            "{}",
            e.message
        );
        let e = scan_map(&map(2, 2, "1,1,,1", "encoding=\"csv\""))
            .err()
            .unwrap();
        assert!(
            e.message
                .contains("cell 3 (x = 0, y = 1) of its CSV data is empty"),
            "{}",
            e.message
        );
        let e = scan_map(&map(2, 2, "1,1,1,4294967296", "encoding=\"csv\""))
            .err()
            .unwrap();
        assert!(e.message.contains("more than 4294967295"), "{}", e.message);
        // Base64 the crate would refuse with "Invalid symbol 64, offset 0.", named.
        for (data, found) in [
            ("@QAAAAEAAAABAAAAAQAAAA==", "'@' at character 1"),
            ("AQAAAAEAAAAB AAAAAQAAAA==", "' ' at character 13"),
            ("AQAAAAEAAAABAAAAAQAAAA=", "not a multiple of 4"),
            ("AQ==AAEAAAABAAAAAQAAAA==", "'=' padding at character 3"),
            ("AQAAAAEAAAABAAAAAQAAAB==", "unused bits"),
        ] {
            let e = scan_map(&map(2, 2, data, "encoding=\"base64\""))
                .err()
                .unwrap();
            assert!(e.message.contains(found), "{data}: {}", e.message);
            assert!(e.message.contains("layer \"ground\""), "{}", e.message);
        }
        // An infinite map's chunk short of its cells, and a bad cell in one, placed in Tiled's
        // cells.
        let chunk = |data: &str| {
            map(
                2,
                2,
                &format!("<chunk x=\"-16\" y=\"0\" width=\"2\" height=\"2\">{data}</chunk>"),
                "encoding=\"csv\"",
            )
        };
        assert!(scan_map(&chunk("1,1,1,1")).is_ok());
        let e = scan_map(&chunk("1,1,1")).err().unwrap();
        assert!(
            e.message
                .contains("chunk at x = -16, y = 0: its data holds 3"),
            "{}",
            e.message
        );
        let e = scan_map(&chunk("1,1,1,y")).err().unwrap();
        assert!(e.message.contains("(x = -15, y = 1)"), "{}", e.message);
        let huge = map(100_000, 100_000, "", "encoding=\"csv\"");
        let e = scan_map(&huge).err().unwrap();
        assert!(e.message.contains("100000 x 100000"), "{}", e.message);
    }
}

//! Where Tiled itself is tolerant and the `tiled` crate is not, the map and tileset text is made
//! into what the crate reads before it reads it: a tileset without `tilecount` (older Tiled
//! versions) gets one computed from its image or its tiles, a tile layer in the old XML cell
//! encoding (`<tile gid=".."/>` per cell) becomes CSV, and a JSON map, tileset or template
//! becomes its XML twin ([`super::json`]). Each change is a note the import passes on as a warning.

use quick_xml::events::Event;

use super::scan::{attr, line_of, ScanError};
use crate::limits;

/// The text the crate reads, and what was changed.
pub(super) struct Normalized {
    /// The text to hand to the crate.
    pub text: String,
    /// What was changed, one note each.
    pub notes: Vec<String>,
}

/// A tileset element being read: what a missing `tilecount` is computed from.
pub(super) struct TilesetInfo {
    pub(super) name: String,
    /// Byte offset just after `<tileset`, where a computed attribute goes.
    pub(super) insert_at: usize,
    pub(super) tilecount: Option<u64>,
    pub(super) tile_width: u64,
    pub(super) tile_height: u64,
    pub(super) spacing: u64,
    pub(super) margin: u64,
    pub(super) image: Option<(u64, u64)>,
    pub(super) max_id: Option<u64>,
    pub(super) line: usize,
    pub(super) depth: usize,
}

/// The number of tiles of an image tileset (columns x rows that fit, as Tiled counts them), or
/// of an image collection (highest tile id + 1).
pub(super) fn count_tiles(t: &TilesetInfo) -> u64 {
    match t.image {
        Some((w, h)) => {
            let fit = |size: u64, tile: u64| {
                if tile == 0 {
                    0
                } else {
                    (size.saturating_sub(2 * t.margin) + t.spacing) / (tile + t.spacing)
                }
            };
            fit(w, t.tile_width) * fit(h, t.tile_height)
        }
        None => t.max_id.map_or(0, |m| m + 1),
    }
}

/// A tile layer in the old XML cell encoding being made CSV: each `<tile gid=".."/>` a cell,
/// and in an infinite map each `<chunk>` a CSV chunk of its own.
struct XmlData {
    layer: String,
    /// Byte offset of `<data`.
    start: usize,
    /// The data's content as CSV so far.
    csv: String,
    /// Cells in the current chunk (or the layer) so far.
    cells: u64,
}

impl XmlData {
    fn push(&mut self, gid: &str) {
        if self.cells > 0 {
            self.csv.push(',');
        }
        self.csv.push_str(gid.trim());
        self.cells += 1;
    }

    /// Starts a chunk whose attributes (`x`, `y`, `width`, `height`) are `attrs`, as written.
    fn open_chunk(&mut self, attrs: &str) {
        self.csv.push_str("<chunk");
        self.csv.push_str(attrs);
        self.csv.push('>');
        self.cells = 0;
    }

    fn close_chunk(&mut self) {
        self.csv.push_str("</chunk>");
        self.cells = 0;
    }
}

/// Makes a map's or tileset's XML readable by the crate (see the module docs). XML errors are
/// left to the crate; what the crate would allocate without bound (a tilecount beyond
/// [`limits::MAX_TILES`]) is an error with its line.
pub(super) fn normalize_xml(text: &str) -> Result<Normalized, ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let mut notes = Vec::new();
    let mut stack: Vec<Vec<u8>> = Vec::new();
    let mut tileset: Option<TilesetInfo> = None;
    // An XML-encoded layer: its name, the start of its <data>, and its cells as CSV so far
    // (an infinite map's chunks each with their own CSV).
    let mut xml_data: Option<XmlData> = None;
    let mut layer_name = String::new();
    loop {
        let pos = reader.buffer_position();
        let event = match reader.read_event() {
            Ok(e) => e,
            Err(_) => break,
        };
        let (e, empty) = match &event {
            Event::Eof => break,
            Event::Start(e) => (Some(e.clone()), false),
            Event::Empty(e) => (Some(e.clone()), true),
            Event::End(end) => {
                let name = end.name().as_ref().to_vec();
                stack.pop();
                if name == b"tileset" {
                    close_tileset(&mut tileset, stack.len(), &mut edits, &mut notes)?;
                }
                if name == b"chunk" {
                    if let Some(d) = &mut xml_data {
                        d.close_chunk();
                    }
                }
                if name == b"data" {
                    if let Some(d) = xml_data.take() {
                        let end_pos = reader.buffer_position();
                        let lines = text[d.start..end_pos].matches('\n').count();
                        edits.push((
                            d.start,
                            end_pos,
                            format!(
                                "<data encoding=\"csv\">{}{}</data>",
                                d.csv,
                                "\n".repeat(lines)
                            ),
                        ));
                        notes.push(format!("layer {:?} is in the old XML cell encoding; read as CSV (Tiled: Map > Map Properties > Tile Layer Format to change it)", d.layer));
                    }
                }
                continue;
            }
            _ => continue,
        };
        let Some(e) = e else { continue };
        let name = e.name().as_ref().to_vec();
        let parent = stack.last().cloned();
        match name.as_slice() {
            b"tileset" if attr(&e, "source").is_none() => {
                let num = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                tileset = Some(TilesetInfo {
                    name: attr(&e, "name").unwrap_or_default(),
                    insert_at: pos + "<tileset".len(),
                    tilecount: num("tilecount"),
                    tile_width: num("tilewidth").unwrap_or(0),
                    tile_height: num("tileheight").unwrap_or(0),
                    spacing: num("spacing").unwrap_or(0),
                    margin: num("margin").unwrap_or(0),
                    image: None,
                    max_id: None,
                    line: line_of(text, pos),
                    depth: stack.len(),
                });
                if empty {
                    close_tileset(&mut tileset, stack.len(), &mut edits, &mut notes)?;
                }
            }
            b"image" if parent.as_deref() == Some(b"tileset") => {
                if let Some(t) = &mut tileset {
                    let num = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                    if let (Some(w), Some(h)) = (num("width"), num("height")) {
                        t.image = Some((w, h));
                    }
                }
            }
            b"tile" if parent.as_deref() == Some(b"tileset") => {
                if let Some(t) = &mut tileset {
                    if let Some(id) = attr(&e, "id").and_then(|v| v.trim().parse::<u64>().ok()) {
                        t.max_id = Some(t.max_id.map_or(id, |m| m.max(id)));
                    }
                }
            }
            b"tile" if matches!(parent.as_deref(), Some(b"data" | b"chunk")) => {
                if let Some(d) = &mut xml_data {
                    let gid = attr(&e, "gid").unwrap_or_else(|| "0".into());
                    if gid.trim().parse::<u32>().is_err() {
                        return Err(ScanError {
                            line: line_of(text, pos),
                            message: format!(
                                "layer {:?}: a <tile> cell has gid=\"{gid}\"; expected a tile id, a whole number from 0 (no tile) to 4294967295 (a global tile id with its flip bits)",
                                d.layer
                            ),
                        });
                    }
                    d.push(&gid);
                }
            }
            b"chunk" if xml_data.is_some() => {
                if let Some(d) = &mut xml_data {
                    d.open_chunk(&String::from_utf8_lossy(e.attributes_raw()));
                    if empty {
                        d.close_chunk();
                    }
                }
            }
            b"layer" => layer_name = attr(&e, "name").unwrap_or_default(),
            b"data" if !empty && attr(&e, "encoding").is_none() => {
                xml_data = Some(XmlData {
                    layer: layer_name.clone(),
                    start: pos,
                    csv: String::new(),
                    cells: 0,
                });
            }
            _ => {}
        }
        if !empty {
            stack.push(name);
        }
    }
    if edits.is_empty() {
        return Ok(Normalized {
            text: text.to_string(),
            notes,
        });
    }
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (start, end, with) in edits {
        if start < at {
            continue;
        }
        out.push_str(&text[at..start]);
        out.push_str(&with);
        at = end;
    }
    out.push_str(&text[at..]);
    Ok(Normalized { text: out, notes })
}

fn close_tileset(
    tileset: &mut Option<TilesetInfo>,
    depth: usize,
    edits: &mut Vec<(usize, usize, String)>,
    notes: &mut Vec<String>,
) -> Result<(), ScanError> {
    let Some(t) = tileset.take_if(|t| t.depth == depth) else {
        return Ok(());
    };
    let count = match t.tilecount {
        Some(c) => c,
        None => {
            let c = count_tiles(&t);
            edits.push((t.insert_at, t.insert_at, format!(" tilecount=\"{c}\"")));
            notes.push(format!(
                "tileset {:?} has no tilecount (written by an older Tiled); {c} computed from its {}",
                t.name,
                if t.image.is_some() { "image" } else { "tiles" }
            ));
            c
        }
    };
    if count > limits::MAX_TILES {
        return Err(ScanError {
            line: t.line,
            message: format!(
                "tileset {:?} has {count} tiles; expected at most {} (the most tiles platbench reads)",
                t.name,
                limits::MAX_TILES
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_tilecount_is_computed_from_the_image() {
        // A 64 x 32 image of 16 px tiles: 4 columns x 2 rows.
        let t = "<map><tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\"><image source=\"a.png\" width=\"64\" height=\"32\"/></tileset></map>";
        let n = normalize_xml(t).ok().unwrap();
        assert!(
            n.text.contains("<tileset tilecount=\"8\" firstgid"),
            "{}",
            n.text
        );
        // An image collection: highest id + 1.
        let t = "<tileset name=\"c\" tilewidth=\"16\" tileheight=\"16\"><tile id=\"0\"/><tile id=\"4\"/></tileset>";
        assert!(normalize_xml(t)
            .ok()
            .unwrap()
            .text
            .contains("tilecount=\"5\""));
    }

    #[test]
    fn xml_cells_become_csv_on_the_same_lines() {
        let t = "<map><layer name=\"g\" width=\"2\" height=\"1\"><data>\n<tile gid=\"1\"/>\n<tile/>\n</data></layer></map>";
        let n = normalize_xml(t).ok().unwrap();
        assert!(
            n.text.contains("<data encoding=\"csv\">1,0\n\n\n</data>"),
            "{}",
            n.text
        );
    }
}

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

/// A tile layer in the old XML cell encoding (`<tile gid=".."/>` per cell), being read.
struct XmlData {
    layer: String,
    /// Where its `<data>` starts and its start tag ends.
    start: usize,
    tag_end: usize,
    /// The gids of the layer, or of the chunk being read.
    gids: Vec<String>,
    /// Whether it holds chunks (an infinite map's layer), each made CSV on its own.
    chunked: bool,
    /// Where the open chunk's content starts.
    chunk: Option<usize>,
}

/// `gids` as CSV followed by as many line breaks as `was` held, so later lines keep their
/// numbers.
fn csv_on_lines(gids: &[String], was: &str) -> String {
    format!(
        "{}{}",
        gids.join(","),
        "\n".repeat(was.matches('\n').count())
    )
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
                    if let Some(x) = &mut xml_data {
                        if let Some(start) = x.chunk.take() {
                            // A chunk's cells become CSV inside it, on the same lines.
                            let end = pos;
                            edits.push((start, end, csv_on_lines(&x.gids, &text[start..end])));
                            x.gids.clear();
                        }
                    }
                }
                if name == b"data" {
                    if let Some(x) = xml_data.take() {
                        let end_pos = reader.buffer_position();
                        if x.chunked {
                            edits.push((x.start, x.tag_end, "<data encoding=\"csv\">".into()));
                        } else {
                            let inner = csv_on_lines(&x.gids, &text[x.start..end_pos]);
                            edits.push((
                                x.start,
                                end_pos,
                                format!("<data encoding=\"csv\">{inner}</data>"),
                            ));
                        }
                        notes.push(format!("layer {:?} is in the old XML cell encoding; read as CSV (Tiled: Map > Map Properties > Tile Layer Format to change it)", x.layer));
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
                if let Some(x) = &mut xml_data {
                    x.gids.push(attr(&e, "gid").unwrap_or_else(|| "0".into()));
                }
            }
            b"chunk" if !empty => {
                if let Some(x) = &mut xml_data {
                    x.chunked = true;
                    x.chunk = Some(reader.buffer_position());
                }
            }
            // Tiled writes a colour property left unset as value=""; the crate refuses a colour
            // that short, so it is read as the empty string it is (platbench reads no colour).
            b"property"
                if attr(&e, "type").as_deref() == Some("color")
                    && attr(&e, "value").is_some_and(|v| v.chars().count() <= 1) =>
            {
                let tag = &text[pos..reader.buffer_position()];
                if let Some(at) = tag
                    .find("type=\"color\"")
                    .or_else(|| tag.find("type='color'"))
                {
                    let colour = pos + at + "type=\"".len();
                    edits.push((colour, colour + "color".len(), "string".into()));
                    let name = attr(&e, "name").unwrap_or_default();
                    notes.push(format!("property {name:?} is a colour left unset (value \"\"); read as an empty string"));
                }
            }
            b"layer" => layer_name = attr(&e, "name").unwrap_or_default(),
            b"data" if !empty && attr(&e, "encoding").is_none() => {
                xml_data = Some(XmlData {
                    layer: layer_name.clone(),
                    start: pos,
                    tag_end: reader.buffer_position(),
                    gids: Vec::new(),
                    chunked: false,
                    chunk: None,
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
            column: None,
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

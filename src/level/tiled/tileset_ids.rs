//! The numbering of a map's tilesets and their tiles, checked before the crate reads them:
//! two of the map's tilesets starting at the same `firstgid` (which one a gid names is then
//! the reader's choice; Tiled keeps the last), a tile described twice in one tileset (Tiled
//! merges the two, the crate keeps the second), and, as a warning, a tile of an image's
//! tileset whose id is past the image's `tilecount` (Tiled keeps such tiles, left from a
//! larger image, and shows them with no picture).

use std::collections::HashMap;

use quick_xml::events::Event;

use super::attrs::{attr_offset, line_col};
use super::scan::{attr, line_of, ScanError};

/// A `<tileset>` being read: its name, `tilecount`, whether it has an `<image>`, and the ids
/// of its `<tile>`s with where each starts (byte offsets: a line is counted only for an error,
/// so that a tileset of many tiles is read in one pass).
struct Open {
    name: String,
    count: Option<u32>,
    image: bool,
    over: Vec<u32>,
    ids: HashMap<u32, usize>,
}

/// Checks `text` (a map's TMX or a tileset's TSX); the warnings for tiles past `tilecount`.
pub(super) fn check_tileset_ids(text: &str) -> Result<Vec<String>, ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut depth = 0usize;
    let mut firstgids: HashMap<u32, (String, usize)> = HashMap::new();
    let mut open: Option<(usize, Open)> = None;
    let mut notes = Vec::new();
    loop {
        let pos = reader.buffer_position();
        let (e, start) = match reader.read_event() {
            Ok(Event::Start(e)) => (e, true),
            Ok(Event::Empty(e)) => (e, false),
            Ok(Event::End(e)) => {
                depth = depth.saturating_sub(1);
                if e.name().as_ref() == b"tileset" && open.as_ref().is_some_and(|o| o.0 == depth) {
                    notes.extend(open.take().and_then(|(_, t)| over_note(t)));
                }
                continue;
            }
            // Malformed XML is reported elsewhere, with its line.
            Ok(Event::Eof) | Err(_) => return Ok(notes),
            Ok(_) => continue,
        };
        let name = e.name().as_ref().to_vec();
        match name.as_slice() {
            b"tileset" => {
                let ts_name = attr(&e, "name").unwrap_or_default();
                // The map's own tilesets (depth 1, inside `<map>`) are numbered by firstgid.
                let first = attr(&e, "firstgid").and_then(|g| g.trim().parse::<u32>().ok());
                if let (1, Some(g)) = (depth, first) {
                    if let Some((other, at)) = firstgids.get(&g) {
                        let line = line_of(text, *at);
                        let (l, c) = line_col(text, attr_offset(text, pos, &e, "firstgid"));
                        return Err(ScanError {
                            line: l,
                            column: Some(c),
                            message: format!(
                                "tileset {:?}: attribute \"firstgid\" is {g}, where tileset {other:?} (line {line}) starts too; expected each tileset its own gids, from the previous one's firstgid plus its tilecount, as Tiled numbers them",
                                source_or(&e, &ts_name)
                            ),
                        });
                    }
                    firstgids.insert(g, (source_or(&e, &ts_name), pos));
                }
                if start {
                    let count = attr(&e, "tilecount").and_then(|c| c.trim().parse().ok());
                    let t = Open {
                        name: ts_name,
                        count,
                        image: false,
                        over: Vec::new(),
                        ids: HashMap::new(),
                    };
                    open = Some((depth, t));
                }
            }
            b"image" => {
                if let Some((_, t)) = open.as_mut().filter(|(d, _)| *d + 1 == depth) {
                    t.image = true;
                }
            }
            b"tile" => {
                let id = attr(&e, "id").and_then(|i| i.trim().parse::<u32>().ok());
                if let (Some((d, t)), Some(id)) = (open.as_mut(), id) {
                    if *d + 1 == depth {
                        if let Some(at) = t.ids.get(&id) {
                            let first = line_of(text, *at);
                            let (l, c) = line_col(text, attr_offset(text, pos, &e, "id"));
                            return Err(ScanError {
                                line: l,
                                column: Some(c),
                                message: format!(
                                    "tileset {:?}: tile {id} is described a second time (first at line {first}); expected each tile once, as Tiled writes it (Tiled merges the two, the reader platbench uses keeps the second)",
                                    t.name
                                ),
                            });
                        }
                        t.ids.insert(id, pos);
                        if t.count.is_some_and(|c| id >= c) {
                            t.over.push(id);
                        }
                    }
                }
            }
            _ => {}
        }
        depth += usize::from(start);
    }
}

/// A tileset's `source` (a file it names) or else its name, to name it by.
fn source_or(e: &quick_xml::events::BytesStart, name: &str) -> String {
    attr(e, "source").unwrap_or_else(|| name.to_string())
}

/// The warning for an image's tileset whose tiles include ids past its `tilecount`.
fn over_note(t: Open) -> Option<String> {
    if !t.image || t.over.is_empty() {
        return None;
    }
    let ids: Vec<String> = t.over.iter().take(5).map(u32::to_string).collect();
    let more = if t.over.len() > 5 { ", ..." } else { "" };
    Some(format!(
        "tileset {:?}: tile(s) {}{more} are past its image's {} tiles (tilecount): a cell names them only by a gid beyond the image, which Tiled shows with no picture; their properties and shapes are read for such cells",
        t.name,
        ids.join(", "),
        t.count.unwrap_or(0)
    ))
}

#[cfg(test)]
mod tests {
    use super::check_tileset_ids;

    #[test]
    fn tilesets_and_tiles_numbered_twice_are_refused_and_tiles_past_the_image_noted() {
        let dup_gid = "<map>\n<tileset firstgid=\"1\" name=\"a\" tilecount=\"4\"/>\n<tileset firstgid=\"1\" name=\"b\"/>\n</map>";
        let e = check_tileset_ids(dup_gid).err().unwrap();
        assert_eq!((e.line, e.column), (3, Some(10)));
        assert!(
            e.message
                .contains("where tileset \"a\" (line 2) starts too"),
            "{}",
            e.message
        );
        let dup_tile = "<tileset name=\"t\" tilecount=\"4\">\n<image source=\"t.png\"/>\n<tile id=\"0\"/>\n<tile id=\"0\"/>\n</tileset>";
        let e = check_tileset_ids(dup_tile).err().unwrap();
        assert_eq!(e.line, 4);
        assert!(
            e.message
                .contains("tile 0 is described a second time (first at line 3)"),
            "{}",
            e.message
        );
        let over = "<tileset name=\"t\" tilecount=\"1\">\n<image source=\"t.png\"/>\n<tile id=\"5\"/>\n</tileset>";
        let notes = check_tileset_ids(over).ok().unwrap();
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].contains("tile(s) 5 are past its image's 1 tiles"),
            "{}",
            notes[0]
        );
        // An image collection lists its tiles by id, sparse ones included: no word.
        let collection = "<tileset name=\"c\" tilecount=\"1\">\n<tile id=\"7\"><image source=\"a.png\"/></tile>\n</tileset>";
        assert!(check_tileset_ids(collection).ok().unwrap().is_empty());
    }
}

//! A cell whose tile id (gid) names no tile of the map's tilesets: the error names the layer,
//! the cell as Tiled shows it (column and row from the map's top-left), the line of the map
//! where the cell is written (a JSON map's: the cell's line in its layer's `data` array, else
//! the line where the layer starts), the gid and the gids the map's tilesets hold. Also why a
//! gid is below every tileset, as the scan checks before the crate reads the map.

use quick_xml::events::Event;

use super::scan::{attr, line_of};
use super::{Importer, TiledError};

impl<'m> Importer<'m> {
    /// Whether the tile `lt` of layer `layer` (its path, `group/child`), at Tiled cell
    /// `(x, y)`, is a tile of its tileset; if not, the error says where and what is.
    pub(super) fn check_gid(
        &self,
        layer: &str,
        lt: &tiled::LayerTile,
        (x, y): (i64, i64),
    ) -> Result<(), TiledError> {
        let ts = lt.get_tileset();
        let id = lt.id();
        if names_tile(ts, id) {
            return Ok(());
        }
        let (found, ranges) = self.no_tile(lt.tileset_index(), ts, id);
        let line = cell_line(self.text, layer, (x, y));
        Err(TiledError::Layer {
            file: line.map_or(self.file.clone(), |l| (self.cell_at)(l, (x, y))),
            layer: layer.into(),
            message: format!(
                "cell x = {x}, y = {y} (column and row from the map's top-left, as Tiled shows them) holds {found}, which names no tile; expected 0 (no tile) or a gid of the map's tilesets: {}",
                ranges
            ),
        })
    }

    /// Whether the tile of object `o`, if it has one, is a tile of its tileset; if not, the
    /// error names the object and its gid, as for a cell.
    pub(super) fn check_object_tile(&self, o: &tiled::Object) -> Result<(), TiledError> {
        let (Some(t), Some(data)) = (o.get_tile(), o.tile_data()) else {
            return Ok(());
        };
        let ts = t.get_tileset();
        let id = data.id();
        if names_tile(ts, id) {
            return Ok(());
        }
        let tiled::TilesetLocation::Map(index) = data.tileset_location() else {
            // A template's own tileset, which the map's gids do not number.
            return Err(self.obj_err(
                o,
                format!(
                    "its template's tile is tile {id} of tileset {:?}, which names no tile; expected a tile of that tileset ({})",
                    ts.name,
                    match last_tile(ts) {
                        Some(l) => format!("ids 0 to {l}"),
                        None => "it has none".into(),
                    }
                ),
            ));
        };
        let (found, ranges) = self.no_tile(*index, ts, id);
        Err(self.obj_err(
            o,
            format!("its tile is {found}, which names no tile; expected a gid of the map's tilesets: {ranges}"),
        ))
    }

    /// Tile `id` of the map's tileset `index` as found (with its gid), and the gids each of the
    /// map's tilesets holds.
    fn no_tile(&self, index: usize, ts: &tiled::Tileset, id: u32) -> (String, String) {
        let first = tileset_firstgids(self.text);
        let gid = |k: usize, id: u32| first.get(k).map(|f| u64::from(*f) + u64::from(id));
        let found = match gid(index, id) {
            Some(g) => format!("gid {g} (tile {id} of tileset {:?})", ts.name),
            None => format!("tile {id} of tileset {:?}", ts.name),
        };
        let ranges: Vec<String> = self
            .map
            .tilesets()
            .iter()
            .enumerate()
            .map(
                |(k, t)| match (gid(k, 0), last_tile(t).and_then(|l| gid(k, l))) {
                    (Some(a), Some(b)) => format!("{a} to {b} ({:?})", t.name),
                    _ => format!("none ({:?}, which has no tiles)", t.name),
                },
            )
            .collect();
        (found, ranges.join(", "))
    }
}

/// The highest tile id of tileset `ts`: its image's last cell, or the highest it lists.
fn last_tile(ts: &tiled::Tileset) -> Option<u32> {
    match ts.image {
        Some(_) => ts.tilecount.checked_sub(1),
        None => ts.tiles().map(|(i, _)| i).max(),
    }
}

/// Whether tile `id` is one of tileset `ts`'s: a tile it lists, or a cell of its image.
fn names_tile(ts: &tiled::Tileset, id: u32) -> bool {
    ts.get_tile(id).is_some() || (ts.image.is_some() && id < ts.tilecount)
}

/// The `firstgid` of each of the map's tilesets, in the file's order (the `tiled` crate's).
fn tileset_firstgids(text: &str) -> Vec<u32> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut out = Vec::new();
    // Elements open around the next one: 1 inside `<map>`, where its tilesets are.
    let mut depth = 0usize;
    loop {
        let (e, start) = match reader.read_event() {
            Ok(Event::Start(e)) => (e, true),
            Ok(Event::Empty(e)) => (e, false),
            Ok(Event::End(_)) => {
                depth = depth.saturating_sub(1);
                continue;
            }
            Ok(Event::Eof) | Err(_) => return out,
            Ok(_) => continue,
        };
        if depth == 1 && e.name().as_ref() == b"tileset" {
            out.push(
                attr(&e, "firstgid")
                    .and_then(|v| v.trim().parse().ok())
                    .unwrap_or(1),
            );
        }
        depth += usize::from(start);
    }
}

/// The line of the map's XML where layer `path`'s cell `(x, y)` is written: the line of its
/// CSV entry or `<tile>` element, in the chunk that holds it for an infinite map; else the
/// line of the layer's `<data>` (base64 data). `None` if the layer is not found.
fn cell_line(text: &str, path: &str, (x, y): (i64, i64)) -> Option<usize> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut groups: Vec<String> = Vec::new();
    let mut infinite = false;
    // The layer's width once it is found; its `<data>`'s offset and encoding.
    let mut width: Option<i64> = None;
    let mut data: Option<(usize, bool)> = None;
    // The index of the cell in the data (or chunk) being read, -1 if it holds no such cell;
    // and the `<tile>` elements read so far.
    let mut index = -1i64;
    let mut tiles = 0i64;
    loop {
        let pos = reader.buffer_position();
        match reader.read_event().ok()? {
            Event::Start(e) | Event::Empty(e) => {
                let int = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<i64>().ok());
                match e.name().as_ref() {
                    b"map" => infinite = int("infinite") == Some(1),
                    b"group" => groups.push(attr(&e, "name").unwrap_or_default()),
                    b"layer" if width.is_none() => {
                        let mut full = groups.join("/");
                        if !full.is_empty() {
                            full.push('/');
                        }
                        full.push_str(&attr(&e, "name").unwrap_or_default());
                        if full == path {
                            width = Some(int("width").unwrap_or(0));
                        }
                    }
                    b"data" if width.is_some() && data.is_none() => {
                        let csv = attr(&e, "encoding").as_deref() == Some("csv");
                        data = Some((pos, csv));
                        if !infinite {
                            index = y * width.unwrap_or(0) + x;
                        }
                    }
                    b"chunk" if data.is_some() => {
                        let (cx, cy) = (int("x").unwrap_or(0), int("y").unwrap_or(0));
                        let (cw, ch) = (int("width").unwrap_or(0), int("height").unwrap_or(0));
                        let inside = (cx..cx + cw).contains(&x) && (cy..cy + ch).contains(&y);
                        index = if inside { (y - cy) * cw + (x - cx) } else { -1 };
                        tiles = 0;
                    }
                    b"tile" if data.is_some() => {
                        if index >= 0 && tiles == index {
                            return Some(line_of(text, pos));
                        }
                        tiles += 1;
                    }
                    _ => {}
                }
            }
            Event::Text(t) if index >= 0 && data.is_some_and(|(_, csv)| csv) => {
                let raw = std::str::from_utf8(&t).ok()?;
                // The cell's entry comes after its `index`-th comma (and the spaces after it).
                let mut at = 0;
                for _ in 0..index {
                    at += raw[at..].find(',')? + 1;
                }
                at += raw[at..].len() - raw[at..].trim_start().len();
                return Some(line_of(text, pos + at));
            }
            Event::End(e) => match e.name().as_ref() {
                b"group" => {
                    groups.pop();
                }
                b"layer" if data.is_some() => return data.map(|(p, _)| line_of(text, p)),
                _ => {}
            },
            Event::Eof => return None,
            _ => {}
        }
    }
}

/// Why gid `bits` (flip bits aside, as the crate masks them) is in none of the map's
/// tilesets, whose lowest `firstgid` is `first`: the crate would drop such a tile unseen.
pub(super) fn no_tileset(bits: u32, first: Option<u32>) -> Option<String> {
    let gid = bits & 0x1FFF_FFFF;
    let expected = "expected 0 (no tile) or a gid of the map's tilesets";
    match first {
        _ if gid == 0 => None,
        None => Some(format!(
            "gid {gid}, but the map has no tileset; {expected} (add the tileset the map was drawn with)"
        )),
        Some(f) if gid < f => Some(format!(
            "gid {gid}, below the first tileset's firstgid {f}; {expected}, from {f}"
        )),
        Some(_) => None,
    }
}

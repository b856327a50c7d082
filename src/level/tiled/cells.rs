//! The level's cells while a map is read: each cell's tile and what put it there (interned,
//! so a cell costs a tile and an index, not a string), and the rule for two layers that put
//! different tiles into one cell: the tile that stops more is kept (solid over a slope over a
//! one-way platform or a ladder; a ladder and a one-way platform make a ladder), and each such
//! meeting is counted for one warning per pair of layers.

use std::collections::{BTreeMap, HashMap};

use super::error::CellError;
use super::tile_name;
use crate::level::Tile;

/// What put a tile into a cell: a tileset tile or an object, and the layer it is in.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) struct Source {
    /// The tile or object (`tileset "t" tile 3`, `object 4 "floor"`).
    pub what: String,
    /// Its layer.
    pub layer: String,
}

impl std::fmt::Display for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} in layer {:?}", self.what, self.layer)
    }
}

/// Cells where two layers' different tiles met, for the warning: layers and kinds of the kept
/// and the dropped tile, the first cell and the count.
type Meetings = BTreeMap<(String, String, String, String), ((u32, u32), u64)>;

/// The cells of one import.
#[derive(Default)]
pub(super) struct Cells {
    /// Width of the level in cells (row 0 at the bottom).
    w: u32,
    /// Each cell's tile and source index.
    tiles: Vec<Option<(Tile, u32)>>,
    sources: Vec<Source>,
    ids: HashMap<Source, u32>,
    meetings: Meetings,
}

/// How much a tile stops a character: the kept tile of two in one cell stops more.
fn rank(t: &Tile) -> u8 {
    match t {
        Tile::Empty => 0,
        Tile::OneWay | Tile::Ladder => 1,
        Tile::Slope(_) => 2,
        Tile::Solid => 3,
    }
}

impl Cells {
    /// `w` by `h` empty cells (the size is checked by the caller before this allocates).
    pub fn new(w: u32, h: u32) -> Self {
        Cells {
            w,
            tiles: vec![None; w as usize * h as usize],
            ..Cells::default()
        }
    }

    /// The index of a source, added once.
    pub fn source(&mut self, what: String, layer: &str) -> u32 {
        let s = Source {
            what,
            layer: layer.to_string(),
        };
        if let Some(&id) = self.ids.get(&s) {
            return id;
        }
        let id = self.sources.len() as u32;
        self.sources.push(s.clone());
        self.ids.insert(s, id);
        id
    }

    /// Puts `tile` into cell `k`, set by source `by`: an empty tile gives way to any other; a
    /// ladder and a one-way platform make a ladder (whose top is walkable like a one-way
    /// platform); otherwise the tile that stops more is kept and the meeting counted. Two
    /// different slopes in one cell are an error: neither stops more.
    pub fn set(&mut self, k: usize, tile: Tile, by: u32) -> Result<(), CellError> {
        let Some((prev, prev_by)) = self.tiles[k] else {
            self.tiles[k] = Some((tile, by));
            return Ok(());
        };
        if prev == tile || tile == Tile::Empty {
            return Ok(());
        }
        if prev == Tile::Empty || (prev == Tile::OneWay && tile == Tile::Ladder) {
            self.tiles[k] = Some((tile, by));
            return Ok(());
        }
        if prev == Tile::Ladder && tile == Tile::OneWay {
            return Ok(());
        }
        let (keep, drop) = match rank(&tile).cmp(&rank(&prev)) {
            std::cmp::Ordering::Greater => ((tile, by), (prev, prev_by)),
            std::cmp::Ordering::Less => ((prev, prev_by), (tile, by)),
            std::cmp::Ordering::Equal => {
                return Err(CellError::Conflict {
                    tile,
                    held: prev,
                    held_by: self.sources[prev_by as usize].to_string(),
                })
            }
        };
        self.tiles[k] = Some(keep);
        let key = (
            self.sources[keep.1 as usize].layer.clone(),
            kind(&keep.0),
            self.sources[drop.1 as usize].layer.clone(),
            kind(&drop.0),
        );
        let cell = (k % self.w as usize) as u32;
        let row = (k / self.w as usize) as u32;
        self.meetings.entry(key).or_insert(((cell, row), 0)).1 += 1;
        Ok(())
    }

    /// The tiles, row 0 at the bottom, and one warning (subject, message) per pair of layers
    /// whose tiles met in a cell, the first cell as Tiled shows it (`tiled` gives the column and
    /// row from the map's top-left of a cell `(i, j)`).
    pub fn finish(
        &mut self,
        tiled: impl Fn(u32, u32) -> (i64, i64),
    ) -> (Vec<Tile>, Vec<(String, String)>) {
        let tiles = self
            .tiles
            .iter()
            .map(|t| t.map_or(Tile::Empty, |(t, _)| t))
            .collect();
        let warnings = std::mem::take(&mut self.meetings)
            .into_iter()
            .map(|((kept_layer, kept, dropped_layer, dropped), ((i, j), n))| {
                let (x, y) = tiled(i, j);
                let whose = if kept_layer == dropped_layer {
                    "its own".to_string()
                } else {
                    format!("layer {kept_layer:?}'s")
                };
                (
                    format!("layer {dropped_layer:?}"),
                    format!("{n} cell(s) (the first at x = {x}, y = {y}, column and row from the map's top-left) where its {dropped} tiles meet {whose} {kept} tiles: the {kept} tile is kept, as it stops the character from more sides"),
                )
            })
            .collect();
        (tiles, warnings)
    }
}

/// A tile's kind for the meeting warning (a slope's shape left out).
fn kind(t: &Tile) -> String {
    match t {
        Tile::Slope(_) => "slope".into(),
        Tile::Ladder => "ladder".into(),
        other => tile_name(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tile_that_stops_more_is_kept_and_the_meeting_warned_once_per_layer_pair() {
        let mut c = Cells::new(3, 1);
        let solid = c.source("tileset \"t\" tile 1".into(), "walls");
        let plank = c.source("tileset \"t\" tile 2".into(), "platforms");
        assert_eq!(c.source("tileset \"t\" tile 1".into(), "walls"), solid);
        c.set(0, Tile::Solid, solid).unwrap();
        c.set(0, Tile::OneWay, plank).unwrap();
        c.set(1, Tile::OneWay, plank).unwrap();
        c.set(1, Tile::Solid, solid).unwrap();
        c.set(2, Tile::Ladder, plank).unwrap();
        c.set(2, Tile::OneWay, plank).unwrap();
        // One row: Tiled's row 0.
        let (tiles, warnings) = c.finish(|i, _| (i.into(), 0));
        assert_eq!(tiles, vec![Tile::Solid, Tile::Solid, Tile::Ladder]);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert_eq!(warnings[0].0, "layer \"platforms\"");
        assert!(warnings[0].1.starts_with(
            "2 cell(s) (the first at x = 0, y = 0, column and row from the map's top-left)"
        ));
    }

    #[test]
    fn two_different_slopes_in_one_cell_are_an_error_naming_the_first() {
        use crate::level::Slope;
        let mut c = Cells::new(1, 1);
        let a = c.source("object 1 \"\"".into(), "ramps");
        let b = c.source("object 2 \"\"".into(), "ramps");
        let up = Tile::Slope(Slope::Line {
            left: 0.0,
            right: 1.0,
        });
        let down = Tile::Slope(Slope::Line {
            left: 1.0,
            right: 0.0,
        });
        c.set(0, up, a).unwrap();
        let e = c.set(0, down, b).unwrap_err().to_string();
        assert!(e.contains("object 1 \"\" in layer \"ramps\""), "{e}");
    }
}

//! A level's grid of tiles as it is kept for the whole run ([`Cells`]): one byte per cell (an
//! index into a palette of the level's distinct tiles), shared, so that every copy of a level's
//! geometry a backend keeps ([`crate::level::Level::geometry`]) costs nothing per tile. A level
//! with ladders also keeps each ladder cell's run top (four bytes a cell), which the ladder
//! rules read every step.
//!
//! A [`Tile`] is 20 bytes (a slope's 16 heights and its tag); a million-tile map held as tiles
//! took 20 MB per copy, and the sweep kept a copy per configuration. A level has few
//! distinct tiles (the four plain kinds and its slopes), so a palette index is a byte; a level
//! with more than 256 distinct tiles (slopes of many different heights) keeps four bytes a cell.

use std::collections::HashMap;
use std::sync::Arc;

use super::{Slope, Tile};

/// The tiles of a level, row by row from the bottom (`j * width + i`), as palette indices.
#[derive(Clone, Debug)]
pub(super) struct Cells {
    /// Each cell's index in `palette`.
    codes: Codes,
    /// The level's distinct tiles, in the order first met.
    palette: Arc<[Tile]>,
    /// Per cell, one more than the top row of the run of ladder tiles holding it (0: not a
    /// ladder), built only when the level has ladders, so that the ladder rules that every
    /// backend runs each step find a run's top with one read instead of a walk up the column.
    ladder_tops: Option<Arc<[u32]>>,
}

/// Palette indices, a byte each while the palette has at most 256 entries.
#[derive(Clone, Debug)]
enum Codes {
    Narrow(Arc<[u8]>),
    Wide(Arc<[u32]>),
}

/// A slope as a hashable key: the bits of its surface (so that a NaN height, were one to get
/// here, is one entry, not one per cell). Two slopes with the same key are the same surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct SlopeKey(Key);

impl SlopeKey {
    /// The key of `s`.
    pub(crate) fn of(s: &Slope) -> SlopeKey {
        SlopeKey(key(&Tile::Slope(*s)))
    }
}

/// A tile as a hashable key: its kind and, for a slope, the bits of its surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Key {
    Empty,
    Solid,
    OneWay,
    Ladder,
    Heights([u8; 16]),
    Line(u32, u32),
}

fn key(t: &Tile) -> Key {
    match t {
        Tile::Empty => Key::Empty,
        Tile::Solid => Key::Solid,
        Tile::OneWay => Key::OneWay,
        Tile::Ladder => Key::Ladder,
        Tile::Slope(Slope::Heights(h)) => Key::Heights(*h),
        Tile::Slope(Slope::Line { left, right }) => Key::Line(left.to_bits(), right.to_bits()),
    }
}

impl Cells {
    /// The cells of `tiles` (rows of `width` cells), in their order.
    pub(super) fn new(tiles: &[Tile], width: u32) -> Cells {
        let mut palette: Vec<Tile> = Vec::new();
        let mut index: HashMap<Key, u32> = HashMap::new();
        let mut code = |t: &Tile| -> u32 {
            *index.entry(key(t)).or_insert_with(|| {
                palette.push(*t);
                (palette.len() - 1) as u32
            })
        };
        let wide: Vec<u32> = tiles.iter().map(&mut code).collect();
        let codes = if palette.len() <= 256 {
            Codes::Narrow(wide.iter().map(|&c| c as u8).collect())
        } else {
            Codes::Wide(wide.into())
        };
        let ladder_tops = palette
            .contains(&Tile::Ladder)
            .then(|| ladder_tops(tiles, width as usize));
        Cells {
            codes,
            palette: palette.into(),
            ladder_tops,
        }
    }

    /// The top row of the run of ladder tiles holding cell `k`, or none if `k` is not a ladder
    /// (`k` below [`Cells::len`]).
    #[inline]
    pub(super) fn ladder_top(&self, k: usize) -> Option<u32> {
        let top = self.ladder_tops.as_ref()?[k];
        top.checked_sub(1)
    }

    /// The number of cells.
    pub(super) fn len(&self) -> usize {
        match &self.codes {
            Codes::Narrow(c) => c.len(),
            Codes::Wide(c) => c.len(),
        }
    }

    /// The tile of cell `k` (`j * width + i`); `k` must be below [`Cells::len`].
    #[inline]
    pub(super) fn get(&self, k: usize) -> Tile {
        let code = match &self.codes {
            Codes::Narrow(c) => c[k] as usize,
            Codes::Wide(c) => c[k] as usize,
        };
        self.palette[code]
    }

    /// Every cell's tile, in order.
    pub(super) fn iter(&self) -> impl Iterator<Item = Tile> + '_ {
        (0..self.len()).map(|k| self.get(k))
    }

    /// The distinct tiles the cells hold, each once.
    pub(super) fn distinct(&self) -> impl Iterator<Item = Tile> + '_ {
        self.palette.iter().copied()
    }

    /// Whether any cell holds a tile for which `f` is true, looking at each distinct tile once.
    pub(super) fn any_distinct(&self, f: impl Fn(&Tile) -> bool) -> bool {
        self.palette.iter().any(f)
    }
}

/// Per cell of `tiles` (rows of `width`), one more than the top row of its run of ladder
/// tiles, 0 where it holds no ladder: each column walked down from its top row.
fn ladder_tops(tiles: &[Tile], width: usize) -> Arc<[u32]> {
    let mut tops = vec![0u32; tiles.len()];
    let rows = tiles.len().checked_div(width).unwrap_or(0);
    for i in 0..width {
        let mut top = 0;
        for j in (0..rows).rev() {
            let k = j * width + i;
            if tiles[k] != Tile::Ladder {
                top = 0;
                continue;
            }
            if top == 0 {
                top = j as u32 + 1;
            }
            tops[k] = top;
        }
    }
    tops.into()
}

impl PartialEq for Cells {
    /// Cell by cell, whatever the palette's order.
    fn eq(&self, other: &Cells) -> bool {
        self.len() == other.len() && self.iter().zip(other.iter()).all(|(a, b)| a == b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_keep_every_tile_in_a_byte_or_four() {
        let line = Tile::Slope(Slope::Line {
            left: 0.0,
            right: 0.5,
        });
        let tiles = vec![
            Tile::Solid,
            Tile::Empty,
            line,
            Tile::Ladder,
            line,
            Tile::OneWay,
        ];
        let cells = Cells::new(&tiles, 2);
        assert!(matches!(cells.codes, Codes::Narrow(_)));
        assert_eq!(cells.iter().collect::<Vec<_>>(), tiles);
        // 300 distinct slopes (more than a byte indexes) keep four bytes a cell.
        let many: Vec<Tile> = (0..300)
            .map(|k| {
                Tile::Slope(Slope::Line {
                    left: 0.0,
                    right: k as f32 / 300.0,
                })
            })
            .collect();
        let cells = Cells::new(&many, 300);
        assert!(matches!(cells.codes, Codes::Wide(_)));
        assert_eq!(cells.iter().collect::<Vec<_>>(), many);
    }

    #[test]
    fn a_ladder_cell_knows_the_top_row_of_its_run() {
        // Three columns, five rows from the bottom: a run of rows 0-2 and one of row 4 in
        // column 0, a run of rows 1-4 (the map's top) in column 2, and row 4 alone in column 1.
        let (l, e) = (Tile::Ladder, Tile::Empty);
        #[rustfmt::skip]
        let tiles = vec![
            l, e, e,
            l, Tile::Solid, l,
            l, e, l,
            e, e, l,
            l, l, l,
        ];
        let cells = Cells::new(&tiles, 3);
        let tops: Vec<Option<u32>> = (0..tiles.len()).map(|k| cells.ladder_top(k)).collect();
        #[rustfmt::skip]
        let expected = vec![
            Some(2), None, None,
            Some(2), None, Some(4),
            Some(2), None, Some(4),
            None, None, Some(4),
            Some(4), Some(4), Some(4),
        ];
        assert_eq!(tops, expected);
        // Without a ladder tile there is no table to read.
        assert_eq!(Cells::new(&[Tile::Solid, e], 2).ladder_top(0), None);
    }
}

//! The `map` string: rows of characters, top row first, of equal length, each character a
//! tile of the legend; errors at the row and column of the file.

use std::collections::HashMap;

use toml::Spanned;

use crate::level::Tile;
use crate::limits;

use super::error::{LevelError, Locator};
use super::strings::value_offsets;

pub(super) fn parse_map(
    loc: &Locator,
    map: &Spanned<String>,
    legend: &HashMap<char, Tile>,
) -> Result<(u32, u32, Vec<Tile>), LevelError> {
    let span = map.span();
    let body = map.get_ref();
    // Where each byte of the value sits in the file: escapes in a basic string ("a\nb") make
    // the value and its text differ, so value offsets are mapped, never added to the start.
    let offsets = loc
        .text
        .get(span.clone())
        .and_then(|raw| value_offsets(raw, body));
    let file_offset = |value_offset: usize| {
        offsets
            .as_ref()
            .and_then(|o| o.get(value_offset))
            .map_or(span.start, |o| span.start + o)
    };
    // Each row with the offset in the value where it starts.
    let mut rows: Vec<(usize, &str)> = Vec::new();
    let mut row_start = 0;
    for row in body.split('\n') {
        rows.push((row_start, row.trim_end_matches('\r')));
        row_start += row.len() + 1;
    }
    if rows.last().is_some_and(|(_, r)| r.is_empty()) {
        rows.pop();
    }
    if rows.is_empty() || rows.iter().all(|(_, r)| r.is_empty()) {
        return Err(loc.at(
            &span,
            "the map is empty; expected at least one row of tiles",
        ));
    }
    let width = rows[0].1.chars().count();
    for (r, (row_start, row)) in rows.iter().enumerate() {
        let n = row.chars().count();
        if n != width {
            return Err(loc.err(
                file_offset(row_start + row.len()),
                format!("map row {} has {n} tiles, expected {width} like the first row (rows must have equal length)", r + 1),
            ));
        }
    }
    let height = rows.len();
    if (width as u64) * (height as u64) > limits::MAX_TILES {
        return Err(loc.at(
            &span,
            format!(
                "the map is {width} x {height} tiles; expected at most {} tiles (as for Tiled maps)",
                limits::MAX_TILES
            ),
        ));
    }
    let mut tiles = vec![Tile::Empty; width * height];
    for (r, (row_start, row)) in rows.iter().enumerate() {
        let j = height - 1 - r;
        for (i, (byte, c)) in row.char_indices().enumerate() {
            let tile = legend.get(&c).ok_or_else(|| {
                // Placed at the string's start when its text could not be mapped: the row
                // and column within the map then say where.
                let within = match offsets {
                    Some(_) => String::new(),
                    None => format!(" at map row {}, column {}", r + 1, i + 1),
                };
                loc.err(
                    file_offset(row_start + byte),
                    format!("unknown map character {c:?}{within}; expected '#', '.', ' ', '=', 'H', '/', '\\' or a key of [legend]"),
                )
            })?;
            tiles[j * width + i] = *tile;
        }
    }
    Ok((width as u32, height as u32, tiles))
}

//! The `map` string: rows of characters, top row first, of equal length, each character a
//! tile of the legend; errors at the row and column of the file.

use std::collections::HashMap;

use toml::Spanned;

use crate::level::Tile;
use crate::limits;

use super::error::{LevelError, Locator};

pub(super) fn parse_map(
    loc: &Locator,
    map: &Spanned<String>,
    legend: &HashMap<char, Tile>,
) -> Result<(u32, u32, Vec<Tile>), LevelError> {
    let span = map.span();
    // Where the string's content starts in the file: after the opening quotes, and after
    // the newline that TOML trims right after triple quotes.
    let raw = &loc.text[span.clone()];
    let mut content_start = span.start;
    if raw.starts_with("\"\"\"") || raw.starts_with("'''") {
        content_start += 3;
        let rest = &loc.text[content_start..];
        if rest.starts_with("\r\n") {
            content_start += 2;
        } else if rest.starts_with('\n') {
            content_start += 1;
        }
    } else {
        content_start += 1;
    }
    let body = map.get_ref();
    let mut rows: Vec<&str> = body.split('\n').map(|r| r.trim_end_matches('\r')).collect();
    if rows.last() == Some(&"") {
        rows.pop();
    }
    if rows.is_empty() || rows.iter().all(|r| r.is_empty()) {
        return Err(loc.at(
            &span,
            "the map is empty; expected at least one row of tiles",
        ));
    }
    // Byte offset in the file of each row, for errors.
    let line_offsets: Vec<usize> = {
        let mut v = Vec::with_capacity(rows.len());
        let mut off = content_start;
        for r in &rows {
            v.push(off);
            off += r.len() + 1;
        }
        v
    };
    let width = rows[0].chars().count();
    for (r, row) in rows.iter().enumerate() {
        let n = row.chars().count();
        if n != width {
            return Err(loc.err(
                line_offsets[r] + row.len(),
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
    for (r, row) in rows.iter().enumerate() {
        let j = height - 1 - r;
        for (i, (byte, c)) in row.char_indices().enumerate() {
            let tile = legend.get(&c).ok_or_else(|| {
                loc.err(
                    line_offsets[r] + byte,
                    format!("unknown map character {c:?}; expected '#', '.', ' ', '=', 'H', '/', '\\' or a key of [legend]"),
                )
            })?;
            tiles[j * width + i] = *tile;
        }
    }
    Ok((width as u32, height as u32, tiles))
}

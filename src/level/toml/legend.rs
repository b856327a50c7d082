//! The `[legend]` table: the built-in map characters and the tiles a level's own characters
//! stand for (solid, empty, one-way, ladder, height-array and line slopes).

use std::collections::{BTreeMap, HashMap};

use toml::Spanned;

use super::error::{LevelError, Locator};
use crate::level::{Slope, Tile};

pub(super) fn parse_legend(
    loc: &Locator,
    raw: &BTreeMap<Spanned<String>, Spanned<toml::Value>>,
) -> Result<HashMap<char, Tile>, LevelError> {
    let mut legend: HashMap<char, Tile> = HashMap::from([
        ('#', Tile::Solid),
        ('.', Tile::Empty),
        (' ', Tile::Empty),
        ('=', Tile::OneWay),
        ('H', Tile::Ladder),
        (
            '/',
            Tile::Slope(Slope::Line {
                left: 0.0,
                right: 1.0,
            }),
        ),
        (
            '\\',
            Tile::Slope(Slope::Line {
                left: 1.0,
                right: 0.0,
            }),
        ),
    ]);
    for (key, value) in raw {
        let mut chars = key.get_ref().chars();
        let c = match (chars.next(), chars.next()) {
            (Some(c), None) => c,
            _ => {
                return Err(loc.at(
                    &key.span(),
                    format!("legend key {:?} must be a single character", key.get_ref()),
                ))
            }
        };
        let tile = parse_legend_value(loc, value)?;
        if let Some(builtin) = legend.get(&c) {
            if *builtin != tile {
                return Err(loc.at(
                    &key.span(),
                    format!(
                        "legend key {c:?} is a built-in tile ({}) and cannot be redefined as {}; expected a character of your own (built in: '#' solid, '.' and ' ' empty, '=' one-way, 'H' ladder, '/' and '\\' slopes)",
                        tile_kind(builtin),
                        tile_kind(&tile)
                    ),
                ));
            }
        }
        legend.insert(c, tile);
    }
    Ok(legend)
}

/// A tile kind in words, for messages.
fn tile_kind(t: &Tile) -> &'static str {
    match t {
        Tile::Empty => "empty",
        Tile::Solid => "solid",
        Tile::OneWay => "one-way",
        Tile::Ladder => "ladder",
        Tile::Slope(_) => "a slope",
    }
}

fn parse_legend_value(loc: &Locator, value: &Spanned<toml::Value>) -> Result<Tile, LevelError> {
    let span = value.span();
    let expected = "expected \"solid\", \"empty\", \"oneway\", \"ladder\", { heights = [16 integers 0..=16] } or { line = [left, right] }";
    match value.get_ref() {
        toml::Value::String(s) => match s.as_str() {
            "solid" => Ok(Tile::Solid),
            "empty" => Ok(Tile::Empty),
            "oneway" => Ok(Tile::OneWay),
            "ladder" => Ok(Tile::Ladder),
            other => Err(loc.at(&span, format!("unknown tile kind {other:?}; {expected}"))),
        },
        toml::Value::Table(t) if t.len() == 1 && t.contains_key("heights") => {
            let arr = t["heights"].as_array();
            let heights: Option<Vec<u8>> = arr.map(|a| {
                a.iter()
                    .filter_map(|v| v.as_integer())
                    .filter(|h| (0..=16).contains(h))
                    .map(|h| h as u8)
                    .collect()
            });
            match (arr.map(|a| a.len()), heights) {
                (Some(16), Some(h)) if h.len() == 16 => {
                    let mut out = [0u8; 16];
                    out.copy_from_slice(&h);
                    Ok(Tile::Slope(Slope::Heights(out)))
                }
                _ => Err(loc.at(
                    &span,
                    "a height array is 16 integers; expected exactly 16 integers between 0 and 16 (sixteenths of a tile)",
                )),
            }
        }
        toml::Value::Table(t) if t.len() == 1 && t.contains_key("line") => {
            let pair: Option<Vec<f64>> = t["line"].as_array().map(|a| {
                a.iter()
                    .filter_map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
                    .collect()
            });
            match pair.as_deref() {
                Some(&[l, r]) if l.abs() <= 16.0 && r.abs() <= 16.0 => {
                    Ok(Tile::Slope(Slope::Line {
                        left: l as f32,
                        right: r as f32,
                    }))
                }
                _ => Err(loc.at(
                    &span,
                    "a line slope is [left, right]; expected two numbers between -16 and 16 (heights of the line at the tile's edges, in tiles; the surface is clamped into the tile)",
                )),
            }
        }
        other => Err(loc.at(
            &span,
            format!("found {} as a legend entry; {expected}", other.type_str()),
        )),
    }
}

//! The JSON of an LDtk project or external level that the import reads (serde; every other
//! field ignored), with the bounds that keep its pixel coordinates and layer sizes within
//! what a level may be.

use serde::Deserialize;

#[derive(Deserialize)]
pub(super) struct Project {
    #[serde(rename = "worldLayout", default)]
    pub(super) world_layout: Option<String>,
    #[serde(default)]
    pub(super) levels: Vec<LdLevel>,
    #[serde(default)]
    pub(super) worlds: Vec<World>,
    #[serde(default)]
    pub(super) defs: Defs,
}

#[derive(Deserialize)]
pub(super) struct World {
    #[serde(default)]
    pub(super) identifier: String,
    #[serde(rename = "worldLayout", default)]
    pub(super) world_layout: Option<String>,
    #[serde(default)]
    pub(super) levels: Vec<LdLevel>,
}

#[derive(Deserialize, Default)]
pub(super) struct Defs {
    #[serde(default)]
    pub(super) layers: Vec<LayerDef>,
}

#[derive(Deserialize)]
pub(super) struct LayerDef {
    #[serde(default)]
    pub(super) uid: i64,
    #[serde(rename = "intGridValues", default)]
    pub(super) int_grid_values: Vec<IntGridValueDef>,
}

#[derive(Deserialize)]
pub(super) struct IntGridValueDef {
    #[serde(default)]
    pub(super) value: Option<i64>,
    #[serde(default)]
    pub(super) identifier: Option<String>,
}

/// Largest pixel coordinate or size read from a project (a level's `worldX`, `worldY`, `pxWid`,
/// `pxHei`, a layer's grid size and offsets), from zero: 10^15, [`crate::limits::MAX_ORIGIN`]
/// (a level placed farther is refused even at one pixel a cell). Sums of four such values stay
/// far within an `i64` (the world's bounds add a level's corner, its size and a grid cell).
const MAX_PIXELS: i64 = 1_000_000_000_000_000;

/// A pixel coordinate or size within [`MAX_PIXELS`] of zero; beyond, an error that serde_json
/// places at the value's line and column.
fn pixels<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    let v = i64::deserialize(d)?;
    if v.checked_abs().is_none_or(|a| a > MAX_PIXELS) {
        return Err(serde::de::Error::custom(format!(
            "a pixel coordinate or size of {v}; expected -10^15 to 10^15 pixels (platbench \
             places a level at most 1e15 tiles from the world's origin)"
        )));
    }
    Ok(v)
}

/// A level's width or height in pixels (`pxWid`, `pxHei`): 0 to [`MAX_PIXELS`], as LDtk
/// writes it (never negative); otherwise an error serde_json places.
fn size<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    let v = i64::deserialize(d)?;
    if !(0..=MAX_PIXELS).contains(&v) {
        return Err(serde::de::Error::custom(format!(
            "a level size of {v} pixels; expected 0 to 10^15 pixels, as LDtk writes it"
        )));
    }
    Ok(v)
}

/// A layer's width or height in cells, 0 to [`crate::limits::MAX_TILES`] (a layer wider than
/// that is more cells than any level may have); otherwise an error serde_json places.
fn cells<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    let v = i64::deserialize(d)?;
    if u64::try_from(v).is_ok_and(|c| c <= crate::limits::MAX_TILES) {
        return Ok(v);
    }
    Err(serde::de::Error::custom(format!(
        "a layer of {v} cells across; expected 0 to {} (the most tiles a level may have)",
        crate::limits::MAX_TILES
    )))
}

/// An entity's place or size in pixels, a number within [`MAX_PIXELS`] of zero (1e39 was read
/// as infinity); otherwise an error serde_json places.
fn px_value(v: f64, what: &str) -> Result<f64, String> {
    if v.is_finite() && v.abs() <= MAX_PIXELS as f64 {
        return Ok(v);
    }
    Err(format!(
        "an entity {what} of {v:e} pixels; expected -10^15 to 10^15 pixels"
    ))
}

/// Exactly two numbers, under `key`.
fn pair<'de, D: serde::Deserializer<'de>>(d: D, key: &str) -> Result<[f64; 2], D::Error> {
    let v = Vec::<f64>::deserialize(d)?;
    match v[..] {
        [x, y] => Ok([x, y]),
        _ => Err(serde::de::Error::custom(format!(
            "an entity's {key} holds {} number{}; expected exactly 2 (x, y), as LDtk writes it",
            v.len(),
            if v.len() == 1 { "" } else { "s" }
        ))),
    }
}

/// An entity's `px`: exactly two numbers (x, y), each within [`MAX_PIXELS`].
fn point<'de, D: serde::Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    let p = pair(d, "px")?;
    for v in p {
        px_value(v, "place").map_err(serde::de::Error::custom)?;
    }
    Ok(p)
}

/// An entity's `__pivot`: exactly two fractions of its size, 0 to 1 as LDtk's editor sets them.
fn pivot<'de, D: serde::Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    let p = pair(d, "__pivot")?;
    if p.iter().any(|v| !(0.0..=1.0).contains(v)) {
        return Err(serde::de::Error::custom(format!(
            "a pivot of ({}, {}); expected two fractions of the entity's size from 0 to 1, as LDtk writes them",
            p[0], p[1]
        )));
    }
    Ok(p)
}

/// An entity's `width` or `height`: 0 to [`MAX_PIXELS`].
fn extent<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let v = f64::deserialize(d)?;
    match px_value(v, "size") {
        Ok(v) if v >= 0.0 => Ok(v),
        Ok(_) => Err(serde::de::Error::custom(format!(
            "an entity size of {v} pixels; expected 0 to 10^15 pixels"
        ))),
        Err(m) => Err(serde::de::Error::custom(m)),
    }
}

/// An IntGrid layer's `intGridCsv`: each value 0 (empty) or positive, as LDtk writes them.
fn csv<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Vec<i64>>, D::Error> {
    let v: Option<Vec<i64>> = Option::deserialize(d)?;
    if let Some((k, bad)) = v.iter().flatten().enumerate().find(|(_, v)| **v < 0) {
        return Err(serde::de::Error::custom(format!(
            "intGridCsv's cell {k} holds {bad}; expected 0 (empty) or a value the layer defines (1 and up), as LDtk writes them"
        )));
    }
    Ok(v)
}

#[derive(Deserialize)]
pub(super) struct LdLevel {
    #[serde(default)]
    pub(super) identifier: String,
    #[serde(rename = "worldX", default, deserialize_with = "pixels")]
    pub(super) world_x: i64,
    #[serde(rename = "worldY", default, deserialize_with = "pixels")]
    pub(super) world_y: i64,
    #[serde(rename = "pxWid", default, deserialize_with = "size")]
    pub(super) px_wid: i64,
    #[serde(rename = "pxHei", default, deserialize_with = "size")]
    pub(super) px_hei: i64,
    #[serde(rename = "layerInstances", default)]
    pub(super) layer_instances: Option<Vec<LayerInstance>>,
    #[serde(rename = "externalRelPath", default)]
    pub(super) external_rel_path: Option<String>,
    /// The levels this one touches (LDtk's `__neighbours`): `dir` is `w` or `e` for a level
    /// beside it, among others (`n`, `s`, `<`, `>`, `o`, corners).
    #[serde(rename = "__neighbours", default)]
    pub(super) neighbours: Vec<Neighbour>,
}

/// One entry of a level's `__neighbours`.
#[derive(Deserialize)]
pub(super) struct Neighbour {
    #[serde(default)]
    pub(super) dir: String,
}

#[derive(Deserialize)]
pub(super) struct LayerInstance {
    #[serde(rename = "__identifier", default)]
    pub(super) identifier: String,
    #[serde(rename = "__type", default)]
    pub(super) kind: String,
    #[serde(rename = "__cWid", default, deserialize_with = "cells")]
    pub(super) c_wid: i64,
    #[serde(rename = "__cHei", default, deserialize_with = "cells")]
    pub(super) c_hei: i64,
    #[serde(rename = "__gridSize", default, deserialize_with = "pixels")]
    pub(super) grid_size: i64,
    #[serde(rename = "__pxTotalOffsetX", default, deserialize_with = "pixels")]
    pub(super) px_offset_x: i64,
    #[serde(rename = "__pxTotalOffsetY", default, deserialize_with = "pixels")]
    pub(super) px_offset_y: i64,
    #[serde(rename = "layerDefUid", default)]
    pub(super) layer_def_uid: i64,
    #[serde(rename = "intGridCsv", default, deserialize_with = "csv")]
    pub(super) int_grid_csv: Option<Vec<i64>>,
    /// LDtk before 0.7: the non-zero cells as (cell index, value index from 0).
    #[serde(rename = "intGrid", default)]
    pub(super) int_grid: Option<Vec<OldCell>>,
    #[serde(rename = "entityInstances", default)]
    pub(super) entity_instances: Vec<Entity>,
}

#[derive(Deserialize)]
pub(super) struct OldCell {
    #[serde(rename = "coordId")]
    pub(super) coord_id: i64,
    pub(super) v: i64,
}

#[derive(Deserialize)]
pub(super) struct Entity {
    #[serde(rename = "__identifier", default)]
    pub(super) identifier: String,
    #[serde(rename = "__pivot", default, deserialize_with = "pivot")]
    pub(super) pivot: [f64; 2],
    #[serde(default, deserialize_with = "point")]
    pub(super) px: [f64; 2],
    #[serde(default, deserialize_with = "extent")]
    pub(super) width: f64,
    #[serde(default, deserialize_with = "extent")]
    pub(super) height: f64,
}

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

/// A layer's width or height in cells, within [`crate::limits::MAX_TILES`] (a layer wider
/// than that is more cells than any level may have); beyond, an error serde_json places.
fn cells<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    let v = i64::deserialize(d)?;
    if v.checked_abs()
        .is_none_or(|a| a as u64 > crate::limits::MAX_TILES)
    {
        return Err(serde::de::Error::custom(format!(
            "a layer of {v} cells across; expected at most {} (the most tiles a level may \
             have)",
            crate::limits::MAX_TILES
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
    #[serde(rename = "pxWid", default, deserialize_with = "pixels")]
    pub(super) px_wid: i64,
    #[serde(rename = "pxHei", default, deserialize_with = "pixels")]
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
    #[serde(rename = "intGridCsv", default)]
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
    #[serde(rename = "__pivot", default)]
    pub(super) pivot: Vec<f64>,
    #[serde(default)]
    pub(super) px: Vec<f64>,
    #[serde(default)]
    pub(super) width: f64,
    #[serde(default)]
    pub(super) height: f64,
}

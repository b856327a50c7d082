//! What an IntGrid layer's cells may hold, from the project's layer definitions: the values
//! each layer defines and their names (which `--intgrid` and the names' words read), a layer
//! whose definition is missing, a cell holding a value its layer does not define, and an
//! `--intgrid` value no layer defines. LDtk removes a value's cells when the value is deleted,
//! so a project it saved holds none of these.

use std::collections::HashMap;

use super::json::{Defs, LayerInstance};
use crate::level::import::ImportOptions;

/// The values layer `layer` (named `lname` in errors) defines, each with its name (empty when
/// unnamed); none for a project without layer definitions (written by hand), whose values are
/// read without names. A layer whose `layerDefUid` names no definition is an error.
pub(super) fn defined(defs: &Defs, layer: &LayerInstance, lname: &str) -> Result<Defined, String> {
    if defs.layers.is_empty() {
        return Ok(Defined::default());
    }
    let Some(def) = defs.layers.iter().find(|d| d.uid == layer.layer_def_uid) else {
        let uids: Vec<String> = defs.layers.iter().map(|d| d.uid.to_string()).collect();
        return Err(format!(
            "layer {lname:?}: its layerDefUid {} names no layer definition; expected the uid of one of the project's (defs.layers: {})",
            layer.layer_def_uid,
            uids.join(", ")
        ));
    };
    let list: Vec<(i64, String)> = (def.int_grid_values.iter().enumerate())
        .map(|(i, v)| {
            let name = v.identifier.clone().unwrap_or_default();
            (v.value.unwrap_or(i as i64 + 1), name)
        })
        .collect();
    // The first of a value defined twice names it, as a search of the list would.
    let mut by_value = HashMap::new();
    for (k, (v, _)) in list.iter().enumerate() {
        by_value.entry(*v).or_insert(k);
    }
    Ok(Defined { list, by_value })
}

/// The values a layer defines, in its definition's order, and each value's place in it: a
/// cell's value is looked up once, whatever the number of values.
#[derive(Default)]
pub(super) struct Defined {
    list: Vec<(i64, String)>,
    by_value: HashMap<i64, usize>,
}

impl Defined {
    /// The name of value `v` (empty when unnamed or not defined).
    pub(super) fn name(&self, v: i64) -> &str {
        self.by_value
            .get(&v)
            .and_then(|&k| self.list.get(k))
            .map_or("", |(_, n)| n.as_str())
    }

    /// An error unless `v`, the value of cell `(x, y)` (the layer's column and row from its
    /// top-left, as LDtk shows them), is one the layer defines (none to check without
    /// definitions).
    pub(super) fn check_cell(&self, lname: &str, (x, y): (i64, i64), v: i64) -> Result<(), String> {
        if self.list.is_empty() || self.by_value.contains_key(&v) {
            return Ok(());
        }
        Err(format!(
            "layer {lname:?}: cell x = {x}, y = {y} holds IntGrid value {v}, which the layer's definition does not list; expected 0 (empty) or one of {} (LDtk removes a value's cells when the value is deleted)",
            listed(&self.list)
        ))
    }
}

/// `1 "Wall", 2 "Platform", 3`: values and their names, the first 20 of a longer list.
fn listed(values: &[(i64, String)]) -> String {
    let each = values.iter().take(20).map(|(v, n)| match n.is_empty() {
        true => v.to_string(),
        false => format!("{v} {n:?}"),
    });
    let mut out = each.collect::<Vec<_>>().join(", ");
    if values.len() > 20 {
        out.push_str(&format!(", ... ({} in all)", values.len()));
    }
    out
}

/// The `--intgrid` keys (a value's number or name) that no IntGrid layer definition of the
/// project defines, each with what the project defines: they change nothing. None for a
/// project without definitions, whose values have no names to check.
pub(super) fn unused_options(defs: &Defs, opts: &ImportOptions) -> Vec<String> {
    if opts.intgrid.is_empty() {
        return Vec::new();
    }
    // Each value once, in the definitions' order (a set: a project may define many).
    let mut seen = std::collections::HashSet::new();
    let values: Vec<(i64, String)> = defs
        .layers
        .iter()
        .flat_map(|d| {
            (d.int_grid_values.iter().enumerate())
                .map(|(i, v)| (v.value.unwrap_or(i as i64 + 1), v.identifier.clone()))
        })
        .map(|(v, n)| (v, n.unwrap_or_default()))
        .filter(|v| seen.insert(v.clone()))
        .collect();
    if values.is_empty() {
        return Vec::new();
    }
    let norm = crate::level::import::normalize;
    opts.intgrid
        .iter()
        .map(|(key, _)| key)
        .filter(|key| {
            !values.iter().any(|(v, n)| {
                key.trim() == v.to_string() || (!n.is_empty() && norm(key) == norm(n))
            })
        })
        .map(|key| {
            format!(
                "--intgrid {key}: no IntGrid value of the project is {key} or named so; it changes nothing (the values: {})",
                listed(&values)
            )
        })
        .collect()
}

//! Tiled's JSON formats as the XML the `tiled` crate reads: a JSON map (`.tmj`, or `.json`) as
//! its TMX twin, a JSON tileset (`.tsj`) as TSX and a JSON template (`.tj`) as TX. The crate
//! reads TMX only; translating the text keeps one reader, so a JSON map gets the same rules,
//! limits and errors as a TMX map. The text is walked first ([`super::json_walk`]): what the tree
//! serde_json builds would hold is counted and refused past the limits before it is built. Each
//! layer of a translated map starts a line of its own, so an error found at a line of the TMX
//! names the JSON layer it came from ([`JsonMap::layer_at`]) and its line in the JSON.

use std::fmt::Write as _;

use serde_json::{Map, Value};

use super::error::JsonError;
use super::json_walk::{walk, Lines, Walked};
use super::normalize::{count_tiles, Normalized, TilesetInfo};
use crate::limits;

pub(super) use super::json_walk::JsonMap;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn scalar(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Null => String::new(),
        other => other.to_string(),
    }
}

/// `<properties>` of a JSON properties list (`[{name, type, value}]`, Tiled 1.2+) or object
/// (older: `{name: value}`).
fn properties_xml(v: Option<&Value>) -> String {
    let mut out = String::new();
    let mut push = |name: &str, ty: &str, value: &Value| {
        let ty = match ty {
            "" => match value {
                Value::Bool(_) => "bool",
                Value::Number(n) if n.is_i64() || n.is_u64() => "int",
                Value::Number(_) => "float",
                _ => "string",
            },
            t => t,
        };
        if ty == "class" {
            return;
        }
        let _ = write!(
            out,
            "<property name=\"{}\" type=\"{}\" value=\"{}\"/>",
            esc(name),
            esc(ty),
            esc(&scalar(value))
        );
    };
    match v {
        Some(Value::Array(list)) => {
            for p in list {
                let name = p.get("name").and_then(Value::as_str).unwrap_or_default();
                let ty = p.get("type").and_then(Value::as_str).unwrap_or("");
                push(name, ty, p.get("value").unwrap_or(&Value::Null));
            }
        }
        Some(Value::Object(map)) => {
            for (k, value) in map {
                push(k, "", value);
            }
        }
        _ => {}
    }
    if out.is_empty() {
        out
    } else {
        format!("<properties>{out}</properties>")
    }
}

fn num_attr(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

/// The attributes among `keys` that `v` has, as XML: numbers and strings as they are, bools as
/// 1 or 0 (as TMX writes them). A key absent from the JSON is left out, so an object made from a
/// template keeps what its template gives.
fn attrs(v: &Value, keys: &[&str]) -> String {
    let mut out = String::new();
    for k in keys {
        let text = match v.get(*k) {
            Some(Value::Bool(b)) => u8::from(*b).to_string(),
            Some(Value::Number(n)) => n.to_string(),
            Some(Value::String(s)) => esc(s),
            _ => continue,
        };
        let _ = write!(out, " {k}=\"{text}\"");
    }
    out
}

/// One object (of an object layer, a tile's collision shapes or a template) as XML.
fn object_xml(o: &Value) -> String {
    let mut a = attrs(
        o,
        &[
            "id", "name", "x", "y", "width", "height", "rotation", "gid", "visible", "template",
        ],
    );
    // Tiled 1.9 writes `class` where older versions wrote `type`; the crate reads either.
    if let Some(c) = o
        .get("class")
        .or_else(|| o.get("type"))
        .and_then(Value::as_str)
    {
        if !c.is_empty() {
            let _ = write!(a, " type=\"{}\"", esc(c));
        }
    }
    let points = |key: &str| -> Option<String> {
        let list = o.get(key)?.as_array()?;
        let p: Vec<String> = list
            .iter()
            .map(|p| {
                format!(
                    "{},{}",
                    num_attr(p, "x").unwrap_or(0.0),
                    num_attr(p, "y").unwrap_or(0.0)
                )
            })
            .collect();
        Some(p.join(" "))
    };
    let flag = |k: &str| o.get(k).and_then(Value::as_bool) == Some(true);
    let inner = if let Some(p) = points("polygon") {
        format!("<polygon points=\"{p}\"/>")
    } else if let Some(p) = points("polyline") {
        format!("<polyline points=\"{p}\"/>")
    } else if flag("ellipse") {
        "<ellipse/>".into()
    } else if flag("capsule") {
        "<capsule/>".into()
    } else if flag("point") {
        "<point/>".into()
    } else if let Some(t) = o.get("text") {
        let s = t.get("text").and_then(Value::as_str).unwrap_or_default();
        format!("<text>{}</text>", esc(s))
    } else {
        String::new()
    };
    format!(
        "<object{a}>{}{inner}</object>",
        properties_xml(o.get("properties"))
    )
}

/// A tileset's JSON as a `<tileset>` element; `firstgid` for one embedded in a map.
fn tileset_xml(
    v: &Value,
    firstgid: Option<u64>,
    notes: &mut Vec<String>,
) -> Result<String, JsonError> {
    let n = |k: &str| num_attr(v, k).map(|x| x.max(0.0) as u64);
    let name = v.get("name").and_then(Value::as_str).unwrap_or_default();
    let (tw, th) = (n("tilewidth").unwrap_or(0), n("tileheight").unwrap_or(0));
    let image = v.get("image").and_then(Value::as_str);
    let mut tiles: Vec<(u64, &Value)> = Vec::new();
    match v.get("tiles") {
        Some(Value::Array(list)) => {
            for t in list {
                if let Some(id) = num_attr(t, "id") {
                    tiles.push((id.max(0.0) as u64, t));
                }
            }
        }
        Some(Value::Object(map)) => {
            for (k, t) in map {
                if let Ok(id) = k.parse::<u64>() {
                    tiles.push((id, t));
                }
            }
        }
        _ => {}
    }
    let info = TilesetInfo {
        name: name.to_string(),
        insert_at: 0,
        tilecount: n("tilecount"),
        tile_width: tw,
        tile_height: th,
        spacing: n("spacing").unwrap_or(0),
        margin: n("margin").unwrap_or(0),
        image: image.map(|_| (n("imagewidth").unwrap_or(0), n("imageheight").unwrap_or(0))),
        max_id: tiles.iter().map(|t| t.0).max(),
        line: 1,
        depth: 0,
    };
    let count = match info.tilecount {
        Some(c) => c,
        None => {
            let c = count_tiles(&info);
            notes.push(format!("tileset {name:?} has no tilecount; {c} computed"));
            c
        }
    };
    if count > limits::MAX_TILES {
        return Err(JsonError::TooManyTiles {
            count,
            max: limits::MAX_TILES,
        });
    }
    let mut out = String::from("<tileset");
    if let Some(g) = firstgid {
        let _ = write!(out, " firstgid=\"{g}\"");
    }
    let _ = write!(
        out,
        " name=\"{}\" tilewidth=\"{tw}\" tileheight=\"{th}\" tilecount=\"{count}\" spacing=\"{}\" margin=\"{}\"",
        esc(name),
        info.spacing,
        info.margin
    );
    if let Some(c) = n("columns") {
        let _ = write!(out, " columns=\"{c}\"");
    }
    out.push('>');
    out.push_str(&properties_xml(v.get("properties")));
    if let Some(img) = image {
        let _ = write!(
            out,
            "<image source=\"{}\" width=\"{}\" height=\"{}\"/>",
            esc(img),
            info.image.map_or(0, |i| i.0),
            info.image.map_or(0, |i| i.1)
        );
    }
    for (id, t) in tiles {
        let class = t
            .get("class")
            .or_else(|| t.get("type"))
            .and_then(Value::as_str)
            .unwrap_or_default();
        let _ = write!(out, "<tile id=\"{id}\"");
        if !class.is_empty() {
            let _ = write!(out, " type=\"{}\"", esc(class));
        }
        out.push('>');
        out.push_str(&properties_xml(t.get("properties")));
        if let Some(img) = t.get("image").and_then(Value::as_str) {
            let _ = write!(
                out,
                "<image source=\"{}\" width=\"{}\" height=\"{}\"/>",
                esc(img),
                num_attr(t, "imagewidth").unwrap_or(0.0) as u64,
                num_attr(t, "imageheight").unwrap_or(0.0) as u64
            );
        }
        if let Some(objs) = t
            .get("objectgroup")
            .and_then(|g| g.get("objects"))
            .and_then(Value::as_array)
        {
            out.push_str("<objectgroup>");
            for o in objs {
                out.push_str(&object_xml(o));
            }
            out.push_str("</objectgroup>");
        }
        out.push_str("</tile>");
    }
    out.push_str("</tileset>");
    Ok(out)
}

/// The top object of a JSON file walked within the limits, or why it is not one.
fn top(text: &str, what: &'static str) -> Result<(Map<String, Value>, Walked), JsonError> {
    let walked = walk(text, what)?;
    match serde_json::from_str(text).map_err(JsonError::Syntax)? {
        Value::Object(m) => Ok((m, walked)),
        _ => Err(JsonError::NotObject),
    }
}

/// A JSON tileset (Tiled's `.tsj`, or `.json` from older versions) as the TSX the crate reads.
/// `Err` says what is wrong, with the line and column of a JSON syntax error.
pub(super) fn json_tileset_to_tsx(text: &str) -> Result<Normalized, JsonError> {
    let v = Value::Object(top(text, "a Tiled tileset")?.0);
    let mut notes = vec!["a JSON tileset; read through its TSX equivalent".to_string()];
    let ts = tileset_xml(&v, None, &mut notes)?;
    Ok(Normalized {
        text: format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{ts}\n"),
        notes,
    })
}

/// A JSON template (`.tj`) as the TX the crate reads: its object, and the tileset a tile
/// object's `gid` refers to.
pub(super) fn json_template_to_tx(text: &str) -> Result<Normalized, JsonError> {
    let v = Value::Object(top(text, "a Tiled template")?.0);
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<template>");
    if let Some(ts) = v.get("tileset") {
        out.push_str(&format!("<tileset{}/>", attrs(ts, &["firstgid", "source"])));
    }
    if let Some(o) = v.get("object") {
        out.push_str(&object_xml(o));
    }
    out.push_str("</template>\n");
    Ok(Normalized {
        text: out,
        notes: vec!["a JSON template; read through its TX equivalent".into()],
    })
}

/// A layer's tile data (`data`, or a chunk's) as the text of a `<data>` or `<chunk>`: an array
/// of gids as CSV, one map row a line; a base64 string as it is.
fn data_text(v: &Value, width: u64, layer: &str, out: &mut String) -> Result<(), JsonError> {
    match v.get("data") {
        Some(Value::Array(cells)) => {
            out.push('\n');
            for (i, c) in cells.iter().enumerate() {
                let gid = c
                    .as_u64()
                    .filter(|g| *g <= u64::from(u32::MAX))
                    .ok_or_else(|| JsonError::BadCell {
                        layer: layer.to_string(),
                        index: i,
                        found: c.to_string(),
                    })?;
                let _ = write!(out, "{gid}");
                if i + 1 < cells.len() {
                    out.push(',');
                }
                if width > 0 && (i as u64 + 1).is_multiple_of(width) {
                    out.push('\n');
                }
            }
        }
        Some(Value::String(s)) => out.push_str(&esc(s.trim())),
        _ => {}
    }
    Ok(())
}

/// `<data>`'s attributes: a JSON array of cells is CSV (a `<data>` with no encoding would be
/// TMX's XML cells), a string is as `encoding` and `compression` say.
fn data_attrs(l: &Value) -> String {
    let chunked = l.get("chunks").and_then(Value::as_array);
    let data = chunked.and_then(|c| c.first()).unwrap_or(l).get("data");
    if !matches!(data, Some(Value::String(_))) {
        return " encoding=\"csv\"".into();
    }
    attrs(l, &["encoding", "compression"]).replace(" compression=\"\"", "")
}

/// One layer (and the layers of a group) as TMX, each element on a line of its own; `path` is
/// its place in the map.
fn layer_xml(
    l: &Value,
    out: &mut String,
    lines: &mut Lines,
    path: &mut Vec<u32>,
) -> Result<(), JsonError> {
    let name = l.get("name").and_then(Value::as_str).unwrap_or_default();
    let cells = matches!(l.get("data"), Some(Value::Array(_))) && l.get("chunks").is_none();
    let width = num_attr(l, "width")
        .filter(|_| cells)
        .map(|w| w.max(0.0) as u64);
    lines.push(out, format!("layer {name:?}"), Some((path, width)));
    let common = [
        "id",
        "name",
        "class",
        "opacity",
        "visible",
        "offsetx",
        "offsety",
        "parallaxx",
        "parallaxy",
        "tintcolor",
    ];
    let props = properties_xml(l.get("properties"));
    match l.get("type").and_then(Value::as_str).unwrap_or_default() {
        "tilelayer" => {
            let width = num_attr(l, "width").unwrap_or(0.0).max(0.0) as u64;
            let _ = write!(
                out,
                "<layer{}{}>{props}<data{}>",
                attrs(l, &common),
                attrs(l, &["width", "height"]),
                data_attrs(l)
            );
            if let Some(chunks) = l.get("chunks").and_then(Value::as_array) {
                for c in chunks {
                    let cw = num_attr(c, "width").unwrap_or(0.0).max(0.0) as u64;
                    let _ = write!(out, "\n<chunk{}>", attrs(c, &["x", "y", "width", "height"]));
                    data_text(c, cw, name, out)?;
                    out.push_str("</chunk>");
                }
            } else {
                data_text(l, width, name, out)?;
            }
            out.push_str("</data></layer>\n");
        }
        "objectgroup" => {
            let _ = writeln!(
                out,
                "<objectgroup{}{}>{props}",
                attrs(l, &common),
                attrs(l, &["color", "draworder"])
            );
            for o in l
                .get("objects")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
            {
                out.push_str(&object_xml(o));
                out.push('\n');
            }
            out.push_str("</objectgroup>\n");
        }
        "imagelayer" => {
            let _ = write!(out, "<imagelayer{}>{props}", attrs(l, &common));
            if let Some(img) = l.get("image").and_then(Value::as_str) {
                // The crate requires an image's size; Tiled writes it as imagewidth/height.
                let size = |k: &str| num_attr(l, k).unwrap_or(0.0).max(0.0) as u64;
                let _ = write!(
                    out,
                    "<image source=\"{}\" width=\"{}\" height=\"{}\"/>",
                    esc(img),
                    size("imagewidth"),
                    size("imageheight")
                );
            }
            out.push_str("</imagelayer>\n");
        }
        "group" => {
            let _ = writeln!(out, "<group{}>{props}", attrs(l, &common));
            for (k, c) in l
                .get("layers")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
                .enumerate()
            {
                path.push(k as u32);
                layer_xml(c, out, lines, path)?;
                path.pop();
            }
            out.push_str("</group>\n");
            lines.push(out, "the map's layers".into(), None);
        }
        other => {
            return Err(JsonError::LayerType {
                layer: name.to_string(),
                found: other.to_string(),
            })
        }
    }
    Ok(())
}

/// The attributes of a map's header, as TMX names them (the JSON keys are the same).
#[rustfmt::skip]
const MAP_ATTRS: &[&str] = &[
    "version", "tiledversion", "class", "orientation", "renderorder", "width", "height",
    "tilewidth", "tileheight", "hexsidelength", "staggeraxis", "staggerindex", "infinite",
    "nextlayerid", "nextobjectid", "backgroundcolor",
];

/// A JSON map (Tiled's `.tmj`, or `.json`) as the TMX the crate reads. `Err` says what is
/// wrong: a JSON syntax error with its line and column, a tileset or LDtk file given as a map,
/// a cell that is not a tile id with its layer and index.
pub(super) fn json_map_to_tmx(text: &str) -> Result<JsonMap, JsonError> {
    let (m, walked) = top(text, "a Tiled map")?;
    let kind = m.get("type").and_then(Value::as_str).unwrap_or("map");
    if kind != "map" || !m.contains_key("layers") {
        let mut keys: Vec<&str> = m.keys().map(String::as_str).take(8).collect();
        keys.sort_unstable();
        return Err(JsonError::NotAMap {
            kind: kind.to_string(),
            keys: keys.join(", "),
        });
    }
    let v = Value::Object(m);
    let mut notes = Vec::new();
    let mut out = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<map{}>{}\n",
        attrs(&v, MAP_ATTRS),
        properties_xml(v.get("properties"))
    );
    for ts in v
        .get("tilesets")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
    {
        let firstgid = num_attr(ts, "firstgid").unwrap_or(1.0).max(0.0) as u64;
        match ts.get("source").and_then(Value::as_str) {
            Some(s) => {
                let _ = writeln!(
                    out,
                    "<tileset firstgid=\"{firstgid}\" source=\"{}\"/>",
                    esc(s)
                );
            }
            None => {
                out.push_str(&tileset_xml(ts, Some(firstgid), &mut notes)?);
                out.push('\n');
            }
        }
    }
    let mut lines = Lines::new(&walked);
    for (k, l) in v
        .get("layers")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
    {
        layer_xml(l, &mut out, &mut lines, &mut vec![k as u32])?;
    }
    out.push_str("</map>\n");
    Ok(JsonMap {
        tmx: Normalized { text: out, notes },
        layers: lines.list,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_json_map_becomes_tmx_with_its_layers_on_their_lines() {
        let j = r#"{"type":"map","width":2,"height":2,"tilewidth":16,"tileheight":16,
            "orientation":"orthogonal","infinite":false,
            "tilesets":[{"firstgid":1,"source":"t.tsj"}],
            "layers":[{"type":"tilelayer","name":"ground","width":2,"height":2,"data":[0,1,1,1]},
                      {"type":"group","name":"g","layers":[
                        {"type":"objectgroup","name":"objects","objects":[
                          {"id":3,"name":"spawn","point":true,"x":8,"y":4}]}]}]}"#;
        let m = json_map_to_tmx(j).ok().unwrap();
        let t = &m.tmx.text;
        assert!(t.contains("infinite=\"0\""), "{t}");
        assert!(
            t.contains("<data encoding=\"csv\">\n0,1,\n1,1\n</data>"),
            "{t}"
        );
        assert!(
            t.contains("<object id=\"3\" name=\"spawn\" x=\"8\" y=\"4\"><point/></object>"),
            "{t}"
        );
        let line = t.lines().position(|l| l == "0,1,").unwrap() + 1;
        assert_eq!(m.layer_at(line), "layer \"ground\"");
        let line = t.lines().position(|l| l.contains("<object ")).unwrap() + 1;
        assert_eq!(m.layer_at(line), "layer \"objects\"");
        assert_eq!(m.layer_at(1), "the map's header");
    }

    #[test]
    fn a_tileset_or_a_bad_cell_is_said_as_such() {
        let e = json_map_to_tmx(r#"{"type":"tileset","tilewidth":16}"#)
            .err()
            .unwrap();
        assert!(e.to_string().contains("a Tiled tileset"), "{e}");
        let e = json_map_to_tmx(
            r#"{"layers":[{"type":"tilelayer","name":"g","width":2,"data":[0,-3]}]}"#,
        )
        .err()
        .unwrap();
        // Found by the walk, at the cell.
        assert!(e
            .to_string()
            .contains("1, column 63: layer \"g\": cell x = 1"));
        assert!(e
            .to_string()
            .contains("of its data) is -3; expected a tile id"));
    }

    #[test]
    fn a_json_template_becomes_tx() {
        let t = r#"{"type":"template","tileset":{"firstgid":1,"source":"t.tsj"},
            "object":{"name":"crate","class":"Block","width":16,"height":16,"gid":2}}"#;
        let x = json_template_to_tx(t).ok().unwrap().text;
        assert!(
            x.contains("<tileset firstgid=\"1\" source=\"t.tsj\"/>"),
            "{x}"
        );
        assert!(
            x.contains(
                "<object name=\"crate\" width=\"16\" height=\"16\" gid=\"2\" type=\"Block\">"
            ),
            "{x}"
        );
    }
}

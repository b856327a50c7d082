//! Files as Tiled writes them import to the same level as their CSV twins (the old XML cell
//! encoding in an infinite map's chunks, an infinite map's empty layer), and what the import
//! says is the same each run, although the `tiled` crate keeps properties in hash maps; an
//! unset colour property (value "") imports.

#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::Path;

use platbench::level::{import_tiled_map_with, Edges, ImportOptions};

use super::tiled::shipped;

fn open_edges() -> ImportOptions {
    ImportOptions {
        edges: Some(Edges::Open),
        ..ImportOptions::default()
    }
}

/// The level's tiles as the level format writes them, top row first.
fn grid_of(path: &Path) -> String {
    let r = import_tiled_map_with(path, &open_edges())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    platbench::level::import::ascii_map(&r.level).0
}

/// tests/maps/infinite.tmx with its CSV chunk written as Tiled's old XML cells: one
/// `<tile gid=".."/>` per cell (`<tile/>` for an empty one), no `encoding` attribute.
fn as_xml_cells(csv_map: &str) -> String {
    let open = csv_map
        .find("<data encoding=\"csv\">")
        .expect("a CSV layer");
    let chunk = csv_map[open..]
        .find('>')
        .map(|k| open + k + 1)
        .expect("<data>");
    let body_start = csv_map[chunk..]
        .find('>')
        .map(|k| chunk + k + 1)
        .expect("<chunk>");
    let body_end = csv_map[body_start..]
        .find("</chunk>")
        .map(|k| body_start + k)
        .expect("</chunk>");
    let cells: String = csv_map[body_start..body_end]
        .split(',')
        .map(|c| match c.trim() {
            "0" => "<tile/>\n".to_string(),
            gid => format!("<tile gid=\"{gid}\"/>\n"),
        })
        .collect();
    format!(
        "{}<data>{}{cells}{}",
        &csv_map[..open],
        &csv_map[chunk..body_start],
        &csv_map[body_end..]
    )
}

#[test]
fn an_infinite_map_in_the_old_xml_cell_encoding_imports_as_its_csv_twin() {
    let dir = tempfile::tempdir().unwrap();
    let csv = std::fs::read_to_string(shipped("infinite.tmx")).unwrap();
    let xml = as_xml_cells(&csv);
    assert!(xml.contains("<tile gid=\"1\"/>") && !xml.contains("encoding=\"csv\""));
    let path = dir.path().join("xml_cells.tmx");
    std::fs::write(&path, &xml).unwrap();
    // Before: "its data holds 1 comma-separated cells; expected exactly 600 cells" (the
    // chunks were dropped when the cells became CSV).
    assert_eq!(grid_of(&path), grid_of(&shipped("infinite.tmx")));
}

#[test]
fn an_infinite_maps_empty_layer_imports() {
    // Tiled writes a tile layer of an infinite map that holds nothing as "chunks": [] with
    // width and height 0 (tests/maps/infinite.json is the same map with its one chunk).
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shipped("infinite.json")).unwrap();
    let mut map: serde_json::Value = serde_json::from_str(&text).unwrap();
    let layers = map["layers"].as_array_mut().unwrap();
    layers.push(serde_json::json!({
        "id": 9, "name": "empty", "type": "tilelayer", "chunks": [], "width": 0, "height": 0,
        "startx": 0, "starty": 0, "x": 0, "y": 0, "opacity": 1, "visible": true
    }));
    let path = dir.path().join("empty_layer.tmj");
    std::fs::write(&path, serde_json::to_string_pretty(&map).unwrap()).unwrap();
    // Before: "its data holds 1 comma-separated cells; expected exactly 0 cells".
    assert_eq!(grid_of(&path), grid_of(&shipped("infinite.json")));
}

#[test]
fn a_spawns_unread_properties_are_warned_about_in_name_order() {
    // The tiled crate keeps properties in a hash map, whose order changes from run to run:
    // the warnings follow the names, so `inspect` says the same each time. Eight properties
    // given in reverse: a hash order that happened to be sorted would pass 1 time in 40,320.
    let names = ["h", "g", "f", "e", "d", "c", "b", "a"];
    let props: String = names
        .iter()
        .map(|n| format!(r#"<property name="{n}" value="1"/>"#))
        .collect();
    let objects = format!(
        r#"<object id="1" name="s" class="spawn" x="8" y="16"><properties>{props}</properties><point/></object>"#
    );
    let r = super::tiled::MapText {
        objects: &objects,
        ..Default::default()
    }
    .import()
    .unwrap();
    let warned: Vec<String> = r
        .warnings
        .iter()
        .map(ToString::to_string)
        .filter(|w| w.contains("on a spawn point"))
        .collect();
    let order: Vec<&str> = names.iter().rev().copied().collect();
    let found: Vec<&str> = warned
        .iter()
        .filter_map(|w| {
            order
                .iter()
                .copied()
                .find(|n| w.contains(&format!("\"{n}\"")))
        })
        .collect();
    assert_eq!(found, order, "{warned:#?}");
}

#[test]
fn a_colour_property_left_unset_imports() {
    // Tiled writes a colour property with no colour as value="" (the tiled crate refused it:
    // "Unknown property value type 'color'"); a set one beside it is read as before.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shipped("showcase.tmx")).unwrap();
    let props = r##"<properties>
  <property name="tint" type="color" value=""/>
  <property name="sky" type="color" value="#ff80a0c0"/>"##;
    let text = text.replacen("<properties>", props, 1);
    assert!(text.contains("name=\"tint\""));
    let path = dir.path().join("unset_colour.tmx");
    std::fs::write(&path, &text).unwrap();
    // The showcase's external tileset, beside it.
    std::fs::copy(shipped("terrain.tsx"), dir.path().join("terrain.tsx")).unwrap();
    assert_eq!(grid_of(&path), grid_of(&shipped("showcase.tmx")));
    let r = import_tiled_map_with(&path, &open_edges()).unwrap();
    let said: Vec<String> = r.warnings.iter().map(ToString::to_string).collect();
    assert!(
        said.iter()
            .any(|w| w.contains("\"tint\" is a colour left unset")),
        "{said:#?}"
    );
}

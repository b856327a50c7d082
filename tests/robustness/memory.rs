//! Issue 40, memory and work proportional to the map: a character far larger than its map is
//! measured on the map's cells only (the metrics once scanned every cell of its box, a million
//! a frame for a 1000-tile character), and a Tiled map whose tile layers together hold more
//! cells than platbench reads is refused before any layer is read, naming the file and the limit.

#![cfg(all(feature = "rapier", feature = "box2d", feature = "tiled"))]

use crate::common::{assert_success, platbench};

use super::hostile::assert_error;

/// A 10 x 5 map, and a character of 1000 x 1000 tiles (the largest `size`, SIZE_RANGE in
/// src/limits.rs) walking on its floor for a second.
const BIG_CHARACTER: &str = "name = \"bigchar\"\nmap = \"\"\"\n..........\n..........\n..........\n..........\n##########\n\"\"\"\n[[scenario]]\nname = \"walk\"\nspawn = [5.0, 1.0]\nsize = [1000.0, 1000.0]\nduration = 1.0\ninputs = [ { t = 0.0, right = true }, { t = 0.5, right = false } ]\n";

#[test]
fn a_character_far_larger_than_its_map_is_measured_on_the_map() {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("bigchar.toml");
    std::fs::write(&level, BIG_CHARACTER).unwrap();
    let out = dir.path().join("o");
    let run = platbench()
        .arg("run")
        .arg(&level)
        .args(["--traces", "none", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_success(&run);
    let csv = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let value = |backend: &str, metric: &str| -> Vec<f64> {
        rows.iter()
            .filter(|r| r[2] == backend && r[4] == metric)
            .map(|r| r[5].parse::<f64>().unwrap())
            .collect()
    };
    // Every backend ran and was measured (its configurations each have their rows).
    for backend in ["sweep", "rapier", "box2d"] {
        assert!(!value(backend, "max_penetration").is_empty(), "{csv}");
    }
    // The box stands on the floor's row (a wall of the map's own width under a body a hundred
    // times wider): nothing of the map is inside it, it passes through nothing, and it stays
    // over the map. The sweep's three configurations measured 0 for each when the scan covered
    // the whole box, and the values with the scan clipped to the map are the same (the
    // per-cell equality is `metrics::ground`'s `clipped_scans_equal_the_whole_box` test).
    for metric in ["max_penetration", "tunneled", "left_level"] {
        let sweep = value("sweep", metric);
        assert_eq!(sweep, vec![0.0; 3], "{metric}: {csv}");
    }
}

#[test]
fn tile_layers_holding_more_cells_than_platbench_reads_are_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("layers.tmx");
    // Seventeen layers of the largest map (MAX_TILES, a million cells each) hold 17 million
    // cells together, over MAX_LAYER_CELLS (16 million, src/limits.rs): refused at the
    // seventeenth layer's line, before any layer is read (the layers need no data for that).
    let mut text = String::from(
        "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"1000\" height=\"1000\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n",
    );
    for k in 0..17 {
        text.push_str(&format!(
            " <layer id=\"{}\" name=\"l{k}\" width=\"1000\" height=\"1000\"/>\n",
            k + 1
        ));
    }
    text.push_str("</map>\n");
    std::fs::write(&map, text).unwrap();
    let out = platbench().arg("inspect").arg(&map).output().unwrap();
    // The file, the seventeenth layer's line (line 2 opens the map, the layers follow), and
    // the limit.
    assert_error(&out, "layers.tmx:19");
    assert_error(&out, "layer \"l16\"");
    assert_error(&out, "expected at most 16000000");
    // Sixteen such layers are within the limit: no such refusal (the map then reads as empty
    // layers, whatever else is said of it).
    let sixteen: String = std::fs::read_to_string(&map)
        .unwrap()
        .lines()
        .filter(|l| !l.contains("name=\"l16\""))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&map, sixteen).unwrap();
    let out = platbench().arg("inspect").arg(&map).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("cells together"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A 10 x 5 map whose object layer holds `n` empty objects, one a line from line 4.
fn objects_map(n: usize) -> String {
    let mut text = String::from(
        "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"10\" height=\"5\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n <objectgroup id=\"1\" name=\"coins\">\n",
    );
    for i in 0..n {
        text.push_str(&format!("  <object id=\"{}\" x=\"8\" y=\"8\"/>\n", i + 1));
    }
    text.push_str(" </objectgroup>\n</map>\n");
    text
}

#[test]
fn a_tmx_map_of_more_elements_than_a_json_map_may_hold_objects_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("objects.tmx");
    // The map, its object layer and MAX_JSON_OBJECTS - 2 objects are 500,000 elements
    // (MAX_JSON_OBJECTS, src/limits.rs, shared with Tiled JSON maps); one object more passes
    // the limit, at the line of that object: line 3 opens the layer, object k is on line 3 + k.
    let limit = 500_000;
    std::fs::write(&map, objects_map(limit - 2)).unwrap();
    let out = platbench().arg("inspect").arg(&map).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("expected at most 500000"), "{err}");
    std::fs::write(&map, objects_map(limit - 1)).unwrap();
    let out = platbench().arg("inspect").arg(&map).output().unwrap();
    assert_error(&out, &format!("objects.tmx:{}", 3 + limit - 1));
    assert_error(&out, "<object> is element 500001 of the map");
    assert_error(&out, "expected at most 500000");
}

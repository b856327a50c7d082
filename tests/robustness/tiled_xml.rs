//! Hostile Tiled XML (issue 40, the adversary's F2, F5, F10, F16, F6/F7, F9, F21, F22): each
//! ends in one error that names the file, line and column, what was found and what was
//! expected, or in a finished run. Every map, tileset and template is written by the test.

#![cfg(feature = "tiled")]

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::platbench;

use super::hostile::{assert_error, stderr};

/// A 6 x 4 map of one ground row, its tileset `ts.tsx` beside it, and `objects` (XML lines in
/// its object layer) with a spawn first. `map_attrs` are added to `<map>`.
fn write_map(dir: &Path, name: &str, map_attrs: &str, objects: &str) -> PathBuf {
    let ts = dir.join("ts.tsx");
    std::fs::write(
        &ts,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<tileset version=\"1.10\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\">\n <image source=\"t.png\" width=\"16\" height=\"16\"/>\n</tileset>\n",
    )
    .unwrap();
    let path = dir.join(name);
    std::fs::write(
        &path,
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"6\" height=\"4\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" nextlayerid=\"4\" nextobjectid=\"5\"{map_attrs}>\n <tileset firstgid=\"1\" source=\"ts.tsx\"/>\n <layer id=\"1\" name=\"ground\" width=\"6\" height=\"4\">\n  <data encoding=\"csv\">\n0,0,0,0,0,0,\n0,0,0,0,0,0,\n0,0,0,0,0,0,\n1,1,1,1,1,1\n</data>\n </layer>\n <objectgroup id=\"3\" name=\"objects\">\n  <object id=\"1\" name=\"start\" class=\"spawn\" x=\"40\" y=\"48\"><point/></object>\n{objects}\n </objectgroup>\n</map>\n"
        ),
    )
    .unwrap();
    path
}

fn inspect(path: &Path) -> Output {
    platbench().arg("inspect").arg(path).output().unwrap()
}

#[test]
fn an_element_of_thousands_of_attributes_is_refused_at_the_first_past_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    // 20,000 attributes on <map> took 6.7 s (quadratic); 64 is MAX_XML_ATTRIBUTES in
    // src/limits.rs, so attribute 65 is the first refused. The map's own 10 come first.
    let many: String = (0..20_000).map(|i| format!(" a{i}=\"1\"")).collect();
    let map = write_map(dir.path(), "many.tmx", &many, "");
    let out = inspect(&map);
    assert_error(&out, "many.tmx:2:");
    assert_error(
        &out,
        "<map> has 20010 attributes (attribute 65 is \"a54\"); expected at most 64",
    );
    // The same in a tileset the map uses: the tileset is named, at its line.
    let ts = dir.path().join("many.tsx");
    std::fs::write(
        &ts,
        format!("<?xml version=\"1.0\"?>\n<tileset name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"1\" columns=\"1\"{many}>\n</tileset>\n"),
    )
    .unwrap();
    let text = std::fs::read_to_string(write_map(dir.path(), "uses.tmx", "", ""))
        .unwrap()
        .replace("ts.tsx", "many.tsx");
    std::fs::write(dir.path().join("uses.tmx"), text).unwrap();
    let out = inspect(&dir.path().join("uses.tmx"));
    assert_error(&out, "many.tsx:2:");
    assert_error(&out, "<tileset> has 20005 attributes");
    // At the limit the map is read.
    let at: String = (0..54).map(|i| format!(" a{i}=\"1\"")).collect();
    let out = inspect(&write_map(dir.path(), "at.tmx", &at, ""));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn a_tileset_or_template_given_as_the_level_is_named_as_such() {
    let dir = tempfile::tempdir().unwrap();
    write_map(dir.path(), "m.tmx", "", "");
    let tx = dir.path().join("t.tx");
    std::fs::write(
        &tx,
        "<?xml version=\"1.0\"?>\n<template>\n <object width=\"16\" height=\"16\"/>\n</template>\n",
    )
    .unwrap();
    for (file, root, what) in [
        ("ts.tsx", "tileset", "a Tiled tileset"),
        ("t.tx", "template", "a Tiled object template"),
    ] {
        let out = platbench()
            .arg("run")
            .arg(dir.path().join(file))
            .output()
            .unwrap();
        assert_error(
            &out,
            &format!("{file}:2:1: the root element is <{root}> ({what}"),
        );
        assert_error(&out, "expected <map>, a Tiled map");
        // The crate's "missing or not a number" gloss said something false here.
        assert!(!stderr(&out).contains("not a number"), "{}", stderr(&out));
    }
}

#[test]
fn a_firstgid_of_0_is_refused_at_its_column_without_contradiction() {
    let dir = tempfile::tempdir().unwrap();
    let map = write_map(dir.path(), "m.tmx", "", "");
    let text = std::fs::read_to_string(&map)
        .unwrap()
        .replace("firstgid=\"1\"", "firstgid=\"0\"");
    std::fs::write(&map, text).unwrap();
    let out = inspect(&map);
    // Line 3, `<tileset ` is 10 bytes after the space that indents it.
    assert_error(&out, "m.tmx:3:11: <tileset>: attribute \"firstgid\" is \"0\"; expected a whole number from 1 to 4294967295");
    // It once said "expected 0 (no tile) or … gids 0 to 0".
    assert!(!stderr(&out).contains("0 to 0"), "{}", stderr(&out));
}

#[test]
fn numbers_past_f32_are_named_with_their_attribute_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let range =
        "expected a number such as 16, -2.5 or 1e3, finite within f32's range (-3.4e38 to 3.4e38)";
    // 1e39 and 1e308 are finite as text but infinite as f32; inf is what the crate reads.
    for (value, attr) in [("1e39", "x"), ("1e308", "y"), ("inf", "width")] {
        let objects =
            "  <object id=\"2\" name=\"wall\" x=\"0\" y=\"0\" width=\"16\" height=\"16\"/>"
                .replace(
                    &format!(" {attr}=\"{}\"", if attr == "width" { "16" } else { "0" }),
                    &format!(" {attr}=\"{value}\""),
                );
        let map = write_map(dir.path(), "m.tmx", "", &objects);
        let out = inspect(&map);
        assert_error(&out, "m.tmx:14:");
        assert_error(
            &out,
            &format!("object 2 \"wall\": attribute \"{attr}\" is \"{value}\"; {range}"),
        );
    }
    // A layer's offset of 1e39 once became inf and dropped every cell of the layer.
    let map = write_map(dir.path(), "o.tmx", "", "");
    let text = std::fs::read_to_string(&map)
        .unwrap()
        .replace("name=\"ground\"", "name=\"ground\" offsetx=\"1e39\"");
    std::fs::write(&map, text).unwrap();
    let out = inspect(&map);
    // ` <layer id="1" name="ground" ` is 29 bytes before it.
    assert_error(
        &out,
        &format!("o.tmx:4:30: layer \"ground\": attribute \"offsetx\" is \"1e39\"; {range}"),
    );
    // A float property (a platform's speed) the same.
    let objects = "  <object id=\"2\" name=\"lift\" x=\"0\" y=\"0\" width=\"16\" height=\"16\">\n   <properties><property name=\"speed\" type=\"float\" value=\"1e39\"/></properties>\n  </object>";
    let out = inspect(&write_map(dir.path(), "s.tmx", "", objects));
    assert_error(&out, "s.tmx:15:");
    assert_error(
        &out,
        &format!("property \"speed\": attribute \"value\" is \"1e39\"; {range}"),
    );
}

#[test]
fn malformed_xml_entities_and_cut_files_are_named_at_their_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let full = std::fs::read_to_string(write_map(dir.path(), "m.tmx", "", "")).unwrap();
    // An entity no DTD-less XML defines, and a character reference of no character: the
    // crate said "Unrecognized escape symbol" and "Null character entity" with no place.
    for (entity, name) in [("&bogus;", "e.tmx"), ("&#0;", "z.tmx")] {
        let p = write(
            name,
            &full.replace("name=\"start\"", &format!("name=\"s{entity}\"")),
        );
        let out = inspect(&p);
        // `  <object id="1" name="s` is 24 bytes before the `&` on line 13.
        assert_error(
            &out,
            &format!("{name}:13:25: <object>: attribute \"name\" holds {entity:?}; expected &amp;"),
        );
    }
    // A map cut short, inside an element and after one: the crate said "Document ended before
    // we expected." or gave its reader's byte position.
    let cut = &full[..full.find("<objectgroup").unwrap() + 20];
    let out = inspect(&write("cut.tmx", cut));
    assert_error(
        &out,
        "cut.tmx:12:2: the file ends inside the element that starts here",
    );
    let out = inspect(&write("open.tmx", &full.replace("</map>\n", "")));
    assert_error(&out, "open.tmx:16:1: the file ends before <map> (opened on line 2) is closed; expected </map> (was the file cut short?)");
    // A tileset cut short is named, not the map that uses it.
    write(
        "ts.tsx",
        "<?xml version=\"1.0\"?>\n<tileset name=\"t\" tilewid",
    );
    let out = inspect(&dir.path().join("m.tmx"));
    assert_error(&out, "ts.tsx:2:1:");
    assert_error(&out, "the file ends inside");
    // A property type Tiled does not write: the crate said "Unknown property value type".
    let objects = "  <object id=\"2\" name=\"o\" x=\"0\" y=\"0\" width=\"16\" height=\"16\">\n   <properties><property name=\"p\" type=\"bogus\" value=\"1\"/></properties>\n  </object>";
    let out = inspect(&write_map(dir.path(), "p.tmx", "", objects));
    assert_error(&out, "p.tmx:15:");
    assert_error(&out, "property \"p\": attribute \"type\" is \"bogus\"; expected one of string, int, float, bool, color, file, object, class");
}

#[test]
fn a_platforms_path_error_is_at_the_platforms_line() {
    let dir = tempfile::tempdir().unwrap();
    // Object 2 on line 14 names a path, object 999, that is not in the map: once said with
    // no line at all.
    let objects = "  <object id=\"2\" name=\"lift\" x=\"0\" y=\"0\" width=\"16\" height=\"16\">\n   <properties><property name=\"path\" type=\"object\" value=\"999\"/><property name=\"speed\" type=\"float\" value=\"1\"/></properties>\n  </object>";
    let out = platbench()
        .arg("run")
        .arg(write_map(dir.path(), "m.tmx", "", objects))
        .args(["--backend", "sweep", "--out"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert_error(
        &out,
        "m.tmx:14: object 2 \"lift\": its path names object 999, which is not in any object layer",
    );
}

#[test]
fn tilesets_numbered_twice_and_unread_encodings_are_refused_where_written() {
    // Issue 40, F21/F22: each ran with exit 0 (two tilesets at one firstgid, a tile described
    // twice, a template's tile naming none) or said the crate's words with no line or layer.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = std::fs::read_to_string(write_map(d, "base.tmx", "", "")).unwrap();
    let ts = std::fs::read_to_string(d.join("ts.tsx")).unwrap();
    let map = |name: &str, text: String| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let tileset = "<tileset firstgid=\"1\" source=\"ts.tsx\"/>";
    let cases = [
        (
            "twice.tmx",
            base.replace(tileset, &format!("{tileset}\n {tileset}")),
            // The second tileset's firstgid: line 4, column 11 (after " <tileset ").
            "twice.tmx:4:11: tileset \"ts.tsx\": attribute \"firstgid\" is 1, where tileset \"ts.tsx\" (line 3) starts too",
        ),
        (
            "lzma.tmx",
            base.replace("<data encoding=\"csv\">", "<data encoding=\"base64\" compression=\"lzma\">"),
            "lzma.tmx:5:27: layer \"ground\", <data>: attribute \"compression\" is \"lzma\"; expected csv, or base64 with no compression, zlib or gzip",
        ),
        (
            "hex.tmx",
            base.replace("encoding=\"csv\"", "encoding=\"hex\""),
            "hex.tmx:5:9: layer \"ground\", <data>: attribute \"encoding\" is \"hex\"",
        ),
        (
            "zero.tmx",
            base.replace("tilewidth=\"16\" tileheight=\"16\" infinite", "tilewidth=\"0\" tileheight=\"16\" infinite"),
            "zero.tmx:2:92: <map>: attribute \"tilewidth\" is \"0\"; expected a whole number of pixels from 1 to 4294967295",
        ),
    ];
    for (name, text, want) in cases {
        assert_error(&inspect(&map(name, text)), want);
    }
    // A tile described twice in the tileset: its second `id`, line 5, column 8.
    let dup = ts.replace(
        " <image",
        " <tile id=\"0\" type=\"solid\"/>\n <tile id=\"0\" type=\"oneway\"/>\n <image",
    );
    std::fs::write(d.join("dup.tsx"), dup).unwrap();
    let out = inspect(&map("dup.tmx", base.replace("ts.tsx", "dup.tsx")));
    assert_error(
        &out,
        "dup.tsx:4:8: cannot load the Tiled map: tileset \"t\": tile 0 is described a second time (first at line 3)",
    );
    // A template whose object's gid names no tile of its tileset (gid 4294967295: every flip
    // bit and id 0x1FFFFFFE), as a map object's already was.
    std::fs::write(
        d.join("tile.tx"),
        "<?xml version=\"1.0\"?>\n<template>\n <tileset firstgid=\"1\" source=\"ts.tsx\"/>\n <object gid=\"4294967295\" width=\"16\" height=\"16\"/>\n</template>\n",
    )
    .unwrap();
    let uses = write_map(
        d,
        "tpl.tmx",
        "",
        "  <object id=\"2\" template=\"tile.tx\" x=\"16\" y=\"16\"/>",
    );
    assert_error(
        &inspect(&uses),
        "object 2 \"\": its template's tile is tile 536870910 of tileset \"t\", which names no tile; expected a tile of that tileset (ids 0 to 0)",
    );
    // A tile past the image's tilecount is kept, as Tiled keeps it: a warning, exit 0.
    let over = ts.replace(" <image", " <tile id=\"5\" type=\"solid\"/>\n <image");
    std::fs::write(d.join("over.tsx"), over).unwrap();
    let out = inspect(&map("over.tmx", base.replace("ts.tsx", "over.tsx")));
    assert!(out.status.success(), "{}", stderr(&out));
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        said.contains("tile(s) 5 are past its image's 1 tiles (tilecount)"),
        "{said}"
    );
}

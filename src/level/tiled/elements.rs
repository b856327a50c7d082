//! How many elements a Tiled XML file (a map, a `.tsx` tileset, a `.tx` template) holds, and
//! how many attributes each element has, counted before the `tiled` crate reads it: the crate
//! holds some hundreds of bytes an element, so a file of small elements is bounded as a Tiled
//! JSON file's objects are; and it reads an element's attributes in time that grows with the
//! square of their number.

use quick_xml::events::{BytesStart, Event};

use super::attrs::line_col;
use super::scan::{line_of, ScanError};
use crate::limits;

/// Counts an element against [`limits::MAX_JSON_OBJECTS`], as the JSON side counts its objects:
/// the `tiled` crate holds some hundreds of bytes an element (3 million `<object/>`s, a 104 MB
/// map, took 1.2 GB). A `<tile>` inside a layer's `<data>` is a cell, which
/// [`limits::MAX_LAYER_CELLS`] bounds instead. `of` names the file's kind (`the map`).
pub(super) fn count_element(
    elements: &mut u64,
    e: &BytesStart,
    in_data: bool,
    of: &str,
    line: impl Fn() -> usize,
) -> Result<(), ScanError> {
    if in_data && e.name().as_ref() == b"tile" {
        return Ok(());
    }
    *elements += 1;
    if *elements > limits::MAX_JSON_OBJECTS {
        return Err(ScanError {
            column: None,
            line: line(),
            message: format!(
                "<{}> is element {} of {of} (layers, objects, properties, tilesets' tiles; a layer's cells aside); expected at most {}, as a Tiled JSON map's objects",
                String::from_utf8_lossy(e.name().as_ref()),
                *elements,
                limits::MAX_JSON_OBJECTS
            ),
        });
    }
    Ok(())
}

/// Refuses element `e` (at byte `pos` of `text`) if it has more than
/// [`limits::MAX_XML_ATTRIBUTES`] attributes, at the column of the first one past the limit.
/// Counted without quick-xml's duplicate check, in time linear in the element's length.
pub(super) fn check_attribute_count(
    text: &str,
    pos: usize,
    e: &BytesStart,
) -> Result<(), ScanError> {
    let Some(extra) = e
        .attributes()
        .with_checks(false)
        .nth(limits::MAX_XML_ATTRIBUTES)
    else {
        return Ok(());
    };
    let total = e.attributes().with_checks(false).count();
    let key = extra.ok().map(|a| a.key.as_ref().to_vec());
    // The key lies within the element's bytes, which start just after its `<`.
    let raw: &[u8] = e;
    let at = e
        .attributes()
        .with_checks(false)
        .nth(limits::MAX_XML_ATTRIBUTES)
        .and_then(|a| a.ok())
        .and_then(|a| (a.key.as_ref().as_ptr() as usize).checked_sub(raw.as_ptr() as usize))
        .filter(|&off| off < raw.len())
        .map_or(pos, |off| pos + 1 + off);
    let (line, column) = line_col(text, at);
    let shown = key.map_or(String::new(), |k| {
        format!(
            " (attribute {} is {:?})",
            limits::MAX_XML_ATTRIBUTES + 1,
            String::from_utf8_lossy(&k)
        )
    });
    Err(ScanError {
        line,
        column: Some(column),
        message: format!(
            "<{}> has {total} attributes{shown}; expected at most {} an element (Tiled writes at most 19, on <map>)",
            String::from_utf8_lossy(e.name().as_ref()),
            limits::MAX_XML_ATTRIBUTES
        ),
    })
}

/// Counts the elements of a tileset or template file (`of`: `the tileset file`, …) with
/// [`count_element`], and every element's attributes with [`check_attribute_count`].
/// Malformed XML is left to the crate, which reports it.
pub(super) fn check_element_count(text: &str, of: &str) -> Result<(), ScanError> {
    check_counts(text, Some(of))
}

/// Checks every element's attributes, and with `of` counts the elements too.
fn check_counts(text: &str, of: Option<&str>) -> Result<(), ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut elements = 0;
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e) | Event::Empty(e)) => {
                if let Some(of) = of {
                    count_element(&mut elements, &e, false, of, || line_of(text, pos))?;
                }
                check_attribute_count(text, pos, &e)?;
            }
            Ok(Event::Eof) | Err(_) => return Ok(()),
            Ok(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_of_more_elements_than_a_json_maps_objects_is_refused_at_the_first_too_many() {
        let n = limits::MAX_JSON_OBJECTS as usize;
        // The tileset element and n - 1 tiles: at the limit.
        let tiles = |k: usize| {
            format!(
                "<tileset name=\"t\">\n{}</tileset>",
                "<tile id=\"0\"/>\n".repeat(k)
            )
        };
        assert!(check_element_count(&tiles(n - 1), "the tileset file").is_ok());
        let e = check_element_count(&tiles(n), "the tileset file")
            .err()
            .unwrap();
        // The n + 1st element is the last tile, on line n + 1.
        assert_eq!(e.line, n + 1);
        assert!(
            e.message
                .contains("<tile> is element 500001 of the tileset file"),
            "{}",
            e.message
        );
    }

    #[test]
    fn an_element_of_more_attributes_than_the_limit_is_refused_at_the_first_too_many() {
        let n = limits::MAX_XML_ATTRIBUTES;
        let map = |k: usize| {
            let attrs: String = (0..k).map(|i| format!(" a{i}=\"1\"")).collect();
            format!("<?xml version=\"1.0\"?>\n<map{attrs}>\n</map>")
        };
        assert!(check_element_count(&map(n), "the map").is_ok());
        let e = check_element_count(&map(n + 1), "the map").err().unwrap();
        // Attribute n + 1 is `a{n}`: after `<map` (4 bytes) and n attributes of ` aI="1"`.
        let before: usize = 4 + (0..n).map(|i| format!(" a{i}=\"1\"").len()).sum::<usize>();
        assert_eq!((e.line, e.column), (2, Some(before + 2)), "{}", e.message);
        assert!(
            e.message.contains(&format!(
                "<map> has {} attributes (attribute {} is \"a{n}\")",
                n + 1,
                n + 1
            )),
            "{}",
            e.message
        );
    }
}

//! How many elements a Tiled XML file (a map, a `.tsx` tileset, a `.tx` template) holds,
//! counted before the `tiled` crate reads it: the crate holds some hundreds of bytes an
//! element, so a file of small elements is bounded as a Tiled JSON file's objects are.

use quick_xml::events::{BytesStart, Event};

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

/// Counts the elements of a tileset or template file (`of`: `the tileset file`, …) with
/// [`count_element`]. Malformed XML is left to the crate, which reports it.
pub(super) fn check_element_count(text: &str, of: &str) -> Result<(), ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut elements = 0;
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e) | Event::Empty(e)) => {
                count_element(&mut elements, &e, false, of, || line_of(text, pos))?;
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
}

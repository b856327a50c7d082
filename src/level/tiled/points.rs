//! The points of each polygon and polyline of a map, tileset or template, counted in its XML
//! before the `tiled` crate reads them: at most [`limits::MAX_POLYGON_POINTS`], so no shape
//! costs more than that to parse, place or recognise as a ramp.

use quick_xml::events::{BytesStart, Event};

use super::scan::{attr, line_of, ScanError};
use crate::limits;

/// The object (and tileset tile) whose shape is being read, to name it in the error.
#[derive(Default)]
pub(super) struct Shapes {
    /// `object ID "NAME"` of the last `<object>` opened.
    object: String,
    /// The last `<tile id>` of a tileset, when the object is one of its collision shapes.
    tile: Option<String>,
}

impl Shapes {
    /// Reads element `e` (`empty` if it closes itself): notes an object or a tileset's tile,
    /// and checks a polygon's or polyline's points; `line` gives the element's line, computed
    /// only for an error.
    pub(super) fn element(
        &mut self,
        e: &BytesStart,
        empty: bool,
        line: impl Fn() -> usize,
    ) -> Result<(), ScanError> {
        match e.name().as_ref() {
            b"object" => {
                let id = attr(e, "id").unwrap_or_default();
                let name = attr(e, "name").unwrap_or_default();
                self.object = format!("object {id} {name:?}");
            }
            b"tile" if !empty => self.tile = attr(e, "id"),
            shape @ (b"polygon" | b"polyline") => {
                let points = e
                    .attributes()
                    .with_checks(false)
                    .filter_map(|a| a.ok())
                    .find(|a| a.key.as_ref() == b"points")
                    .map_or(0, |a| {
                        a.value
                            .split(|b| b.is_ascii_whitespace())
                            .filter(|p| !p.is_empty())
                            .count()
                    });
                if points > limits::MAX_POLYGON_POINTS {
                    let what = if shape == b"polygon" {
                        "polygon"
                    } else {
                        "polyline"
                    };
                    let tile = self.tile.as_ref().map_or(String::new(), |t| {
                        format!(" (a collision shape of tile {t})")
                    });
                    return Err(ScanError {
                        column: None,
                        line: line(),
                        message: format!(
                            "{}{tile}: its {what} has {points} points; expected at most {} (a ramp has 3 or 4 corners, a drawn outline some dozens)",
                            self.object,
                            limits::MAX_POLYGON_POINTS
                        ),
                    });
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Reads the end of an element: past a tile, its shapes are the map's.
    pub(super) fn end(&mut self, name: &[u8]) {
        if name == b"tile" {
            self.tile = None;
        }
    }
}

/// Checks the polygons and polylines of a tileset's or template's XML ([`Shapes`]); the
/// map's own are checked by `scan::scan_map`. Malformed XML is left to the `tiled` crate.
pub(super) fn check_points(text: &str) -> Result<(), ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut shapes = Shapes::default();
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e)) => shapes.element(&e, false, || line_of(text, pos))?,
            Ok(Event::Empty(e)) => shapes.element(&e, true, || line_of(text, pos))?,
            Ok(Event::End(e)) => shapes.end(e.name().as_ref()),
            Ok(Event::Eof) | Err(_) => return Ok(()),
            Ok(_) => {}
        }
    }
}

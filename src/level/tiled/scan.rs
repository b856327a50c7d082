//! A look at a map's XML before the `tiled` crate reads it, for what that crate would turn into
//! a huge allocation or a panic: the map's declared size (checked against
//! [`limits::MAX_TILES`] before anything is allocated for it), and each tile layer's data,
//! which must hold exactly one cell per cell of the layer (the crate indexes a short layer out
//! of bounds, and inflates a compressed layer without a bound).

use std::io::Read;

use quick_xml::events::{BytesStart, Event};

use crate::limits;

/// What is wrong with the map, and the 1-based line where it is.
pub(super) struct ScanError {
    /// The line of the element at fault.
    pub line: usize,
    /// What was found and what was expected.
    pub message: String,
}

/// An attribute's value, unescaped.
pub(super) fn attr(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .filter_map(|a| a.ok())
        .find(|a| a.key.as_ref() == name.as_bytes())
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
}

/// The line of byte offset `pos` in `text`.
pub(super) fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The tile layer whose `<data>` is being read.
struct Data {
    layer: String,
    cells: u64,
    encoding: Option<String>,
    compression: Option<String>,
    line: usize,
    text: String,
    chunked: bool,
}

/// The line of the first XML syntax error in `text`, if it has one.
pub(super) fn xml_error_line(text: &str) -> Option<usize> {
    let mut reader = quick_xml::Reader::from_str(text);
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => return None,
            Ok(_) => {}
            Err(_) => return Some(line_of(text, reader.buffer_position())),
        }
    }
}

/// Checks the map's size and every tile layer's data length, and returns the `source` of each
/// external tileset. The XML's own errors are left to the `tiled` crate (and
/// [`xml_error_line`]).
pub(super) fn scan_map(text: &str) -> Result<Vec<String>, ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut layer: Option<(String, u64)> = None;
    let mut data: Option<Data> = None;
    let mut sources = Vec::new();
    loop {
        let pos = reader.buffer_position();
        let event = match reader.read_event() {
            Ok(e) => e,
            // Malformed XML: the tiled crate reports it, and xml_error_line finds the line.
            Err(_) => return Ok(sources),
        };
        match event {
            Event::Eof => return Ok(sources),
            Event::Start(e) | Event::Empty(e) => match e.name().as_ref() {
                b"tileset" => {
                    if let Some(s) = attr(&e, "source") {
                        sources.push(s);
                    }
                }
                b"map" => {
                    let dim = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                    if let (Some(w), Some(h)) = (dim("width"), dim("height")) {
                        if w.saturating_mul(h) > limits::MAX_TILES {
                            return Err(ScanError {
                                line: line_of(text, pos),
                                message: format!(
                                    "the map is {w} x {h} tiles; expected at most {} tiles (checked before reading its layers)",
                                    limits::MAX_TILES
                                ),
                            });
                        }
                    }
                }
                b"layer" => {
                    let dim = |n: &str| attr(&e, n).and_then(|v| v.trim().parse::<u64>().ok());
                    let name = attr(&e, "name").unwrap_or_default();
                    let (w, h) = (dim("width").unwrap_or(0), dim("height").unwrap_or(0));
                    if w.saturating_mul(h) > limits::MAX_TILES {
                        return Err(ScanError {
                            line: line_of(text, pos),
                            message: format!(
                                "layer {name:?} is {w} x {h} tiles; expected at most {} tiles",
                                limits::MAX_TILES
                            ),
                        });
                    }
                    layer = Some((name, w * h));
                }
                b"data" => {
                    if let Some((name, cells)) = &layer {
                        data = Some(Data {
                            layer: name.clone(),
                            cells: *cells,
                            encoding: attr(&e, "encoding"),
                            compression: attr(&e, "compression"),
                            line: line_of(text, pos),
                            text: String::new(),
                            chunked: false,
                        });
                    }
                }
                b"chunk" | b"tile" => {
                    // Infinite maps' chunks and the old XML cell encoding: the crate checks
                    // those itself (and platbench refuses infinite maps).
                    if let Some(d) = &mut data {
                        d.chunked = true;
                    }
                }
                _ => {}
            },
            Event::Text(t) => {
                if let Some(d) = &mut data {
                    if let Ok(s) = t.unescape() {
                        d.text.push_str(&s);
                    }
                }
            }
            Event::CData(c) => {
                if let Some(d) = &mut data {
                    d.text.push_str(&String::from_utf8_lossy(&c.into_inner()));
                }
            }
            Event::End(e) => match e.name().as_ref() {
                b"data" => {
                    if let Some(d) = data.take() {
                        check_data(&d)?;
                    }
                }
                b"layer" => layer = None,
                _ => {}
            },
            _ => {}
        }
    }
}

/// Whether a layer's data holds one cell per cell of the layer.
fn check_data(d: &Data) -> Result<(), ScanError> {
    if d.chunked {
        return Ok(());
    }
    let err = |found: String| {
        ScanError {
        line: d.line,
        message: format!(
            "layer {:?}: its data holds {found}; expected exactly {} cells, one per cell of the layer (was the file cut short, or the layer resized by hand?)",
            d.layer, d.cells
        ),
    }
    };
    match (d.encoding.as_deref(), d.compression.as_deref()) {
        (Some("csv"), None) => {
            let n = d.text.split(',').count() as u64;
            if n != d.cells {
                return Err(err(format!("{n} comma-separated cells")));
            }
        }
        (Some("base64"), compression) => {
            let Some(bytes) = base64_decode(&d.text) else {
                // Not base64: the crate reports it.
                return Ok(());
            };
            let expected = d.cells.saturating_mul(4);
            let len = match compression {
                None => bytes.len() as u64,
                Some("zlib") => inflated_len(flate2::read::ZlibDecoder::new(&bytes[..]), expected),
                Some("gzip") => inflated_len(flate2::read::GzDecoder::new(&bytes[..]), expected),
                // zstd and unknown compressions: the crate refuses them.
                Some(_) => return Ok(()),
            };
            if len != expected {
                let found = if len > expected {
                    format!("more than {expected} bytes ({} cells)", d.cells)
                } else {
                    format!("{len} bytes ({} cells of 4 bytes)", len / 4)
                };
                return Err(err(found));
            }
        }
        _ => {}
    }
    Ok(())
}

/// How many bytes `r` inflates to, reading at most one byte more than `expected` (so a small
/// layer that inflates to gigabytes is found after `expected + 1` bytes). A corrupt stream
/// counts what it gave; the crate reports the corruption.
fn inflated_len(r: impl Read, expected: u64) -> u64 {
    let mut sink = Vec::new();
    let _ = r.take(expected + 1).read_to_end(&mut sink);
    sink.len() as u64
}

/// Standard base64 with padding, whitespace ignored; `None` if it is not base64.
fn base64_decode(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let clean: Vec<u8> = text.bytes().filter(|b| !b.is_ascii_whitespace()).collect();
    if !clean.len().is_multiple_of(4) {
        return None;
    }
    let mut out = Vec::with_capacity(clean.len() / 4 * 3);
    for quad in clean.chunks_exact(4) {
        let pad = quad.iter().rev().take_while(|&&b| b == b'=').count();
        if pad > 2 {
            return None;
        }
        let mut acc = 0u32;
        for &b in &quad[..4 - pad] {
            acc = (acc << 6) | value(b)?;
        }
        acc <<= 6 * pad as u32;
        let bytes = acc.to_be_bytes();
        out.extend_from_slice(&bytes[1..4 - pad]);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips() {
        assert_eq!(base64_decode("AQAAAA==").unwrap(), vec![1, 0, 0, 0]);
        assert_eq!(base64_decode(" AQID\nBA== ").unwrap(), vec![1, 2, 3, 4]);
        assert_eq!(base64_decode("AQIDBAUG").unwrap(), vec![1, 2, 3, 4, 5, 6]);
        assert!(base64_decode("A").is_none());
        assert!(base64_decode("A*==").is_none());
    }

    fn map(w: u32, h: u32, data: &str, encoding: &str) -> String {
        format!(
            "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"{w}\" height=\"{h}\" tilewidth=\"16\" tileheight=\"16\">\n<layer id=\"1\" name=\"ground\" width=\"{w}\" height=\"{h}\">\n<data {encoding}>{data}</data>\n</layer>\n</map>\n"
        )
    }

    #[test]
    fn short_and_oversized_layers_and_maps_are_found() {
        assert!(scan_map(&map(2, 2, "1,1,1,1", "encoding=\"csv\"")).is_ok());
        let e = scan_map(&map(2, 2, "1,1,1", "encoding=\"csv\""))
            .err()
            .unwrap();
        assert!(
            e.message.contains("3 comma-separated cells"),
            "{}",
            e.message
        );
        assert_eq!(e.line, 4);
        // 4 cells of 4 bytes: 16 bytes, "AQAAAAEAAAABAAAAAQAAAA==" in base64.
        let ok = map(2, 2, "AQAAAAEAAAABAAAAAQAAAA==", "encoding=\"base64\"");
        assert!(scan_map(&ok).is_ok());
        let short = map(2, 2, "AQAAAAEAAAABAAAA", "encoding=\"base64\"");
        assert!(scan_map(&short).is_err());
        let huge = map(100_000, 100_000, "", "encoding=\"csv\"");
        let e = scan_map(&huge).err().unwrap();
        assert!(e.message.contains("100000 x 100000"), "{}", e.message);
    }
}

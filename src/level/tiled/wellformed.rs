//! A Tiled XML file (a map, a `.tsx` tileset, a `.tx` template) read through once before the
//! `tiled` crate reads it, for what the crate reports with no line and in its XML reader's
//! words ("Document ended before we expected.", "Unrecognized escape symbol", "position 54:
//! attribute key must be directly followed by `=`"): malformed XML, a file cut short, an entity
//! XML does not define, each named at its line and column with what was found and expected.
//! Each element's attributes are counted first ([`check_attribute_count`]).

use quick_xml::events::{BytesStart, Event};

use super::attrs::line_col;
use super::elements::check_attribute_count;
use super::scan::ScanError;

/// An error at byte offset `at` of `text`.
fn at(text: &str, at: usize, message: String) -> ScanError {
    let (line, column) = line_col(text, at);
    ScanError {
        line,
        column: Some(column),
        message,
    }
}

/// The byte offset of `part` in `text`, when `part` is a slice of it.
fn offset(text: &str, part: &[u8]) -> Option<usize> {
    let off = (part.as_ptr() as usize).checked_sub(text.as_ptr() as usize)?;
    (off + part.len() <= text.len()).then_some(off)
}

/// The first `&…;` of `raw` that XML's unescaping refuses: its offset and text.
fn bad_entity(raw: &[u8]) -> Option<(usize, String)> {
    raw.iter()
        .enumerate()
        .filter(|(_, &b)| b == b'&')
        .find_map(|(i, _)| {
            // An entity's name is short; 32 bytes show it without copying a long value.
            let end = raw[i..]
                .iter()
                .take(32)
                .position(|&b| b == b';')
                .map_or((i + 32).min(raw.len()), |p| i + p + 1);
            let piece = String::from_utf8_lossy(&raw[i..end]).into_owned();
            quick_xml::escape::unescape(&piece)
                .is_err()
                .then_some((i, piece))
        })
}

const ENTITIES: &str = "expected &amp; &lt; &gt; &quot; &apos; or a character reference of a character, such as &#65; (Tiled reads no DTD, so no other entity is defined)";

/// Checks element `e`'s attributes as the crate reads them: at most the limit, each
/// `name="value"` once, each value's entities defined.
fn check_element(text: &str, pos: usize, e: &BytesStart) -> Result<(), ScanError> {
    check_attribute_count(text, pos, e)?;
    let raw: &[u8] = e;
    let tag = String::from_utf8_lossy(e.name().as_ref()).into_owned();
    // Positions in the crate's attribute errors count from just after the element's `<`.
    let inside = |p: usize| pos + 1 + p.min(raw.len());
    for a in e.attributes() {
        use quick_xml::events::attributes::AttrError::*;
        let a = match a {
            Ok(a) => a,
            Err(err) => {
                let (p, what) = match err {
                    ExpectedEq(p) => (p, "an attribute name not followed by `=`".to_string()),
                    ExpectedValue(p) => (p, "an attribute with no value".to_string()),
                    UnquotedValue(p) => (p, "an attribute value without quotes".to_string()),
                    ExpectedQuote(p, q) => (
                        p,
                        format!("an attribute value with no closing {}", q as char),
                    ),
                    Duplicated(p, first) => {
                        let (_, c) = line_col(text, inside(first));
                        (
                            p,
                            format!("an attribute given a second time (first at column {c})"),
                        )
                    }
                };
                return Err(at(
                    text,
                    inside(p),
                    format!("<{tag}> has {what}; expected name=\"value\" pairs, each name once"),
                ));
            }
        };
        if let Some((i, found)) = bad_entity(&a.value) {
            let start = offset(text, &a.value).map_or(pos, |o| o + i);
            return Err(at(
                text,
                start,
                format!(
                    "<{tag}>: attribute \"{}\" holds {found:?}; {ENTITIES}",
                    String::from_utf8_lossy(a.key.as_ref())
                ),
            ));
        }
    }
    Ok(())
}

/// Reads `text` through, as the crate's XML reader would: the first fault is named at its line
/// and column. A file that ends before its elements close was most likely cut short.
pub(super) fn check_xml(text: &str) -> Result<(), ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut open: Vec<(String, usize)> = Vec::new();
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e)) => {
                check_element(text, pos, &e)?;
                open.push((String::from_utf8_lossy(e.name().as_ref()).into_owned(), pos));
            }
            Ok(Event::Empty(e)) => check_element(text, pos, &e)?,
            Ok(Event::End(_)) => {
                open.pop();
            }
            Ok(Event::Text(t)) => {
                if let Some((i, found)) = bad_entity(&t) {
                    let start = offset(text, &t).map_or(pos, |o| o + i);
                    return Err(at(text, start, format!("the text holds {found:?}; {ENTITIES}")));
                }
            }
            Ok(Event::Eof) => {
                return match open.last() {
                    None => Ok(()),
                    Some((name, opened)) => {
                        let (line, _) = line_col(text, *opened);
                        Err(at(
                            text,
                            text.len(),
                            format!("the file ends before <{name}> (opened on line {line}) is closed; expected </{name}> (was the file cut short?)"),
                        ))
                    }
                };
            }
            Err(quick_xml::Error::UnexpectedEof(what)) => {
                return Err(at(
                    text,
                    pos,
                    format!("the file ends inside the {} that starts here; expected it closed, and the rest of the file (was the file cut short?)", what.to_lowercase()),
                ))
            }
            Err(quick_xml::Error::EndEventMismatch { expected, found }) => {
                return Err(at(
                    text,
                    pos,
                    format!("found </{found}>; expected </{expected}>, which closes the element open here"),
                ))
            }
            Err(e) => {
                return Err(at(
                    text,
                    pos,
                    format!("the XML is malformed here ({e}); expected XML as Tiled writes it"),
                ))
            }
            Ok(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> (usize, Option<usize>, String) {
        let e = check_xml(text).err().unwrap();
        (e.line, e.column, e.message)
    }

    #[test]
    fn faults_are_named_where_they_are() {
        assert!(check_xml("<map a=\"&amp;&#65;\">\n <x>&lt;</x>\n</map>\n").is_ok());
        let (l, c, m) = err("<map>\n <x a=\"1 &bogus; 2\"/>\n</map>");
        // ` <x a="1 ` is 9 bytes before the `&`.
        assert_eq!((l, c), (2, Some(10)), "{m}");
        assert!(m.contains("attribute \"a\" holds \"&bogus;\""), "{m}");
        let (l, c, m) = err("<map>\n <x>a &#0;</x>\n</map>");
        assert_eq!((l, c), (2, Some(7)), "{m}");
        assert!(m.contains("the text holds \"&#0;\""), "{m}");
        let (l, c, m) = err("<map>\n <layer>\n");
        assert_eq!((l, c), (3, Some(1)), "{m}");
        assert!(m.contains("ends before <layer> (opened on line 2)"), "{m}");
        let (l, c, m) = err("<map>\n <layer a=\"1\" heig");
        assert_eq!((l, c), (2, Some(2)), "{m}");
        assert!(m.contains("the file ends inside"), "{m}");
        let (l, c, m) = err("<map>\n <x a=\"1\" a=\"2\"/></map>");
        assert_eq!((l, c), (2, Some(11)), "{m}");
        assert!(m.contains("second time (first at column 5)"), "{m}");
    }
}

//! What a TOML level or side file may cost before the `toml` crate parses it: at most
//! [`limits::MAX_TOML_BYTES`] bytes and [`limits::MAX_TOML_ITEMS`] items, counted by a pass over
//! the text that skips strings and comments. The crate builds a tree of every value, some hundreds
//! of bytes an item, so these two bound the memory a file can take before any of it is read.

use super::error::{LevelError, Locator};
use crate::limits;

/// Checks the size of `loc`'s text and the number of its items (each `=`, `,`, `.`, `[` and `{`
/// outside strings and comments: a dot joins the parts of a dotted key, each of which the crate
/// makes a table); the error names the line of the first item past the limit.
pub(super) fn check_budget(loc: &Locator) -> Result<(), LevelError> {
    if loc.text.len() as u64 > limits::MAX_TOML_BYTES {
        return Err(loc.err(
            0,
            format!(
                "the file is {} bytes; expected at most {} (32 MiB) in a TOML level or side file (a map of the largest size, 1,000,000 tiles, takes about 1 MB)",
                loc.text.len(),
                limits::MAX_TOML_BYTES
            ),
        ));
    }
    if let Some(at) = item_past_limit(loc.text, limits::MAX_TOML_ITEMS) {
        return Err(loc.err(
            at,
            format!(
                "the file holds more than {} TOML items (keys, array entries, tables; this is where the count passes it); expected at most {} (a scenario holds at most {} input events; split long scripts into scenarios or levels)",
                limits::MAX_TOML_ITEMS,
                limits::MAX_TOML_ITEMS,
                limits::MAX_INPUT_EVENTS
            ),
        ));
    }
    Ok(())
}

/// The byte offset of item `max + 1` of `text` (each `=`, `,`, `.`, `[` and `{` outside strings
/// and comments; the point of a float counts too, which only makes the bound safer), or `None` if it has at most `max`. Linear in the text; a malformed file is counted
/// as far as it goes (the `toml` crate reports what is wrong with it).
fn item_past_limit(text: &str, max: usize) -> Option<usize> {
    let b = text.as_bytes();
    let mut count = 0usize;
    let mut k = 0;
    while k < b.len() {
        match b[k] {
            b'#' => {
                while k < b.len() && b[k] != b'\n' {
                    k += 1;
                }
            }
            q @ (b'"' | b'\'') => {
                k = string_end(b, k, q);
                continue;
            }
            b'=' | b',' | b'.' | b'[' | b'{' => {
                count += 1;
                if count > max {
                    return Some(k);
                }
            }
            _ => {}
        }
        k += 1;
    }
    None
}

/// The offset just past the string that opens at `start` with quote `q`: a basic (`"`) or
/// literal (`'`) string, one line or multi-line (three quotes, closed by a run of three to five,
/// the extra ones part of the string). Backslash escapes count in basic strings only.
fn string_end(b: &[u8], start: usize, q: u8) -> usize {
    let run = |at: usize| b[at..].iter().take_while(|&&c| c == q).count();
    let multi = run(start) >= 3;
    let mut k = start + if multi { 3 } else { 1 };
    while k < b.len() {
        let c = b[k];
        if c == b'\\' && q == b'"' {
            k += 2;
        } else if c == q {
            if !multi {
                return k + 1;
            }
            let n = run(k);
            if n >= 3 {
                return k + n;
            }
            k += n;
        } else if c == b'\n' && !multi {
            // An unclosed one-line string ends at its line.
            return k;
        } else {
            k += 1;
        }
    }
    b.len()
}

#[cfg(test)]
mod tests {
    use super::item_past_limit;

    #[test]
    fn items_inside_strings_and_comments_are_not_counted() {
        let count = |t: &str| (0..100).find(|&m| item_past_limit(t, m).is_none()).unwrap();
        assert_eq!(count("a = 1\nb = [1, 2]\n"), 4);
        assert_eq!(count("a = \"=,[{\" # = , [ {\n"), 1);
        assert_eq!(count("a = 'x\\' # b = 2\n"), 1);
        assert_eq!(count("m = \"\"\"\n=,\n\\\"\"\" , \"\"\"\"\"\nx = 1"), 2);
        assert_eq!(count("m = '''=''''' \ny = 2"), 2);
        assert_eq!(count("[[scenario]]\ninputs = [{ t = 1, left = true }]"), 8);
        // A dotted key's parts, each a table the crate builds (a file of keys 80 parts long
        // slipped past a count of `=` alone and took 4 GB), and a float's point.
        assert_eq!(count("a.b.c = 1.5"), 4);
        // The offset of the first item past the limit.
        assert_eq!(item_past_limit("a = 1, 2", 1), Some(5));
    }
}

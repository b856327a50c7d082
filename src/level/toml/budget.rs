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
    match past_limit(loc.text, limits::MAX_TOML_ITEMS, limits::MAX_TOML_DEPTH) {
        Some(Past::Items(at)) => Err(loc.err(
            at,
            format!(
                "the file holds more than {} TOML items (keys, array entries, tables; this is where the count passes it); expected at most {} (a scenario holds at most {} input events; split long scripts into scenarios or levels)",
                limits::MAX_TOML_ITEMS,
                limits::MAX_TOML_ITEMS,
                limits::MAX_INPUT_EVENTS
            ),
        )),
        Some(Past::Depth(at)) => Err(loc.err(
            at,
            format!(
                "nesting passes {} levels here (a table header's parts, then each open bracket and brace and each part of a dotted key on the way); expected at most {} (a level nests at most four deep: `[[scenario]]`, `inputs = [{{ t = 1.0 }}]`)",
                limits::MAX_TOML_DEPTH,
                limits::MAX_TOML_DEPTH
            ),
        )),
        None => Ok(()),
    }
}

/// Where a text first passes a limit of [`past_limit`], as a byte offset.
#[derive(Debug, PartialEq)]
enum Past {
    /// The offset of the first item past the item limit.
    Items(usize),
    /// The offset of the first bracket, brace or key part past the depth limit.
    Depth(usize),
}

/// Where `text` first holds more than `max_items` items (each `=`, `,`, `.`, `[` and `{` outside
/// strings and comments; the point of a float counts too, which only makes the bound safer) or
/// nests deeper than `max_depth`: a value's depth is its table header's parts, plus one for each
/// array and inline table around it, plus the parts of every dotted key on the way (the crate
/// recurses once per level, and past about 80 gives a bare "recursion limit" at line 1, column
/// 1). Linear in the text; a malformed file is counted as far as it goes (the `toml` crate
/// reports what is wrong with it).
fn past_limit(text: &str, max_items: usize, max_depth: usize) -> Option<Past> {
    let b = text.as_bytes();
    let mut count = 0usize;
    // The depth of each open array and inline table; of the table the last header opened; the
    // dots of the key being read; those of a header being read.
    let mut open: Vec<usize> = Vec::new();
    let mut table = 0usize;
    let mut dots = 0usize;
    let mut header: Option<usize> = None;
    let mut line_start = true;
    let mut k = 0;
    while k < b.len() {
        let c = b[k];
        match c {
            b'#' => {
                while k < b.len() && b[k] != b'\n' {
                    k += 1;
                }
                continue;
            }
            b'"' | b'\'' => {
                k = string_end(b, k, c);
                line_start = false;
                continue;
            }
            b'=' | b',' | b'.' | b'[' | b'{' => {
                count += 1;
                if count > max_items {
                    return Some(Past::Items(k));
                }
            }
            _ => {}
        }
        let around = open.last().copied().unwrap_or(table);
        let depth = match c {
            // A table header, `[a.b]` or `[[a.b]]`, at the start of a line outside any value.
            b'[' if open.is_empty() && (line_start || header.is_some()) => {
                header.get_or_insert(0);
                0
            }
            b'[' | b'{' => {
                open.push(around + dots + 1);
                dots = 0;
                around + 1
            }
            b']' if header.is_some() => 0,
            b']' | b'}' => {
                open.pop();
                dots = 0;
                0
            }
            b'.' => match header.as_mut() {
                Some(h) => {
                    *h += 1;
                    1 + *h
                }
                None => {
                    dots += 1;
                    around + dots
                }
            },
            b',' => {
                dots = 0;
                0
            }
            b'\n' => {
                if let Some(h) = header.take() {
                    table = 1 + h;
                }
                if open.is_empty() {
                    dots = 0;
                }
                0
            }
            _ => 0,
        };
        if depth > max_depth || open.last().is_some_and(|&d| d > max_depth) {
            return Some(Past::Depth(k));
        }
        line_start = c == b'\n' || (line_start && matches!(c, b' ' | b'\t' | b'\r'));
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
    use super::{past_limit, Past};

    fn item_past_limit(text: &str, max: usize) -> Option<usize> {
        match past_limit(text, max, usize::MAX) {
            Some(Past::Items(at)) => Some(at),
            _ => None,
        }
    }

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

    #[test]
    fn depth_counts_open_brackets_and_a_key_s_parts() {
        let depth = |t: &str| {
            (0..100)
                .find(|&m| past_limit(t, usize::MAX, m).is_none())
                .unwrap()
        };
        assert_eq!(depth("a = 1\n"), 0);
        assert_eq!(depth("a.b.c = 1\n"), 2);
        // A header, then an array and a table; a float's point is one more (harmless).
        assert_eq!(
            depth("[[scenario]]\ninputs = [{ t = 1.5, left = true }]\n"),
            4
        );
        // Dotted keys inside inline tables and under a dotted header add up (an adversary's
        // `zz = { k0.….k31 = { k0.….k30 = { … } } }` nested 528 deep past a per-key count):
        // the header's two parts, the table, `a.b`'s second part, the table, `c.d`'s.
        assert_eq!(depth("[h.i]\nz = { a.b = { c.d = 1 } }\n"), 6);
        assert_eq!(depth("a = [[[1]]]\nb = [2]\n"), 3);
        // Brackets in strings and comments do not nest.
        assert_eq!(depth("a = \"[[[{\" # [[[[\n"), 0);
        assert_eq!(
            past_limit("a = [[[1]]]", usize::MAX, 2),
            Some(Past::Depth(6))
        );
    }
}

//! Where each byte of a TOML string's value sits in the file. A basic string's escapes (`\n`,
//! `\u00e9`, a line-ending backslash) make its value shorter or longer than its text, so a
//! position in the value is mapped back through the string's own text, never added to where the
//! string starts.

/// For a string whose token in the file is `raw` (quotes included) and whose value is `value`,
/// the byte offset in `raw` of each byte of `value`, plus one more entry for the end of the
/// value (the closing quotes). `None` when decoding `raw` does not give `value` back (a form of
/// string this does not know), so the caller places its error at the string's start instead.
pub(super) fn value_offsets(raw: &str, value: &str) -> Option<Vec<usize>> {
    let delim = ["\"\"\"", "'''", "\"", "'"]
        .into_iter()
        .find(|d| raw.starts_with(d))?;
    let literal = delim.starts_with('\'');
    let multiline = delim.len() == 3;
    let end = raw.len().checked_sub(delim.len())?;
    let mut start = delim.len();
    if multiline {
        // TOML trims a newline right after the opening quotes.
        let rest = raw.get(start..)?;
        if rest.starts_with("\r\n") {
            start += 2;
        } else if rest.starts_with('\n') {
            start += 1;
        }
    }
    let body = raw.get(start..end)?;
    let mut decoded = String::with_capacity(value.len());
    let mut offsets = Vec::with_capacity(value.len() + 1);
    let mut chars = body.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let ch = if literal || c != '\\' {
            Some(c)
        } else {
            match chars.next()?.1 {
                'n' => Some('\n'),
                't' => Some('\t'),
                'r' => Some('\r'),
                'b' => Some('\u{8}'),
                'f' => Some('\u{c}'),
                'e' => Some('\u{1b}'),
                '"' => Some('"'),
                '\\' => Some('\\'),
                'x' => Some(hex(&mut chars, 2)?),
                'u' => Some(hex(&mut chars, 4)?),
                'U' => Some(hex(&mut chars, 8)?),
                // A line-ending backslash: it, the newline and the whitespace after are dropped.
                w if multiline && w.is_whitespace() => {
                    while chars.next_if(|(_, c)| c.is_whitespace()).is_some() {}
                    None
                }
                _ => return None,
            }
        };
        if let Some(ch) = ch {
            offsets.extend(std::iter::repeat_n(start + i, ch.len_utf8()));
            decoded.push(ch);
        }
    }
    offsets.push(end);
    (decoded == value).then_some(offsets)
}

/// The character of an escape's `digits` hex digits.
fn hex(chars: &mut impl Iterator<Item = (usize, char)>, digits: usize) -> Option<char> {
    let mut code = 0u32;
    for _ in 0..digits {
        code = code * 16 + chars.next()?.1.to_digit(16)?;
    }
    char::from_u32(code)
}

#[cfg(test)]
mod tests {
    use super::value_offsets;

    #[test]
    fn each_byte_of_the_value_maps_to_its_place_in_the_text() {
        // Literal and multi-line literal strings: the value is the text between the quotes.
        assert_eq!(value_offsets("'ab'", "ab"), Some(vec![1, 2, 3]));
        assert_eq!(value_offsets("'''\nab'''", "ab"), Some(vec![4, 5, 6]));
        // A `\n` escape is one byte of the value from two of the text.
        assert_eq!(value_offsets("\"a\\nb\"", "a\nb"), Some(vec![1, 2, 4, 5]));
        // A `\u` escape of a two-byte character: both bytes at the backslash.
        assert_eq!(
            value_offsets("\"\\u00e9x\"", "\u{e9}x"),
            Some(vec![1, 1, 7, 8])
        );
        // A line-ending backslash drops itself, the newline and the indent after it.
        assert_eq!(
            value_offsets("\"\"\"\na\\\n   b\"\"\"", "ab"),
            Some(vec![4, 10, 11])
        );
        // A value the text does not decode to: no positions, never wrong ones.
        assert_eq!(value_offsets("\"a\\nb\"", "ab"), None);
        assert_eq!(value_offsets("\"\\q\"", "q"), None);
        assert_eq!(value_offsets("x", "x"), None);
    }
}

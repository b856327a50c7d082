//! The TOML parser's errors put in platbench's words where its own say too little: a duplicate
//! key is named with the line that set it first, and a control character is named by its code
//! point, with what TOML allows instead, rather than as the token the parser wanted next.

/// Where in `text` the parser's error `e` is (a byte offset) and what it says: the parser's own
/// message, made to name what was found and what was expected where it does not.
pub(crate) fn explain(text: &str, e: &toml::de::Error) -> (usize, String) {
    let span = e.span().unwrap_or(0..0);
    let message = e.message().trim();
    if let Some(c) = control_at(text, span.start) {
        return (
            span.start,
            format!(
                "found the control character U+{:04X}, which TOML allows nowhere but as an escape in a basic string; expected text (tab is the only control character allowed as it is; write \\u{:04X} in a \"...\" string)",
                u32::from(c),
                u32::from(c)
            ),
        );
    }
    if let Some(field) = message.strip_prefix("missing field ") {
        if text.trim_start_matches('\u{feff}').trim().is_empty() {
            return (
                0,
                format!("found an empty file; expected TOML that sets {field}"),
            );
        }
        // The span is the table that lacks the key: its header, or the file's top.
        let line = text
            .get(span.start..)
            .and_then(|t| t.lines().next())
            .unwrap_or_default()
            .trim();
        let table = if line.starts_with('[') {
            format!("the table {line}")
        } else if span.start == 0 {
            "the file's top level".to_string()
        } else {
            "this table".to_string()
        };
        return (
            span.start,
            format!("{table} does not set {field}; expected it set: the key is required there"),
        );
    }
    if message == "duplicate key" {
        let key = text.get(span.clone()).unwrap_or_default().trim();
        let first = first_definition(text, span.start, key)
            .map(|line| format!(", first set at line {line}"))
            .unwrap_or_default();
        return (
            span.start,
            format!("duplicate key `{key}`{first}; expected each key once in a table"),
        );
    }
    if let Some(unclosed) = unclosed_string(text, span.start, message) {
        return unclosed;
    }
    (span.start, message.to_string())
}

/// A string the file or its line ends inside (the parser: "invalid multi-line basic string,
/// expected `\"`"), said at its opening quotes: where it starts, what closes it.
fn unclosed_string(text: &str, at: usize, message: &str) -> Option<(usize, String)> {
    let kind = message.strip_prefix("invalid ")?;
    let quote = match kind {
        "multi-line basic string, expected `\"`" => "\"\"\"",
        "multi-line literal string, expected `'`" => "'''",
        "basic string, expected `\"`" => "\"",
        "literal string, expected `'`" => "'",
        _ => return None,
    };
    let rest = text.get(at..)?;
    if quote.len() == 3 {
        // Only the end of the file leaves a multi-line string open.
        if !rest.is_empty() {
            return None;
        }
        let open = text.get(..at)?.rfind(quote)?;
        return Some((open, format!("the multi-line string opened here ({quote}) is never closed: the file ends inside it; expected {quote} to close it (was the file cut short?)")));
    }
    if !(rest.is_empty() || rest.starts_with(['\n', '\r'])) {
        return None;
    }
    let line_start = text.get(..at)?.rfind('\n').map_or(0, |k| k + 1);
    let open = line_start + open_quote(text.get(line_start..at)?)?;
    let many = if quote == "\"" { "\"\"\"" } else { "'''" };
    Some((open, format!("the string opened here ({quote}) is not closed on its line; expected {quote} before the line ends (a string of several lines is written between {many} and {many})")))
}

/// Where the string left open at the end of `line` starts: quotes are followed from the line's
/// start (a basic string's `\\"` is no quote, a `'` inside `"..."` none either, `#` outside a
/// string starts a comment).
fn open_quote(line: &str) -> Option<usize> {
    let mut open: Option<(usize, u8)> = None;
    let mut escaped = false;
    for (k, b) in line.bytes().enumerate() {
        match open {
            Some((_, b'"')) if escaped => escaped = false,
            Some((_, b'"')) if b == b'\\' => escaped = true,
            Some((_, q)) if b == q => open = None,
            Some(_) => {}
            None if b == b'#' => return None,
            None if matches!(b, b'"' | b'\'') => open = Some((k, b)),
            None => {}
        }
    }
    open.map(|(k, _)| k)
}

/// The control character (other than tab, line feed and carriage return) at byte `offset` of
/// `text`, if that is what is there.
fn control_at(text: &str, offset: usize) -> Option<char> {
    let c = text.get(offset..)?.chars().next()?;
    (c.is_control() && !matches!(c, '\t' | '\n' | '\r')).then_some(c)
}

/// The 1-based line, before byte `before` of `text` and after the last table header (`[...]`)
/// there, on which `key` is set (`key =` at the line's start); `None` when it is not found that
/// simply (a dotted or quoted key), and the error then names the key alone.
fn first_definition(text: &str, before: usize, key: &str) -> Option<usize> {
    if key.is_empty() {
        return None;
    }
    let head = text.get(..before)?;
    let mut found = None;
    for (i, line) in head.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with('[') {
            found = None;
        } else if t
            .strip_prefix(key)
            .is_some_and(|rest| rest.trim_start().starts_with('='))
            && found.is_none()
        {
            found = Some(i + 1);
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::explain;

    fn err(text: &str) -> (usize, String) {
        let e = toml::from_str::<toml::Table>(text).unwrap_err();
        explain(text, &e)
    }

    #[test]
    fn a_duplicate_key_is_named_with_its_first_line() {
        let text = "[a]\nx = 1\n[b]\nx = 1\ny = 2\nx = 3\n";
        let (at, m) = err(text);
        assert_eq!(crate::input::line_column(text, at), (6, 1), "{m}");
        // Line 4 sets x in [b]; line 2's x is another table's.
        assert!(m.contains("duplicate key `x`, first set at line 4"), "{m}");
    }

    #[test]
    fn an_empty_file_is_said_to_be_one() {
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Needs {
            map: String,
        }
        let e = toml::from_str::<Needs>("\n").unwrap_err();
        let (at, m) = explain("\n", &e);
        assert_eq!(
            (at, m.as_str()),
            (0, "found an empty file; expected TOML that sets `map`")
        );
    }

    #[test]
    fn a_missing_key_names_the_table_that_lacks_it() {
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Scenario {
            name: String,
            spawn: [f64; 2],
        }
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Level {
            map: String,
            scenario: Vec<Scenario>,
        }
        let text = "name = \"e\"\n[[scenario]]\nname = \"w\"\nspawn = [1, 1]\n";
        let (at, m) = explain(text, &toml::from_str::<Level>(text).unwrap_err());
        assert_eq!(at, 0, "{m}");
        assert!(
            m.starts_with("the file's top level does not set `map`"),
            "{m}"
        );
        let text = "map = \"#\"\n\n[[scenario]]\nname = \"w\"\n";
        let (at, m) = explain(text, &toml::from_str::<Level>(text).unwrap_err());
        // Line 3: the header of the table without `spawn`.
        assert_eq!(crate::input::line_column(text, at), (3, 1), "{m}");
        assert!(
            m.starts_with("the table [[scenario]] does not set `spawn`"),
            "{m}"
        );
    }

    #[test]
    fn a_string_left_open_is_named_where_it_opens() {
        // Once the parser's "invalid multi-line basic string, expected `\"`" at the file's end.
        let text = "name = \"a\"\nmap = \"\"\"\n###\n";
        let (at, m) = err(text);
        assert_eq!(at, text.find("\"\"\"").unwrap());
        assert!(
            m.contains("is never closed: the file ends inside it"),
            "{m}"
        );
        let text = "name = 'a\nmap = 1\n";
        let (at, m) = err(text);
        assert_eq!(at, 7);
        assert!(
            m.contains("not closed on its line; expected ' before"),
            "{m}"
        );
        // An escaped quote inside is not where the string opens.
        let text = "x = 1\n\"a b\" = \"say \\\"hi\n";
        let (at, m) = err(text);
        assert_eq!(at, text.find("\"say").unwrap(), "{m}");
    }

    #[test]
    fn a_control_character_is_named_by_its_code_point() {
        let text = "m = \"\"\"\nab\0c\n\"\"\"\n";
        let (at, m) = err(text);
        assert_eq!(crate::input::line_column(text, at), (2, 3), "{m}");
        assert!(m.starts_with("found the control character U+0000"), "{m}");
        assert!(m.contains("expected text"), "{m}");
    }
}

//! A CSV error in platbench's words: what was found and what was expected, at the line where
//! it is (a column the header lacks is the header's, line 1), instead of the csv crate's
//! "CSV deserialize error: record 1 (line: 2, byte: 63): missing field `level`".

/// What a field that failed to parse was expected to hold, by the parser that refused it.
pub(crate) fn expected_of(kind: &csv::DeserializeErrorKind) -> Option<&'static str> {
    use csv::DeserializeErrorKind as K;
    match kind {
        K::ParseFloat(_) => Some("a number (NaN and inf are numbers too)"),
        K::ParseInt(_) => Some("a whole number 0 or more within the column's range, or nothing where the column allows it"),
        K::ParseBool(_) => Some("true or false"),
        _ => None,
    }
}

/// `e` worded, with the line it belongs to when that is not the record's own (`Some(1)`: the
/// header). `row` is the header and the record, to quote the field at fault.
pub(crate) fn worded(
    e: &csv::Error,
    row: Option<(&csv::StringRecord, &csv::StringRecord)>,
) -> (Option<u64>, String) {
    match e.kind() {
        csv::ErrorKind::Utf8 { err, .. } => (
            None,
            format!(
                "field {} is not UTF-8; expected UTF-8 text (save the file as UTF-8)",
                err.field() + 1
            ),
        ),
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => (
            None,
            format!("found {len} fields; expected {expected_len}, as many as the header"),
        ),
        csv::ErrorKind::Deserialize { err, .. } => {
            let message = err.kind().to_string();
            if let Some(column) = message
                .strip_prefix("missing field `")
                .and_then(|m| m.strip_suffix('`'))
            {
                // A field serde misses is a column the header lacks.
                return (
                    Some(1),
                    format!("the header has no column `{column}`; expected the header platbench writes in this file"),
                );
            }
            let at = err.field().and_then(|f| usize::try_from(f).ok());
            let expected = expected_of(err.kind()).map_or(message.as_str(), |x| x);
            match (at, row) {
                (Some(at), Some((headers, record))) => (
                    None,
                    format!(
                        "field {} ({}): found {:?}; expected {expected}",
                        at + 1,
                        headers.get(at).unwrap_or("?"),
                        record.get(at).unwrap_or_default()
                    ),
                ),
                _ => (
                    None,
                    format!("{expected}; expected the CSV platbench writes there (its header names every column it reads)"),
                ),
            }
        }
        _ => (None, format!("not the CSV platbench writes there: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[allow(dead_code)]
    struct Row {
        level: String,
        value: f64,
    }

    fn first_error(csv: &str) -> (Option<u64>, String) {
        let mut r = csv::Reader::from_reader(csv.as_bytes());
        let headers = r.headers().unwrap().clone();
        let mut record = csv::StringRecord::new();
        loop {
            match r.read_record(&mut record) {
                Err(e) => return worded(&e, None),
                Ok(false) => panic!("no error in {csv:?}"),
                Ok(true) => {
                    if let Err(e) = record.deserialize::<Row>(Some(&headers)) {
                        return worded(&e, Some((&headers, &record)));
                    }
                }
            }
        }
    }

    #[test]
    fn each_error_says_what_was_found_and_expected() {
        let (line, m) = first_error("level,other\nflat,1\n");
        assert_eq!(line, Some(1));
        assert!(m.contains("the header has no column `value`"), "{m}");
        let (line, m) = first_error("level,value\nflat,zz\n");
        assert_eq!(line, None);
        assert!(
            m.contains("field 2 (value): found \"zz\"; expected a number"),
            "{m}"
        );
        let (_, m) = first_error("level,value\nflat,1,2\n");
        assert!(m.contains("found 3 fields; expected 2"), "{m}");
    }
}

//! The true line of a CSV record. The csv crate's `Position::line` counts `\n` bytes as it
//! parses, so in a file whose lines end in `\r\n` each record after the first is placed a line
//! too early, and in one whose lines end in `\r` alone every record is on line 1. [`Lines`]
//! counts the line ends itself (`\n`, `\r` or both, as the csv crate ends a record) and gives
//! the line of a record from the record's byte offset, which the csv crate counts exactly.

use std::collections::VecDeque;

/// A reader that notes where each line starts as the bytes pass through it, so that the line
/// of a byte offset read earlier can be told. It keeps only the starts not yet asked past: as
/// many as the CSV reader's buffer holds ahead of the record asked about.
pub(crate) struct Lines<R> {
    inner: R,
    /// Bytes read so far.
    offset: u64,
    /// The line starts read but not yet passed by [`Lines::line_of`], in order: each with
    /// whether its line is blank (`None` until its first byte is read) and how many lines it
    /// stands for (a run of blank lines is one entry, so a file of blank lines, which the csv
    /// crate reads past without a record, holds one entry, not one a line).
    starts: VecDeque<(u64, Option<bool>, u64)>,
    /// Line starts passed (the lines before the last offset asked about, less one).
    passed: u64,
    /// Whether the line of the last offset asked about is blank.
    blank: bool,
    /// Whether the last byte was `\r` (a `\n` right after it ends the same line).
    after_cr: bool,
}

impl<R> Lines<R> {
    pub(crate) fn new(inner: R) -> Self {
        Lines {
            inner,
            offset: 0,
            starts: VecDeque::new(),
            passed: 0,
            blank: false,
            after_cr: false,
        }
    }

    /// The 1-based line of byte `byte`, a record's start as the csv crate reports it: that may
    /// be the end of the line before (the `\n` of a `\r\n`) or a blank line before the record,
    /// which the csv crate skips, so the record is on the first line from there that is not
    /// blank. Offsets asked about must not go back.
    pub(crate) fn line_of(&mut self, byte: u64) -> u64 {
        while let Some(&(start, blank, lines)) = self.starts.front() {
            if start > byte && !self.blank {
                break;
            }
            self.starts.pop_front();
            self.passed += lines;
            // Not read yet: the file ends there, and no record is on it.
            self.blank = blank.unwrap_or(true);
        }
        self.passed + 1
    }
}

impl<R> Lines<R> {
    /// Folds the last line start into the one before when both lines are blank: `line_of`
    /// passes a blank line whatever its start, so a run of them passes as one.
    fn merge_blank_run(&mut self) {
        let n = self.starts.len();
        if n >= 2 && self.starts[n - 1].1 == Some(true) && self.starts[n - 2].1 == Some(true) {
            if let Some((_, _, lines)) = self.starts.pop_back() {
                self.starts[n - 2].2 += lines;
            }
        }
    }
}

impl<R: std::io::Read> std::io::Read for Lines<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            let ends = b == b'\r' || b == b'\n';
            // The first byte of a line says whether it is blank; the `\n` of a `\r\n` is the
            // line before's.
            if let Some((_, blank @ None, _)) = self.starts.back_mut() {
                if !(self.after_cr && b == b'\n') {
                    *blank = Some(ends);
                    self.merge_blank_run();
                }
            }
            // A line starts after `\r`, and after a `\n` that does not end a `\r\n`; the start
            // after `\r\n` is noted at its `\n`.
            if b == b'\r' || (b == b'\n' && !self.after_cr) {
                self.starts.push_back((self.offset + 1, None, 1));
            }
            self.after_cr = b == b'\r';
            self.offset += 1;
        }
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::Lines;

    /// The line of each record of `text` as read through [`Lines`] by the csv crate.
    fn record_lines(text: &str) -> Vec<u64> {
        let mut r = csv::Reader::from_reader(Lines::new(text.as_bytes()));
        let mut rec = csv::StringRecord::new();
        let mut lines = Vec::new();
        while r.read_record(&mut rec).unwrap() {
            let byte = rec.position().map_or(0, |p| p.byte());
            lines.push(r.get_mut().line_of(byte));
        }
        lines
    }

    #[test]
    fn every_line_end_gives_the_true_line() {
        // Header on line 1, then records on lines 2, 3 and (after a blank line) 5.
        for end in ["\n", "\r\n", "\r"] {
            let text = ["h,v", "a,1", "b,2", "", "c,3", ""].join(end);
            assert_eq!(record_lines(&text), [2, 3, 5], "{end:?}");
        }
        // A quoted field across a line end: the next record is a line further on.
        assert_eq!(record_lines("h,v\n\"a\r\nb\",1\nc,2\n"), [2, 4]);
    }

    #[test]
    fn a_run_of_blank_lines_is_one_entry_and_counts_every_line() {
        // 100,000 blank lines before the second record (line 100,003) and 100,000 at the
        // end: the lines are counted, and the starts held are one per run (one per line, 50
        // million blank lines after a metrics file took `platbench diff` 791 MB; now 9.6 MB).
        for end in ["\n", "\r\n", "\r"] {
            let blanks = end.repeat(100_000);
            let text = format!("h,v{end}a,1{end}{blanks}b,2{end}{blanks}");
            assert_eq!(record_lines(&text), [2, 100_003], "{end:?}");
            let mut lines = Lines::new(text.as_bytes());
            std::io::copy(&mut lines, &mut std::io::sink()).unwrap();
            // Five: the starts of "a,1", of the first run, of "b,2", of the last run, and the
            // start after the last line end (never read).
            assert_eq!(lines.starts.len(), 5, "{end:?}");
        }
    }
}

//! A level file's errors: [`LevelError`], which names the file, line and column, and the
//! locator that turns a byte offset in the file into them.

use std::ops::Range;

/// A level file that could not be read, with where and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}:{column}: {message}")]
pub struct LevelError {
    /// The file (or `builtin:NAME`).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What was found and what was expected.
    pub message: String,
}

/// Turns byte offsets into line and column.
pub(super) struct Locator<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
}

impl Locator<'_> {
    pub(super) fn err(&self, offset: usize, message: impl Into<String>) -> LevelError {
        // Never inside a character: an offset a caller got wrong still names a place.
        let (line, column) = crate::input::line_column(self.text, offset);
        LevelError {
            file: self.file.to_string(),
            line,
            column,
            message: message.into(),
        }
    }

    /// The TOML parser's error `e`, at its place, in words that name what was found.
    pub(super) fn toml(&self, e: &toml::de::Error) -> LevelError {
        let (offset, message) = super::syntax::explain(self.text, e);
        self.err(offset, message)
    }

    pub(super) fn at(&self, span: &Range<usize>, message: impl Into<String>) -> LevelError {
        self.err(span.start, message)
    }
}

//! What a level file is — a platbench level (TOML), a Tiled map (TMX or JSON) or an LDtk
//! project — told by its content, with the extension only breaking a tie: a `.json` file may
//! be a Tiled map or an LDtk project, and a map renamed by a build step keeps its format.

use std::fmt;
use std::io::Read;
use std::path::Path;

use crate::input::{self, InputError};

/// The formats platbench reads a level from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelFormat {
    /// platbench's own level file (TOML, docs/formats.md).
    Level,
    /// A Tiled map in XML (`.tmx`).
    Tmx,
    /// A Tiled map in JSON (`.tmj`, `.json`).
    TiledJson,
    /// An LDtk project (`.ldtk`, JSON).
    Ldtk,
}

impl LevelFormat {
    /// Whether the file is a map an importer reads (not a platbench level).
    pub fn is_map(self) -> bool {
        self != Self::Level
    }
}

impl fmt::Display for LevelFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Level => "a platbench level (TOML)",
            Self::Tmx => "a Tiled map (TMX)",
            Self::TiledJson => "a Tiled map (JSON)",
            Self::Ldtk => "an LDtk project (JSON)",
        })
    }
}

/// How much of a file is looked at: LDtk writes `__header__` and `jsonVersion` first.
const PEEK_BYTES: u64 = 64 * 1024;

/// What a JSON map or project that starts with a byte order mark is told: serde_json reads
/// none ("expected value" at 1:1), and Tiled and LDtk write none.
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) const JSON_BOM: &str = "found a byte order mark (U+FEFF) before the JSON; expected the JSON to start at `{` (Tiled and LDtk write none: save the file as UTF-8 without a BOM)";

/// Whether text is JSON rather than XML or TOML: its first character, after a byte-order mark
/// and white space, opens an object.
pub(crate) fn looks_like_json(text: &str) -> bool {
    text.trim_start_matches('\u{feff}')
        .trim_start()
        .starts_with('{')
}

/// Whether `body` (trimmed) is empty or starts a JSON value other than an object: an array, a
/// string, a number or a literal.
fn starts_json_value(body: &str) -> bool {
    body.is_empty()
        || body.starts_with([
            '[', '"', '-', '0', '1', '2', '3', '4', '5', '6', '7', '8', '9',
        ])
        || ["null", "true", "false"]
            .iter()
            .any(|l| body.starts_with(l))
}

/// The format of `text`, the content of the file at `path` (its extension breaks a tie).
#[cfg(feature = "tiled")]
pub(crate) fn format_of_text(text: &str, path: &Path) -> LevelFormat {
    format_of(text, &extension(path))
}

/// Where the first thing in `text` is (line and column, 1-based) and its start as an error shows
/// it: `an empty file`, or its first line's first 40 characters, quoted.
pub(crate) fn first_text(text: &str) -> (usize, usize, String) {
    let body = text.trim_start_matches('\u{feff}').trim_start();
    let (line, column) = crate::input::line_column(text, text.len() - body.len());
    let first: String = body
        .lines()
        .next()
        .unwrap_or_default()
        .chars()
        .take(40)
        .collect();
    let shown = if body.is_empty() {
        "an empty file".to_string()
    } else {
        format!("{first:?}")
    };
    (line, column, shown)
}

fn extension(path: &Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

/// The format of the text a file starts with; `ext` (lower case) breaks the tie between Tiled
/// JSON and LDtk when the start does not say.
fn format_of(start: &str, ext: &str) -> LevelFormat {
    let body = start.trim_start_matches('\u{feff}').trim_start();
    if body.starts_with('<') {
        return LevelFormat::Tmx;
    }
    if !looks_like_json(body) {
        // Named like a JSON map but holding another JSON value, or nothing: a broken map, whose
        // reader says what its top level is, not a level.
        return match ext {
            "tmj" | "json" if starts_json_value(body) => LevelFormat::TiledJson,
            "ldtk" if starts_json_value(body) => LevelFormat::Ldtk,
            _ => LevelFormat::Level,
        };
    }
    if start.contains("\"__header__\"") || start.contains("\"jsonVersion\"") || ext == "ldtk" {
        LevelFormat::Ldtk
    } else {
        LevelFormat::TiledJson
    }
}

/// The format of the level file at `path`, from its first bytes (a regular file only, as every
/// input: a pipe or a directory is an error, not a wait).
pub fn detect_format(path: &Path) -> Result<LevelFormat, InputError> {
    let mut start = Vec::new();
    input::open(path, crate::limits::MAX_INPUT_BYTES, "input file")?
        .take(PEEK_BYTES)
        .read_to_end(&mut start)
        .map_err(|cause| InputError::Io {
            path: path.to_path_buf(),
            cause,
        })?;
    Ok(format_of(
        &String::from_utf8_lossy(&start),
        &extension(path),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_content_decides_and_the_extension_breaks_ties() {
        assert_eq!(format_of("<?xml ?><map>", "json"), LevelFormat::Tmx);
        assert_eq!(
            format_of("\u{feff}  {\"layers\":[]}", "tmx"),
            LevelFormat::TiledJson
        );
        assert_eq!(format_of("{\"layers\":[]}", "json"), LevelFormat::TiledJson);
        assert_eq!(
            format_of("{ \"__header__\": {}, \"jsonVersion\": \"1.5\"", "json"),
            LevelFormat::Ldtk
        );
        assert_eq!(format_of("{ \"levels\": [] }", "ldtk"), LevelFormat::Ldtk);
        assert_eq!(
            format_of("name = \"a\"\nmap = '''", "tmj"),
            LevelFormat::Level
        );
        assert_eq!(format_of("", "toml"), LevelFormat::Level);
        // Named like a JSON map, another JSON value or nothing is a broken map, not a level.
        for broken in ["", "null", "[]", " 5", "\"map\"", "-1"] {
            assert_eq!(format_of(broken, "tmj"), LevelFormat::TiledJson, "{broken}");
            assert_eq!(format_of(broken, "ldtk"), LevelFormat::Ldtk, "{broken}");
        }
        assert_eq!(format_of("name = \"a\"", "json"), LevelFormat::Level);
        assert_eq!(
            first_text("\n  name = 1\nmap"),
            (2, 3, "\"name = 1\"".into())
        );
        assert_eq!(first_text(" \n"), (2, 1, "an empty file".into()));
    }
}

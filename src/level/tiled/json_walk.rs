//! A walk over a Tiled JSON file (a map, a tileset or a template) before serde_json reads it into
//! the tree [`super::json`] translates: that tree takes 32 bytes a value and a node of 632 bytes
//! and more an object (a polygon's point `{"x":0,"y":0}` about 750 bytes for its 14), so what it
//! would hold is counted here first and refused with the line and column where the count passes,
//! naming the layer or object, as the TMX path refuses it ([`super::scan`], [`super::points`]):
//! the points of each polygon and polyline ([`limits::MAX_POLYGON_POINTS`]), the size of the map,
//! of each tile layer and chunk and the cells of their data ([`limits::MAX_TILES`]), the tile
//! layers' cells together ([`limits::MAX_LAYER_CELLS`]), the file's objects and values
//! ([`limits::MAX_JSON_OBJECTS`], [`limits::MAX_JSON_VALUES`]) and how deep its arrays and objects
//! nest ([`limits::MAX_JSON_DEPTH`]). The walk keeps one frame per open array or object and
//! nothing per value; JSON it cannot read is left to serde_json, which says where.
//!
//! The same walk finds the line where each layer starts, and the line of a layer's cell, for an
//! error found later in the map's TMX twin ([`cell_line`]).

use std::collections::BTreeMap;

use super::error::JsonError;
use super::json_frame::{key_of, Frame, Key, Role};
use super::json_values::numeric_key;
use super::normalize::Normalized;

/// A layer's place in the map: its index in the map's `layers`, then in each group's.
pub(super) type LayerPath = Vec<u32>;

/// What the walk found in a file within the limits: the line each layer starts at.
pub(super) struct Walked {
    /// The 1-based line of each layer's `{`, by its place in the map.
    pub layers: BTreeMap<LayerPath, usize>,
}

/// Walks `text`, which holds `what` (`a Tiled map`; see the module's doc): `Err` names the first
/// thing past a limit, or the first value Tiled does not write where it is ([`super::json_values`]).
pub(super) fn walk(text: &str, what: &'static str) -> Result<Walked, JsonError> {
    let mut w = Walker::new(text, None, what);
    w.run()?;
    Ok(Walked { layers: w.layers })
}

/// The 1-based line of cell `index` (counted from 0) of the `data` array of the layer at `path`,
/// if the layer has such an array and the file is within the limits.
pub(super) fn cell_line(text: &str, path: &[u32], index: u64) -> Option<usize> {
    let mut w = Walker::new(text, Some((path.to_vec(), index)), "");
    w.run().ok()?;
    w.found
}

/// A JSON map as TMX, with the line each layer starts at in both.
pub(super) struct JsonMap {
    /// The TMX text and the notes of the translation.
    pub tmx: Normalized,
    /// Each layer (and each return to the map's layers after a group), in the twin's order.
    pub(super) layers: Vec<LayerLines>,
}

/// Where a layer of a JSON map is, in its TMX twin and in the JSON.
pub(super) struct LayerLines {
    /// The twin's line where it starts.
    pub tmx: usize,
    /// `layer "NAME"`, or `the map's layers` past a group.
    pub label: String,
    /// Its place in the map, and the JSON line where it starts.
    pub path: Option<LayerPath>,
    pub json: Option<usize>,
    /// Its width, when its `data` is an array of cells (not chunks, not base64).
    pub width: Option<u64>,
}

impl JsonMap {
    /// What of the JSON map a line of its TMX twin belongs to: the layer it is in, or the map.
    pub(super) fn layer_at(&self, line: usize) -> String {
        self.entry(line)
            .map_or_else(|| "the map's header".to_string(), |l| l.label.clone())
    }

    /// The JSON line where the layer a twin's line is in starts.
    pub(super) fn layer_start(&self, line: usize) -> Option<usize> {
        self.entry(line)?.json
    }

    /// The JSON line of a twin's line, when it is in a layer: the line of cell `(x, y)` of the
    /// layer's `data` array (Tiled's column and row), else the line where the layer starts.
    pub(super) fn json_line(&self, json: &str, line: usize, (x, y): (i64, i64)) -> Option<usize> {
        let l = self.entry(line)?;
        let cell = match (l.width, &l.path) {
            (Some(w), Some(path)) if x >= 0 && y >= 0 && (x as u64) < w => cell_line(
                json,
                path,
                (y as u64).saturating_mul(w).saturating_add(x as u64),
            ),
            _ => None,
        };
        cell.or(l.json)
    }

    fn entry(&self, line: usize) -> Option<&LayerLines> {
        self.layers.iter().rev().find(|l| l.tmx <= line)
    }
}

/// The layers' lines of a JSON map, gathered as its TMX twin is written.
pub(super) struct Lines<'w> {
    pub list: Vec<LayerLines>,
    walked: &'w Walked,
    /// The twin's bytes counted so far, and the line breaks in them.
    counted: (usize, usize),
}

impl<'w> Lines<'w> {
    pub(super) fn new(walked: &'w Walked) -> Self {
        Lines {
            list: Vec::new(),
            walked,
            counted: (0, 0),
        }
    }

    /// Notes that `label` starts at the end of `out` (the twin so far), at `path` in the JSON.
    pub(super) fn push(&mut self, out: &str, label: String, at: Option<(&[u32], Option<u64>)>) {
        let (bytes, breaks) = self.counted;
        let breaks = breaks + out.get(bytes..).map_or(0, |t| t.matches('\n').count());
        self.counted = (out.len(), breaks);
        self.list.push(LayerLines {
            tmx: breaks + 1,
            label,
            path: at.map(|a| a.0.to_vec()),
            json: at.and_then(|a| self.walked.layers.get(a.0).copied()),
            width: at.and_then(|a| a.1),
        });
    }
}

/// A 1-based line and column (in bytes, as serde_json counts them).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Pos {
    pub line: usize,
    pub column: usize,
}

/// The walk: the text, the cursor, the open arrays and objects, and the counts.
pub(super) struct Walker<'t> {
    b: &'t [u8],
    i: usize,
    line: usize,
    line_start: usize,
    pub stack: Vec<Frame>,
    pub objects: u64,
    pub values: u64,
    /// The tile layers' cells so far.
    pub layer_cells: u64,
    /// Bytes of the strings and member names so far, a tile layer's `data` string aside.
    pub text_bytes: u64,
    pub layers: BTreeMap<LayerPath, usize>,
    /// The cell [`cell_line`] looks for, and its line once found.
    target: Option<(LayerPath, u64)>,
    found: Option<usize>,
    /// What the file holds, for an error at its top (`a Tiled map`).
    pub what: &'static str,
}

/// A JSON string with its quotes, unescaped (as serde_json reads it; lossy where it would fail).
pub(super) fn unescape(quoted: &[u8]) -> String {
    serde_json::from_slice(quoted).unwrap_or_else(|_| {
        String::from_utf8_lossy(quoted)
            .trim_matches('"')
            .to_string()
    })
}

impl<'t> Walker<'t> {
    fn new(text: &'t str, target: Option<(LayerPath, u64)>, what: &'static str) -> Self {
        Walker {
            b: text.as_bytes(),
            i: 0,
            line: 1,
            line_start: 0,
            stack: Vec::new(),
            objects: 0,
            values: 0,
            layer_cells: 0,
            text_bytes: 0,
            layers: BTreeMap::new(),
            target,
            found: None,
            what,
        }
    }

    fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            column: self.i - self.line_start + 1,
        }
    }

    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    fn ws(&mut self) {
        while let Some(c) = self.peek() {
            match c {
                b'\n' => {
                    self.i += 1;
                    self.line += 1;
                    self.line_start = self.i;
                }
                b' ' | b'\t' | b'\r' => self.i += 1,
                _ => return,
            }
        }
    }

    /// A string at its opening quote: the range of its content, `None` if it does not end.
    fn string(&mut self) -> Option<(usize, usize)> {
        let start = self.i + 1;
        let mut i = start;
        while let Some(&c) = self.b.get(i) {
            match c {
                b'"' => {
                    self.i = i + 1;
                    return Some((start, i));
                }
                b'\\' => i += 2,
                b'\n' => {
                    i += 1;
                    self.line += 1;
                    self.line_start = i;
                }
                _ => i += 1,
            }
        }
        None
    }

    /// The text of the number or literal at the cursor, which it passes.
    fn token(&mut self) -> &'t [u8] {
        let start = self.i;
        while self
            .peek()
            .is_some_and(|c| c.is_ascii_alphanumeric() || matches!(c, b'-' | b'+' | b'.'))
        {
            self.i += 1;
        }
        &self.b[start..self.i]
    }

    /// The token or string (with its quotes) at the cursor, which it does not pass.
    fn token_here(&mut self) -> &'t [u8] {
        let (start, line, line_start) = (self.i, self.line, self.line_start);
        let raw = match self.peek() {
            Some(b'"') => self
                .string()
                .map_or(&self.b[start..], |(_, e)| &self.b[start..=e]),
            _ => self.token(),
        };
        (self.i, self.line, self.line_start) = (start, line, line_start);
        raw
    }

    /// Reads the whole text; stops early at what is not JSON (serde_json reports it) or once
    /// the target cell is found.
    fn run(&mut self) -> Result<(), JsonError> {
        let mut want_value = true;
        loop {
            if self.found.is_some() {
                return Ok(());
            }
            self.ws();
            if want_value {
                match self.value()? {
                    None => return Ok(()),
                    Some(false) => want_value = false,
                    Some(true) => {
                        self.ws();
                        let array = self.stack.last().is_some_and(|f| f.array);
                        let close = if array { b']' } else { b'}' };
                        if self.peek() == Some(close) {
                            self.i += 1;
                            self.close()?;
                            want_value = false;
                        } else if !array && !self.member() {
                            return Ok(());
                        }
                    }
                }
            } else {
                let Some(array) = self.stack.last().map(|f| f.array) else {
                    return Ok(());
                };
                match self.peek() {
                    Some(b',') => {
                        self.i += 1;
                        self.ws();
                        if !array && !self.member() {
                            return Ok(());
                        }
                        want_value = true;
                    }
                    Some(b']') if array => {
                        self.i += 1;
                        self.close()?;
                    }
                    Some(b'}') if !array => {
                        self.i += 1;
                        self.close()?;
                    }
                    _ => return Ok(()),
                }
            }
        }
    }

    /// A member's name and colon; `false` if they are not there.
    fn member(&mut self) -> bool {
        if self.peek() != Some(b'"') {
            return false;
        }
        let at = self.pos();
        let Some((s, e)) = self.string() else {
            return false;
        };
        let quoted = &self.b[s - 1..e + 1];
        self.text_bytes += (e - s) as u64;
        if let Some(f) = self.stack.last_mut() {
            let key = key_of(quoted);
            if key != Key::Other && f.role() != Role::Properties {
                if f.seen & key.bit() != 0 && f.bad.is_none() {
                    let name = String::from_utf8_lossy(&self.b[s..e]);
                    f.bad = Some((at, format!("{name:?} is written a second time here; expected each member once, as Tiled writes it (JSON readers differ in which of the two they keep)")));
                }
                f.seen |= key.bit();
            }
            f.key = Some(key);
            f.key_text = (f.role() == Role::Tiles).then(|| unescape(quoted));
            f.number = numeric_key(f.role(), &self.b[s..e]);
        }
        self.ws();
        if self.peek() != Some(b':') {
            return false;
        }
        self.i += 1;
        true
    }

    /// Reads the start of a value: a container is opened (`Some(true)`), a scalar read whole
    /// (`Some(false)`); `None` if no value starts here.
    fn value(&mut self) -> Result<Option<bool>, JsonError> {
        let at = self.pos();
        let Some(c) = self.peek() else {
            if self.stack.is_empty() && self.values == 0 {
                return Err(self.empty(at));
            }
            return Ok(None);
        };
        if self.stack.is_empty() {
            let raw = self.token_here();
            self.check_top(at, c, raw)?;
        }
        let parent = self.stack.last().map(Frame::role);
        if let Some(p) = self.stack.last_mut().filter(|p| p.array) {
            p.count += 1;
        }
        if parent == Some(Role::Cells) {
            self.look_for_cell(at);
        }
        self.count(at, c, parent)?;
        match c {
            b'{' | b'[' => {
                self.judge(at, c, b"");
                self.open(at, c);
                self.i += 1;
                Ok(Some(true))
            }
            b'"' => {
                let Some((s, e)) = self.string() else {
                    return Ok(None);
                };
                let data = self.stack.last().is_some_and(|p| {
                    !p.array
                        && p.key == Some(Key::Data)
                        && matches!(p.role(), Role::Layer | Role::Chunk)
                });
                if !data {
                    self.text_bytes += (e - s) as u64;
                    self.check_text(at)?;
                }
                // With its quotes, for serde_json to unescape.
                self.judge(at, c, &self.b[s - 1..e + 1]);
                self.scalar(&self.b[s - 1..e + 1], true);
                Ok(Some(false))
            }
            _ if c == b'-' || c.is_ascii_alphanumeric() => {
                let raw = self.token();
                self.judge(at, c, raw);
                self.scalar(raw, false);
                Ok(Some(false))
            }
            _ => Ok(None),
        }
    }

    /// The place of a layer starting now: the index in each `layers` array it is in.
    pub(super) fn layer_path(&self) -> LayerPath {
        self.stack
            .iter()
            .filter(|f| f.array && f.role() == Role::Layers)
            .map(|f| f.count.saturating_sub(1) as u32)
            .collect()
    }

    /// Notes the line of the target cell when the value starting at `at` is it.
    fn look_for_cell(&mut self, at: Pos) {
        let n = self.stack.len();
        let (Some((path, index)), Some(cells), Some(layer)) = (
            &self.target,
            self.stack.last(),
            n.checked_sub(2).and_then(|k| self.stack.get(k)),
        ) else {
            return;
        };
        if layer.role() == Role::Layer && layer.path == *path && cells.count == index + 1 {
            self.found = Some(at.line);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_are_found_by_their_place_and_line() {
        let t = "{\"layers\": [\n {\"type\": \"group\", \"layers\": [\n  {\"type\": \"tilelayer\", \"name\": \"a\", \"data\": [1,\n 2]}]},\n {\"type\": \"objectgroup\", \"name\": \"b\"}]}";
        let w = walk(t, "a Tiled map").ok().unwrap();
        let got: Vec<_> = w.layers.into_iter().collect();
        assert_eq!(got, vec![(vec![0], 2), (vec![0, 0], 3), (vec![1], 5)]);
        assert_eq!(cell_line(t, &[0, 0], 1), Some(4));
        assert_eq!(cell_line(t, &[0, 0], 2), None);
        assert_eq!(cell_line(t, &[1], 0), None);
    }

    #[test]
    fn escapes_and_strings_do_not_confuse_the_walk() {
        assert_eq!(
            unescape(br#""a\"b\\\u0041\ud83d\ude00""#),
            "a\"b\\A\u{1F600}"
        );
        // A key spelled with escapes is the key; brackets inside strings are text.
        let t = r#"{"l\u0061yers": [{"type": "tilelayer", "name": "[{\"", "data": "]}"}]}"#;
        let got: Vec<_> = walk(t, "a Tiled map")
            .ok()
            .unwrap()
            .layers
            .into_iter()
            .collect();
        assert_eq!(got, vec![(vec![0], 1)]);
    }
}

//! The roles the walk of a Tiled JSON file ([`super::json_walk`]) gives the values it opens, what
//! a layer, chunk or object says of itself (name, id, type, size), and the counts, each refused
//! where it passes its limit as the TMX path refuses it ([`super::scan`], [`super::points`]),
//! naming the layer or object.

use super::error::JsonError;
use super::json_frame::{Frame, Key, Role};
use super::json_walk::{unescape, Pos, Walker};
use crate::limits;

/// A limit passed at `at`.
fn limit(at: Pos, message: String) -> JsonError {
    JsonError::Limit {
        line: at.line,
        column: at.column,
        message,
    }
}

impl Walker<'_> {
    /// The role of the value starting under the innermost frame, if it is a container (`open`).
    pub(super) fn child_role(&self, open: u8) -> Role {
        let Some(p) = self.stack.last() else {
            return if open == b'{' { Role::Top } else { Role::Other };
        };
        if matches!(p.role(), Role::Properties | Role::Property) {
            // The elements of a `properties` array are properties; all else in it is user data.
            let n = self.stack.len();
            let holder = n.checked_sub(2).and_then(|k| self.stack.get(k));
            let list = p.array
                && p.role() == Role::Properties
                && open == b'{'
                && holder.is_some_and(|h| !matches!(h.role(), Role::Properties | Role::Property));
            return if list {
                Role::Property
            } else {
                Role::Properties
            };
        }
        let (role, wants) = if p.array {
            match p.role() {
                Role::Layers => (Role::Layer, b'{'),
                Role::Chunks => (Role::Chunk, b'{'),
                Role::Objects => (Role::Object, b'{'),
                Role::Tiles => (Role::Tile, b'{'),
                Role::Tilesets => (Role::Tileset, b'{'),
                Role::Points => (Role::Point, b'{'),
                _ => (Role::Other, open),
            }
        } else {
            match (p.key.unwrap_or(Key::Other), p.role()) {
                (Key::Properties, _) => (Role::Properties, open),
                (_, Role::Tiles) => (Role::Tile, b'{'),
                (Key::Layers, Role::Top | Role::Layer) => (Role::Layers, b'['),
                (Key::Chunks, Role::Layer) => (Role::Chunks, b'['),
                (Key::Objects, _) => (Role::Objects, b'['),
                (Key::Object, Role::Top) => (Role::Object, b'{'),
                (Key::Tilesets, Role::Top) => (Role::Tilesets, b'['),
                (Key::Tileset, Role::Top) => (Role::Tileset, b'{'),
                (Key::Tiles, Role::Tileset | Role::Top) => (Role::Tiles, open),
                (Key::Data, Role::Layer | Role::Chunk) => (Role::Cells, b'['),
                (Key::Polygon | Key::Polyline, Role::Object) => (Role::Points, b'['),
                _ => (Role::Other, open),
            }
        };
        if open == wants {
            role
        } else {
            Role::Other
        }
    }

    /// Counts the value starting at `at` with byte `c`, under a parent of role `parent`: past
    /// a limit, says which and where.
    pub(super) fn count(&mut self, at: Pos, c: u8, parent: Option<Role>) -> Result<(), JsonError> {
        self.check_text(at)?;
        let cell = parent == Some(Role::Cells) && matches!(c, b'-' | b'0'..=b'9');
        if !cell {
            self.values += 1;
            if self.values > limits::MAX_JSON_VALUES {
                return Err(limit(at, format!(
                    "the file holds more than {} JSON values besides the cells of its tile layers; expected at most {} (serde_json reads each into the tree it builds, 32 bytes and more each)",
                    limits::MAX_JSON_VALUES, limits::MAX_JSON_VALUES
                )));
            }
        }
        if parent == Some(Role::Points) {
            self.check_points(at)?;
        }
        if matches!(c, b'{' | b'[') && self.stack.len() + 1 > limits::MAX_JSON_DEPTH {
            return Err(limit(at, format!(
                "arrays and objects nest more than {} deep here; expected at most {} (serde_json, which reads the file, stops at 128; a group layer nests two, its object and its layers)",
                limits::MAX_JSON_DEPTH, limits::MAX_JSON_DEPTH
            )));
        }
        if c == b'{' {
            self.objects += 1;
            if self.objects > limits::MAX_JSON_OBJECTS {
                return Err(limit(at, format!(
                    "the file holds more than {} JSON objects ({{...}}: a layer, an object, a property, a tileset's tile and a polygon's point are one each); expected at most {} (serde_json reads each into a tree node of 632 bytes and more)",
                    limits::MAX_JSON_OBJECTS, limits::MAX_JSON_OBJECTS
                )));
            }
        }
        Ok(())
    }

    /// Past [`limits::MAX_JSON_TEXT_BYTES`] of strings and member names, says where.
    pub(super) fn check_text(&self, at: Pos) -> Result<(), JsonError> {
        if self.text_bytes > limits::MAX_JSON_TEXT_BYTES {
            return Err(limit(at, format!(
                "the file's strings and member names (a tile layer's data aside) pass {} bytes here; expected at most {} (16 MiB: names, types, properties and paths of a map take kilobytes, and the translation to TMX escapes and copies each)",
                limits::MAX_JSON_TEXT_BYTES, limits::MAX_JSON_TEXT_BYTES
            )));
        }
        Ok(())
    }

    /// Opens the array or object starting at `at` with byte `c`, with its role.
    pub(super) fn open(&mut self, at: Pos, c: u8) {
        let role = self.child_role(c);
        let mut f = Frame {
            role: Some(role),
            array: c == b'[',
            start: at,
            ..Frame::default()
        };
        match role {
            Role::Layer => {
                f.path = self.layer_path();
                self.layers.insert(f.path.clone(), at.line);
            }
            Role::Tile => f.id = self.stack.last().and_then(|p| p.key_text.clone()),
            Role::Chunks => {
                if let Some(p) = self.stack.last_mut() {
                    p.chunked = true;
                }
            }
            _ => {}
        }
        self.stack.push(f);
    }

    /// Notes a string (`quoted`, with its quotes) or another scalar that a layer, chunk, object
    /// or tile says of itself.
    pub(super) fn scalar(&mut self, raw: &[u8], quoted: bool) {
        let Some(p) = self.stack.last_mut().filter(|p| !p.array) else {
            return;
        };
        if !matches!(
            p.role(),
            Role::Top
                | Role::Layer
                | Role::Chunk
                | Role::Object
                | Role::Tile
                | Role::Tileset
                | Role::Property
        ) {
            return;
        }
        let text = || {
            if quoted {
                unescape(raw)
            } else {
                String::from_utf8_lossy(raw).into_owned()
            }
        };
        let n = || {
            std::str::from_utf8(raw)
                .ok()
                .and_then(|t| t.parse::<f64>().ok())
                .filter(|n| n.is_finite() && !quoted)
        };
        match p.key {
            Some(Key::Name) => p.name = Some(text()),
            Some(Key::Type) => p.ty = Some(text()),
            Some(Key::Id) => p.id = Some(text()),
            Some(Key::Width) => p.width = n().map(|n| n.max(0.0) as u64),
            Some(Key::Height) => p.height = n().map(|n| n.max(0.0) as u64),
            Some(Key::X) => p.x = n().map(|n| n as i64),
            Some(Key::Y) => p.y = n().map(|n| n as i64),
            Some(Key::Infinite) => p.chunked |= raw == b"true",
            _ => {}
        }
    }

    /// The points array being read has one more point: past the limit, the object is named.
    fn check_points(&self, at: Pos) -> Result<(), JsonError> {
        let n = self.stack.len();
        let (Some(points), Some(object)) = (
            self.stack.last(),
            n.checked_sub(2).and_then(|k| self.stack.get(k)),
        ) else {
            return Ok(());
        };
        let max = limits::MAX_POLYGON_POINTS as u64;
        if points.count <= max {
            return Ok(());
        }
        let what = match object.key {
            Some(Key::Polyline) => "polyline",
            _ => "polygon",
        };
        let tile = self
            .stack
            .iter()
            .rev()
            .find(|f| f.role() == Role::Tile)
            .and_then(|f| f.id.as_ref())
            .map_or(String::new(), |t| {
                format!(" (a collision shape of tile {t})")
            });
        Err(limit(at, format!(
            "object {} {:?}{tile}: its {what} has more than {max} points (this is point {}); expected at most {max} (a ramp has 3 or 4 corners, a drawn outline some dozens)",
            object.id.as_deref().unwrap_or_default(),
            object.name.as_deref().unwrap_or_default(),
            points.count
        )))
    }

    /// Closes the innermost array or object, checking a layer, a chunk or the map as a whole.
    pub(super) fn close(&mut self) -> Result<(), JsonError> {
        let Some(f) = self.stack.pop() else {
            return Ok(());
        };
        self.check_values(&f)?;
        match f.role() {
            Role::Cells => {
                if let Some(p) = self.stack.last_mut() {
                    p.cells = p.cells.saturating_add(f.count);
                }
            }
            Role::Chunk => {
                let (w, h) = (f.width.unwrap_or(0), f.height.unwrap_or(0));
                let bad = if w.saturating_mul(h) > limits::MAX_TILES {
                    Some(format!("the chunk is {w} x {h} tiles"))
                } else if f.cells > limits::MAX_TILES {
                    Some(format!("the chunk's data holds {} cells", f.cells))
                } else {
                    None
                };
                // Its layer holds its `chunks` array.
                let layer = self
                    .stack
                    .iter_mut()
                    .rev()
                    .find(|p| p.role() == Role::Layer);
                if let Some(p) = layer {
                    p.cells = p.cells.saturating_add(f.cells);
                    if let Some(bad) = bad.filter(|_| p.bad_chunk.is_none()) {
                        let message = format!(
                            "chunk at x = {}, y = {}: {bad}; expected at most {} tiles",
                            f.x.unwrap_or(0),
                            f.y.unwrap_or(0),
                            limits::MAX_TILES
                        );
                        p.bad_chunk = Some((f.start, message));
                    }
                }
            }
            Role::Layer => self.layer_end(f)?,
            Role::Top => {
                if let (Some(w), Some(h)) = (f.width, f.height) {
                    if w.saturating_mul(h) > limits::MAX_TILES {
                        return Err(limit(f.start, format!(
                            "the map is {w} x {h} tiles; expected at most {} tiles (checked before reading its layers)",
                            limits::MAX_TILES
                        )));
                    }
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// A layer read whole: its size, its data's cells and the tile layers' cells so far, each
    /// refused at the layer's start as the TMX path refuses them at its `<layer>`.
    fn layer_end(&mut self, f: Frame) -> Result<(), JsonError> {
        let name = f.name.as_deref().unwrap_or_default();
        let (w, h) = (f.width.unwrap_or(0), f.height.unwrap_or(0));
        let declared = match f.ty.as_deref() {
            Some("tilelayer") => w.saturating_mul(h),
            _ => 0,
        };
        let max = limits::MAX_TILES;
        if declared > max {
            return Err(limit(
                f.start,
                format!("layer {name:?} is {w} x {h} tiles; expected at most {max} tiles"),
            ));
        }
        if let Some((at, message)) = f.bad_chunk {
            return Err(limit(at, format!("layer {name:?}, {message}")));
        }
        if !f.chunked && f.cells > max {
            return Err(limit(f.start, format!(
                "layer {name:?}: its data holds {} cells; expected at most {max}, one per cell of the layer",
                f.cells
            )));
        }
        self.layer_cells = self.layer_cells.saturating_add(declared.max(f.cells));
        if self.layer_cells > limits::MAX_LAYER_CELLS {
            let size = if f.cells > declared {
                format!("{} cells in its data", f.cells)
            } else {
                format!("{w} x {h} tiles")
            };
            return Err(limit(f.start, format!(
                "layer {name:?} ({size}) brings the map's tile layers to {} cells together; expected at most {} (each layer's cells are held while the map is read)",
                self.layer_cells,
                limits::MAX_LAYER_CELLS
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::json_walk::Walked;
    use super::*;

    fn walk(text: &str) -> Result<Walked, JsonError> {
        super::super::json_walk::walk(text, "a Tiled map")
    }

    /// The walk's refusal of `text`: line, column and message.
    fn err(text: &str) -> (usize, usize, String) {
        match walk(text) {
            Err(JsonError::Limit {
                line,
                column,
                message,
            }) => (line, column, message),
            Err(e) => panic!("{e}"),
            Ok(_) => panic!("no error"),
        }
    }

    #[test]
    fn points_past_the_limit_are_refused_where_they_pass_naming_the_object_and_tile() {
        let pts = |n: usize| vec![r#"{"x":0,"y":0}"#; n].join(",");
        let t = |n: usize| {
            format!(
                r#"{{"tiles":[{{"id":4,"objectgroup":{{"objects":[{{"id":2,"name":"r","polyline":[{}]}}]}}}}]}}"#,
                pts(n)
            )
        };
        assert!(walk(&t(limits::MAX_POLYGON_POINTS)).is_ok());
        let over = t(limits::MAX_POLYGON_POINTS + 1);
        let (line, column, m) = err(&over);
        // The point past the limit: 14 characters a point from the first (`{"x":0,"y":0},`).
        let first = over.find(r#"{"x""#).unwrap() + 1;
        assert_eq!((line, column), (1, first + 14 * limits::MAX_POLYGON_POINTS));
        assert!(m.starts_with("object 2 \"r\" (a collision shape of tile 4): its polyline has more than 10000 points (this is point 10001); expected at most 10000"), "{m}");
        // A tileset's tiles by id (older Tiled): the id is the key.
        let old = over
            .replace(r#""tiles":[{"id":4,"#, r#""tiles":{"7":{"#)
            .replace("]}]}", "]}}}");
        assert!(err(&old).2.contains("(a collision shape of tile 7)"));
    }

    #[test]
    fn nesting_past_serde_jsons_limit_is_refused_where_it_passes() {
        // `{"a":` then arrays: `d` deep in all.
        let t = |d: usize| format!("{{\"a\":{}{}}}", "[".repeat(d - 1), "]".repeat(d - 1));
        assert!(walk(&t(limits::MAX_JSON_DEPTH)).is_ok());
        // serde_json reads as deep as the walk lets through, and no deeper.
        assert!(serde_json::from_str::<serde_json::Value>(&t(limits::MAX_JSON_DEPTH)).is_ok());
        assert!(serde_json::from_str::<serde_json::Value>(&t(limits::MAX_JSON_DEPTH + 1)).is_err());
        let (line, column, m) = err(&t(limits::MAX_JSON_DEPTH + 1));
        // The array that passes: the 127th, at column 5 + 127.
        assert_eq!((line, column), (1, 5 + limits::MAX_JSON_DEPTH));
        assert!(
            m.contains("nest more than 127 deep here; expected at most 127"),
            "{m}"
        );
    }

    #[test]
    fn objects_and_values_past_their_limits_are_refused_where_they_pass() {
        let objects = |n: usize| format!("{{\"a\":[{}]}}", vec!["{}"; n].join(","));
        // The top object is one.
        assert!(walk(&objects(limits::MAX_JSON_OBJECTS as usize - 1)).is_ok());
        let (line, column, m) = err(&objects(limits::MAX_JSON_OBJECTS as usize));
        // The object past the limit: 3 characters an object after `{"a":[`.
        assert_eq!(
            (line, column),
            (1, 7 + 3 * (limits::MAX_JSON_OBJECTS as usize - 1))
        );
        assert!(m.contains("more than 500000 JSON objects"), "{m}");
        // Values: the top object, the array and its numbers.
        let values = |n: usize| format!("{{\"a\":[{}]}}", vec!["0"; n].join(","));
        assert!(walk(&values(limits::MAX_JSON_VALUES as usize - 2)).is_ok());
        let m = err(&values(limits::MAX_JSON_VALUES as usize - 1)).2;
        assert!(
            m.contains("more than 5000000 JSON values besides the cells"),
            "{m}"
        );
        // A tile layer's cells are not values: they have their own limit.
        let cells = format!(
            r#"{{"layers":[{{"data":[{}],"height":1000,"name":"big","type":"tilelayer","width":7000}}]}}"#,
            vec!["0"; 7_000_000].join(",")
        );
        let m = err(&cells).2;
        assert!(m.starts_with("layer \"big\" is 7000 x 1000 tiles"), "{m}");
    }

    #[test]
    fn layers_and_chunks_past_the_cell_limits_are_refused_at_their_start() {
        let layer = |name: &str, w: u64, h: u64| {
            format!(r#"{{"data":"","height":{h},"name":"{name}","type":"tilelayer","width":{w}}}"#)
        };
        // 16 layers of 1000 x 1000: the map's tile layers at MAX_LAYER_CELLS; a 17th passes it.
        let n = (limits::MAX_LAYER_CELLS / limits::MAX_TILES) as usize;
        let layers: Vec<String> = (0..=n)
            .map(|k| layer(&format!("l{k}"), 1000, 1000))
            .collect();
        let at_limit = format!("{{\"layers\":[\n{}]}}", layers[..n].join(",\n"));
        assert!(walk(&at_limit).is_ok());
        let over = format!("{{\"layers\":[\n{}]}}", layers.join(",\n"));
        let (line, column, m) = err(&over);
        assert_eq!((line, column), (2 + n, 1));
        assert!(m.starts_with("layer \"l16\" (1000 x 1000 tiles) brings the map's tile layers to 17000000 cells together; expected at most 16000000"), "{m}");
        // Data that holds more cells than the layer could have.
        let long = format!(
            r#"{{"layers":[{{"data":[{}],"name":"g","type":"tilelayer","width":2,"height":1}}]}}"#,
            vec!["0"; limits::MAX_TILES as usize + 1].join(",")
        );
        assert!(err(&long)
            .2
            .starts_with("layer \"g\": its data holds 1000001 cells; expected at most 1000000"));
        // A chunk too large, named with its layer at the chunk's start.
        let chunk = r#"{"layers":[{"chunks":[{"data":"", "height":2000,"width":1000,"x":16,"y":-16}],
            "name":"inf","type":"tilelayer","width":16,"height":16}]}"#;
        let (line, column, m) = err(chunk);
        assert_eq!((line, column), (1, 23));
        assert!(m.starts_with("layer \"inf\", chunk at x = 16, y = -16: the chunk is 1000 x 2000 tiles; expected at most 1000000 tiles"), "{m}");
        // The map's own size.
        let (line, column, m) = err(r#"{"height":5000,"layers":[],"width":5000}"#);
        assert_eq!((line, column), (1, 1));
        assert!(
            m.starts_with("the map is 5000 x 5000 tiles; expected at most 1000000 tiles"),
            "{m}"
        );
    }

    #[test]
    fn strings_past_the_text_limit_are_refused_but_a_layer_s_data_string_is_not_counted() {
        let max = limits::MAX_JSON_TEXT_BYTES as usize;
        // A property value of `&`s (the translation escapes each to `&amp;`: 120 MB of them
        // took 3.1 GB): at the limit with its member names (`properties`, `value`: 15 bytes).
        let prop = |n: usize| format!(r#"{{"properties":[{{"value":"{}"}}]}}"#, "&".repeat(n));
        assert!(walk(&prop(max - 15)).is_ok());
        let (line, column, m) = err(&prop(max - 14));
        // Named at the string's opening quote.
        assert_eq!((line, column), (1, 25));
        assert!(m.starts_with("the file's strings and member names (a tile layer's data aside) pass 16777216 bytes here; expected at most 16777216"), "{m}");
        // A base64 layer's data string is bounded by its cells, not by this limit.
        let data = format!(
            r#"{{"layers":[{{"data":"{}","encoding":"base64","name":"g","type":"tilelayer","width":1,"height":1}}]}}"#,
            "A".repeat(max + 1)
        );
        assert!(
            !matches!(walk(&data), Err(JsonError::Limit { message, .. }) if message.contains("strings and member names"))
        );
    }
}

//! The map read through the `tiled` crate: within the input cap, made readable where Tiled is
//! tolerant and the crate is not ([`super::normalize`]), looked at for what the crate would
//! allocate without bound ([`super::scan`]), tilesets and templates through the same reader;
//! and, when the crate fails, the file at fault named.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use super::{
    attrs, elements, json, normalize, points, refs, scan, tileset_ids, wellformed, Importer,
    TiledError, TiledImport, TiledWarning,
};
use crate::level::import::{ImportFailure, ImportOptions};
use crate::level::toml::{options_beside, SideFailure};

/// The file a map refers to, found as the `tiled` crate finds it: relative to the map's folder.
fn sibling(map: &Path, source: &str) -> PathBuf {
    map.parent()
        .map_or_else(|| PathBuf::from(source), |d| d.join(source))
}

/// Reads a Tiled map's geometry, platforms and spawn points (no scenarios), with the command
/// line's overrides. On failure the warnings gathered so far come with the error.
pub fn import_tiled_map_with(
    path: &Path,
    opts: &ImportOptions,
) -> Result<TiledImport, ImportFailure<TiledError>> {
    let file = path.display().to_string();
    let notes: Rc<RefCell<Vec<TiledWarning>>> = Rc::new(RefCell::new(Vec::new()));
    let failed = |error: TiledError, notes: &Rc<RefCell<Vec<TiledWarning>>>| ImportFailure {
        error,
        warnings: notes.borrow().clone(),
    };
    // The side file's [import] table, under the command line's flags.
    let merged = options_beside(path, opts).map_err(|e| {
        failed(
            match e {
                SideFailure::Read { file, message } => TiledError::SideFileRead { file, message },
                SideFailure::Level(e) => TiledError::SideFile(e),
            },
            &notes,
        )
    })?;
    let opts = &merged;
    // Read once, within the input cap, made readable by the crate where Tiled is tolerant and
    // the crate is not, and looked at for what the crate would allocate or index before it does.
    let raw = crate::input::read_text(path, crate::limits::MAX_INPUT_BYTES, "input file").map_err(
        |e| {
            let (file, message) = match &e {
                crate::input::InputError::NotText {
                    line,
                    column,
                    found,
                    ..
                } => (
                    format!("{file}:{line}:{column}"),
                    crate::input::not_text(found),
                ),
                _ => (file.clone(), e.reason()),
            };
            failed(TiledError::Load { file, message }, &notes)
        },
    )?;
    // A JSON map (told by its content, whatever its extension) is read as its TMX twin; a line
    // of that twin is shown as the JSON line where its layer starts (a cell's own line for an
    // error at a cell), or as the part of the map it is in.
    use crate::level::format::{first_text, format_of_text, LevelFormat};
    let (json, text) = if matches!(
        format_of_text(&raw, path),
        LevelFormat::TiledJson | LevelFormat::Ldtk
    ) {
        if raw.starts_with('\u{feff}') {
            let message = crate::level::format::JSON_BOM.to_string();
            let file = format!("{file}:1:1");
            return Err(failed(TiledError::Map { file, message }, &notes));
        }
        let mut j = json::json_map_to_tmx(&raw).map_err(|e| {
            let (file, message) = match e.located() {
                Some((line, column, m)) => (format!("{file}:{line}:{column}"), m),
                None => (file.clone(), e.to_string()),
            };
            failed(TiledError::Map { file, message }, &notes)
        })?;
        for n in &j.tmx.notes {
            notes.borrow_mut().push(TiledWarning {
                file: file.clone(),
                subject: "map".into(),
                message: n.clone(),
            });
        }
        let tmx = std::mem::take(&mut j.tmx.text);
        (Some((j, raw)), tmx)
    } else if format_of_text(&raw, path) == LevelFormat::Level {
        let (line, column, found) = first_text(&raw);
        return Err(failed(
            TiledError::Map {
                file: format!("{file}:{line}:{column}"),
                message: format!("found {found}, which starts neither XML (`<`, a .tmx map) nor a JSON object (`{{`, a .tmj map); expected a Tiled map"),
            },
            &notes,
        ));
    } else {
        (None, raw)
    };
    let at = |line: usize| match &json {
        Some((j, _)) => j.layer_start(line).map_or_else(
            || format!("{file} ({})", j.layer_at(line)),
            |l| format!("{file}:{l}"),
        ),
        None => format!("{file}:{line}"),
    };
    let cell_at = |line: usize, cell: (i64, i64)| match &json {
        Some((j, raw)) => j
            .json_line(raw, line, cell)
            .map_or_else(|| file.clone(), |l| format!("{file}:{l}")),
        None => format!("{file}:{line}"),
    };
    // A tileset or template given as the level: the crate reads only maps.
    if let Some((root, at)) = scan::root_element(&text).filter(|(r, _)| r != "map") {
        let (line, column) = attrs::line_col(&text, at);
        let what = match root.as_str() {
            "tileset" => "a Tiled tileset, which maps use for their tiles",
            "template" => "a Tiled object template, which maps' objects use",
            _ => "not a Tiled map",
        };
        return Err(failed(
            TiledError::Map {
                file: format!("{file}:{line}:{column}"),
                message: format!("the root element is <{root}> ({what}); expected <map>, a Tiled map (give the map that uses it)"),
            },
            &notes,
        ));
    }
    // A TMX map's numbers, named at their line and column before the crate reads them.
    if json.is_none() {
        wellformed::check_xml(&text)
            .and_then(|()| attrs::check_attributes(&text))
            .map_err(|e| {
                let column = e.column.map_or(String::new(), |c| format!(":{c}"));
                failed(
                    TiledError::Map {
                        file: format!("{file}:{}{column}", e.line),
                        message: e.message,
                    },
                    &notes,
                )
            })?;
    }
    let norm = normalize::normalize_xml(&text).map_err(|e| {
        failed(
            TiledError::Map {
                file: at(e.line),
                message: e.message,
            },
            &notes,
        )
    })?;
    for n in norm.notes {
        notes.borrow_mut().push(TiledWarning {
            file: file.clone(),
            subject: "map".into(),
            message: n,
        });
    }
    // A column is given where the text the scan reads is the file's own (a TMX map the
    // normalizer left as it was).
    let columns = json.is_none() && norm.text == text;
    let norm_same = columns;
    let text = norm.text;
    let checked = scan::scan_map(&text)
        .and_then(|s| tileset_ids::check_tileset_ids(&text).map(|notes| (s, notes)));
    let (sources, id_notes) = checked.map_err(|e| {
        let file = match e.column.filter(|_| columns) {
            Some(c) => format!("{}:{c}", at(e.line)),
            None => at(e.line),
        };
        failed(
            TiledError::Map {
                file,
                message: e.message,
            },
            &notes,
        )
    })?;
    for n in id_notes {
        notes.borrow_mut().push(TiledWarning {
            file: file.clone(),
            subject: "map".into(),
            message: n,
        });
    }
    // Templates and tilesets that loop back, and groups nested without end, which the crate
    // would follow until the stack overflows.
    let load = |p: &Path| crate_text(p).ok();
    refs::check_references(path, &text, &load).map_err(|e| {
        // A reference in the map itself is shown at the map's line and column, or its JSON
        // layer (whose twin's columns are not the file's).
        let in_map = e.file.strip_prefix(&format!("{file}:")).and_then(|lc| {
            let (l, c) = lc.split_once(':').unwrap_or((lc, ""));
            Some((l.parse::<usize>().ok()?, c.to_string()))
        });
        let shown = match in_map {
            Some((l, c)) if json.is_none() && norm_same && !c.is_empty() => {
                format!("{}:{c}", at(l))
            }
            Some((l, _)) => at(l),
            None => e.file,
        };
        failed(
            TiledError::Map {
                file: shown,
                message: e.message,
            },
            &notes,
        )
    })?;
    let map_path = path.to_path_buf();
    let bytes = text.clone().into_bytes();
    // The map as read above; tilesets and templates through the same cap, made readable too.
    // The failure of a file the crate reads names that file.
    let reader_notes = notes.clone();
    let reader = move |p: &Path| -> std::io::Result<std::io::Cursor<Vec<u8>>> {
        if p == map_path {
            return Ok(std::io::Cursor::new(bytes.clone()));
        }
        let shown = p.display().to_string();
        let data = crate::limits::read_capped(p)?;
        let ext = p
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        let bad = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
        let text = String::from_utf8(data.clone());
        let out = match (ext.as_str(), text) {
            ("tsj" | "json", Ok(t)) => {
                let n = json::json_tileset_to_tsx(&t).map_err(|e| bad(e.to_string()))?;
                (n.text, n.notes)
            }
            ("tj", Ok(t)) => {
                let n = json::json_template_to_tx(&t).map_err(|e| bad(e.to_string()))?;
                (n.text, n.notes)
            }
            ("tsx", Ok(t)) => {
                wellformed::check_xml(&t).map_err(located)?;
                elements::check_element_count(&t, "the tileset file").map_err(located)?;
                attrs::check_attributes(&t).map_err(located)?;
                let over = tileset_ids::check_tileset_ids(&t).map_err(located)?;
                let mut n = normalize::normalize_xml(&t).map_err(located)?;
                n.notes.extend(over);
                (n.text, n.notes)
            }
            // A template (`.tx`): read as it is, its shapes counted first.
            (_, Ok(t)) => {
                wellformed::check_xml(&t).map_err(located)?;
                elements::check_element_count(&t, "the template file").map_err(located)?;
                points::check_points(&t).map_err(located)?;
                return Ok(std::io::Cursor::new(data));
            }
            _ => return Ok(std::io::Cursor::new(data)),
        };
        // Each shape's points counted before the crate reads them (the line is the XML's; a
        // JSON tileset's shape is named by its object and tile).
        points::check_points(&out.0).map_err(|e| match ext.as_str() {
            "tsx" => located(e),
            _ => bad(e.message),
        })?;
        for n in out.1 {
            reader_notes.borrow_mut().push(TiledWarning {
                file: shown.clone(),
                subject: "tileset".into(),
                message: n,
            });
        }
        Ok(std::io::Cursor::new(out.0.into_bytes()))
    };
    let map = match tiled::Loader::with_reader(reader).load_tmx_map(path) {
        Ok(m) => m,
        Err(e) => {
            let error = load_error(path, &text, &sources, e, &at);
            return Err(failed(error, &notes));
        }
    };
    let mut im = Importer::new((file.clone(), &text, &cell_at), &map, opts);
    im.warnings = notes.borrow().clone();
    match im.run(path) {
        Ok(r) => Ok(r),
        Err(error) => Err(ImportFailure {
            error,
            warnings: im.warnings,
        }),
    }
}

/// A tileset's or template's fault found before the crate reads the file, with its place: it
/// passes through the crate's loader as an I/O error, and [`load_error`] names the file at it.
#[derive(Debug)]
struct Located {
    line: usize,
    column: Option<usize>,
    message: String,
}

impl Located {
    /// `:LINE` or `:LINE:COLUMN`, to follow the file's name.
    fn place(&self) -> String {
        match self.column {
            Some(c) => format!(":{}:{c}", self.line),
            None => format!(":{}", self.line),
        }
    }
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for Located {}

/// A scan's finding in a tileset or template, as the reader's I/O error.
fn located(e: scan::ScanError) -> std::io::Error {
    let l = Located {
        line: e.line,
        column: e.column,
        message: e.message,
    };
    std::io::Error::new(std::io::ErrorKind::InvalidData, l)
}

/// The place of a reader's error, where the reader found one.
fn place_of<'a>(err: &'a (dyn std::error::Error + Send + Sync + 'static)) -> Option<&'a Located> {
    err.downcast_ref::<std::io::Error>()?
        .get_ref()?
        .downcast_ref::<Located>()
}

/// The crate's error with the file it was reading: an external tileset or template that fails
/// on its own is named; otherwise the map, with the line of an XML syntax error.
fn load_error(
    path: &Path,
    text: &str,
    sources: &[String],
    e: tiled::Error,
    at: &dyn Fn(usize) -> String,
) -> TiledError {
    let file = path.display().to_string();
    if let tiled::Error::ResourceLoadingError { path: p, err } = &e {
        if let Some(l) = place_of(err.as_ref()) {
            return TiledError::Load {
                file: format!("{}{}", p.display(), l.place()),
                message: format!("{} (the map {file} refers to it)", l.message),
            };
        }
        return TiledError::Load {
            file: p.display().to_string(),
            message: format!("cannot read it ({err}); the map {file} refers to it"),
        };
    }
    // An external tileset that fails to load on its own is the file at fault.
    for s in sources {
        let p = sibling(path, s);
        let reader = |q: &Path| crate_text(q).map(|t| std::io::Cursor::new(t.into_bytes()));
        if let Err(te) = tiled::Loader::with_reader(reader).load_tsx_tileset(&p) {
            let (place, message) = match te {
                tiled::Error::ResourceLoadingError { err, .. } => match place_of(err.as_ref()) {
                    Some(l) => (l.place(), l.message.clone()),
                    None => (String::new(), err.to_string()),
                },
                other => (String::new(), explain(&other)),
            };
            return TiledError::Load {
                file: format!("{}{place}", p.display()),
                message: format!("{message} (a tileset the map {file} uses)"),
            };
        }
    }
    TiledError::Load {
        file: scan::xml_error_line(text).map_or(file, at),
        message: explain(&e),
    }
}

/// A tileset's or template's text as the crate reads it: within the input cap, a JSON tileset
/// as its TSX twin, XML made readable where Tiled is tolerant and the crate is not.
fn crate_text(q: &Path) -> std::io::Result<String> {
    let data = crate::limits::read_capped(q)?;
    let ext = q
        .extension()
        .map(|x| x.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let bad = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
    let t = String::from_utf8(data).map_err(|e| {
        let (line, column, found) = crate::input::not_utf8_at(e.as_bytes(), e.utf8_error());
        bad(format!(
            "line {line}, column {column}: {}",
            crate::input::not_text(&found)
        ))
    })?;
    let t = match ext.as_str() {
        "tsj" | "json" => {
            json::json_tileset_to_tsx(&t)
                .map_err(|e| bad(e.to_string()))?
                .text
        }
        "tj" => {
            json::json_template_to_tx(&t)
                .map_err(|e| bad(e.to_string()))?
                .text
        }
        _ => {
            wellformed::check_xml(&t).map_err(located)?;
            normalize::normalize_xml(&t).map_err(located)?.text
        }
    };
    Ok(t)
}

/// The crate's message, with what to do where platbench knows it.
fn explain(e: &tiled::Error) -> String {
    match e {
        tiled::Error::InvalidEncodingFormat { encoding, compression } => format!(
            "a tile layer's data is in {} encoding with {} compression, which the tiled crate does not read; save the map with CSV or Base64 (uncompressed, zlib or gzip) layer format",
            encoding.as_deref().unwrap_or("XML (no)"),
            compression.as_deref().unwrap_or("no")
        ),
        // Found with the layer and line by scan::scan_map before the crate reads the map; these
        // say at least what was wrong should one get past it.
        tiled::Error::CsvDecodingError(e) => format!(
            "a tile layer's CSV data has a cell that is not a tile id ({e}); expected whole numbers from 0 to 4294967295"
        ),
        tiled::Error::Base64DecodingError(e) => format!(
            "a tile layer's base64 data cannot be decoded ({e}); expected standard base64 as Tiled writes it"
        ),
        tiled::Error::DecompressingError(e) => format!(
            "a tile layer's compressed data cannot be inflated ({e}); expected zlib or gzip data as Tiled writes it"
        ),
        tiled::Error::InvalidTileFound => "an infinite map's chunk holds fewer cells than its width x height; expected one cell per cell of the chunk".into(),
        tiled::Error::MalformedAttributes(m) => {
            format!("{m} (an attribute the tiled crate requires is missing or not a number)")
        }
        other => other.to_string(),
    }
}

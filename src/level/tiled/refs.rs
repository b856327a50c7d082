//! Recursion the `tiled` crate would follow until the stack overflows, found before it reads
//! the map: object templates (`.tx`) that refer back to themselves (directly, through other
//! templates, or through a tileset whose tile uses a template), chains of files longer than
//! [`limits::MAX_TILED_FILE_CHAIN`], group layers nested deeper than
//! [`limits::MAX_GROUP_DEPTH`] and elements nested deeper than [`limits::MAX_XML_DEPTH`]. The
//! crate reads each of these by recursion, with no limit of its own.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use quick_xml::events::Event;

use super::attrs::{attr_offset, line_col};
use super::scan::{attr, line_of, ScanError};
use crate::limits;

/// A file that cannot be read as it is: the file (with its line when known) and why.
#[derive(Debug)]
pub(super) struct RefError {
    /// The file at fault, as `FILE` or `FILE:LINE`.
    pub file: String,
    /// What was found and what was expected.
    pub message: String,
}

/// A file another file refers to, and the line of the reference.
struct Reference {
    line: usize,
    /// The 1-based column of the `template` or `source` attribute.
    column: usize,
    /// `object template` or `tileset`.
    what: &'static str,
    target: String,
}

/// Checks the map whose (normalized) text is `text` and every tileset and template it reaches.
/// `load` gives the XML the crate would read for a referenced file; a file it cannot give is
/// left to the crate, which reports it.
pub(super) fn check_references(
    map: &Path,
    text: &str,
    load: &dyn Fn(&Path) -> Option<String>,
) -> Result<(), RefError> {
    let mut walk = Walk {
        load,
        chain: vec![(key(map), name(map))],
        done: HashSet::new(),
    };
    walk.visit(map, text)
}

/// A depth-first walk over the files: those being read (the chain from the map) and those
/// already checked to the bottom.
struct Walk<'a> {
    load: &'a dyn Fn(&Path) -> Option<String>,
    chain: Vec<(PathBuf, String)>,
    done: HashSet<PathBuf>,
}

impl Walk<'_> {
    /// Where reference `r` of the file at `path` is: its line, or for a JSON tileset or
    /// template (read as its XML twin, whose lines are not the file's) the line of its
    /// `template` or `source` key in the JSON. The map's own lines are placed by the caller.
    fn place(&self, path: &Path, r: &Reference) -> String {
        let shown = path.display().to_string();
        let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
        let json = matches!(ext.as_deref(), Some("tj" | "tsj" | "json"));
        if self.chain.len() < 2 || !json {
            return format!("{shown}:{}:{}", r.line, r.column);
        }
        let key = if r.what == "tileset" {
            "source"
        } else {
            "template"
        };
        let raw = crate::limits::read_capped(path).ok();
        let raw = raw.as_deref().and_then(|b| std::str::from_utf8(b).ok());
        match raw.and_then(|t| json_key_line(t, key, &r.target)) {
            Some(line) => format!("{shown}:{line}"),
            None => shown,
        }
    }

    fn visit(&mut self, path: &Path, text: &str) -> Result<(), RefError> {
        let shown = path.display().to_string();
        let refs = scan_file(text).map_err(|e| RefError {
            file: format!("{shown}:{}", e.line),
            message: e.message,
        })?;
        for r in refs {
            // As the crate finds it: relative to the folder of the file that refers to it.
            let target = path
                .parent()
                .map_or_else(|| PathBuf::from(&r.target), |d| d.join(&r.target));
            let k = key(&target);
            let at = self.place(path, &r);
            if let Some(pos) = self.chain.iter().position(|(c, _)| *c == k) {
                let mut names: Vec<&str> =
                    self.chain[pos..].iter().map(|(_, n)| n.as_str()).collect();
                names.push(&self.chain[pos].1);
                return Err(RefError {
                    file: at,
                    message: format!(
                        "{} {:?} refers back to {}, which is already being read ({}); expected templates and tilesets that do not refer to themselves",
                        r.what,
                        r.target,
                        self.chain[pos].1,
                        names.join(" -> ")
                    ),
                });
            }
            if self.done.contains(&k) {
                continue;
            }
            if self.chain.len() >= limits::MAX_TILED_FILE_CHAIN {
                return Err(RefError {
                    file: at,
                    message: format!(
                        "{} {:?} is file {} in a chain of references from the map; expected at most {} (a template or tileset that refers to the next, and so on)",
                        r.what,
                        r.target,
                        self.chain.len() + 1,
                        limits::MAX_TILED_FILE_CHAIN
                    ),
                });
            }
            let Some(text) = (self.load)(&target) else {
                continue;
            };
            self.chain.push((k.clone(), name(&target)));
            self.visit(&target, &text)?;
            self.chain.pop();
            self.done.insert(k);
        }
        Ok(())
    }
}

/// The line of the first `"KEY": "VALUE"` in JSON `text`.
fn json_key_line(text: &str, key: &str, value: &str) -> Option<usize> {
    let quoted = format!("\"{key}\"");
    text.match_indices(&quoted).find_map(|(at, _)| {
        let rest = text[at + quoted.len()..].trim_start().strip_prefix(':')?;
        let mut strings = serde_json::Deserializer::from_str(rest).into_iter::<String>();
        (strings.next()?.ok()? == value).then(|| line_of(text, at))
    })
}

/// The same file however it is spelled (`a.tx`, `./a.tx`, a symbolic link): its canonical path
/// when it has one.
fn key(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// A file's name, as a cycle lists it.
fn name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The nesting of one file's elements and groups, checked against their limits, and the files it
/// refers to. Malformed XML ends the scan: the crate reports it.
fn scan_file(text: &str) -> Result<Vec<Reference>, ScanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut refs = Vec::new();
    let mut depth = 0usize;
    // The depths at which group layers are open.
    let mut groups: Vec<usize> = Vec::new();
    loop {
        let pos = reader.buffer_position();
        let (e, opens) = match reader.read_event() {
            Ok(Event::Start(e)) => (e, true),
            Ok(Event::Empty(e)) => (e, false),
            Ok(Event::End(_)) => {
                if groups.last() == Some(&depth) {
                    groups.pop();
                }
                depth = depth.saturating_sub(1);
                continue;
            }
            Ok(Event::Eof) | Err(_) => return Ok(refs),
            Ok(_) => continue,
        };
        let line = || line_of(text, pos);
        let tag = e.name();
        if opens {
            depth += 1;
            if depth > limits::MAX_XML_DEPTH {
                return Err(ScanError {
                    column: None,
                    line: line(),
                    message: format!(
                        "<{}> is nested {depth} elements deep; expected at most {}",
                        String::from_utf8_lossy(tag.as_ref()),
                        limits::MAX_XML_DEPTH
                    ),
                });
            }
            if tag.as_ref() == b"group" {
                groups.push(depth);
                if groups.len() > limits::MAX_GROUP_DEPTH {
                    let group = attr(&e, "name").unwrap_or_default();
                    return Err(ScanError {
                        column: None,
                        line: line(),
                        message: format!(
                            "group layer {group:?} is nested {} groups deep; expected group layers nested at most {} deep",
                            groups.len(),
                            limits::MAX_GROUP_DEPTH
                        ),
                    });
                }
            }
        }
        let reference = match tag.as_ref() {
            b"object" => attr(&e, "template").map(|t| ("object template", "template", t)),
            b"tileset" => attr(&e, "source").map(|s| ("tileset", "source", s)),
            _ => None,
        };
        if let Some((what, key, target)) = reference {
            let (line, column) = line_col(text, attr_offset(text, pos, &e, key));
            refs.push(Reference {
                line,
                column,
                what,
                target,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(dir: &Path, map: &str) -> Result<(), RefError> {
        let load = |p: &Path| std::fs::read_to_string(p).ok();
        check_references(&dir.join("m.tmx"), map, &load)
    }

    const TX: &str = "<?xml version=\"1.0\"?>\n<template>\n <object template=\"{T}\" width=\"16\" height=\"16\"/>\n</template>\n";

    #[test]
    fn templates_that_refer_back_are_found_with_the_file_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let map =
            "<map>\n<objectgroup>\n<object id=\"1\" template=\"a.tx\"/>\n</objectgroup>\n</map>\n";
        // Itself.
        std::fs::write(d.join("a.tx"), TX.replace("{T}", "a.tx")).unwrap();
        let e = check(d, map).unwrap_err();
        // ` <object ` is 9 bytes before `template`.
        assert!(e.file.ends_with("a.tx:3:10"), "{e:?}");
        assert!(e.message.contains("a.tx -> a.tx"), "{e:?}");
        // Through another template, spelled differently.
        std::fs::write(d.join("a.tx"), TX.replace("{T}", "b.tx")).unwrap();
        std::fs::write(d.join("b.tx"), TX.replace("{T}", "./a.tx")).unwrap();
        let e = check(d, map).unwrap_err();
        assert!(e.file.ends_with("b.tx:3:10"), "{e:?}");
        assert!(e.message.contains("a.tx -> b.tx -> a.tx"), "{e:?}");
        // A template used twice that refers to nothing: no cycle.
        std::fs::write(d.join("b.tx"), TX.replace(" template=\"{T}\"", "")).unwrap();
        let twice = map.replace(
            "</objectgroup>",
            "<object id=\"2\" template=\"b.tx\"/>\n</objectgroup>",
        );
        assert!(check(d, &twice).is_ok());
    }

    #[test]
    fn deep_groups_and_elements_are_refused_at_their_line() {
        let dir = tempfile::tempdir().unwrap();
        let deep = |n: usize, tag: &str| {
            format!(
                "<map>\n{}{}</map>\n",
                format!("<{tag}>\n").repeat(n),
                format!("</{tag}>\n").repeat(n)
            )
        };
        assert!(check(dir.path(), &deep(limits::MAX_GROUP_DEPTH, "group")).is_ok());
        let e = check(dir.path(), &deep(limits::MAX_GROUP_DEPTH + 1, "group")).unwrap_err();
        assert!(
            e.file
                .ends_with(&format!("m.tmx:{}", limits::MAX_GROUP_DEPTH + 2)),
            "{e:?}"
        );
        assert!(e.message.contains("nested at most 64 deep"), "{e:?}");
        let e = check(dir.path(), &deep(limits::MAX_XML_DEPTH, "properties")).unwrap_err();
        assert!(e.message.contains("expected at most"), "{e:?}");
    }
}

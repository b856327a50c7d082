//! Game profiles: what one kind of game needs of its character controller, as data. A profile
//! weighs behaviours (the registry's [`Behaviour`]s) and lists what the pick must have run or
//! declare; the verdict ([`super::verdict`]) picks, per profile, the configuration with the
//! lowest weighted error. The built-in profiles are the files of `compare/profiles`; a user
//! passes their own with `platbench run --profile FILE`.

use serde::Deserialize;

use crate::backend::{Capabilities, Precision};
use crate::level::Features;
use crate::metrics::registry::Behaviour;

/// Longest profile name the verdict prints, in characters (it heads a line of 120 columns).
const MAX_NAME: usize = 32;
/// Longest profile title, in characters (one line of 120 columns with its indent).
const MAX_TITLE: usize = 100;

/// Something a profile needs of its pick: a level feature the pick must have run on every
/// scenario that has it, or a capability it must declare.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// Ran every scenario of levels with this feature (slopes, one-way, ladders, moving
    /// platforms): measured.
    Feature(Behaviour),
    /// Declares pushing dynamic bodies ([`Capabilities::pushes_bodies`]).
    PushesBodies,
    /// Declares positions on a grid ([`Capabilities::integer_positions`]).
    IntegerPositions,
    /// Keeps world positions in f64 ([`Precision::F64`]).
    F64Positions,
    /// Declares determinism across machines ([`Capabilities::cross_platform_determinism`]).
    CrossPlatformDeterminism,
}

impl Need {
    /// Every need, with its name in a profile file.
    pub const ALL: [(&'static str, Need); 8] = [
        ("slopes", Need::Feature(Behaviour::Slopes)),
        ("one_way", Need::Feature(Behaviour::OneWay)),
        ("ladders", Need::Feature(Behaviour::Ladders)),
        ("moving_platforms", Need::Feature(Behaviour::Platforms)),
        ("pushes_bodies", Need::PushesBodies),
        ("integer_positions", Need::IntegerPositions),
        ("f64_positions", Need::F64Positions),
        ("cross_platform_determinism", Need::CrossPlatformDeterminism),
    ];

    /// Its name in a profile file.
    pub fn name(self) -> &'static str {
        Need::ALL
            .iter()
            .find(|(_, n)| *n == self)
            .map_or("?", |(s, _)| s)
    }

    /// Whether a configuration with these declarations declares this need (a feature: whether
    /// it models it; whether it ran it is the verdict's to check).
    pub fn declared_by(self, features: Features, precision: Precision, caps: Capabilities) -> bool {
        match self {
            Need::Feature(Behaviour::Slopes) => features.slopes,
            Need::Feature(Behaviour::OneWay) => features.one_way,
            Need::Feature(Behaviour::Ladders) => features.ladders,
            Need::Feature(Behaviour::Platforms) => features.moving_platforms,
            Need::Feature(_) => true,
            Need::PushesBodies => caps.pushes_bodies,
            Need::IntegerPositions => caps.integer_positions,
            Need::F64Positions => precision == Precision::F64,
            Need::CrossPlatformDeterminism => caps.cross_platform_determinism,
        }
    }
}

/// One game profile.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Short name (`pixel-precise`).
    pub name: String,
    /// The kind of game, one line.
    pub title: String,
    /// Behaviour weights, each above 0, in [`Behaviour::ALL`] order.
    pub weights: Vec<(Behaviour, f64)>,
    /// What the pick must have run or declare.
    pub needs: Vec<Need>,
}

impl Profile {
    /// The weight of `b` (0 when the profile does not count it).
    pub fn weight(&self, b: Behaviour) -> f64 {
        self.weights
            .iter()
            .find(|(x, _)| *x == b)
            .map_or(0.0, |(_, w)| *w)
    }

    /// The weights as the verdict prints them: `landing 3, seams 3, walls 2`.
    pub fn describe_weights(&self) -> String {
        let mut w = self.weights.clone();
        // Heaviest first; ties in behaviour order (the sort is stable).
        w.sort_by(|a, b| b.1.total_cmp(&a.1));
        w.iter()
            .map(|(b, x)| format!("{} {x}", b.key()))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// A profile file that could not be read: where, and what was found against what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}:{column}: {message}")]
pub struct ProfileError {
    /// The file (or `builtin:NAME`).
    pub file: String,
    /// 1-based line (1 when the whole file is at fault).
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What was found and what was expected.
    pub message: String,
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: toml::Spanned<String>,
    title: toml::Spanned<String>,
    #[serde(default)]
    needs: Vec<toml::Spanned<String>>,
    weights: toml::Spanned<
        std::collections::BTreeMap<toml::Spanned<String>, toml::Spanned<toml::Value>>,
    >,
}

/// Whether `c` may appear in a name or title: printable, and not a format character that
/// reorders or hides text (bidirectional controls, zero-width characters, the BOM).
fn printable(c: char) -> bool {
    !c.is_control()
        && !matches!(
            c,
            '\u{200B}'..='\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2060}'..='\u{206F}' | '\u{FEFF}'
        )
}

/// At most 40 characters of `s`, for an error message that echoes it.
fn excerpt(s: &str) -> String {
    if s.chars().count() <= 40 {
        s.to_string()
    } else {
        format!("{}...", s.chars().take(40).collect::<String>())
    }
}

/// Parses a profile file's `text`; `file` names it in errors.
pub fn parse_profile(text: &str, file: &str) -> Result<Profile, ProfileError> {
    let at = |offset: usize, message: String| {
        let (line, column) = crate::input::line_column(text, offset);
        ProfileError {
            file: file.to_string(),
            line,
            column,
            message,
        }
    };
    let f: File = toml::from_str(text).map_err(|e| {
        let (offset, message) = crate::level::explain_toml_error(text, &e);
        at(offset, message)
    })?;
    let name = f.name.get_ref().trim();
    if name.is_empty() || name.chars().count() > MAX_NAME || name.chars().any(|c| c.is_control()) {
        return Err(at(
            f.name.span().start,
            format!("name {name:?}: expected 1 to {MAX_NAME} printable characters"),
        ));
    }
    let title = f.title.get_ref().trim();
    if title.is_empty() || title.chars().count() > MAX_TITLE || !title.chars().all(printable) {
        return Err(at(
            f.title.span().start,
            format!("title: expected 1 to {MAX_TITLE} printable characters on one line"),
        ));
    }
    let mut needs = Vec::new();
    for n in &f.needs {
        let need = Need::ALL
            .iter()
            .find(|(s, _)| s == n.get_ref())
            .map(|(_, x)| *x)
            .ok_or_else(|| {
                at(
                    n.span().start,
                    format!(
                        "need {:?}: expected one of {}",
                        excerpt(n.get_ref()),
                        Need::ALL.map(|(s, _)| s).join(", ")
                    ),
                )
            })?;
        if !needs.contains(&need) {
            needs.push(need);
        }
    }
    let mut weights = Vec::new();
    let table_at = f.weights.span().start;
    for (key, value) in f.weights.get_ref() {
        let (key_at, value_at) = (key.span().start, value.span().start);
        let key = key.get_ref();
        let b = Behaviour::ALL
            .into_iter()
            .find(|b| b.key() == key)
            .ok_or_else(|| {
                at(
                    key_at,
                    format!(
                        "[weights] key {:?}: expected a behaviour, one of {}",
                        excerpt(key),
                        Behaviour::ALL.map(|b| b.key()).join(", ")
                    ),
                )
            })?;
        let w = match value.get_ref() {
            toml::Value::Integer(i) => *i as f64,
            toml::Value::Float(x) => *x,
            other => {
                return Err(at(
                    value_at,
                    format!(
                        "[weights] {key}: expected a number from 0 to 1000, found a {}",
                        other.type_str()
                    ),
                ))
            }
        };
        // A weight far above the others would make every other behaviour irrelevant; 1000 is
        // far beyond any ratio a profile needs and keeps sums finite.
        if !(w.is_finite() && (0.0..=1000.0).contains(&w)) {
            return Err(at(
                value_at,
                format!(
                    "[weights] {key} = {}: expected a number from 0 to 1000",
                    excerpt(&w.to_string())
                ),
            ));
        }
        if w > 0.0 {
            weights.push((b, w));
        }
    }
    if weights.is_empty() {
        return Err(at(
            table_at,
            "[weights]: expected at least one behaviour with a weight above 0".into(),
        ));
    }
    weights.sort_by_key(|(b, _)| Behaviour::ALL.iter().position(|x| x == b));
    Ok(Profile {
        name: name.to_string(),
        title: title.to_string(),
        weights,
        needs,
    })
}

/// `(file name, TOML text)` of every built-in game profile, in verdict order.
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "pixel_precise.toml",
        include_str!("../../compare/profiles/pixel_precise.toml"),
    ),
    (
        "slopes.toml",
        include_str!("../../compare/profiles/slopes.toml"),
    ),
    (
        "moving_platforms.toml",
        include_str!("../../compare/profiles/moving_platforms.toml"),
    ),
    (
        "huge_worlds.toml",
        include_str!("../../compare/profiles/huge_worlds.toml"),
    ),
    (
        "crowds.toml",
        include_str!("../../compare/profiles/crowds.toml"),
    ),
];

/// The built-in profiles (`compare/profiles`), in verdict order.
pub fn builtin_profiles() -> Vec<Profile> {
    BUILTIN
        .iter()
        .map(|(file, text)| {
            // The built-in files are checked by this module's tests; a broken one is a bug.
            parse_profile(text, &format!("builtin:{file}")).expect("a built-in profile parses")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builtin_profiles_parse_and_have_distinct_names() {
        let p = builtin_profiles();
        assert_eq!(p.len(), BUILTIN.len());
        for (i, a) in p.iter().enumerate() {
            assert!(p[i + 1..].iter().all(|b| b.name != a.name), "{}", a.name);
        }
        let pixel = &p[0];
        assert_eq!(pixel.weight(Behaviour::Seams), 3.0);
        assert_eq!(pixel.weight(Behaviour::Slopes), 0.0);
    }

    #[test]
    fn a_bad_profile_is_located() {
        let e = parse_profile(
            "name = \"x\"\ntitle = \"t\"\nneeds = [\"wings\"]\n[weights]\nseams = 1\n",
            "p.toml",
        )
        .unwrap_err();
        assert_eq!((e.line, e.column), (3, 10), "{e}");
        assert!(e.message.contains("one_way"), "{e}");
        let e = parse_profile(
            "name = \"x\"\ntitle = \"t\"\n[weights]\nfly = 1\n",
            "p.toml",
        )
        .unwrap_err();
        // Located at the key, not at the table.
        assert!(e.to_string().starts_with("p.toml:4:1:"), "{e}");
        assert!(e.message.contains("seams"), "{e}");
        let e = parse_profile(
            "name = \"x\"\ntitle = \"t\"\n[weights]\nseams = -1\n",
            "p.toml",
        )
        .unwrap_err();
        assert!(e.message.contains("from 0 to 1000"), "{e}");
        let e = parse_profile(
            "name = \"x\"\ntitle = \"t\"\n[weights]\nseams = 0\n",
            "p.toml",
        )
        .unwrap_err();
        assert!(e.message.contains("at least one"), "{e}");
        let e = parse_profile(
            "name = \"x\"\ntitle = \"t\"\ncolour = 1\n[weights]\nseams = 1\n",
            "p.toml",
        )
        .unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        let e = parse_profile(
            "name = \"\"\ntitle = \"t\"\n[weights]\nseams = 1\n",
            "p.toml",
        )
        .unwrap_err();
        assert_eq!((e.line, e.column), (1, 8), "{e}");
    }
}

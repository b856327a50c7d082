//! What the map importers ([`super::tiled`], [`super::ldtk`]) share: the overrides a user
//! gives on the command line ([`ImportOptions`]), the warnings and the per-layer report an
//! import returns, the tile kinds a user writes, and the ASCII picture of an imported level
//! (`platbench inspect`). Built with an importer: `names` (the naming conventions games use for
//! collision, decoration and spawn layers and objects) and `spawns` (the spawn rules every
//! import ends with: `--spawn`, the fallback spawn, a level's name made of the map's).

use std::fmt;

use glam::Vec2;

#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) use edges::wall_sides;
pub use edges::Edges;

use super::probes::SpawnPoint;
use super::{Level, Slope, Tile};

// Edges itself is an option of every build; the walls are the importers'.
#[cfg_attr(not(any(feature = "tiled", feature = "ldtk")), allow(dead_code))]
mod edges;
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) mod names;
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) mod spawns;

/// Something in a map that platbench does not use, or a rule it applied, said aloud rather than
/// dropped in silence.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportWarning {
    /// The map (or tileset) file.
    pub file: String,
    /// What it is about: `tileset "NAME" tile ID`, `object ID "NAME"`, `layer "NAME"` or `map`.
    pub subject: String,
    /// What was found and what platbench does with it.
    pub message: String,
}

impl fmt::Display for ImportWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}: {}", self.file, self.subject, self.message)
    }
}

/// An import that failed, with the warnings gathered before it failed (a user sees what was
/// read so far, not only the error).
#[derive(Debug)]
pub struct ImportFailure<E> {
    /// Why the import stopped.
    pub error: E,
    /// The warnings raised before it stopped.
    pub warnings: Vec<ImportWarning>,
}

impl<E: fmt::Display> fmt::Display for ImportFailure<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.error.fmt(f)
    }
}

impl<E: std::error::Error + 'static> std::error::Error for ImportFailure<E> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// A map imported without its scenarios, whatever its format: the level, its spawn points,
/// where each came from, each layer's role and why, and the warnings raised on the way.
#[derive(Clone, Debug)]
pub struct MapImport {
    /// The level, with no scenarios yet.
    pub level: Level,
    /// The spawn points, in the order of the file (or the fallback spawn `auto`).
    pub spawns: Vec<SpawnPoint>,
    /// Where each spawn point came from, one per spawn.
    pub spawn_sources: Vec<String>,
    /// Each layer with the role it was given and why.
    pub layers: Vec<LayerReport>,
    /// Everything that was ignored or assumed.
    pub warnings: Vec<ImportWarning>,
}

/// What a layer is read as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerRole {
    /// Collision: tiles by their own meaning (properties, collision shape, default solid);
    /// objects by their class (spawns, platforms), and rectangles as solids in an object layer.
    Collision,
    /// Every tile or rectangle of the layer is solid.
    Solid,
    /// Every tile or rectangle of the layer is a one-way platform.
    OneWay,
    /// Every tile or rectangle of the layer is a ladder.
    Ladder,
    /// Objects only: spawns and moving platforms by their class or name; other shapes are not
    /// collision. The default of an object layer no name marks.
    Objects,
    /// Left out: drawn, but not collision.
    Decoration,
}

impl LayerRole {
    /// The role a user writes (`--layer NAME=ROLE`, a layer property `collision`), if `s` is
    /// one: `collision`, `solid`, `one_way` (or `oneway`), `ladder`, `objects`, `decoration`
    /// (or `none`); any case.
    pub fn parse(s: &str) -> Option<LayerRole> {
        Some(match normalize(s).as_str() {
            "collision" | "tiles" => LayerRole::Collision,
            "solid" => LayerRole::Solid,
            "oneway" => LayerRole::OneWay,
            "ladder" => LayerRole::Ladder,
            "objects" => LayerRole::Objects,
            "decoration" | "none" | "ignore" => LayerRole::Decoration,
            _ => return None,
        })
    }

    /// The name a user writes for this role.
    pub fn name(&self) -> &'static str {
        match self {
            LayerRole::Collision => "collision",
            LayerRole::Solid => "solid",
            LayerRole::OneWay => "one_way",
            LayerRole::Ladder => "ladder",
            LayerRole::Objects => "objects",
            LayerRole::Decoration => "decoration",
        }
    }

    /// Whether the layer's tiles or shapes collide (collision, solid, one-way, ladder).
    pub fn collides(&self) -> bool {
        matches!(
            self,
            LayerRole::Collision | LayerRole::Solid | LayerRole::OneWay | LayerRole::Ladder
        )
    }

    /// The tile every drawn cell of the layer becomes, for the roles that force one.
    pub fn forced_tile(&self) -> Option<Tile> {
        match self {
            LayerRole::Solid => Some(Tile::Solid),
            LayerRole::OneWay => Some(Tile::OneWay),
            LayerRole::Ladder => Some(Tile::Ladder),
            _ => None,
        }
    }
}

/// The role given to one layer of a map and why, for `platbench inspect`.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerReport {
    /// The layer's name (a group's children as `group/child`).
    pub name: String,
    /// What kind of layer it is in the editor: `tiles`, `objects`, `group`, `image`, `intgrid`,
    /// `entities`.
    pub kind: String,
    /// What it was read as.
    pub role: LayerRole,
    /// Why: the rule, property or flag that decided.
    pub why: String,
    /// The layer holds no tile, cell or object, so its role changes nothing in the level
    /// (`inspect` says so beside its kind).
    pub empty: bool,
}

impl LayerReport {
    /// Whether the role is a guess: a naming convention or a default decided it, not the map's
    /// own property, the layer's kind or the user (a side file or the command line).
    pub fn is_guess(&self) -> bool {
        const CERTAIN: &[&str] = &[
            GIVEN,
            "its property",
            "an image layer",
            "entities:",
            "a Tiles layer",
            "a AutoLayer layer",
        ];
        !CERTAIN.iter().any(|c| self.why.starts_with(c))
    }

    /// The side-file entry that would make the role certain, for the `layers` table of the
    /// `[import]` table: `"NAME" = "ROLE"` (a group's child by its own name).
    pub fn side_file_entry(&self) -> String {
        let name = self.name.rsplit('/').next().unwrap_or(&self.name);
        format!("{name:?} = {:?}", self.role.name())
    }
}

/// How a role the user gave is said (its `why` starts with this).
const GIVEN: &str = "given:";

/// The `why` of a role the user gave a layer: in a side file's `[import] layers`, or `--layer`.
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) fn given(name: &str, role: LayerRole) -> String {
    format!(
        "{GIVEN} {name} = {} (the side file's [import] layers, or --layer)",
        role.name()
    )
}

/// Overrides of the import's defaults, from the command line. Each default is documented in the
/// "Tiled maps" and "LDtk maps" sections of docs/formats.md; the map's own properties override the
/// defaults, and these override both.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImportOptions {
    /// Roles of layers by name (any case): `--layer NAME=ROLE`.
    pub layer_roles: Vec<(String, LayerRole)>,
    /// What tile layers that no name, property or flag marks are read as (`--tile-layers`):
    /// by default collision, unless an object layer holds collision rectangles or a tile layer
    /// is named for collision, when they are decoration.
    pub tile_layers: Option<LayerRole>,
    /// Spawn points to use instead of the map's (`--spawn X,Y`, in tiles, y up).
    pub spawns: Vec<Vec2>,
    /// LDtk: the tile an IntGrid value becomes, by its number or its name (`--intgrid V=KIND`).
    pub intgrid: Vec<(String, Tile)>,
    /// LDtk: the one level of a world to import (`--level NAME`); the whole world otherwise
    /// (GridVania and Free layouts) or the first level (linear layouts).
    pub level: Option<String>,
    /// The map's left and right sides (`--edges`): walls outside the sides the map leaves open,
    /// or open (`None`: the format's default, walls for Tiled maps and open for LDtk projects,
    /// as the games of each format measured in docs/maps.md mostly do).
    pub edges: Option<Edges>,
    /// Tiled: tile properties that make a tile a kind whatever else it says (a side file's
    /// `tile_properties`): a tile with the property (any value but `false`) is that kind.
    pub tile_properties: Vec<(String, Tile)>,
}

impl ImportOptions {
    /// The role the command line gives the layer named `name`, if any.
    pub fn role_of(&self, name: &str) -> Option<LayerRole> {
        let n = normalize(name);
        self.layer_roles
            .iter()
            .rev()
            .find(|(k, _)| normalize(k) == n)
            .map(|(_, r)| *r)
    }
}

/// A warning for each layer the options give a role (`--layer`, a side file's `[import]`
/// layers) that the map does not have: a misspelt name would otherwise change nothing,
/// silently. A name matches a layer's whole name or its last part (`group/child`, a world's
/// `Level_0/Collisions`), in any case.
#[cfg(any(feature = "tiled", feature = "ldtk"))]
pub(crate) fn unmatched_layer_roles(
    opts: &ImportOptions,
    reports: &[LayerReport],
    file: &str,
) -> Vec<ImportWarning> {
    let last = |n: &str| normalize(n.rsplit('/').next().unwrap_or(n));
    let mut seen: Vec<String> = Vec::new();
    let mut out = Vec::new();
    for (k, _) in &opts.layer_roles {
        let n = normalize(k);
        if seen.contains(&n) {
            continue;
        }
        seen.push(n.clone());
        if reports
            .iter()
            .any(|r| normalize(&r.name) == n || last(&r.name) == n)
        {
            continue;
        }
        let mut names: Vec<&str> = reports.iter().map(|r| r.name.as_str()).collect();
        names.dedup();
        out.push(ImportWarning {
            file: file.into(),
            subject: format!("layer {k:?}"),
            message: format!(
                "given a role (--layer or the side file's [import] layers), but the map has no layer of that name; ignored (its layers: {})",
                names.join(", ")
            ),
        });
    }
    out
}

/// A tile kind as a user writes it (`solid`, `one_way`, `ladder`, `empty`, and the one-way and ladder
/// words games use: `jumpthrough`, `semisolid`, `climbable`, ...), any case.
pub(crate) fn parse_tile_kind(s: &str) -> Option<Tile> {
    Some(match normalize(s).as_str() {
        "solid" | "wall" => Tile::Solid,
        "oneway" | "platform" | "jumpthrough" | "jumpthru" | "semisolid" | "passthrough"
        | "unisolid" => Tile::OneWay,
        "ladder" | "climb" | "climbable" => Tile::Ladder,
        "empty" | "none" => Tile::Empty,
        _ => return None,
    })
}

/// Lower case with everything but letters and digits dropped: `Player-Spawn` → `playerspawn`.
pub(crate) fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect()
}

/// The level's tiles in the level format's characters, top row first (`#` solid, `.` empty, `=`
/// one-way, `H` ladder, `/` and `\` 45-degree slopes, letters for other slopes), and the legend
/// of the letters.
pub fn ascii_map(level: &Level) -> (String, Vec<(char, Slope)>) {
    let mut legend: Vec<(char, Slope)> = Vec::new();
    let letters: Vec<char> = ('a'..='z').chain('A'..='G').chain('I'..='Z').collect();
    let mut text = String::with_capacity(((level.width + 1) * level.height) as usize);
    for j in (0..level.height as i64).rev() {
        for i in 0..level.width as i64 {
            let c = match level.tile(i, j) {
                Tile::Empty => '.',
                Tile::Solid => '#',
                Tile::OneWay => '=',
                Tile::Ladder => 'H',
                Tile::Slope(s) => match s {
                    Slope::Line { left, right } if left == 0.0 && right == 1.0 => '/',
                    Slope::Line { left, right } if left == 1.0 && right == 0.0 => '\\',
                    s => match legend.iter().find(|(_, l)| *l == s) {
                        Some((c, _)) => *c,
                        None => match letters.get(legend.len()) {
                            Some(&c) => {
                                legend.push((c, s));
                                c
                            }
                            None => '?',
                        },
                    },
                },
            };
            text.push(c);
        }
        text.push('\n');
    }
    (text, legend)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_kinds_read_the_words_games_use() {
        for (word, tile) in [
            ("Solid", Tile::Solid),
            ("one_way", Tile::OneWay),
            ("jumpthrough", Tile::OneWay),
            ("semi-solid", Tile::OneWay),
            ("Climbable", Tile::Ladder),
            ("none", Tile::Empty),
        ] {
            assert_eq!(parse_tile_kind(word), Some(tile), "{word}");
        }
        assert_eq!(parse_tile_kind("grass"), None);
    }
}

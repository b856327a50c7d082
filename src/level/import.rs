//! What the map importers ([`super::tiled`], [`super::ldtk`]) share: the naming conventions
//! games use for collision, decoration and spawn layers and objects, the overrides a user gives
//! on the command line ([`ImportOptions`]), the warnings and the per-layer report an import
//! returns, the fallback spawn, and the ASCII picture of an imported level (`platbench inspect`).

use std::fmt;

use glam::Vec2;

use super::probes::SpawnPoint;
use super::{character_box, Level, Slope, Tile, DEFAULT_CHARACTER_SIZE};

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
}

/// Overrides of the import's defaults, from the command line. Each default is documented in the
/// README's "Tiled maps" and "LDtk maps" sections; the map's own properties override the
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

/// A tile kind as a user writes it (`solid`, `one_way`, `ladder`, `empty`), any case.
pub fn parse_tile_kind(s: &str) -> Option<Tile> {
    Some(match normalize(s).as_str() {
        "solid" | "wall" => Tile::Solid,
        "oneway" | "platform" => Tile::OneWay,
        "ladder" => Tile::Ladder,
        "empty" | "none" => Tile::Empty,
        _ => return None,
    })
}

/// Lower case with everything but letters and digits dropped: `Player-Spawn` → `playerspawn`.
pub fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect()
}

/// The words of a name, lower case: split at anything but letters and digits, at lower-to-upper
/// case changes and around digits (`Platform-Colliders` → `platform`, `colliders`;
/// `bgLayer2` → `bg`, `layer`, `2`).
pub fn words(s: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut cur = String::new();
    let mut prev: Option<char> = None;
    for c in s.chars() {
        let split = match prev {
            _ if !c.is_alphanumeric() => true,
            Some(p) => {
                (p.is_lowercase() && c.is_uppercase()) || (p.is_ascii_digit() != c.is_ascii_digit())
            }
            None => false,
        };
        if split && !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
        if c.is_alphanumeric() {
            cur.extend(c.to_lowercase());
        }
        prev = Some(c);
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// Words that make a layer (or an LDtk IntGrid value) one-way platforms.
pub const ONE_WAY_WORDS: &[&str] = &[
    "oneway",
    "jumpthrough",
    "jumpthru",
    "semisolid",
    "passthrough",
    "dropthrough",
    "thru",
];
/// Words that make a layer (or IntGrid value) ladders.
pub const LADDER_WORDS: &[&str] = &["ladder", "ladders", "climb", "climbable", "vine", "vines"];
/// Words that make a layer collision.
pub const COLLISION_WORDS: &[&str] = &[
    "collision",
    "collisions",
    "collide",
    "collides",
    "collider",
    "colliders",
    "solid",
    "solids",
    "wall",
    "walls",
    "ground",
    "grounds",
    "platform",
    "platforms",
    "floor",
    "floors",
    "terrain",
    "world",
    "blocks",
    "block",
    "obstacles",
    "physics",
    "hitbox",
    "hitboxes",
];
/// Words that make a layer decoration.
pub const DECORATION_WORDS: &[&str] = &[
    "background",
    "backgrounds",
    "bg",
    "backdrop",
    "foreground",
    "fg",
    "decor",
    "decoration",
    "decorations",
    "deco",
    "detail",
    "details",
    "scenery",
    "props",
    "sky",
    "clouds",
    "parallax",
    "coin",
    "coins",
    "items",
    "item",
    "collectible",
    "collectibles",
    "pickups",
    "gems",
    "water",
    "lava",
    "spikes",
    "spike",
    "hazard",
    "hazards",
    "acid",
    "enemies",
    "enemy",
    "text",
    "shadows",
    "lights",
];
/// Words of an LDtk IntGrid value (or a tile layer) that is a hazard, not a wall.
pub const HAZARD_WORDS: &[&str] = &[
    "water", "spike", "spikes", "acid", "lava", "hazard", "hazards", "death", "kill", "damage",
    "poison",
];

/// Whether a name's words (or the whole name run together) contain one of `list`.
pub fn says(name: &str, list: &[&str]) -> bool {
    let n = normalize(name);
    list.contains(&n.as_str())
        || words(name).iter().any(|w| list.contains(&w.as_str()))
        || (list == ONE_WAY_WORDS && (n.contains("oneway") || n.contains("jumpthrough")))
}

/// The role a layer's name gives it, and the word that decided, if any.
pub fn role_from_name(name: &str) -> Option<(LayerRole, String)> {
    let ws = words(name);
    let n = normalize(name);
    let hit = |list: &[&str]| -> Option<String> {
        if list.contains(&n.as_str()) {
            return Some(n.clone());
        }
        ws.iter().find(|w| list.contains(&w.as_str())).cloned()
    };
    if says(name, ONE_WAY_WORDS) {
        return Some((LayerRole::OneWay, hit(ONE_WAY_WORDS).unwrap_or(n)));
    }
    if let Some(w) = hit(LADDER_WORDS) {
        return Some((LayerRole::Ladder, w));
    }
    if let Some(w) = hit(COLLISION_WORDS) {
        return Some((LayerRole::Collision, w));
    }
    if let Some(w) = hit(DECORATION_WORDS) {
        return Some((LayerRole::Decoration, w));
    }
    None
}

/// Names (run together, lower case) that mark a spawn: an object's class, type or name, an LDtk
/// entity's identifier, or an object layer whose objects are spawns.
pub const SPAWN_NAMES: &[&str] = &[
    "spawn",
    "spawnpoint",
    "spawnpos",
    "spawnposition",
    "playerspawn",
    "playerspawnpoint",
    "spawnplayer",
    "player",
    "player1",
    "hero",
    "start",
    "startpoint",
    "startpos",
    "startposition",
    "startingpoint",
    "startingpos",
    "startingposition",
    "playerstart",
    "playerstartposition",
    "playerstartingposition",
    "playerposition",
    "playerpos",
    "levelstart",
];

/// Whether `name` marks a spawn (see [`SPAWN_NAMES`]).
pub fn is_spawn_name(name: &str) -> bool {
    SPAWN_NAMES.contains(&normalize(name).as_str())
}

/// A place to start when a map marks none: the lowest cell of the leftmost column where the
/// default character stands on a solid or one-way tile with room above. `None` when no cell
/// qualifies.
pub fn fallback_spawn(level: &Level) -> Option<Vec2> {
    for i in 0..level.width as i64 {
        for j in 1..level.height as i64 {
            let below = level.tile(i, j - 1);
            if !matches!(below, Tile::Solid | Tile::OneWay) || level.tile(i, j) != Tile::Empty {
                continue;
            }
            let feet = Vec2::new(i as f32 + 0.5, j as f32);
            let b = character_box(feet, DEFAULT_CHARACTER_SIZE);
            if level.solids_overlapping(&b).next().is_none() {
                return Some(feet);
            }
        }
    }
    None
}

/// The fallback spawn as a spawn point named `auto` and the warning that says so and how to
/// mark a spawn (`how`, in the map format's terms). `None` (and the warning says so) when the
/// map has no standable cell.
pub fn fallback_spawn_point(
    level: &Level,
    file: &str,
    how: &str,
) -> (Option<SpawnPoint>, ImportWarning) {
    match fallback_spawn(level) {
        Some(p) => (
            Some(SpawnPoint {
                name: "auto".into(),
                position: p,
            }),
            ImportWarning {
                file: file.into(),
                subject: "map".into(),
                message: format!(
                    "no spawn point found, so the probes start at ({}, {}) tiles, the lowest standable cell of the leftmost column that has one; {how}, or pass --spawn X,Y",
                    p.x, p.y
                ),
            },
        ),
        None => (
            None,
            ImportWarning {
                file: file.into(),
                subject: "map".into(),
                message: format!("no spawn point found and no cell to stand on; {how}, or pass --spawn X,Y"),
            },
        ),
    }
}

/// The warning for a level with nothing to collide with, if it has nothing.
pub fn no_solids_warning(level: &Level, file: &str, how: &str) -> Option<ImportWarning> {
    let any = (0..level.height as i64)
        .flat_map(|j| (0..level.width as i64).map(move |i| (i, j)))
        .any(|(i, j)| level.tile(i, j) != Tile::Empty);
    (!any && level.platforms.is_empty()).then(|| ImportWarning {
        file: file.into(),
        subject: "map".into(),
        message: format!(
            "the level has no solids, one-way platforms, ladders or slopes: a character falls through it; {how} (`platbench inspect` shows what each layer was read as)"
        ),
    })
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
    fn names_split_into_words_and_roles() {
        assert_eq!(words("Platform-Colliders"), ["platform", "colliders"]);
        assert_eq!(words("bgLayer2"), ["bg", "layer", "2"]);
        assert_eq!(
            role_from_name("Platform-Colliders").map(|r| r.0),
            Some(LayerRole::Collision)
        );
        assert_eq!(
            role_from_name("one_way").map(|r| r.0),
            Some(LayerRole::OneWay)
        );
        assert_eq!(
            role_from_name("OneWayPlatforms").map(|r| r.0),
            Some(LayerRole::OneWay)
        );
        assert_eq!(
            role_from_name("Background 2").map(|r| r.0),
            Some(LayerRole::Decoration)
        );
        assert_eq!(
            role_from_name("Coins").map(|r| r.0),
            Some(LayerRole::Decoration)
        );
        assert_eq!(role_from_name("Tile Layer 1"), None);
        assert!(is_spawn_name("PlayerSpawn") && is_spawn_name("starting_position"));
        assert!(is_spawn_name("Start_Point") && !is_spawn_name("enemy_spawn"));
    }
}

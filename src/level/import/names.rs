//! The naming conventions games use, which an import reads a map by: the words that make a
//! layer (or an LDtk IntGrid value) collision, one-way, ladder, decoration or hazard, and the
//! names that mark a spawn.

use super::{normalize, LayerRole};

/// The words of a name, lower case: split at anything but letters and digits, at lower-to-upper
/// case changes and around digits (`Platform-Colliders` → `platform`, `colliders`;
/// `bgLayer2` → `bg`, `layer`, `2`).
pub(crate) fn words(s: &str) -> Vec<String> {
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
pub(crate) const ONE_WAY_WORDS: &[&str] = &[
    "oneway",
    "jumpthrough",
    "jumpthru",
    "semisolid",
    "passthrough",
    "dropthrough",
    "thru",
    "shelf",
    "shelves",
];
/// Words that make a layer (or IntGrid value) ladders.
pub(crate) const LADDER_WORDS: &[&str] =
    &["ladder", "ladders", "climb", "climbable", "vine", "vines"];
/// Words that make a layer collision.
pub(crate) const COLLISION_WORDS: &[&str] = &[
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
/// The collision words only a collision layer's name uses: unlike `ground` or `world`, which
/// name art as often, they say the layer is the collision source.
pub(crate) const STRONG_COLLISION_WORDS: &[&str] = &[
    "collision",
    "collisions",
    "collide",
    "collides",
    "collider",
    "colliders",
    "solid",
    "solids",
    "physics",
    "hitbox",
    "hitboxes",
];
/// Decoration words for art drawn where the player is (in front, or details of the scene): a
/// game that marks its tiles for collision may collide with such a layer, unlike a background,
/// water, coins or enemies.
pub(crate) const ART_WORDS: &[&str] = &[
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
];
/// Words that make a layer decoration.
pub(crate) const DECORATION_WORDS: &[&str] = &[
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
    // Enemy in Portuguese, Spanish, French and German, and the creatures games place as
    // entities rather than walls.
    "inimigo",
    "inimigos",
    "enemigo",
    "enemigos",
    "ennemi",
    "ennemis",
    "feind",
    "feinde",
    "monster",
    "monsters",
    "mobs",
    "npc",
    "npcs",
    "text",
    "shadows",
    "lights",
    // Triggers of a level's end or checkpoints: touched, not stood on.
    "flag",
    "flags",
    "goal",
    "goals",
    "exit",
    "exits",
    "finish",
    "checkpoint",
    "checkpoints",
];
/// Words of an LDtk IntGrid value (or a tile layer) that is a hazard, not a wall.
#[cfg(feature = "ldtk")]
pub(crate) const HAZARD_WORDS: &[&str] = &[
    "water", "spike", "spikes", "acid", "lava", "hazard", "hazards", "death", "kill", "damage",
    "poison",
];

/// Whether a name's words (or the whole name run together) contain one of `list`.
pub(crate) fn says(name: &str, list: &[&str]) -> bool {
    let n = normalize(name);
    list.contains(&n.as_str())
        || words(name)
            .iter()
            .any(|w| list.contains(&w.as_str()) || compound(w, list))
        || (list == ONE_WAY_WORDS && (n.contains("oneway") || n.contains("jumpthrough")))
}

/// Whether `w` begins with a strong collision word of `list` and runs on from it, written as
/// one word (`collisionblocks`, `solidtiles`): a name only collision layers use stays one when
/// the author joins another word to it.
fn compound(w: &str, list: &[&str]) -> bool {
    STRONG_COLLISION_WORDS
        .iter()
        .any(|k| list.contains(k) && w.len() > k.len() && w.starts_with(*k))
}

/// The role a layer's name gives it, and the word that decided, if any.
pub(crate) fn role_from_name(name: &str) -> Option<(LayerRole, String)> {
    let ws = words(name);
    let n = normalize(name);
    let hit = |list: &[&str]| -> Option<String> {
        if list.contains(&n.as_str()) {
            return Some(n.clone());
        }
        ws.iter()
            .find(|w| list.contains(&w.as_str()))
            .cloned()
            .or_else(|| ws.iter().find(|w| compound(w, list)).cloned())
    };
    if says(name, ONE_WAY_WORDS) {
        return Some((LayerRole::OneWay, hit(ONE_WAY_WORDS).unwrap_or(n)));
    }
    if let Some(w) = hit(LADDER_WORDS) {
        return Some((LayerRole::Ladder, w));
    }
    // A name with both a collision and a decoration word is what its last one says, the head
    // of an English compound (`WallDecor` is decor, `Decor-Colliders` colliders).
    let last = |list: &[&str]| {
        ws.iter()
            .rposition(|w| list.contains(&w.as_str()) || compound(w, list))
    };
    if let (Some(c), Some(d)) = (last(COLLISION_WORDS), last(DECORATION_WORDS)) {
        if d > c {
            return Some((LayerRole::Decoration, ws[d].clone()));
        }
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
pub(crate) const SPAWN_NAMES: &[&str] = &[
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

/// Names (run together, lower case) that mark a level's end, which a spawn layer may hold
/// beside the start: not spawns.
const END_NAMES: &[&str] = &[
    "exit",
    "end",
    "goal",
    "finish",
    "finishline",
    "levelend",
    "levelexit",
    "endpoint",
    "door",
];

/// Whether `name` marks a level's end (see [`END_NAMES`]).
pub(crate) fn is_end_name(name: &str) -> bool {
    END_NAMES.contains(&normalize(name).as_str())
}

/// A spawn name may carry one of these words after it (`player_spawn_zone`, `StartArea`).
const SPAWN_SUFFIXES: &[&str] = &["zone", "zones", "area", "layer", "marker", "location"];

/// Whether `name` marks a spawn (see [`SPAWN_NAMES`]), alone or followed by one of
/// [`SPAWN_SUFFIXES`].
pub(crate) fn is_spawn_name(name: &str) -> bool {
    let n = normalize(name);
    SPAWN_NAMES.contains(&n.as_str())
        || SPAWN_SUFFIXES.iter().any(|suf| {
            n.strip_suffix(suf).is_some_and(|rest| {
                (rest.contains("spawn") || rest.contains("start")) && SPAWN_NAMES.contains(&rest)
            })
        })
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
        assert_eq!(
            role_from_name("WallDecor").map(|r| r.0),
            Some(LayerRole::Decoration)
        );
        assert_eq!(
            role_from_name("decor_colliders").map(|r| r.0),
            Some(LayerRole::Collision)
        );
        assert!(is_spawn_name("PlayerSpawn") && is_spawn_name("starting_position"));
        assert!(is_spawn_name("Start_Point") && !is_spawn_name("enemy_spawn"));
        assert!(is_spawn_name("player_spawn_zone") && !is_spawn_name("enemy_spawn_zones"));
        assert!(!is_spawn_name("player_zone"));
        assert_eq!(
            role_from_name("collisionblocks"),
            Some((LayerRole::Collision, "collisionblocks".into()))
        );
        assert!(says("SolidTiles", STRONG_COLLISION_WORDS) && !says("Solid", &["wall"]));
        // Enemies in other languages are entities, not walls.
        for name in ["Inimigo", "enemigos", "Ennemis", "Feinde", "Monsters"] {
            assert_eq!(
                role_from_name(name).map(|r| r.0),
                Some(LayerRole::Decoration),
                "{name}"
            );
        }
    }
}

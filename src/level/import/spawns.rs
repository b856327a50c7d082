//! The rules every import ends with: the spawn points (the command line's, the map's, else
//! the fallback spawn), the warning for a level with nothing to collide with, and a level's
//! name made of the map's.

use glam::Vec2;

use super::{ImportOptions, ImportWarning};
use crate::level::{character_box, Level, SpawnPoint, Tile, DEFAULT_CHARACTER_SIZE};

/// How far a spawn's feet may sit inside the ground and still be read as standing on it, in
/// tiles: a spawn box or a sprite's anchor drawn a little into the floor (an LDtk entity box
/// overlapping the floor's top, a 35 px sprite on 70 px tiles).
pub(crate) const SINK_TOLERANCE: f32 = 0.25;

/// Feet inside the ground by at most [`SINK_TOLERANCE`], lifted onto the top of what they are
/// in when the default character fits there; `None` otherwise (the spawn is inside a solid).
pub(crate) fn lift_onto_ground(level: &Level, feet: Vec2) -> Option<Vec2> {
    let b = character_box(feet, DEFAULT_CHARACTER_SIZE);
    let top = level
        .solids_overlapping(&b)
        .map(|t| t.maxs.y)
        .fold(f32::NEG_INFINITY, f32::max);
    let lifted = Vec2::new(feet.x, top);
    (top - feet.y <= SINK_TOLERANCE
        && level
            .solids_overlapping(&character_box(lifted, DEFAULT_CHARACTER_SIZE))
            .next()
            .is_none())
    .then_some(lifted)
}

/// The note for a spawn inside a solid that cannot be lifted out: a map problem, its probes
/// not run.
pub(crate) fn inside_solid_note(feet: Vec2, tile: Vec2) -> String {
    format!(
        "map problem: the spawn at ({}, {}) puts the {} x {} character inside the solid tile at ({}, {}), deeper than {SINK_TOLERANCE} tile, so no probe starts there (whatever the controller); the other spawns, or the fallback spawn, run instead (--spawn X,Y or a side file's spawns place one)",
        feet.x, feet.y, DEFAULT_CHARACTER_SIZE.x, DEFAULT_CHARACTER_SIZE.y, tile.x, tile.y
    )
}

/// A place to start when a map marks none: the lowest cell of the leftmost column where the
/// default character stands on a solid or one-way tile with room above. `None` when no cell
/// qualifies.
pub(crate) fn fallback_spawn(level: &Level) -> Option<Vec2> {
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
pub(crate) fn fallback_spawn_point(
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
pub(crate) fn no_solids_warning(level: &Level, file: &str, how: &str) -> Option<ImportWarning> {
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

/// The spawn points an import ends with, in place: the command line's (`--spawn`, named
/// `spawn1`, `spawn2`, ...) instead of the map's; else the map's; else the fallback spawn,
/// whose warning (how to mark a spawn: `how`) is returned. One source per spawn in `sources`.
pub(crate) fn settle_spawns(
    level: &Level,
    file: &str,
    how: &str,
    opts: &ImportOptions,
    spawns: &mut Vec<SpawnPoint>,
    sources: &mut Vec<String>,
) -> Result<Option<ImportWarning>, String> {
    if !opts.spawns.is_empty() {
        spawns.clear();
        sources.clear();
        for (k, p) in opts.spawns.iter().enumerate() {
            let (w, h) = (level.width as f32, level.height as f32);
            if !(p.x >= 0.0 && p.x <= w && p.y >= 0.0 && p.y <= h) {
                return Err(format!(
                    "--spawn {},{}: the feet are outside the level (0 <= x <= {w}, 0 <= y <= {h} tiles, y up, the side walls included); expected a spawn inside it",
                    p.x, p.y
                ));
            }
            spawns.push(SpawnPoint {
                name: format!("spawn{}", k + 1),
                position: *p,
            });
            sources.push("--spawn on the command line".into());
        }
    } else if spawns.is_empty() {
        let (s, w) = fallback_spawn_point(level, file, how);
        if let Some(s) = s {
            spawns.push(s);
            sources.push(
                "fallback: the lowest standable cell of the leftmost column that has one".into(),
            );
        }
        return Ok(Some(w));
    }
    Ok(None)
}

/// `name` with every character a level's name may not hold (see [`crate::level::valid_name`])
/// replaced by `_`; empty when `name` is.
pub(crate) fn safe_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

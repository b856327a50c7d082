//! The map's sides as games have them: most platformers stop the player at the map's left and
//! right edges (Phaser's `setCollideWorldBounds`, a clamp to the map's width, a frame of
//! colliders), so an imported map gets a wall outside each side that its own tiles leave open.
//! The wall is one tile wide and as tall as the map; the bottom stays open, so a pit still
//! kills. `--edges open` (or a side file's `edges = "open"`) leaves the sides open.

use super::ImportWarning;
use crate::level::{Level, PlatformMotion, SpawnPoint, Tile};

/// What the map's sides are (`--edges`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Edges {
    /// A wall outside each side the map leaves open (the default for Tiled maps).
    #[default]
    Walls,
    /// The sides as the map draws them: a character may walk off into the void (the default
    /// for LDtk projects).
    Open,
}

impl Edges {
    /// The value as a user writes it, any case: `walls` or `open`.
    pub fn parse(s: &str) -> Option<Edges> {
        match s.trim().to_ascii_lowercase().as_str() {
            "walls" | "wall" | "closed" => Some(Edges::Walls),
            "open" => Some(Edges::Open),
            _ => None,
        }
    }
}

/// Whether column `i` is solid from the bottom row to the top.
fn walled(level: &Level, i: i64) -> bool {
    (0..level.height as i64).all(|j| level.tile(i, j) == Tile::Solid)
}

/// Adds the side walls `edges` asks for where the map's own edge column does not already block
/// the whole height, moving the map's cells, platforms and `spawns` right when a wall goes on
/// the left. `continues` names the sides `[left, right]` where the game goes on into another
/// level (an LDtk level with a neighbour there): those stay open. `drawn` names the sides where
/// the map draws collision just outside itself (a boundary a game keeps outside its map): those
/// get the wall whatever `edges` says, as the game has it. Returns the note that says what was
/// added, `None` when nothing was.
pub(crate) fn wall_sides(
    level: &mut Level,
    spawns: &mut [SpawnPoint],
    edges: Edges,
    continues: [bool; 2],
    drawn: [bool; 2],
    file: &str,
) -> Option<ImportWarning> {
    if level.width == 0 || level.height == 0 {
        return None;
    }
    let asked = |side: usize| edges == Edges::Walls || drawn[side];
    let left = asked(0) && !continues[0] && !walled(level, 0);
    let right = asked(1) && !continues[1] && !walled(level, level.width as i64 - 1);
    if !left && !right {
        return None;
    }
    let shift = u32::from(left);
    let width = level.width + shift + u32::from(right);
    let mut tiles = Vec::with_capacity(width as usize * level.height as usize);
    for j in 0..level.height as i64 {
        if left {
            tiles.push(Tile::Solid);
        }
        tiles.extend((0..level.width as i64).map(|i| level.tile(i, j)));
        if right {
            tiles.push(Tile::Solid);
        }
    }
    level.set_tiles(width, &tiles);
    drop(tiles);
    let dx = shift as f32;
    for p in &mut level.platforms {
        p.start.x += dx;
        if let PlatformMotion::Waypoints { points, .. } = &mut p.motion {
            for q in points {
                q.x += dx;
            }
        }
    }
    for s in spawns {
        s.position.x += dx;
    }
    let (sides, are) = match (left, right) {
        (true, true) => ("left and right sides", "are"),
        (true, false) => ("left side", "is"),
        _ => ("right side", "is"),
    };
    if edges == Edges::Open {
        return Some(ImportWarning {
            file: file.into(),
            subject: "map".into(),
            message: format!(
                "the map draws collision just outside its {}, which is dropped; a wall one tile wide and as tall as the map stands for it outside {}{} (--edges open leaves open only the sides the map leaves open)",
                sides,
                if left && right { "each" } else { "it" },
                if left {
                    "; the map's cells are one tile to the right in the level"
                } else {
                    ""
                }
            ),
        });
    }
    Some(ImportWarning {
        file: file.into(),
        subject: "map".into(),
        message: format!(
            "the map's {sides} {are} open, so a wall one tile wide and as tall as the map is added outside {}, as games stop the player at the map's sides (world bounds){}; the bottom stays open, so pits still kill; pass --edges open to leave the sides open",
            if left && right { "each" } else { "it" },
            if left {
                "; the map's cells are one tile to the right in the level"
            } else {
                ""
            }
        ),
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;

    fn level(rows_bottom_first: &[&str]) -> Level {
        let w = rows_bottom_first[0].len() as u32;
        let tiles = rows_bottom_first
            .iter()
            .flat_map(|r| {
                r.chars().map(|c| match c {
                    '#' => Tile::Solid,
                    _ => Tile::Empty,
                })
            })
            .collect();
        Level::from_tiles("t", w, rows_bottom_first.len() as u32, tiles)
    }

    #[test]
    fn open_sides_get_walls_and_the_map_moves_right() {
        let mut l = level(&["####", "...."]);
        let mut spawns = [SpawnPoint {
            name: "s".into(),
            position: Vec2::new(1.5, 1.0),
        }];
        let note = wall_sides(
            &mut l,
            &mut spawns,
            Edges::Walls,
            [false; 2],
            [false; 2],
            "m",
        )
        .unwrap();
        assert!(note.message.contains("left and right sides"), "{note}");
        assert_eq!((l.width, l.height), (6, 2));
        for j in 0..2 {
            assert_eq!(l.tile(0, j), Tile::Solid);
            assert_eq!(l.tile(5, j), Tile::Solid);
        }
        assert_eq!(l.tile(1, 1), Tile::Empty);
        assert_eq!(spawns[0].position, Vec2::new(2.5, 1.0));
    }

    #[test]
    fn a_side_the_map_walls_itself_or_open_edges_change_nothing() {
        let mut l = level(&["####", "#..#"]);
        assert!(wall_sides(&mut l, &mut [], Edges::Walls, [false; 2], [false; 2], "m").is_none());
        assert_eq!(l.width, 4);
        let mut l = level(&["####", "#..."]);
        let note = wall_sides(&mut l, &mut [], Edges::Walls, [false; 2], [false; 2], "m").unwrap();
        assert!(note.message.contains("right side is"), "{note}");
        assert_eq!((l.width, l.tile(1, 1)), (5, Tile::Empty));
        let mut l = level(&["####", "...."]);
        assert!(wall_sides(&mut l, &mut [], Edges::Open, [false; 2], [false; 2], "m").is_none());
        assert_eq!(l.width, 4);
    }
}

//! Probes a map makes impossible whatever the controller: a drop from a spawn with nothing under
//! it, or a walk that reaches a bottomless column (or an open side of the map) on flat ground
//! before anything could stop it. Such a probe measures the map, not a controller, so it is not
//! run and a note names the map's cause. The check is deliberately narrow: only where the
//! geometry decides the outcome (gravity over nothing, a flat floor with no step, slope, ledge
//! or platform before the drop), so a probe a controller could complete is never left out.

use glam::Vec2;

use crate::level::{Level, Tile};

/// Whether anything could catch a character over columns `i0..i1` below height `y` (tiles):
/// a non-empty tile in a row below, or a platform whose reach passes under.
fn catchable(level: &Level, i0: i64, i1: i64, y: f32) -> bool {
    let rows = (y.ceil() as i64).min(level.height as i64);
    let tiles = (i0..i1).any(|i| (0..rows).any(|j| level.tile(i, j) != Tile::Empty));
    tiles
        || level.platforms.iter().any(|p| {
            let (lo, hi) = p.reach();
            lo.x < i1 as f64 && hi.x > i0 as f64 && lo.y < y as f64
        })
}

/// The columns a character of width `w` with feet at `x` stands over.
fn columns(x: f32, w: f32) -> (i64, i64) {
    let half = w * 0.5;
    ((x - half).floor() as i64, (x + half).ceil() as i64)
}

/// Why a drop from `at` cannot land: nothing under the character down to the map's bottom.
pub(crate) fn drop_problem(level: &Level, at: Vec2, size: Vec2) -> Option<String> {
    let (i0, i1) = columns(at.x, size.x);
    (!catchable(level, i0, i1, at.y)).then(|| {
        format!(
            "nothing is under the spawn at x = {} (columns {i0} to {}) down to the map's bottom, so the character falls out of the map whatever the controller",
            at.x,
            i1 - 1
        )
    })
}

/// Why a walk from `at` (after settling) falls out of the map whatever the controller: on a
/// flat floor of solid or one-way tiles, within `reach` tiles, the next column has nothing
/// below it, or the walk passes an open side of the map. `None` when anything else happens
/// first (a wall, a step, a slope, a ledge onto lower ground, a platform) or the walk is
/// shorter.
pub(crate) fn walk_problem(
    level: &Level,
    at: Vec2,
    size: Vec2,
    left: bool,
    reach: f32,
) -> Option<String> {
    let (i0, i1) = columns(at.x, size.x);
    // Where the character settles: on the flat top of the highest tile under it.
    let floor = level.support_below(at.x - size.x * 0.5, at.x + size.x * 0.5, at.y, 1e-3)?;
    let row = floor as i64;
    let step: i64 = if left { -1 } else { 1 };
    let side = if left { "left" } else { "right" };
    let standable = |i: i64| matches!(level.tile(i, row - 1), Tile::Solid | Tile::OneWay);
    let clear = |i: i64| {
        (row..row + size.y.ceil() as i64)
            .all(|j| matches!(level.tile(i, j), Tile::Empty | Tile::OneWay))
    };
    let platform_near = |i: i64| {
        level.platforms.iter().any(|p| {
            let (lo, hi) = p.reach();
            lo.x < (i + 1) as f64 && hi.x > i as f64
        })
    };
    // The columns under the character must be flat floor to begin with.
    if !(i0..i1).all(standable) || (i0..i1).any(platform_near) {
        return None;
    }
    let mut i = if left { i0 - 1 } else { i1 };
    loop {
        let distance = if left {
            at.x - (i + 1) as f32
        } else {
            i as f32 - at.x
        };
        if distance > reach {
            return None;
        }
        if i < 0 || i >= level.width as i64 {
            return Some(format!(
                "the walk {side} reaches the map's open {side} side {distance} tiles from the spawn on flat ground, so the character walks off the map whatever the controller (--edges walls, the default, puts a wall there)"
            ));
        }
        if !clear(i) || platform_near(i) {
            return None;
        }
        if !standable(i) {
            if catchable(level, i, i + 1, floor) {
                return None;
            }
            return Some(format!(
                "the walk {side} reaches the level's column {i} (x = {i} to {}) {distance} tiles from the spawn on flat ground, and nothing is under that column down to the map's bottom, so the character falls out of the map whatever the controller",
                i + 1
            ));
        }
        i += step;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A level from rows given top first (`#` solid, `-` one-way, `.` empty).
    fn level(rows: &[&str]) -> Level {
        let w = rows[0].len() as u32;
        let tiles = rows
            .iter()
            .rev()
            .flat_map(|r| {
                r.chars().map(|c| match c {
                    '#' => Tile::Solid,
                    '-' => Tile::OneWay,
                    _ => Tile::Empty,
                })
            })
            .collect();
        Level::from_tiles("t", w, rows.len() as u32, tiles)
    }

    const SIZE: Vec2 = Vec2::new(0.8, 0.9);

    #[test]
    fn a_bottomless_pit_on_flat_ground_is_the_maps() {
        let l = level(&["........", "........", "###..###"]);
        let at = Vec2::new(1.5, 1.0);
        let right = walk_problem(&l, at, SIZE, false, 9.0).unwrap();
        assert!(right.contains("column 3"), "{right}");
        // Walking left the map's open side comes first.
        let left = walk_problem(&l, at, SIZE, true, 9.0).unwrap();
        assert!(left.contains("open left side"), "{left}");
        // Beyond the reach, nothing is certain.
        assert!(walk_problem(&l, at, SIZE, false, 1.0).is_none());
        assert!(drop_problem(&l, at, SIZE).is_none());
        assert!(drop_problem(&l, Vec2::new(3.5, 2.0), SIZE).is_some());
    }

    #[test]
    fn a_wall_a_step_or_lower_ground_leaves_the_outcome_to_the_controller() {
        let at = Vec2::new(1.5, 1.0);
        // A wall before the pit.
        let l = level(&["...#....", "...#....", "###...##"]);
        assert!(walk_problem(&l, at, SIZE, false, 9.0).is_none());
        // A pit with a floor below it: the character lands, what then is the controller's.
        let l = level(&["........", "###..###", "########"]);
        assert!(walk_problem(&l, Vec2::new(1.5, 2.0), SIZE, false, 9.0).is_none());
        // A one-tile step up.
        let l = level(&["........", "...#####", "########"]);
        assert!(walk_problem(&l, Vec2::new(1.5, 2.0), SIZE, false, 9.0).is_none());
    }
}

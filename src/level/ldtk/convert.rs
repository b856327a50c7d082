//! An LDtk project made into a level: the levels picked (one, a whole GridVania or Free
//! world, or a linear world's first), external levels read, the collision grid and the world's
//! bounds, each IntGrid layer's cells by its role and its values' names, the entities that are
//! spawns, and the spawn rules (`--spawn`, the fallback spawn).

use crate::level::import::given;
use std::path::Path;

use glam::Vec2;

use super::json::{LdLevel, Project};
use super::values;
use super::{parse_json, read, LdtkError, HOW_TO_COLLIDE, HOW_TO_SPAWN};
use crate::level::import::names::{
    is_spawn_name, role_from_name, says, HAZARD_WORDS, LADDER_WORDS, ONE_WAY_WORDS,
    STRONG_COLLISION_WORDS,
};
use crate::level::import::spawns::{
    inside_solid_note, lift_onto_ground, no_solids_warning, safe_name, settle_spawns,
};
use crate::level::import::{
    normalize, ImportOptions, ImportWarning, LayerReport, LayerRole, MapImport,
};
use crate::level::import::{wall_sides, Edges};
use crate::level::probes::SpawnPoint;
use crate::level::{character_box, valid_name, Level, Tile, DEFAULT_CHARACTER_SIZE};

pub(super) fn import(
    path: &Path,
    opts: &ImportOptions,
    warnings: &mut Vec<ImportWarning>,
) -> Result<MapImport, LdtkError> {
    let file = path.display().to_string();
    let perr = |message: String| LdtkError::Project {
        file: file.clone(),
        message,
    };
    let mut warn = |subject: &str, message: String| {
        warnings.push(ImportWarning {
            file: file.clone(),
            subject: subject.into(),
            message,
        })
    };
    let project: Project = parse_json(&read(path)?, &file, "an LDtk project")?;
    for m in values::unused_options(&project.defs, opts) {
        warn("project", m);
    }
    let (mut levels, layout) = if !project.levels.is_empty() || project.worlds.is_empty() {
        (project.levels, project.world_layout.clone())
    } else {
        let mut worlds = project.worlds;
        if worlds.len() > 1 {
            warn(
                "project",
                format!(
                    "{} worlds; the first, {:?}, is imported",
                    worlds.len(),
                    worlds[0].identifier
                ),
            );
        }
        let w = worlds.swap_remove(0);
        (w.levels, w.world_layout)
    };
    if levels.is_empty() {
        return Err(perr("the project has no level".into()));
    }
    let names: Vec<String> = levels.iter().map(|l| l.identifier.clone()).collect();
    // Which levels: the one --level names, the whole world, or a linear world's first.
    let spatial = matches!(layout.as_deref(), Some("GridVania" | "Free"));
    let picked: Vec<usize> = match &opts.level {
        Some(n) => match levels
            .iter()
            .position(|l| normalize(&l.identifier) == normalize(n))
        {
            Some(k) => vec![k],
            None => {
                return Err(perr(format!(
                    "--level {n}: no level has that identifier; the levels are {}",
                    names.join(", ")
                )))
            }
        },
        None if spatial || levels.len() == 1 => (0..levels.len()).collect(),
        None => {
            warn("project", format!(
                "a {} world: its first level, {:?}, is imported (levels: {}); pass --level NAME for another",
                layout.as_deref().unwrap_or("linear"),
                names[0],
                names.join(", ")
            ));
            vec![0]
        }
    };
    // External levels.
    for &k in &picked {
        if levels[k].layer_instances.is_none() {
            let Some(rel) = levels[k].external_rel_path.clone() else {
                return Err(perr(format!(
                    "level {:?} has no layers and no external file",
                    levels[k].identifier
                )));
            };
            let layers = super::external_level(path, &levels[k].identifier, &rel)?;
            levels[k].layer_instances = Some(layers);
        }
    }
    let single = picked.len() == 1;
    // The grid: the cell size of the layer that most surely holds the collision.
    let grid = super::grid::collision_layer(
        picked
            .iter()
            .flat_map(|&k| levels[k].layer_instances.iter().flatten()),
        opts,
    )
        .map(|l| l.grid_size)
        .ok_or_else(|| perr(format!("no IntGrid layer in {}; platbench reads collision from IntGrid layers (paint the walls in one)", if single { format!("level {:?}", levels[picked[0]].identifier) } else { "the world".into() })))?;
    if grid <= 0 {
        return Err(perr(format!(
            "the IntGrid cell size is {grid} pixels; expected a positive size"
        )));
    }
    let origin = |l: &LdLevel| {
        if single {
            (0, 0)
        } else {
            (l.world_x, l.world_y)
        }
    };
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for &k in &picked {
        let l = &levels[k];
        let (ox, oy) = origin(l);
        // Each term is within MAX_PIXELS (read so): the sums cannot overflow, checked anyway.
        let far = |o: i64, size: i64| {
            o.checked_add(size.max(0))
                .and_then(|e| e.checked_add(grid - 1))
                .map(|e| e.div_euclid(grid))
                .ok_or_else(|| {
                    perr(format!(
                        "level {:?} reaches beyond an i64 of pixels ({o} + {size})",
                        l.identifier
                    ))
                })
        };
        let (lw, lh) = ((l.px_wid + grid - 1) / grid, (l.px_hei + grid - 1) / grid);
        if lw.saturating_mul(lh) as u64 > crate::limits::MAX_TILES {
            return Err(perr(format!(
                "level {:?} is {lw} x {lh} cells of {grid} pixels (pxWid {}, pxHei {}); expected at most {} cells",
                l.identifier, l.px_wid, l.px_hei, crate::limits::MAX_TILES
            )));
        }
        x0 = x0.min(ox.div_euclid(grid));
        y0 = y0.min(oy.div_euclid(grid));
        x1 = x1.max(far(ox, l.px_wid)?);
        y1 = y1.max(far(oy, l.px_hei)?);
    }
    let (w, h) = ((x1 - x0).max(0) as u64, (y1 - y0).max(0) as u64);
    if w == 0 || h == 0 || w.saturating_mul(h) > crate::limits::MAX_TILES {
        let what = match single {
            true => format!("level {:?}", levels[picked[0]].identifier),
            false => format!("the world its {} levels span", picked.len()),
        };
        return Err(perr(format!(
            "{what} is {w} x {h} cells of {grid} pixels; expected 1 to {} cells",
            crate::limits::MAX_TILES
        )));
    }
    let mut tiles = vec![Tile::Empty; (w * h) as usize];
    let mut reports: Vec<LayerReport> = Vec::new();
    let mut raw_spawns: Vec<(String, Vec2, String)> = Vec::new();
    let mut box_cells: u64 = 0;
    let int_layers: usize = {
        let mut seen: Vec<&str> = Vec::new();
        for &k in &picked {
            for l in levels[k].layer_instances.iter().flatten() {
                if l.kind == "IntGrid" && !seen.contains(&l.identifier.as_str()) {
                    seen.push(&l.identifier);
                }
            }
        }
        seen.len()
    };
    // An IntGrid layer named for collision makes the unnamed ones something else (pipes,
    // properties, regions), as a tile layer so named does in a Tiled map.
    let named_collision: Option<String> = picked
        .iter()
        .flat_map(|&k| levels[k].layer_instances.iter().flatten())
        .find(|l| {
            l.kind == "IntGrid"
                && matches!(
                    role_from_name(&l.identifier),
                    Some((LayerRole::Collision, _))
                )
                && !(int_layers > 1 && says(&l.identifier, &["platform", "platforms"]))
        })
        .map(|l| l.identifier.clone());
    // An entity layer whose entities are named for collision (`SolidBlock`, `Collider`) holds
    // the collision boxes: unnamed IntGrid layers are then art, as tile layers are beside an
    // object layer of collision shapes in a Tiled map.
    let collision_entity = |e: &super::json::Entity| says(&e.identifier, STRONG_COLLISION_WORDS);
    let entity_collision: Option<String> = picked
        .iter()
        .flat_map(|&k| levels[k].layer_instances.iter().flatten())
        .find(|l| {
            l.kind == "Entities"
                && opts.role_of(&l.identifier).is_none()
                && l.entity_instances.iter().any(collision_entity)
        })
        .map(|l| l.identifier.clone());
    for &k in &picked {
        let lvl = &levels[k];
        let (ox, oy) = origin(lvl);
        let prefix = if single {
            String::new()
        } else {
            format!("{}/", lvl.identifier)
        };
        for layer in lvl.layer_instances.iter().flatten() {
            let lname = format!("{prefix}{}", layer.identifier);
            let report = |role: LayerRole, why: String| LayerReport {
                name: lname.clone(),
                kind: layer.kind.to_lowercase(),
                role,
                why,
                empty: match layer.kind.as_str() {
                    "IntGrid" => {
                        layer.int_grid_csv.iter().flatten().all(|&v| v == 0)
                            && layer.int_grid.as_ref().is_none_or(|c| c.is_empty())
                    }
                    "Entities" => layer.entity_instances.is_empty(),
                    _ => false,
                },
            };
            match layer.kind.as_str() {
                "IntGrid" => {
                    let names = values::defined(&project.defs, layer, &lname).map_err(&perr)?;
                    let by_name = role_from_name(&layer.identifier);
                    let named_platforms = says(&layer.identifier, &["platform", "platforms"]);
                    let (role, why) = if let Some(r) = opts.role_of(&layer.identifier) {
                        (r, given(&layer.identifier, r))
                    } else if int_layers > 1 && named_platforms {
                        (
                            LayerRole::OneWay,
                            "a separate IntGrid layer named like platforms: one-way".into(),
                        )
                    } else {
                        match by_name {
                            Some((r @ (LayerRole::OneWay | LayerRole::Ladder | LayerRole::Decoration), w)) => (r, format!("its name says {w:?}")),
                            None if named_collision.is_some() => (
                                LayerRole::Decoration,
                                format!("no rule marks it, and IntGrid layer {:?} is named for collision (--layer NAME=collision reads it too)", named_collision.as_deref().unwrap_or_default()),
                            ),
                            None if entity_collision.is_some() => (
                                LayerRole::Decoration,
                                format!("no rule marks it, and entity layer {:?} holds entities named for collision, the collision boxes (--layer NAME=collision reads it too)", entity_collision.as_deref().unwrap_or_default()),
                            ),
                            _ => (LayerRole::Collision, "an IntGrid layer: non-zero cells are solid unless the value's name says one-way, ladder or hazard".into()),
                        }
                    };
                    // Cells a whole multiple of the grid's size, read onto it.
                    let scale = if layer.grid_size >= grid && layer.grid_size % grid == 0 {
                        layer.grid_size / grid
                    } else {
                        0
                    };
                    if scale == 0 {
                        warn(
                            &format!("layer {lname:?}"),
                            format!(
                                "cells of {} pixels, not a whole multiple of the collision grid's {grid}; left out",
                                layer.grid_size
                            ),
                        );
                        reports.push(report(
                            LayerRole::Decoration,
                            "its cells are not a whole multiple of the collision grid's".into(),
                        ));
                        continue;
                    }
                    reports.push(report(role, why));
                    if role == LayerRole::Decoration || role == LayerRole::Objects {
                        continue;
                    }
                    let kind_of = |v: i64| -> (Tile, Option<String>) {
                        let name = names.name(v);
                        if let Some((_, t)) = opts.intgrid.iter().rev().find(|(key, _)| {
                            key.trim() == v.to_string()
                                || (!name.is_empty() && normalize(key) == normalize(name))
                        }) {
                            return (*t, None);
                        }
                        if let Some(t) = role.forced_tile() {
                            return (t, None);
                        }
                        if says(name, ONE_WAY_WORDS) || says(name, &["platform", "platforms"]) {
                            (Tile::OneWay, Some(format!("value {v} {name:?}: one-way")))
                        } else if says(name, LADDER_WORDS) {
                            (Tile::Ladder, Some(format!("value {v} {name:?}: ladder")))
                        } else if says(name, HAZARD_WORDS) {
                            (
                                Tile::Empty,
                                Some(format!("value {v} {name:?}: a hazard, not solid")),
                            )
                        } else {
                            (Tile::Solid, None)
                        }
                    };
                    let (cw, ch) = (layer.c_wid.max(0), layer.c_hei.max(0));
                    let mut cells: Vec<(i64, i64)> = Vec::new();
                    if let Some(csv) = &layer.int_grid_csv {
                        if csv.len() as i64 != cw * ch {
                            return Err(perr(format!("layer {lname:?}: intGridCsv holds {} cells; expected {cw} x {ch} = {}", csv.len(), cw * ch)));
                        }
                        cells.extend(
                            csv.iter()
                                .enumerate()
                                .filter(|(_, v)| **v != 0)
                                .map(|(i, v)| (i as i64, *v)),
                        );
                    } else if let Some(old) = &layer.int_grid {
                        cells.extend(old.iter().map(|c| (c.coord_id, c.v + 1)));
                        // The old format lists cells by id: a repeated one is one cell.
                        cells.sort_unstable();
                        cells.dedup();
                    }
                    let mut kinds: std::collections::HashMap<i64, Tile> = Default::default();
                    for (idx, v) in cells {
                        if idx < 0 || idx >= cw * ch {
                            continue;
                        }
                        (names.check_cell(&lname, (idx % cw, idx / cw), v)).map_err(&perr)?;
                        // Each value judged (and its note given) once, at its first cell.
                        let t = *kinds.entry(v).or_insert_with(|| {
                            let (t, note) = kind_of(v);
                            if let Some(n) = note {
                                warn(&format!("layer {lname:?}"), n);
                            }
                            t
                        });
                        // In i128: a cell size near the 10^15 pixel limit times a column
                        // would wrap an i64.
                        let corner = |o: i64, off: i64, k: i64, lo: i64| {
                            (o + off).div_euclid(grid) as i128 + k as i128 * scale as i128
                                - lo as i128
                        };
                        let cx0 = corner(ox, layer.px_offset_x, idx % cw, x0);
                        let cy0 = corner(oy, layer.px_offset_y, idx / cw, y0);
                        // Clipped to the level first: a layer's cells do not overlap, so a
                        // layer costs at most the level's cells, whatever its cell size.
                        let clip = |c: i128, n: u64| {
                            c.clamp(0, n as i128) as i64
                                ..(c + scale as i128).clamp(0, n as i128) as i64
                        };
                        let (xs, ys) = (clip(cx0, w), clip(cy0, h));
                        for (cx, cy) in ys.flat_map(|cy| xs.clone().map(move |cx| (cx, cy))) {
                            let j = h as i64 - 1 - cy;
                            let cell = &mut tiles[(j as u64 * w + cx as u64) as usize];
                            *cell = match (*cell, t) {
                                (Tile::Empty, t) => t,
                                (_, Tile::Solid) => Tile::Solid,
                                (Tile::OneWay, Tile::Ladder) => Tile::Ladder,
                                (c, _) => c,
                            };
                        }
                    }
                }
                "Entities" => {
                    let boxes = opts.role_of(&layer.identifier).is_none()
                        && layer.entity_instances.iter().any(collision_entity);
                    reports.push(if boxes {
                        report(
                            LayerRole::Collision,
                            "entities: those named for collision (solid, collider, ...) are solid boxes, those named like a spawn spawns".into(),
                        )
                    } else {
                        report(
                            LayerRole::Objects,
                            "entities: those named like a spawn are spawns".into(),
                        )
                    });
                    let mut others = 0;
                    for e in &layer.entity_instances {
                        if boxes && collision_entity(e) {
                            // Its box, the pivot placing it, to the nearest cell edges.
                            let (x, y) = (
                                e.px[0] - e.pivot[0] * e.width + (ox + layer.px_offset_x) as f64,
                                e.px[1] - e.pivot[1] * e.height + (oy + layer.px_offset_y) as f64,
                            );
                            let g = grid as f64;
                            let cell = |v: f64, o: i64| (v / g).round() as i64 - o;
                            let (cx0, cy0) = (cell(x, x0), cell(y, y0));
                            let cx1 = cell(x + e.width, x0).max(cx0 + 1);
                            let cy1 = cell(y + e.height, y0).max(cy0 + 1);
                            // Their cells together stay within the tile limit, so that no
                            // project of overlapping boxes fills the grid without end.
                            let (ax, ay) = (
                                (cx1.min(w as i64) - cx0.max(0)).max(0) as u64,
                                (cy1.min(h as i64) - cy0.max(0)).max(0) as u64,
                            );
                            box_cells = box_cells.saturating_add(ax.saturating_mul(ay));
                            if box_cells > crate::limits::MAX_TILES {
                                return Err(perr(format!("layer {lname:?}: its collision entities cover more than {} cells together; expected at most the tile limit", crate::limits::MAX_TILES)));
                            }
                            for cy in cy0.max(0)..cy1.min(h as i64) {
                                for cx in cx0.max(0)..cx1.min(w as i64) {
                                    let j = h as i64 - 1 - cy;
                                    tiles[(j as u64 * w + cx as u64) as usize] = Tile::Solid;
                                }
                            }
                            continue;
                        }
                        if !is_spawn_name(&e.identifier) {
                            others += 1;
                            continue;
                        }
                        let (px, py) = (e.px[0], e.px[1]);
                        let (pvx, pvy) = (e.pivot[0], e.pivot[1]);
                        // Feet: the bottom centre of the box the pivot places.
                        let fx =
                            px - pvx * e.width + e.width * 0.5 + (ox + layer.px_offset_x) as f64;
                        let fy = py - pvy * e.height + e.height + (oy + layer.px_offset_y) as f64;
                        let g = grid as f64;
                        let feet = Vec2::new(
                            (fx / g - x0 as f64) as f32,
                            (h as f64 - (fy / g - y0 as f64)) as f32,
                        );
                        if raw_spawns.len() >= crate::limits::MAX_SPAWNS {
                            return Err(perr(format!("level {:?}, layer {lname:?}: entity {:?} at px ({px}, {py}) is spawn point {} of the project; expected at most {} (each makes up to five probe scenarios)", lvl.identifier, e.identifier, raw_spawns.len() + 1, crate::limits::MAX_SPAWNS)));
                        }
                        raw_spawns.push((
                            e.identifier.clone(),
                            feet,
                            format!("entity {:?} in layer {lname:?}, by its pivot", e.identifier),
                        ));
                    }
                    if others > 0 {
                        warn(&format!("layer {lname:?}"), format!("{others} entit(ies) not named like a spawn (Player, Spawn, PlayerSpawn, Start_Point); ignored"));
                    }
                }
                _ => reports.push(report(
                    LayerRole::Decoration,
                    format!("a {} layer: art, no collision", layer.kind),
                )),
            }
        }
    }
    let name = {
        let base = if single {
            levels[picked[0]].identifier.clone()
        } else {
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        };
        let safe = safe_name(&base);
        if valid_name(&safe) {
            safe
        } else {
            "ldtk".into()
        }
    };
    let mut level = Level::from_tiles(&name, w as u32, h as u32, tiles);
    level.source = file.clone();
    level.description = format!(
        "LDtk {}",
        if single {
            format!("level {:?}", levels[picked[0]].identifier)
        } else {
            format!("world of {} levels", picked.len())
        }
    );
    let mut spawns = Vec::new();
    let mut sources = Vec::new();
    let mut taken = std::collections::HashSet::new(); // The spawns' names, looked up not searched.
    for (k, (id, feet, why)) in raw_spawns.into_iter().enumerate() {
        // An entity box drawn a little into the floor stands on it.
        let sunk = level
            .solids_overlapping(&character_box(feet, DEFAULT_CHARACTER_SIZE))
            .next();
        let feet = match sunk.and_then(|_| lift_onto_ground(&level, feet)) {
            Some(lifted) => {
                warn(
                    &format!("entity {id:?}"),
                    format!(
                        "the spawn's feet at ({}, {}) are {} tiles inside the ground; lifted onto its top at y = {}",
                        feet.x, feet.y, lifted.y - feet.y, lifted.y
                    ),
                );
                lifted
            }
            None => feet,
        };
        let inside = feet.is_finite()
            && feet.x >= 0.0
            && feet.y >= 0.0
            && feet.x <= w as f32
            && feet.y <= h as f32;
        let in_solid = level
            .solids_overlapping(&character_box(feet, DEFAULT_CHARACTER_SIZE))
            .next()
            .is_some();
        if !inside || in_solid {
            let note = match in_solid.then_some(()).and(sunk) {
                Some(t) if inside => inside_solid_note(feet, Vec2::new(t.mins.x, t.mins.y)),
                _ => format!(
                    "its feet at ({}, {}) tiles are outside the level; not a spawn",
                    feet.x, feet.y
                ),
            };
            warn(&format!("entity {id:?}"), note);
            continue;
        }
        let base = if valid_name(&id) {
            id.clone()
        } else {
            "spawn".into()
        };
        let n = if taken.contains(&base) {
            format!("{base}{}", k + 1)
        } else {
            base
        };
        taken.insert(n.clone());
        spawns.push(SpawnPoint {
            name: n,
            position: feet,
        });
        sources.push(why);
    }
    let mut extra = Vec::new();
    if let Some(wn) = no_solids_warning(&level, &file, HOW_TO_COLLIDE) {
        extra.push(wn);
    }
    // One level of a world laid out in space: a side where another level touches it is where
    // the game goes on (the player walks into the next level), so it gets no wall.
    let continues = if single && spatial {
        let l = &levels[picked[0]];
        let joins = |d: &str| l.neighbours.iter().any(|n| n.dir == d);
        [joins("w"), joins("e")]
    } else {
        [false; 2]
    };
    // LDtk's default is open sides, unlike Tiled's: the LDtk games of the corpus (docs/maps.md)
    // load levels as rooms of a world and stop no player at a level's sides (10 of 12
    // leave them open, the other 2 draw their walls); `--edges walls` adds them.
    let edges = opts.edges.unwrap_or(Edges::Open);
    if continues.contains(&true) && edges == Edges::Walls {
        let sides = match continues {
            [true, true] => "left and right sides join",
            [true, false] => "left side joins",
            _ => "right side joins",
        };
        extra.push(ImportWarning {
            file: file.clone(),
            subject: "map".into(),
            message: format!(
                "the level's {sides} another level of the world, where the game goes on: left open (a probe that walks off it is a map problem); import the world without --level to read them together"
            ),
        });
    }
    if let Some(wn) = wall_sides(&mut level, &mut spawns, edges, continues, [false; 2], &file) {
        extra.push(wn);
    }
    if let Some(wn) =
        settle_spawns(&level, &file, HOW_TO_SPAWN, opts, &mut spawns, &mut sources).map_err(perr)?
    {
        extra.push(wn);
    }
    extra.extend(crate::level::import::unmatched_layer_roles(
        opts, &reports, &file,
    ));
    Ok(MapImport {
        level,
        spawns,
        spawn_sources: sources,
        layers: reports,
        warnings: extra,
    })
}

//! Collision shapes of object layers: rectangles, ramp polygons and polylines in layers whose
//! name or property says collision, each put into the level's cells (edges on the nearest
//! tile edge; a polyline's level and upright legs as one-cell-thick runs). An object's own
//! bool marks (`isOneWay`, a hazard) and the class `platform` without a path (one-way) say
//! how it collides.

use glam::Vec2;
use tiled::{ObjectShape, PropertyValue};

use super::objects::ObjectLayer;
use super::{names, ramp, Importer, TiledError, SHAPE_TOLERANCE_PX};
use crate::level::import::names::{is_spawn_name, says, LADDER_WORDS};
use crate::level::import::LayerRole;
use crate::level::{Slope, Tile};

/// The cells a span from `a` to `b` (tiles) covers: edges rounded to whole tiles, at least one
/// cell (the one below `b`, for a thin platform drawn at a cell's top).
fn span(a: f32, b: f32) -> (i64, i64) {
    let (lo, hi) = (a.round() as i64, b.round() as i64);
    if hi > lo {
        (lo, hi)
    } else {
        (b.ceil() as i64 - 1, b.ceil() as i64)
    }
}

impl<'m> Importer<'m> {
    /// Rectangles and ramp polygons of the collision object layers into the level's cells.
    pub(super) fn collision_objects(&mut self) -> Result<(), TiledError> {
        let layers = std::mem::take(&mut self.objects);
        let result = self.collision_objects_of(&layers);
        self.objects = layers;
        result
    }

    fn collision_objects_of(&mut self, layers: &[ObjectLayer<'m>]) -> Result<(), TiledError> {
        for l in layers {
            // In a layer of objects (spawns, platforms), only shapes named like a ladder.
            let (tile, ladders_only) = match l.role {
                LayerRole::Collision | LayerRole::Solid => (Tile::Solid, false),
                LayerRole::OneWay => (Tile::OneWay, false),
                LayerRole::Ladder => (Tile::Ladder, false),
                LayerRole::Objects if !l.excluded => (Tile::Ladder, true),
                _ => continue,
            };
            let mut snapped = 0;
            let mut outside = 0u64;
            let mut platforms = 0;
            for o in &l.objects {
                if !Self::is_collision_object(o) || (ladders_only && !Self::is_ladder_object(o)) {
                    continue;
                }
                let subject = format!("object {} {:?}", o.id(), o.name);
                // The object's own bool marks: one-way (`isOneWay`), a hazard or `collides =
                // false` (not solid).
                let tile = match object_mark(o) {
                    Some((k, Tile::Empty)) => {
                        self.warn(subject, format!("its property {k:?} marks it as not solid (a hazard or no collision); left out"));
                        continue;
                    }
                    Some((_, Tile::OneWay)) if tile == Tile::Solid => Tile::OneWay,
                    // A collision shape of class `platform` (no path: it does not move) is
                    // one-way, as melonJS's platformer reads it.
                    _ if tile == Tile::Solid && o.user_type == names::PLATFORM => {
                        platforms += 1;
                        Tile::OneWay
                    }
                    _ => tile,
                };
                if o.rotation != 0.0 {
                    self.warn(subject, format!("a collision shape rotated by {} degrees; platbench reads axis-aligned rectangles and ramps only; ignored", o.rotation));
                    continue;
                }
                let (x, y) = (o.x + l.offset.x, o.y + l.offset.y);
                let by = self
                    .cells
                    .source(format!("object {} {:?}", o.id(), o.name), &l.name);
                let cells: Vec<(i64, i64, Tile)> = match &o.shape {
                    ObjectShape::Rect { width, height } => {
                        let a = self.to_level(x, y + height);
                        let b = self.to_level(x + width, y);
                        if !(a.is_finite() && b.is_finite()) {
                            return Err(self.overflow_err(o, if a.is_finite() { b } else { a }));
                        }
                        self.box_cells(a, b, tile, &mut outside, &mut snapped)
                    }
                    ObjectShape::Polyline { points } => {
                        self.check_points(o, "polyline", points.len())?;
                        let pts: Vec<Vec2> = points
                            .iter()
                            .map(|&(px, py)| self.to_level(x + px, y + py))
                            .collect();
                        if pts.iter().any(|p| !p.is_finite()) {
                            return Err(self.obj_err(o, "a point is not finite".into()));
                        }
                        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
                        let mut v = Vec::new();
                        let mut slanted = 0;
                        for w in pts.windows(2) {
                            let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
                            // A level or upright leg is a run of cells one cell thick (below a
                            // level leg, left of an upright one); a slanted leg is no box.
                            if (b.y - a.y) * th <= SHAPE_TOLERANCE_PX
                                || (b.x - a.x) * tw <= SHAPE_TOLERANCE_PX
                            {
                                v.extend(self.box_cells(a, b, tile, &mut outside, &mut snapped));
                            } else {
                                slanted += 1;
                            }
                        }
                        if slanted > 0 {
                            self.warn(subject, format!("a collision polyline with {slanted} slanted leg(s), which platbench does not read (its level and upright legs are read as runs of cells one cell thick)"));
                        }
                        v
                    }
                    ObjectShape::Polygon { points } => {
                        self.check_points(o, "polygon", points.len())?;
                        let pts: Vec<Vec2> = points
                            .iter()
                            .map(|&(px, py)| self.to_level(x + px, y + py))
                            .collect();
                        match self.ramp_cells(&pts, tile) {
                            Some(c) => c,
                            None => {
                                self.warn(subject, "a collision polygon that is not a ramp (a horizontal bottom on the tile grid, vertical sides, one straight top from side to side); ignored".into());
                                continue;
                            }
                        }
                    }
                    _ => continue,
                };
                for (i, j, t) in cells {
                    let k = j as usize * self.grid.w as usize + i as usize;
                    if let Err(m) = self.cells.set(k, t, by) {
                        let (x, y) = self.grid.tiled_cell(i, j);
                        return Err(self.obj_err(o, format!("at cell x = {x}, y = {y} (column and row from the map's top-left): {m}")));
                    }
                }
            }
            if outside > 0 {
                self.warn(
                    format!("layer {:?}", l.name),
                    format!("{outside} cell(s) of its collision rectangles and polylines lie outside the map and are dropped; where they touch a side, a wall outside that side stands for them (with --edges open too)"),
                );
            }
            if platforms > 0 {
                self.warn(
                    format!("layer {:?}", l.name),
                    format!("{platforms} collision shape(s) of class {:?} with no \"path\": read as one-way platforms (a class other than \"platform\" keeps them solid)", names::PLATFORM),
                );
            }
            if snapped > 0 {
                self.warn(
                    format!("layer {:?}", l.name),
                    format!("{snapped} collision rectangle(s) or polyline leg(s) not on the tile grid (by more than {SHAPE_TOLERANCE_PX} pixel); each edge moved to the nearest tile edge"),
                );
            }
        }
        Ok(())
    }

    /// At most [`crate::limits::MAX_POLYGON_POINTS`] points in a shape (counted in the file
    /// before it is read, `points`; checked again here before the shape costs anything).
    fn check_points(&self, o: &tiled::Object, what: &str, n: usize) -> Result<(), TiledError> {
        let max = crate::limits::MAX_POLYGON_POINTS;
        if n > max {
            return Err(self.obj_err(
                o,
                format!("its {what} has {n} points; expected at most {max}"),
            ));
        }
        Ok(())
    }

    /// Whether an object's name or class says ladder (`Ladder`, `climb`): a ladder shape in
    /// any object layer that is read.
    pub(super) fn is_ladder_object(o: &tiled::Object) -> bool {
        says(&o.name, LADDER_WORDS) || says(&o.user_type, LADDER_WORDS)
    }

    /// The cells of a box from corner `a` to corner `b` (level tiles), its edges on the nearest
    /// tile edges (a box thinner than a cell takes the cell below or left of it); counts the
    /// cells beyond the map in `outside` and a box off the grid in `snapped`.
    fn box_cells(
        &mut self,
        a: Vec2,
        b: Vec2,
        tile: Tile,
        outside: &mut u64,
        snapped: &mut u32,
    ) -> Vec<(i64, i64, Tile)> {
        let (i0, i1) = span(a.x, b.x);
        let (j0, j1) = span(a.y, b.y);
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let off = |v: f32| (v - v.round()).abs();
        if off(a.x) * tw > SHAPE_TOLERANCE_PX
            || off(b.x) * tw > SHAPE_TOLERANCE_PX
            || off(a.y) * th > SHAPE_TOLERANCE_PX
            || off(b.y) * th > SHAPE_TOLERANCE_PX
        {
            *snapped += 1;
        }
        // Cells of the box beyond the map (a boundary drawn outside it); a box beside the map
        // within its height, touching its side, is a wall the game keeps there.
        let beside = j0 < self.grid.h as i64 && j1 > 0;
        if beside && i0 < 0 && i1 >= 0 {
            self.drawn_sides[0] = true;
        }
        if beside && i1 > self.grid.w as i64 && i0 <= self.grid.w as i64 {
            self.drawn_sides[1] = true;
        }
        let all = (i1 - i0).max(0) as u64 * (j1 - j0).max(0) as u64;
        let kept = (i1.min(self.grid.w as i64) - i0.max(0)).max(0) as u64
            * (j1.min(self.grid.h as i64) - j0.max(0)).max(0) as u64;
        *outside = outside.saturating_add(all - kept);
        let mut v = Vec::new();
        for j in j0.max(0)..j1.min(self.grid.h as i64) {
            for i in i0.max(0)..i1.min(self.grid.w as i64) {
                v.push((i, j, tile));
            }
        }
        v
    }

    /// Whether an object of a collision layer is a collision shape: a rectangle, polygon or
    /// polyline that is not a spawn, a moving platform (it has a `path`) or a tile object.
    pub(super) fn is_collision_object(o: &tiled::Object) -> bool {
        o.tile_data().is_none()
            && matches!(
                o.shape,
                ObjectShape::Rect { .. }
                    | ObjectShape::Polygon { .. }
                    | ObjectShape::Polyline { .. }
            )
            && !o.properties.contains_key(names::PATH)
            && !is_spawn_name(&o.user_type)
            && !is_spawn_name(&o.name)
    }

    /// The cells of a ramp polygon (level tiles, y up) spanning whole tiles across: solids
    /// under its top line, line slopes where the line crosses a row. `None` if it is no ramp.
    fn ramp_cells(&self, pts: &[Vec2], tile: Tile) -> Option<Vec<(i64, i64, Tile)>> {
        if pts.len() < 3 || pts.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let lo = pts.iter().fold(Vec2::splat(f32::MAX), |a, p| a.min(*p));
        let hi = pts.iter().fold(Vec2::splat(f32::MIN), |a, p| a.max(*p));
        let (x0, x1, y0) = (lo.x.round(), hi.x.round(), lo.y.round());
        let (w, h) = (hi.x - lo.x, hi.y - lo.y);
        if x1 <= x0 || h <= 0.0 || (w * h) as f64 > crate::limits::MAX_TILES as f64 {
            return None;
        }
        // As one big tile in pixels, y down, for `ramp`.
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let local: Vec<Vec2> = pts
            .iter()
            .map(|p| Vec2::new((p.x - lo.x) * tw, (hi.y - p.y) * th))
            .collect();
        let Slope::Line { left, right } = ramp(&local, w * tw, h * th)? else {
            return None;
        };
        if tile != Tile::Solid {
            // A one-way or ladder ramp is not a thing platbench models.
            return None;
        }
        let top = |x: f32| y0 + h * (left + (right - left) * (x - x0) / (x1 - x0));
        let mut out = Vec::new();
        for i in x0 as i64..x1 as i64 {
            if i < 0 || i >= self.grid.w as i64 {
                continue;
            }
            let (hl, hr) = (top(i as f32), top(i as f32 + 1.0));
            let j_top = hl.max(hr).ceil() as i64;
            for j in (y0 as i64).max(0)..j_top.min(self.grid.h as i64) {
                let jf = j as f32;
                let t = if jf + 1.0 <= hl.min(hr) + 1e-4 {
                    Tile::Solid
                } else {
                    Tile::Slope(Slope::Line {
                        left: hl - jf,
                        right: hr - jf,
                    })
                };
                out.push((i, j, t));
            }
        }
        Some(out)
    }
}

/// What an object's own bool properties make it (with the property that says so): one-way
/// (the bools of [`super::tiles::ONE_WAY_BOOLS`]), not solid (a hazard bool true, or a solid
/// bool false), or nothing said.
fn object_mark(o: &tiled::Object<'_>) -> Option<(String, Tile)> {
    use super::tiles::{HAZARD_BOOLS, ONE_WAY_BOOLS, SOLID_BOOLS};
    let mut sorted: Vec<_> = o.properties.iter().collect();
    sorted.sort_by(|a, b| a.0.cmp(b.0));
    for (k, v) in sorted {
        let PropertyValue::BoolValue(b) = v else {
            continue;
        };
        let lower = k.to_lowercase();
        let l = lower.as_str();
        if *b && ONE_WAY_BOOLS.contains(&l) {
            return Some((k.clone(), Tile::OneWay));
        }
        if (*b && HAZARD_BOOLS.contains(&l)) || (!*b && SOLID_BOOLS.contains(&l)) {
            return Some((k.clone(), Tile::Empty));
        }
    }
    None
}

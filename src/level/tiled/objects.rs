//! Object layers: spawn points (by class, type or name, or every object of a layer named like
//! a spawn; points, rectangles and tile objects, feet at the bottom centre) and moving
//! platforms (a rectangle with a `path` naming a polyline, or a point it goes to and back).
//! Collision shapes are read by `shapes`; everything else is a warning.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use glam::Vec2;
use quick_xml::events::Event;
use tiled::{ObjectShape, PropertyValue};

use super::scan::{attr, line_of};
use super::{kind_of, names, shape_name, Importer, TiledError};
use crate::level::import::names::{is_end_name, is_spawn_name};
use crate::level::import::spawns::{inside_solid_note, lift_onto_ground};
use crate::level::import::LayerRole;
use crate::level::probes::SpawnPoint;
use crate::level::DEFAULT_CHARACTER_SIZE;
use crate::level::{character_box, valid_name, Level, Platform, PlatformMotion};

/// An object layer kept for reading once the tiles are known.
pub(super) struct ObjectLayer<'m> {
    /// Its name (`group/child` inside groups).
    pub name: String,
    /// What it was read as.
    pub role: LayerRole,
    /// Its name says spawn: each object is a spawn.
    pub spawn_layer: bool,
    /// Offset in pixels, groups included.
    pub offset: Vec2,
    /// Left out by a property or flag: not even spawns are read from it.
    pub excluded: bool,
    /// Its objects.
    pub objects: Vec<tiled::Object<'m>>,
}

impl<'m> Importer<'m> {
    /// Tiled pixels (y down, from the grid's top-left) to level tiles (y up).
    pub(super) fn to_level(&self, x: f32, y: f32) -> Vec2 {
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        Vec2::new(
            x / tw - self.grid.x0 as f32,
            self.grid.h as f32 - (y / th - self.grid.y0 as f32),
        )
    }

    /// An error about object `o`, at the line of its `<object>` (a JSON map's: where its
    /// layer starts).
    pub(super) fn obj_err(&self, o: &tiled::Object, message: String) -> TiledError {
        let line = object_line(self.text, o.id());
        TiledError::Object {
            file: line.map_or(self.file.clone(), |l| (self.cell_at)(l, (-1, -1))),
            id: o.id(),
            name: o.name.clone(),
            message,
        }
    }

    /// An object whose place or size the crate read as infinite (a number past f32's range,
    /// such as 1e39, in a JSON map; a TMX map's is refused at its column first): names the
    /// first such value, or the sum that overflows.
    pub(super) fn overflow_err(&self, o: &tiled::Object, sum: Vec2) -> TiledError {
        let size = match o.shape {
            ObjectShape::Rect { width, height } | ObjectShape::Ellipse { width, height } => {
                vec![("width", width), ("height", height)]
            }
            _ => vec![],
        };
        let bad = [("x", o.x), ("y", o.y)]
            .into_iter()
            .chain(size)
            .find(|(_, v)| !v.is_finite());
        let message = match bad {
            Some((key, v)) => format!(
                "its {key} is read as {v}, beyond f32's range; expected a finite number from -3.4e38 to 3.4e38 (pixels)"
            ),
            None => format!(
                "its place, x = {} and y = {} plus its size, overflows f32 to ({}, {}) tiles; expected an object within {} tiles of the map's corner",
                o.x,
                o.y,
                sum.x,
                sum.y,
                crate::limits::MAX_COORD
            ),
        };
        self.obj_err(o, message)
    }

    /// Spawn points and platforms from the object layers; everything else is warned about.
    /// Returns the spawns and where each came from.
    pub(super) fn objects(
        &mut self,
        level: &mut Level,
    ) -> Result<(Vec<SpawnPoint>, Vec<String>), TiledError> {
        let layers = std::mem::take(&mut self.objects);
        let all: HashMap<u32, &tiled::Object<'m>> = layers
            .iter()
            .flat_map(|l| l.objects.iter())
            .map(|o| (o.id(), o))
            .collect();
        let mut used_paths: Vec<u32> = Vec::new();
        let mut spawns: Vec<(SpawnPoint, u32, String)> = Vec::new();
        // Each spawn's name and object id, so that a name is looked up, not searched for.
        let mut spawn_names: HashMap<String, u32> = HashMap::new();
        let mut paths: Vec<&tiled::Object<'m>> = Vec::new();
        for l in &layers {
            if l.excluded {
                continue;
            }
            let mut ignored = 0;
            for o in &l.objects {
                self.check_object_tile(o)?;
                let subject = format!("object {} {:?}", o.id(), o.name);
                let class = o.user_type.as_str();
                let by_class = is_spawn_name(class);
                let by_name = is_spawn_name(&o.name);
                let collides = l.role.collides();
                // A moving platform has a path; one of class `platform` without a path is a
                // one-way piece of a collision layer, and elsewhere a platform missing its path.
                let is_platform = o.properties.contains_key(names::PATH)
                    || (class == names::PLATFORM && !collides);
                let spawn_shape = o.tile_data().is_some()
                    || matches!(o.shape, ObjectShape::Point(..) | ObjectShape::Rect { .. });
                // A spawn layer often holds the level's end beside its start (`exit`, `goal`):
                // only the layer made it a spawn, so its own name takes it out (a moving
                // platform is read as one whatever its name).
                let only_by_layer =
                    l.spawn_layer && spawn_shape && !is_platform && !by_class && !by_name;
                if only_by_layer && (is_end_name(&o.name) || is_end_name(class)) {
                    self.warn(subject.clone(), format!("in spawn layer {:?}, named like the level's end: not a spawn (a class or name \"spawn\" makes it one)", l.name));
                    continue;
                }
                let is_spawn =
                    !is_platform && (by_class || by_name || (l.spawn_layer && spawn_shape));
                if is_spawn {
                    let why = if by_class {
                        format!("object {} {:?}: its class {class:?}", o.id(), o.name)
                    } else if by_name {
                        format!("object {} {:?}: its name", o.id(), o.name)
                    } else {
                        format!(
                            "object {} {:?}: in layer {:?}, named like a spawn layer",
                            o.id(),
                            o.name,
                            l.name
                        )
                    };
                    if spawns.len() >= crate::limits::MAX_SPAWNS {
                        return Err(self.obj_err(o, format!("it is spawn point {} of the map; expected at most {} (each spawn makes up to five probe scenarios)", spawns.len() + 1, crate::limits::MAX_SPAWNS)));
                    }
                    let Some(s) = self.spawn(o, l.offset, level)? else {
                        continue;
                    };
                    // Several objects named "Player" are each a spawn, named by id after the first.
                    let unique = !spawn_names.contains_key(&o.name);
                    let name = if valid_name(&o.name) && (!by_name || unique) {
                        o.name.clone()
                    } else {
                        format!("spawn{}", o.id())
                    };
                    if let Some(other) = spawn_names.get(&name) {
                        return Err(self.obj_err(o, format!("spawn name {name:?} is also the name of object {other}; expected unique spawn names (they name the scenarios)")));
                    }
                    // The properties are a hash map: warned in name order, the same each run.
                    for key in o.properties.keys().collect::<BTreeSet<_>>() {
                        self.warn(subject.clone(), format!("property {key:?} is not one platbench reads on a spawn point; ignored"));
                    }
                    spawn_names.insert(name.clone(), o.id());
                    spawns.push((SpawnPoint { name, position: s }, o.id(), why));
                } else if is_platform {
                    let p = self.platform(o, l.offset, &all, &mut used_paths)?;
                    level.platforms.push(p);
                } else if (collides || (l.role == LayerRole::Objects && Self::is_ladder_object(o)))
                    && Self::is_collision_object(o)
                {
                    // Read by collision_objects.
                } else if o.tile_data().is_some() {
                    if l.role == LayerRole::Decoration {
                        ignored += 1;
                    } else {
                        self.warn(subject, "a tile object (a placed sprite) that is not a spawn holds no collision platbench reads; ignored".into());
                    }
                } else {
                    match &o.shape {
                        // A polyline or a point may be a platform's path: said at the end
                        // if none names it.
                        ObjectShape::Polyline { .. } => paths.push(o),
                        ObjectShape::Point(..) if l.role != LayerRole::Decoration => paths.push(o),
                        _ if l.role == LayerRole::Decoration => ignored += 1,
                        other => {
                            let class_text = if class.is_empty() {
                                "no class".to_string()
                            } else {
                                format!("class {class:?}")
                            };
                            self.warn(subject, format!(
                                "{} with {class_text} in layer {:?} is neither a spawn point (class or name \"spawn\", \"player\", \"start\") nor a moving platform (a rectangle with a \"path\" property) nor in a collision layer; ignored",
                                shape_name(other), l.name
                            ));
                        }
                    }
                }
            }
            if ignored > 0 {
                self.warn(
                    format!("layer {:?}", l.name),
                    format!("{ignored} object(s) in a decoration layer; ignored"),
                );
            }
        }
        let used: std::collections::HashSet<u32> = used_paths.into_iter().collect();
        for o in paths {
            if !used.contains(&o.id()) {
                let what = match o.shape {
                    ObjectShape::Point(..) => "a point that is no spawn (class or name \"spawn\", \"player\", \"start\") and",
                    _ => "a polyline that",
                };
                self.warn(
                    format!("object {} {:?}", o.id(), o.name),
                    format!("{what} no platform's \"path\" property names; ignored"),
                );
            }
        }
        self.objects = layers;
        let sources = spawns.iter().map(|s| s.2.clone()).collect();
        Ok((spawns.into_iter().map(|(s, _, _)| s).collect(), sources))
    }

    /// Where a spawn object puts the character's feet: a point is the feet; a rectangle's or
    /// tile object's bottom centre is (a tile object's position is its bottom-left corner).
    /// Feet a little inside the ground are lifted onto it; `None` (with a note) for a spawn
    /// deeper inside a solid, whose probes could measure no controller.
    fn spawn(
        &mut self,
        o: &tiled::Object,
        offset: Vec2,
        level: &Level,
    ) -> Result<Option<Vec2>, TiledError> {
        if o.rotation != 0.0 {
            return Err(self.obj_err(
                o,
                format!(
                    "a spawn point is rotated by {} degrees; expected no rotation",
                    o.rotation
                ),
            ));
        }
        let (x, y) = (o.x + offset.x, o.y + offset.y);
        let feet = match (&o.shape, o.tile_data().is_some()) {
            (ObjectShape::Rect { width, .. }, true) => self.to_level(x + width * 0.5, y),
            (ObjectShape::Point(..), _) => self.to_level(x, y),
            (ObjectShape::Rect { width, height }, false) => {
                self.to_level(x + width * 0.5, y + height)
            }
            (other, _) => {
                return Err(self.obj_err(
                    o,
                    format!("a spawn point is {}; expected a point (the feet), a rectangle or a tile object (feet at its bottom centre)", shape_name(other)),
                ))
            }
        };
        if !(feet.x.is_finite() && feet.y.is_finite()) {
            return Err(self.overflow_err(o, feet));
        }
        let (w, h) = (level.width as f32, level.height as f32);
        if !(feet.x >= 0.0 && feet.x <= w && feet.y >= 0.0 && feet.y <= h) {
            return Err(self.obj_err(o, format!(
                "the spawn point's feet are at ({}, {}) tiles, outside the map (0 <= x <= {w}, 0 <= y <= {h}); expected a spawn inside the map, on or above open space",
                feet.x, feet.y
            )));
        }
        let b = character_box(feet, DEFAULT_CHARACTER_SIZE);
        let subject = format!("object {} {:?}", o.id(), o.name);
        if let Some(t) = level.solids_overlapping(&b).next() {
            // A spawn drawn a little into the floor stands on it; deeper, it is the map's problem.
            if let Some(lifted) = lift_onto_ground(level, feet) {
                self.warn(subject, format!("the spawn's feet at ({}, {}) are {} tiles inside the ground; lifted onto its top at y = {}", feet.x, feet.y, lifted.y - feet.y, lifted.y));
                return Ok(Some(lifted));
            }
            self.warn(
                subject,
                inside_solid_note(feet, Vec2::new(t.mins.x, t.mins.y)),
            );
            return Ok(None);
        }
        Ok(Some(feet))
    }

    /// A moving platform from a rectangle with `path` and `speed`.
    fn platform(
        &mut self,
        o: &tiled::Object<'m>,
        offset: Vec2,
        all: &HashMap<u32, &tiled::Object<'m>>,
        used_paths: &mut Vec<u32>,
    ) -> Result<Platform, TiledError> {
        let (tw, th) = (self.map.tile_width as f32, self.map.tile_height as f32);
        let (file, text, cell_at) = (self.file.clone(), self.text, self.cell_at);
        // At the object's line, as [`Importer::obj_err`] places it.
        let obj_err = |o: &tiled::Object, message: String| TiledError::Object {
            file: object_line(text, o.id()).map_or(file.clone(), |l| cell_at(l, (-1, -1))),
            id: o.id(),
            name: o.name.clone(),
            message,
        };
        let subject = format!("object {} {:?}", o.id(), o.name);
        let ObjectShape::Rect { width, height } = o.shape else {
            return Err(obj_err(
                o,
                format!(
                    "a moving platform is {}; expected a rectangle",
                    shape_name(&o.shape)
                ),
            ));
        };
        if o.rotation != 0.0 {
            return Err(obj_err(
                o,
                format!(
                    "the platform is rotated by {} degrees; expected no rotation",
                    o.rotation
                ),
            ));
        }
        if !(width > 0.0 && height > 0.0 && width.is_finite() && height.is_finite()) {
            return Err(obj_err(
                o,
                format!("the platform is {width} x {height} pixels; expected a positive size"),
            ));
        }
        let start = self.to_level(o.x + offset.x, o.y + offset.y + height);
        let size = Vec2::new(width / tw, height / th);
        let mut speed = None;
        let mut path = None;
        let mut one_way = false;
        let props: BTreeMap<_, _> = o.properties.iter().collect();
        for (key, value) in props {
            match (key.as_str(), value) {
                (names::PATH, PropertyValue::ObjectValue(id)) => path = Some(*id),
                (names::SPEED, PropertyValue::FloatValue(v)) => speed = Some(*v),
                (names::SPEED, PropertyValue::IntValue(v)) => speed = Some(*v as f32),
                (names::ONE_WAY, PropertyValue::BoolValue(b)) => one_way = *b,
                (names::PATH, other) => return Err(obj_err(o, format!("property \"path\" is {}; expected an object reference to a polyline", kind_of(other)))),
                (names::SPEED, other) => return Err(obj_err(o, format!("property \"speed\" is {}; expected a float (tiles/s)", kind_of(other)))),
                (names::ONE_WAY, other) => return Err(obj_err(o, format!("property \"one_way\" is {}; expected a bool", kind_of(other)))),
                _ => self.warn(subject.clone(), format!("property {key:?} is not one platbench reads on a platform (it reads \"path\", \"speed\", \"one_way\"); ignored")),
            }
        }
        let path_id = match path {
            Some(id) if id != 0 => id,
            _ => return Err(obj_err(o, "a moving platform needs a \"path\" property (an object reference to a polyline); none is set".into())),
        };
        let speed = match speed {
            Some(s) if s.is_finite() && s > 0.0 && s as f64 <= crate::limits::MAX_SPEED => s,
            Some(s) => {
                return Err(obj_err(
                    o,
                    format!(
                        "speed = {s}; expected 0 < speed <= {} (tiles/s)",
                        crate::limits::MAX_SPEED
                    ),
                ))
            }
            None => {
                return Err(obj_err(
                    o,
                    "a moving platform needs a \"speed\" property (float, tiles/s)".into(),
                ))
            }
        };
        let Some(p) = all.get(&path_id) else {
            return Err(obj_err(o, format!("its path names object {path_id}, which is not in any object layer platbench reads")));
        };
        if p.rotation != 0.0 {
            return Err(obj_err(
                o,
                format!(
                    "its path, object {path_id} {:?}, is rotated; expected no rotation",
                    p.name
                ),
            ));
        }
        let waypoints: Vec<Vec2> = match &p.shape {
            // The path's shape, moved so that its first point is the platform's start: where
            // the polyline is drawn does not matter, only its legs.
            ObjectShape::Polyline { points } => {
                if points.len() > crate::limits::MAX_PATH_POINTS {
                    return Err(obj_err(
                        o,
                        format!(
                            "its path, object {path_id} {:?}, has {} points; expected at most {}",
                            p.name,
                            points.len(),
                            crate::limits::MAX_PATH_POINTS
                        ),
                    ));
                }
                let Some(&(x0, y0)) = points.first() else {
                    return Err(obj_err(
                        o,
                        format!("its path, object {path_id} {:?}, has no points", p.name),
                    ));
                };
                points
                    .iter()
                    .map(|&(x, y)| start + Vec2::new((x - x0) / tw, -(y - y0) / th))
                    .collect()
            }
            // A point is where the platform's top-left corner goes, and back (Excalibur's
            // Jelly Jumper sample reads its maps so).
            ObjectShape::Point(..) => vec![
                start,
                start + Vec2::new((p.x - o.x) / tw, -(p.y - o.y) / th),
            ],
            other => {
                return Err(obj_err(
                    o,
                    format!(
                        "its path names object {path_id} {:?}, which is {}; expected a polyline (the path's legs) or a point (where the platform goes and back)",
                        p.name,
                        shape_name(other)
                    ),
                ))
            }
        };
        let far =
            |v: Vec2| v.abs().max_element() as f64 > crate::limits::MAX_COORD || !v.is_finite();
        if far(start) || far(size) || waypoints.iter().any(|w| far(*w)) {
            return Err(obj_err(
                o,
                format!(
                    "the platform or its path reaches beyond {} tiles from the map's corner; expected a platform near the map",
                    crate::limits::MAX_COORD
                ),
            ));
        }
        if waypoints.iter().any(|w| !w.is_finite()) {
            return Err(obj_err(
                o,
                format!(
                    "its path, object {path_id} {:?}, has a point that is not finite",
                    p.name
                ),
            ));
        }
        if waypoints.len() < 2 || waypoints.windows(2).all(|w| w[0] == w[1]) {
            return Err(obj_err(o, format!("its path, object {path_id} {:?}, has zero length; expected at least 2 different points", p.name)));
        }
        used_paths.push(path_id);
        Ok(Platform {
            start,
            size,
            motion: PlatformMotion::Waypoints {
                points: waypoints,
                speed,
            },
            one_way,
        })
    }
}

/// The line of the map's `<object id="ID">` (not a tileset tile's collision shape), if any.
fn object_line(text: &str, id: u32) -> Option<usize> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut in_tileset = 0usize;
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Ok(Event::Start(e)) if e.name().as_ref() == b"tileset" => in_tileset += 1,
            Ok(Event::End(e)) if e.name().as_ref() == b"tileset" => in_tileset -= 1,
            Ok(Event::Start(e) | Event::Empty(e))
                if in_tileset == 0
                    && e.name().as_ref() == b"object"
                    && attr(&e, "id").is_some_and(|v| v.parse() == Ok(id)) =>
            {
                return Some(line_of(text, pos));
            }
            Ok(Event::Eof) | Err(_) => return None,
            _ => {}
        }
    }
}

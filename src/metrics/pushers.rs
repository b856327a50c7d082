//! Moving platforms in contact with the character, frame by frame: carrying it, pushing it,
//! inside it, and squeezing it against the level (a crush by design). The rest metrics
//! (`rest_jitter`, `bounce_frames`) leave out the frames a platform moves the character, and
//! `push_penetration` and `crush_count` judge a squeeze by the crush rule
//! ([`CrushRule`]), so a scenario that shoves or crushes by design is judged by its own rule.
//!
//! Everything here is read from the level's platforms and the trace, the same way for every
//! controller, and computed frame by frame as the metrics pass over the rows (a state of a few
//! values: nothing is kept per frame).

use super::faults::INSIDE_TOLERANCE;
use super::ground::Ground;
use super::idle::SIDE_OVERLAP;
use super::platforms::ON_PLATFORM;
use super::{pos, Context};
use crate::level::{Platform, Tile};
use crate::shape::CharacterShape;
use crate::trace::{Frames, TraceRow};
use parry2d::bounding_volume::Aabb;
use parry2d::shape::SharedShape;

/// The character's shape and the per-frame tests that read it.
pub(crate) struct Pushers<'a> {
    ctx: &'a Context<'a>,
    ground: &'a Ground<'a>,
    shape: SharedShape,
}

impl<'a> Pushers<'a> {
    /// The tests for `ctx`'s character.
    pub(crate) fn new(ctx: &'a Context<'a>, ground: &'a Ground<'a>) -> Self {
        Pushers {
            ctx,
            ground,
            shape: ctx.shape.build(ctx.spec.size),
        }
    }

    /// The box of the character's shape with its feet at row `r` (a ball is as wide as it is
    /// tall).
    fn shape_box(&self, r: &TraceRow) -> Aabb {
        self.shape
            .compute_aabb(&CharacterShape::pose(pos(r), self.ctx.spec.size))
    }

    /// Platform `p`'s box at row index `k` on its exact path (as `idle_drift` reads it).
    fn path_box(&self, p: &Platform, k: usize) -> Aabb {
        p.aabb(k as f64 * self.ctx.spec.dt as f64)
    }

    /// Whether a moving platform carries or pushes the character over the step into row `k`
    /// (`k >= 1`): it stands on the platform's top (feet within [`ON_PLATFORM`] plus the
    /// platform's step of it, over it, before or after the step), or a platform that is not
    /// one-way moves toward it and reaches it ([`pushes`]). The test `idle_drift` has always
    /// used for "riding and pushed by no platform".
    pub(crate) fn carried_or_pushed(&self, rows: Frames, k: usize) -> bool {
        let (prev, r) = (rows.at(k - 1), rows.at(k));
        let before = self.shape_box(&prev);
        let half = before.half_extents().x;
        self.ctx.level.platforms.iter().any(|p| {
            let (b0, b1) = (self.path_box(p, k - 1), self.path_box(p, k));
            let step = b1.mins - b0.mins;
            // Before and after the step: a rider stands on the platform's top at either end.
            let on = |b: Aabb, feet: &TraceRow| {
                (feet.y - b.maxs.y).abs() <= ON_PLATFORM + step.length()
                    && feet.x + half > b.mins.x
                    && feet.x - half < b.maxs.x
            };
            on(b1, &r) || on(b0, &prev) || (!p.one_way && pushes(&before, &b0, step))
        })
    }

    /// Whether the character's shape at row `k` is inside a platform that is not one-way by more
    /// than [`INSIDE_TOLERANCE`] (as `push_penetration` measures it, where the configuration
    /// places the platform; the replay marks such a frame inside a moving platform).
    fn inside(&self, r: &TraceRow, k: usize) -> bool {
        super::platforms::platform_depth(self.ctx, self.ground, r, k) > INSIDE_TOLERANCE
    }

    /// Whether a moving platform is in contact with the character at row `k`: carries or
    /// pushes it over the step into it ([`Pushers::carried_or_pushed`]), or holds it inside.
    pub(crate) fn contact(&self, rows: Frames, k: usize) -> bool {
        (k > 0 && self.carried_or_pushed(rows, k)) || self.inside(&rows.at(k), k)
    }

    /// Whether at row `k` (`k >= 1`) a platform that is not one-way squeezes the character
    /// against the level: it moves toward the character along an axis where the two are side by
    /// side and reaches it ([`pushes`]), and the room between the platform's leading face and
    /// the level's first solid tile beyond it, over the character's span across that axis, is
    /// smaller than the character's extent along it: no controller could keep the shape out of
    /// both. A crush by design, whatever the controller does with it.
    pub(crate) fn squeezed(&self, rows: Frames, k: usize) -> bool {
        if k == 0 {
            return false;
        }
        let c = self.shape_box(&rows.at(k - 1));
        self.ctx
            .level
            .platforms
            .iter()
            .filter(|p| !p.one_way)
            .any(|p| {
                let (b0, b1) = (self.path_box(p, k - 1), self.path_box(p, k));
                let step = b1.mins - b0.mins;
                (0..2).any(|a| {
                    let Some(dir) = push_direction(&c, &b0, step, a) else {
                        return false;
                    };
                    let face = if dir > 0.0 { b1.maxs[a] } else { b1.mins[a] };
                    let extent = c.maxs[a] - c.mins[a];
                    let room = room_beyond(
                        self.ctx,
                        face,
                        dir,
                        a,
                        (c.mins[1 - a], c.maxs[1 - a]),
                        extent,
                    );
                    room < extent - SIDE_OVERLAP
                })
            })
    }
}

/// Whether a platform of box `plat` moving by `step` pushes a character of box `ch`: along an
/// axis where the two are side by side (overlapping across it by more than [`SIDE_OVERLAP`]), it
/// moves toward the character and reaches within [`ON_PLATFORM`] (a contact gap such as Rapier's
/// offset) of it, or into it. A wall sliding flush past a character's side does not push it.
pub(crate) fn pushes(ch: &Aabb, plat: &Aabb, step: glam::Vec2) -> bool {
    (0..2).any(|a| push_direction(ch, plat, step, a).is_some())
}

/// The direction (+1 or -1) in which a platform of box `plat` moving by `step` pushes a
/// character of box `ch` along axis `a` (see [`pushes`]), `None` if it does not.
fn push_direction(ch: &Aabb, plat: &Aabb, step: glam::Vec2, a: usize) -> Option<f32> {
    let o = ch.maxs.min(plat.maxs) - ch.mins.max(plat.mins);
    let across = o[1 - a] > SIDE_OVERLAP;
    let dir = if plat.center()[a] < ch.center()[a] {
        1.0
    } else {
        -1.0
    };
    // o[a] is minus the gap along the axis (positive: overlapping).
    (across && step[a] * dir > 0.0 && -o[a] <= ON_PLATFORM + step[a].abs()).then_some(dir)
}

/// The free room along axis `a` from `face` in direction `dir` to the first solid or slope tile
/// over the span `across` of the other axis (less [`ON_PLATFORM`] at each end), in tiles (negative when `face` is inside one); at
/// most `extent` plus a tile (farther is room enough).
fn room_beyond(
    ctx: &Context,
    face: f32,
    dir: f32,
    a: usize,
    across: (f32, f32),
    extent: f32,
) -> f32 {
    let limit = extent + 1.0;
    // The cells the span covers across the axis, less a contact gap at each end: a shape
    // touching a cell's edge does not reach into it, nor does one sunk into the floor by a
    // declared sag (Box2D's pogo) or lifted by an offset (Rapier's), both under ON_PLATFORM.
    let lo = (across.0 + ON_PLATFORM).floor() as i64;
    let hi = ((across.1 - ON_PLATFORM).ceil() as i64).saturating_sub(1);
    // Only cells within the map can block (outside it every cell is empty): the span is
    // clipped to the map, and the walk along the axis stops at the map's far side.
    let level = ctx.level;
    let (lo, hi) = if a == 0 {
        level.clip_rows(lo, hi)
    } else {
        level.clip_columns(lo, hi)
    };
    let cells = if a == 0 { level.width } else { level.height } as i64;
    let blocked = |n: i64| {
        (lo..=hi).any(|m| {
            let (i, j) = if a == 0 { (n, m) } else { (m, n) };
            matches!(ctx.level.tile(i, j), Tile::Solid | Tile::Slope(_))
        })
    };
    let mut n = face.floor() as i64;
    // Before the map's near side nothing blocks and the room only grows: the walk starts at
    // that side (where it would return `limit` on the way, it returns it there too).
    if dir > 0.0 && n < 0 {
        n = 0;
    } else if dir < 0.0 && n >= cells {
        n = cells - 1;
    }
    loop {
        if (dir > 0.0 && n >= cells) || (dir < 0.0 && n < 0) {
            // Past the map's far side nothing blocks: the room grows to `limit`.
            return limit;
        }
        // The near edge of cell n along the direction of the push.
        let edge = if dir > 0.0 { n as f32 } else { (n + 1) as f32 };
        let room = (edge - face) * dir;
        if room >= limit {
            return limit;
        }
        if blocked(n) {
            return room;
        }
        n += dir as i64;
    }
}

/// The crush rule as the metrics pass over the rows in order: a crush episode starts at a
/// squeezed frame ([`Pushers::squeezed`]) and lasts while a platform stays in contact with the
/// character ([`Pushers::contact`]); within it the character may end inside the platform:
/// that is what a crush is, whether or not the controller reports it (the trace's `crushed`
/// column: only the sweep has a crush event; Rapier and Box2D document none, and a game
/// detects a crush itself). `push_penetration` leaves the episode's frames out; `crush_count`
/// counts a deep entry into a platform outside an episode (run through by a platform that had
/// room to push it); where the character is left against the level is
/// `penetration_beyond_declared`'s to judge, alike for every controller.
pub(crate) struct CrushRule {
    /// Within a crush episode.
    pub(crate) crushing: bool,
}

impl CrushRule {
    /// Before the first row.
    pub(crate) fn new() -> Self {
        CrushRule { crushing: false }
    }

    /// Takes in row `k`; returns the deep entries judged wrong at this row (a count and the
    /// first one's frame) when `deep_entry` says the character went deeper than
    /// [`super::platforms::CRUSH_DEPTH`] into a platform at this row.
    pub(crate) fn push(
        &mut self,
        pushers: &Pushers,
        rows: Frames,
        k: usize,
        deep_entry: bool,
    ) -> (usize, Option<u32>) {
        if pushers.squeezed(rows, k) {
            self.crushing = true;
        } else if self.crushing && !pushers.contact(rows, k) {
            self.crushing = false;
        }
        if deep_entry && !self.crushing {
            (1, Some(rows.at(k).frame))
        } else {
            (0, None)
        }
    }

    /// Ends the run: nothing is left to judge (a crush episode's entries are the crush).
    pub(crate) fn end(&mut self) -> (usize, Option<u32>) {
        *self = CrushRule::new();
        (0, None)
    }
}

/// Whether each row from `range.start` on is shoved: a platform in contact with it
/// ([`Pushers::contact`]), or airborne since such a contact without having stood on anything (a
/// fall off a block that slid away is the block's doing, not a bounce). Iterated in order;
/// the state at `range.start` is found by looking back over the airborne rows before it.
pub(crate) fn shoved<'a>(
    pushers: &'a Pushers<'a>,
    rows: Frames<'a>,
    range: std::ops::Range<usize>,
) -> impl Iterator<Item = (TraceRow, bool)> + 'a {
    let mut state = range.start > 0 && {
        let mut j = range.start - 1;
        loop {
            if pushers.contact(rows, j) {
                break true;
            }
            if rows.at(j).is_grounded() || j == 0 {
                break false;
            }
            j -= 1;
        }
    };
    range.map(move |k| {
        let r = rows.at(k);
        state = pushers.contact(rows, k) || (state && !r.is_grounded());
        (r, state)
    })
}

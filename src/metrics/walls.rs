//! Walls hit at speed: tunneling.

use super::{pos, Context, Measure};
use crate::level::{character_box, Level};
use crate::trace::Frames;
use glam::Vec2;
use parry2d::bounding_volume::Aabb;

/// `tunneled`: 1 if between two frames the character passed entirely through a solid tile that
/// overlapped its box's cross-section both before and after the move, else 0.
///
/// Frame: the frame the first such move ends on, on the far side (`None` if it never tunneled).
pub fn tunneled(ctx: &Context, rows: Frames) -> Measure {
    let size = ctx.spec.size;
    let pairs = rows.iter().zip(rows.iter().skip(1));
    let passed = pairs.into_iter().find_map(|(r0, r1)| {
        let a = character_box(pos(&r0), size);
        let b = character_box(pos(&r1), size);
        (passed_through(ctx.level, &a, &b, 0) || passed_through(ctx.level, &a, &b, 1))
            .then_some(r1.frame)
    });
    Measure {
        metric: "tunneled",
        value: passed.is_some() as u8 as f64,
        reference: 0.0,
        frame: passed,
    }
}

/// Whether a solid tile lies wholly between boxes `a` and `b` along `axis` while overlapping
/// both boxes on the other axis.
pub(super) fn passed_through(level: &Level, a: &Aabb, b: &Aabb, axis: usize) -> bool {
    let o = 1 - axis;
    let (gap_lo, gap_hi) = if b.mins[axis] >= a.maxs[axis] {
        (a.maxs[axis], b.mins[axis])
    } else if a.mins[axis] >= b.maxs[axis] {
        (b.maxs[axis], a.mins[axis])
    } else {
        return false;
    };
    let cross_lo = a.mins[o].max(b.mins[o]);
    let cross_hi = a.maxs[o].min(b.maxs[o]);
    if cross_hi <= cross_lo || gap_hi - gap_lo < 1.0 {
        return false;
    }
    let mut area = Aabb::new(Vec2::ZERO, Vec2::ZERO);
    area.mins[axis] = gap_lo;
    area.maxs[axis] = gap_hi;
    area.mins[o] = cross_lo;
    area.maxs[o] = cross_hi;
    level
        .solids_overlapping(&area)
        .any(|t| t.mins[axis] >= gap_lo && t.maxs[axis] <= gap_hi)
}

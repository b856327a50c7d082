//! Jumping: the apex of a jump against the requested height.

use super::{Context, Measure};
use crate::scenario::input_script;
use crate::trace::Frames;
use glam::Vec2;
use parry2d::bounding_volume::Aabb;

/// `apex_error`: the rise of the feet from take-off to the apex of the first jump, minus the
/// requested jump height, in tiles. Only for a jump with no solid within the jump's reach above
/// the character.
///
/// Frame: the first frame at the apex (the take-off frame if it never rose).
pub fn apex_error(ctx: &Context, rows: Frames) -> Option<Measure> {
    let script = input_script(ctx.spec);
    let press = script
        .iter()
        .enumerate()
        .position(|(k, i)| i.jump && (k == 0 || !script[k - 1].jump))?;
    // Down + jump is a drop through a one-way platform, not a jump.
    if script[press].down {
        return None;
    }
    let start = rows.get(press)?;
    let h = ctx.params.jump_height;
    let half = ctx.spec.size.x * 0.5;
    let reach = Aabb::new(
        Vec2::new(start.x - half, start.y + ctx.spec.size.y),
        Vec2::new(start.x + half, start.y + ctx.spec.size.y + h + 0.5),
    );
    if ctx.level.solids_overlapping(&reach).next().is_some() {
        return None;
    }
    let mut apex = start.y;
    let mut frame = start.frame;
    for r in rows.iter().skip(press + 1) {
        if r.y > apex {
            frame = r.frame;
        }
        apex = apex.max(r.y);
        if r.is_grounded() && r.frame as usize > press + 1 {
            break;
        }
    }
    Some(Measure {
        metric: "apex_error",
        value: (apex - start.y) as f64 - h as f64,
        reference: 0.0,
        frame: Some(frame),
    })
}

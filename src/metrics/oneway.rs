//! One-way platforms: where the character ends against where the seed's rule puts it.

use super::{Context, Measure};
use crate::trace::Frames;

/// How close to the expected height the feet must end for `oneway_result`, in tiles: above
/// Rapier's offset, far below a tile.
pub(crate) const EXPECT_TOLERANCE: f32 = 0.05;

/// `oneway_result`: on a level with one-way platforms, 1 if the character ended where the
/// scenario says the seed's rule puts it (`expect_y`: on the platform, or below it), else 0.
/// Frame: the last frame (where the end is read).
pub fn oneway_result(ctx: &Context, rows: Frames) -> Option<Measure> {
    ended_as_expected(ctx, rows, "oneway_result", ctx.level.features.one_way)
}

/// 1 if the last row's feet are within [`EXPECT_TOLERANCE`] of the scenario's `expect_y`, as
/// metric `metric`, when `applies` and the scenario states an `expect_y`; its frame the last
/// row's (the end state is read there).
pub(super) fn ended_as_expected(
    ctx: &Context,
    rows: Frames,
    metric: &'static str,
    applies: bool,
) -> Option<Measure> {
    let expect = ctx.spec.expect_y.filter(|_| applies)?;
    let last = rows.last()?;
    Some(Measure {
        metric,
        value: ((last.y - expect).abs() <= EXPECT_TOLERANCE) as u8 as f64,
        reference: 1.0,
        frame: Some(last.frame),
    })
}

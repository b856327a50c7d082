//! Ladders: climbing speed and where a climb ends.

use super::oneway::ended_as_expected;
use super::{Context, Measure};
use crate::scenario::input_script;
use crate::trace::Frames;

/// `ladder_speed_error`: on a level with ladders, for a scenario that climbs (up or down held),
/// the measured climbing speed minus the configured ladder speed, in tiles/s: the worst over the
/// steps spent on the ladder from start to end while climbing (steps entering or leaving the
/// ladder are not climbing at speed). A character that never climbed measures speed 0.
///
/// Frame: the frame ending the worst step (the first such); for a character that never climbed,
/// the frame ending the first step that held up or down (where it should have climbed).
pub fn ladder_speed_error(ctx: &Context, rows: Frames) -> Option<Measure> {
    let script = input_script(ctx.spec);
    if !ctx.level.features.ladders || !script.iter().any(|i| i.up || i.down) {
        return None;
    }
    let target = ctx.params.ladder_speed as f64;
    let mut worst: Option<f64> = None;
    let mut frame = None;
    for k in 1..rows.len() {
        let i = script[k - 1];
        let (prev, cur) = (rows.at(k - 1), rows.at(k));
        if !(prev.ladder == 1 && cur.ladder == 1 && i.up != i.down && !i.jump) {
            continue;
        }
        let speed = ((cur.y - prev.y) as f64 / ctx.spec.dt as f64).abs();
        let err = speed - target;
        if worst.is_none_or(|w| err.abs() > w.abs()) {
            worst = Some(err);
            frame = Some(cur.frame);
        }
    }
    if worst.is_none() {
        frame = (1..rows.len())
            .find(|&k| script[k - 1].up || script[k - 1].down)
            .map(|k| rows.at(k).frame);
    }
    Some(Measure {
        metric: "ladder_speed_error",
        value: worst.unwrap_or(-target),
        reference: 0.0,
        frame,
    })
}

/// `ladder_result`: on a level with ladders, 1 if the character ended where the scenario says
/// (`expect_y`: at the top, back at the bottom, or on the floor after jumping off), else 0. Not
/// in DESIGN.md's catalog: added so that entering and leaving a ladder is checked, not only the
/// climbing speed. Frame: the last frame (where the end is read).
pub fn ladder_result(ctx: &Context, rows: Frames) -> Option<Measure> {
    ended_as_expected(ctx, rows, "ladder_result", ctx.level.features.ladders)
}

//! Standing still: a character with no input, off ladders and riding no platform, must stay put.

use super::landing::REST_WINDOW;
use super::pushers::Pushers;
use super::reference::Cursor;
use super::{commanded_steps, pos, Context, Measure};
use crate::motion::Input;
use crate::scenario::{input_script, Script};
use crate::trace::{Frames, TraceRow};

/// How much two boxes must overlap across an axis to be side by side along it, in tiles: above
/// f32 rounding of a flush contact, so a wall sliding flush past a character's side is beside
/// it, not against it.
pub(crate) const SIDE_OVERLAP: f32 = 1e-4;

/// Whether row `k` stands still of its own: no input on the step that produced it, grounded,
/// not on a ladder, riding no platform (as the trace says, or standing on one: feet within
/// [`super::platforms::ON_PLATFORM`] plus the platform's step of its top over it, since not every
/// backend names the platform it rides), and not pushed
/// ([`super::pushers::Pushers::carried_or_pushed`]).
fn idle_frame(pushers: &Pushers, script: &Script, rows: Frames, k: usize) -> bool {
    let r = &rows.at(k);
    let idle = script.get(k - 1).is_some_and(|i| *i == Input::default());
    if !idle || !r.is_grounded() || r.ladder != 0 || r.platform.is_some() {
        return false;
    }
    !pushers.carried_or_pushed(rows, k)
}

/// Below this commanded step the shared motion model's friction has stopped the character, in
/// tiles: the glide after releasing a direction is the model's, not a drift.
pub const STOPPED_STEP: f64 = 1e-6;

/// `idle_drift`: over each idle span (consecutive frames with no input, grounded, off ladders,
/// riding and pushed by no platform), the largest displacement from where the character stood
/// once it settled, in tiles; the largest over the spans. It settles at its first frame where
/// neither the shared motion model's commanded walk nor its reported horizontal velocity glides
/// it by [`STOPPED_STEP`] any more and it moved less than 1% of the run speed, and at the latest
/// [`REST_WINDOW`] seconds after the commanded glide ended, whatever it moves or reports (0 if
/// it never stands idle). Reported for every scenario whose script has an idle step and that rides no platform,
/// whatever the controller does, so every configuration is measured on the same scenarios.
///
/// Frame: the first frame at the largest displacement (`None` if it never stood idle).
pub fn idle_drift(ctx: &Context, rows: Frames) -> Option<Measure> {
    let script = input_script(ctx.spec);
    if ctx.spec.ride.is_some() || !script.iter().any(|i| *i == Input::default()) {
        return None;
    }
    let mut commanded = Cursor::new(commanded_steps(
        ctx.params,
        &script,
        ctx.spec.velocity.x,
        ctx.spec.dt,
    ));
    let still = ctx.params.run_speed * ctx.spec.dt * 0.01;
    let settle = (REST_WINDOW / ctx.spec.dt).ceil() as usize;
    let ground = super::ground::Ground::new(ctx.level, ctx.shape, ctx.spec.size);
    let pushers = Pushers::new(ctx, &ground);
    let mut worst: Option<f32> = None;
    let mut frame = None;
    let mut k = 1;
    while k < rows.len() {
        if !idle_frame(&pushers, &script, rows, k) {
            k += 1;
            continue;
        }
        let mut glide_end: Option<usize> = None;
        let mut anchor: Option<TraceRow> = None;
        while k < rows.len() && idle_frame(&pushers, &script, rows, k) {
            let r = rows.at(k);
            let moved = (pos(&r) - pos(&rows.at(k - 1))).length();
            // The commanded glide is over when the shared motion model's walk moves it by less
            // than STOPPED_STEP a step. The velocity the controller reports (a jump off a
            // ladder, a push) may glide it a little longer, but never past REST_WINDOW after
            // the commanded glide: a controller that reports the drift it makes (a slide while
            // standing) is measured from there, as one that reports none.
            let commanded_stopped = commanded.get(k - 1).is_none_or(|c| c.abs() < STOPPED_STEP);
            if commanded_stopped && glide_end.is_none() {
                glide_end = Some(k);
            }
            let stopped = commanded_stopped && ((r.vx * ctx.spec.dt) as f64).abs() < STOPPED_STEP;
            let waited = glide_end.is_some_and(|g| k >= g + settle);
            if anchor.is_none() && ((stopped && moved < still) || waited) {
                anchor = Some(r);
            }
            if let Some(a) = anchor {
                let d = (pos(&r) - pos(&a)).length();
                if worst.is_none_or(|w| d > w) {
                    frame = Some(r.frame);
                }
                worst = Some(worst.map_or(d, |w| w.max(d)));
            }
            k += 1;
        }
    }
    Some(Measure {
        metric: "idle_drift",
        value: worst.unwrap_or(0.0) as f64,
        reference: 0.0,
        frame,
    })
}

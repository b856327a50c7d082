//! What went wrong at each frame, for the report's replay: the per-frame tests behind the
//! metrics (inside the level beyond what the controller declares, stuck on open ground, airborne
//! with the ground within reach, reported grounded over air, crushed), so a reader sees where
//! a metric's count comes from while the character moves.

use super::ground::Ground;
use super::landing::{beyond_declared, supported};
use super::platforms::{platform_depth, CRUSH_DEPTH};
use super::seams::stuck_judge;
use super::Context;
use crate::trace::TraceRow;

/// Inside the level's solid geometry deeper than the configuration declares
/// (`penetration_beyond_declared` at this frame above [`INSIDE_TOLERANCE`]), or its box inside
/// a moving platform that is not one-way by more than that (`push_penetration` at this frame).
pub(crate) const INSIDE: u8 = 1;
/// The step into this frame was stuck on open ground (as `stuck_frames` counts it).
pub(crate) const STUCK: u8 = 2;
/// Airborne, not rising, with the ground within the flicker tolerance under the shape, having
/// left the ground (or stayed in this state) since the frame before: the frames after a switch
/// `grounded_flicker` counts, and a walker hopping down a slope. A fall arriving at the ground
/// is not marked: its frame before was airborne and far.
pub(crate) const AIRBORNE_NEAR_GROUND: u8 = 4;
/// Reported grounded with no ground within the flicker tolerance (as `false_grounded` counts).
pub(crate) const FALSE_GROUNDED: u8 = 8;
/// A moving platform crushed it against the level this frame (the trace's `crushed` column), or
/// its box is inside one by more than [`super::platforms::CRUSH_DEPTH`] (as `crush_count` reads
/// it from the geometry, for a backend without a crush event).
pub(crate) const CRUSHED: u8 = 16;

/// Every fault bit with the words the report shows for it.
pub(crate) const NAMES: [(u8, &str); 5] = [
    (INSIDE, "inside a solid"),
    (STUCK, "stuck"),
    (AIRBORNE_NEAR_GROUND, "airborne, ground near"),
    (FALSE_GROUNDED, "grounded over air"),
    (CRUSHED, "crushed"),
];

/// Overlap beyond the declared contact below which a frame is not marked inside, in tiles: a
/// thousandth of a tile, the threshold the report's static pictures used for their red dots
/// (0.02 px at their 22 px per tile, below what can be seen).
pub(crate) const INSIDE_TOLERANCE: f32 = 1e-3;

/// The fault bits of each of the measured character's rows (the trace's first), in frame order.
pub(crate) fn frame_faults(ctx: &Context) -> Vec<u8> {
    let id = ctx.trace.rows.first().map_or(0, |r| r.character);
    let mut scan = fault_scan(ctx);
    ctx.trace.character(id).map(|r| scan(*r)).collect()
}

/// [`frame_faults`] a row at a time, for rows read as they come: called with each of the
/// measured character's rows in frame order, its fault bits. Reads nothing of `ctx.trace`.
pub(crate) fn fault_scan<'a>(ctx: &'a Context) -> impl FnMut(TraceRow) -> u8 + 'a {
    let g = Ground::new(ctx.level, ctx.shape, ctx.spec.size);
    let mut judge = stuck_judge(ctx);
    // The script's steps run out (or the rows do) once: no step is stuck after that.
    let mut judging = true;
    let mut prev: Option<(TraceRow, u8)> = None;
    let mut k = 0usize;
    move |r: TraceRow| {
        let mut f = 0;
        let in_platform = platform_depth(ctx, &g, &r, k);
        if beyond_declared(ctx, &g, &r) > INSIDE_TOLERANCE || in_platform > INSIDE_TOLERANCE {
            f |= INSIDE;
        }
        // Step k - 1 produced row k.
        if let (Some((before, _)), true) = (&prev, judging) {
            match judge(before, &r) {
                Some(true) => f |= STUCK,
                Some(false) => {}
                None => judging = false,
            }
        }
        let near = supported(ctx, &g, &r);
        let before =
            prev.map(|(row, fault)| (row.is_grounded(), fault & AIRBORNE_NEAR_GROUND != 0));
        let left = matches!(before, Some((true, _)) | Some((_, true)));
        if !r.is_grounded() && near && r.vy <= 0.0 && left {
            f |= AIRBORNE_NEAR_GROUND;
        }
        if r.is_grounded() && !near {
            f |= FALSE_GROUNDED;
        }
        if r.crushed != 0 || in_platform > CRUSH_DEPTH {
            f |= CRUSHED;
        }
        prev = Some((r, f));
        k += 1;
        f
    }
}

/// The words for the fault bits `f`, comma-separated (empty when none).
pub fn describe(f: u8) -> String {
    NAMES
        .iter()
        .filter(|(bit, _)| f & bit != 0)
        .map(|(_, name)| *name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::{parse_level, InputEvent, ScenarioSpec};
    use crate::motion::MotionParams;
    use crate::shape::CharacterShape;
    use crate::trace::Trace;
    use glam::Vec2;

    /// Frames of a bad controller walking right on a floor (top at y = 1): one stuck on open
    /// ground, one sunk into the floor, two hovering just above it after leaving it, one grounded in the
    /// air, one crushed.
    #[test]
    fn each_fault_marks_its_own_frames() {
        let level = parse_level(
            "name = \"m\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n",
            "m.toml",
        )
        .unwrap();
        let spec = ScenarioSpec {
            name: "s".into(),
            spawn: Vec2::new(2.5, 1.0),
            size: Vec2::new(0.8, 0.9),
            velocity: Vec2::ZERO,
            duration: 0.8,
            dt: 0.1,
            inputs: vec![InputEvent {
                t: 0.0,
                right: Some(true),
                ..Default::default()
            }],
            motion: Default::default(),
            expect_y: None,
            ride: None,
            expect: Default::default(),
        };
        // (x, y, grounded, vy, crushed)
        let pts = [
            (2.5, 1.0, true, 0.0, false),
            (2.8, 1.0, true, 0.0, false),
            (2.8, 1.0, true, 0.0, false),   // did not move: stuck
            (3.1, 0.8, true, 0.0, false),   // 0.2 tiles into the floor
            (3.4, 1.05, false, 0.0, false), // left the ground, 0.05 above it
            (3.7, 1.05, false, -0.1, false),
            (4.0, 1.9, true, 0.0, false), // grounded 0.9 above the floor
            (4.3, 1.0, true, 0.0, true),
        ];
        let trace = Trace {
            level: "m".into(),
            scenario: "s".into(),
            backend: "fake".into(),
            config: "default".into(),
            rows: pts
                .iter()
                .enumerate()
                .map(|(k, &(x, y, g, vy, c))| TraceRow {
                    frame: k as u32,
                    t: k as f32 * 0.1,
                    character: 0,
                    x,
                    y,
                    vx: 0.0,
                    vy,
                    grounded: g as u8,
                    ground_nx: 0.0,
                    ground_ny: 0.0,
                    platform: None,
                    ladder: 0,
                    crushed: c as u8,
                })
                .collect(),
        };
        let params = MotionParams::default();
        let f = frame_faults(&Context {
            shape: CharacterShape::Cuboid,
            level: &level,
            spec: &spec,
            params: &params,
            trace: &trace,
            declared: Default::default(),
        });
        assert_eq!(
            f,
            [
                0,
                0,
                STUCK,
                INSIDE,
                AIRBORNE_NEAR_GROUND,
                AIRBORNE_NEAR_GROUND,
                FALSE_GROUNDED,
                CRUSHED
            ]
        );
        assert_eq!(describe(INSIDE | CRUSHED), "inside a solid, crushed");
    }

    /// A box inside a platform rising at 1 tile/s: inside beyond 1e-3 tiles, crushed beyond
    /// CRUSH_DEPTH (0.25), whatever the trace's crush column says.
    #[test]
    fn a_box_inside_a_platform_is_inside_then_crushed() {
        let level = parse_level(
            "name = \"m\"\nmap = \"\"\"\n..........\n..........\n##########\n\"\"\"\n[[platform]]\nrect = [4.0, 1.0, 2.0, 0.5]\npath = [[4.0, 1.0], [4.0, 3.0]]\nspeed = 1.0\n",
            "m.toml",
        )
        .unwrap();
        let spec = ScenarioSpec {
            name: "s".into(),
            spawn: Vec2::new(2.5, 1.0),
            size: Vec2::new(0.8, 0.9),
            velocity: Vec2::ZERO,
            duration: 0.2,
            dt: 0.1,
            inputs: vec![],
            motion: Default::default(),
            expect_y: None,
            ride: None,
            expect: Default::default(),
        };
        // Feet at x 2.5 (clear), 3.7 (box edge 4.1: 0.1 into the platform), 4.5 (0.5 into it).
        let row = |k: u32, x: f32| TraceRow {
            frame: k,
            t: k as f32 * 0.1,
            character: 0,
            x,
            y: 1.0,
            vx: 0.0,
            vy: 0.0,
            grounded: 1,
            ground_nx: 0.0,
            ground_ny: 1.0,
            platform: None,
            ladder: 0,
            crushed: 0,
        };
        let trace = Trace {
            level: "m".into(),
            scenario: "s".into(),
            backend: "fake".into(),
            config: "default".into(),
            rows: vec![row(0, 2.5), row(1, 3.7), row(2, 4.5)],
        };
        let params = MotionParams::default();
        let f = frame_faults(&Context {
            shape: CharacterShape::Cuboid,
            level: &level,
            spec: &spec,
            params: &params,
            trace: &trace,
            declared: Default::default(),
        });
        assert_eq!(f, [0, INSIDE, INSIDE | CRUSHED]);
    }
}

//! The data a replay's script plays, as the inline JSON of each `<div class="replay">`: per
//! drawn frame, each run's state as its trace has it (position, velocity, grounded, ground
//! normal, ladder and platform, faults) and each moving platform's corner. Numbers are fixed
//! point, delta and run-length coded ([`pack`]): a run walking at a steady speed or falling
//! at a steady acceleration codes in a few characters, which keeps the built-in report (64
//! scenarios of 21 configurations, up to [`super::replay::MAX_DRAWN_FRAMES`] frames each) one
//! file under 10 MB with the state the reader inspects frame by frame.

use std::fmt::Write as _;

use glam::Vec2;

use super::replay::{DrawnRun, Style, SCALE};
use crate::level::{Level, ScenarioSpec};
use crate::metrics::faults;
use crate::trace::TraceRow;

/// Positions, in 1/1000 tile: finer than a pixel of the picture (1/22 tile) and than the three
/// decimals the state table shows.
pub(crate) const POSITION_UNIT: f64 = 1000.0;
/// Velocities and normals, in 1/1000: the state table shows three decimals.
pub(crate) const VECTOR_UNIT: f64 = 1000.0;

/// `values` (already in fixed point) as comma-separated differences from the previous value
/// (the first from 0), a difference repeated `n` times written once as `d*n`. The script's
/// `unpack` reverses it.
pub(crate) fn pack(values: impl IntoIterator<Item = i64>) -> String {
    let mut out = String::new();
    let mut prev = 0i64;
    let mut run: Option<(i64, usize)> = None;
    let flush = |out: &mut String, (d, n): (i64, usize)| {
        if !out.is_empty() {
            out.push(',');
        }
        let _ = if n > 1 {
            write!(out, "{d}*{n}")
        } else {
            write!(out, "{d}")
        };
    };
    for v in values {
        let d = v.saturating_sub(prev);
        prev = v;
        run = match run {
            Some((rd, n)) if rd == d => Some((rd, n + 1)),
            Some(r) => {
                flush(&mut out, r);
                Some((d, 1))
            }
            None => Some((d, 1)),
        };
    }
    if let Some(r) = run {
        flush(&mut out, r);
    }
    out
}

/// `v` in fixed point of `unit`; a non-finite value as 0 (the picture has nowhere to put it).
fn fixed(v: f32, unit: f64) -> i64 {
    if v.is_finite() {
        // `as` saturates: a value beyond i64 (1e16 tiles) stays at the bound.
        (v as f64 * unit).round() as i64
    } else {
        0
    }
}

/// A number for the JSON: one decimal of a pixel, 0 for a non-finite one.
pub(crate) fn px(v: f32) -> String {
    if v.is_finite() {
        let s = format!("{v:.1}");
        s.strip_suffix(".0").unwrap_or(&s).to_string()
    } else {
        "0".into()
    }
}

/// The state bits of a row, as one character `'0' + bits`: 1 grounded, 2 on a ladder, 4 on a
/// moving platform.
fn state_char(r: &TraceRow) -> char {
    let bits = u8::from(r.is_grounded())
        | (u8::from(r.ladder != 0) << 1)
        | (u8::from(r.platform.is_some()) << 2);
    char::from(b'0' + bits)
}

/// The drawn frames as JSON: time step, stride, frame count, fault names, the picture's origin
/// (`ox`, `oy`: the level point at pixel 0, 0) and scale, each platform's corner per drawn frame
/// (pixels), and per run: half its height (`h`, tiles), its position (`x`, `y`: feet, tiles),
/// velocity (`vx`, `vy`, tiles/s) and ground normal (`nx`, `ny`) per drawn frame, [`pack`]ed;
/// its state bits (`s`, [`state_char`]) and faults (`f`, `'0'` plus the fault bits of the
/// frames the drawn frame stands for) as one character per drawn frame.
pub(crate) fn replay_json(
    level: &Level,
    spec: &ScenarioSpec,
    rows: &[(DrawnRun, &Style)],
    picked: &[usize],
    stride: usize,
    origin: Vec2,
    to_px: &impl Fn(Vec2) -> (f32, f32),
) -> String {
    let frames = picked.last().map_or(0, |l| l + 1);
    let mut j = format!(
        "{{\"dt\":{},\"stride\":{stride},\"frames\":{frames},\"scale\":{SCALE},\"ox\":{},\"oy\":{},\"pu\":{POSITION_UNIT},\"vu\":{VECTOR_UNIT},\"names\":[",
        spec.dt, origin.x, origin.y
    );
    for (i, (bit, name)) in faults::NAMES.iter().enumerate() {
        let _ = write!(j, "{}[{bit},\"{name}\"]", if i > 0 { "," } else { "" });
    }
    j.push_str("],\"platforms\":[");
    let times: Vec<f64> = picked
        .iter()
        .enumerate()
        .map(|(i, &f)| {
            rows.iter()
                .find_map(|(run, _)| run.rows.get(i).map(|r| r.t as f64))
                .unwrap_or(f as f64 * spec.dt as f64)
        })
        .collect();
    for (pi, p) in level.platforms.iter().enumerate() {
        let (mut xs, mut ys) = (Vec::new(), Vec::new());
        for &t in &times {
            let b = p.aabb(t);
            let (x, y) = to_px(Vec2::new(b.mins.x, b.maxs.y));
            xs.push(px(x));
            ys.push(px(y));
        }
        let _ = write!(
            j,
            "{}{{\"x\":[{}],\"y\":[{}]}}",
            if pi > 0 { "," } else { "" },
            xs.join(","),
            ys.join(",")
        );
    }
    j.push_str("],\"runs\":[");
    for (k, (run, _)) in rows.iter().enumerate() {
        let drawn = &run.rows;
        let faults: String = (0..drawn.len())
            .map(|i| char::from(b'0' + run.faults.get(i).copied().unwrap_or(0)))
            .collect();
        let channel =
            |f: fn(&TraceRow) -> f32, unit: f64| pack(drawn.iter().map(|r| fixed(f(r), unit)));
        let _ = write!(
            j,
            "{}{{\"h\":{},\"x\":\"{}\",\"y\":\"{}\",\"vx\":\"{}\",\"vy\":\"{}\",\"nx\":\"{}\",\"ny\":\"{}\",\"s\":\"{}\",\"f\":\"{faults}\"}}",
            if k > 0 { "," } else { "" },
            run.size.y * 0.5,
            channel(|r| r.x, POSITION_UNIT),
            channel(|r| r.y, POSITION_UNIT),
            channel(|r| r.vx, VECTOR_UNIT),
            channel(|r| r.vy, VECTOR_UNIT),
            channel(|r| r.ground_nx, VECTOR_UNIT),
            channel(|r| r.ground_ny, VECTOR_UNIT),
            drawn.iter().map(state_char).collect::<String>(),
        );
    }
    j.push_str("]}");
    // Inside <script>, "</" would end the element: JSON allows "<" escaped.
    j.replace('<', "\\u003c")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the script's `unpack` does, for the test.
    fn unpack(s: &str) -> Vec<i64> {
        let mut out = Vec::new();
        let mut v = 0;
        for tok in s.split(',').filter(|t| !t.is_empty()) {
            let (d, n) = tok.split_once('*').unwrap_or((tok, "1"));
            for _ in 0..n.parse::<usize>().unwrap() {
                v += d.parse::<i64>().unwrap();
                out.push(v);
            }
        }
        out
    }

    #[test]
    fn packing_round_trips_and_codes_steady_motion_short() {
        let walk: Vec<i64> = (0..300).map(|k| 2000 + 100 * k).collect();
        assert_eq!(pack(walk.clone()), "2000,100*299");
        assert_eq!(unpack(&pack(walk.clone())), walk);
        let jumpy = vec![5, -3, -3, 7, 7, 7, 0];
        assert_eq!(pack(jumpy.clone()), "5,-8,0,10,0*2,-7");
        assert_eq!(unpack(&pack(jumpy.clone())), jumpy);
        assert_eq!(pack(Vec::new()), "");
        assert_eq!(fixed(f32::NAN, POSITION_UNIT), 0);
        assert_eq!(fixed(-1.25, POSITION_UNIT), -1250);
    }
}

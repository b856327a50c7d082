//! The generator: case `index` of seed `seed` is a small level and input script drawn from the
//! ranges below (docs/hunt.md lists them), the same on every machine and with any number of
//! threads, since each case has a random stream of its own.
//!
//! Every level has a floor; on it, in some cases: pits, a wall at each side with a ceiling,
//! solid blocks, a ramp (45, 26.6 or 63.4 degrees, either way, or height-array tiles), a run of
//! one-way tiles, a ladder and up to two moving platforms (back and forth on a path or on a
//! sine). The character spawns above the floor, drops, then runs, jumps, drops through, climbs
//! and stops; or it rides a platform whose path nothing blocks, idle.

use fastrand::Rng;

use super::sketch::{Button, Cell, Event, Expect, Motion, PlatformSketch, Sketch};

/// The generator's ranges, in tiles, seconds and tiles/s.
pub(crate) mod ranges {
    /// Map width (tiles).
    pub(crate) const WIDTH: (usize, usize) = (8, 20);
    /// Map height (tiles).
    pub(crate) const HEIGHT: (usize, usize) = (6, 10);
    /// Scenario length (s), before the final idle span.
    pub(crate) const ACTIVE: (f32, f32) = (0.5, 4.0);
    /// The final idle span when there is one (s): long enough to land from anywhere and then
    /// rest the 0.5 s the rest metrics read.
    pub(crate) const IDLE: (f32, f32) = (1.5, 2.5);
    /// Platform speed on a path (tiles/s).
    pub(crate) const PLATFORM_SPEED: (f32, f32) = (0.5, 6.0);
    /// A sine platform's period (s).
    pub(crate) const SINE_PERIOD: (f32, f32) = (2.0, 6.0);
}

/// A number in `lo..hi` on a grid of `step` (generated numbers are round: a found case reads
/// well before it is shrunk).
fn pick(rng: &mut Rng, (lo, hi): (f32, f32), step: f32) -> f32 {
    let n = ((hi - lo) / step).floor() as u32;
    lo + rng.u32(0..=n) as f32 * step
}

/// The random stream of case `index` of `seed`.
pub(crate) fn case_rng(seed: u64, index: u64) -> Rng {
    let bytes = seed.to_le_bytes().into_iter().chain(index.to_le_bytes());
    Rng::with_seed(crate::input::fnv1a64(bytes))
}

/// Case `index` of `seed`.
pub(crate) fn generate(seed: u64, index: u64) -> Sketch {
    let mut rng = case_rng(seed, index);
    let rng = &mut rng;
    let w = rng.usize(ranges::WIDTH.0..=ranges::WIDTH.1);
    let h = rng.usize(ranges::HEIGHT.0..=ranges::HEIGHT.1);
    let mut rows = vec![vec![Cell::Empty; w]; h];
    rows[0] = vec![Cell::Solid; w];
    let boxed = rng.bool();
    if boxed {
        for row in rows.iter_mut() {
            row[0] = Cell::Solid;
            row[w - 1] = Cell::Solid;
        }
        rows[h - 1] = vec![Cell::Solid; w];
    }
    let pits = rng.u32(0..4) == 0;
    if pits {
        let at = rng.usize(2..w - 3);
        for c in &mut rows[0][at..at + rng.usize(1..=2)] {
            *c = Cell::Empty;
        }
    }
    // Solid blocks on the floor: one to three, 1-2 wide, 1-2 high.
    for _ in 0..rng.usize(0..=3) {
        let (bw, bh) = (rng.usize(1..=2), rng.usize(1..=2));
        let i = rng.usize(1..w - bw);
        for row in rows.iter_mut().take(1 + bh).skip(1) {
            for c in &mut row[i..i + bw] {
                *c = Cell::Solid;
            }
        }
    }
    let mut steep = false;
    if rng.bool() {
        steep = ramp(rng, &mut rows);
    }
    if rng.u32(0..3) == 0 {
        let j = rng.usize(2..=(h - 2).min(4));
        let len = rng.usize(2..=4).min(w - 2);
        let i = rng.usize(1..w - len);
        for c in &mut rows[j][i..i + len] {
            if *c == Cell::Empty {
                *c = Cell::OneWay;
            }
        }
    }
    let ladder = rng.u32(0..4) == 0;
    if ladder {
        let i = rng.usize(1..w - 1);
        let top = rng.usize(2..=(h - 2).min(5));
        for row in rows.iter_mut().take(top + 1).skip(1) {
            row[i] = Cell::Ladder;
        }
    }
    let mut platforms = Vec::new();
    for _ in 0..rng.usize(0..=2).saturating_sub(usize::from(rng.bool())) {
        // Platforms apart: one whose reach (with room for a rider) meets another's is dropped.
        let p = platform(rng, w, h);
        if platforms.iter().all(|q| apart(q, &p)) {
            platforms.push(p);
        }
    }
    let ride = (!platforms.is_empty() && rng.u32(0..3) == 0).then(|| rng.usize(0..platforms.len()));
    let (spawn, events, duration) = match ride {
        Some(k) => {
            // The ride's path and the rider above it are kept clear, so the platform is one
            // the rider can follow.
            clear_path(&mut rows, &platforms[k]);
            let p = &platforms[k];
            let spawn = [p.at[0] + p.size[0] / 2.0, p.at[1] + p.size[1]];
            (spawn, Vec::new(), pick(rng, (2.0, 5.0), 0.5))
        }
        None => {
            // A column with room for the character under the top row (a ceiling), or the
            // last one tried (the case then fails to load and is skipped, said in docs).
            let mut x = pick(rng, (1.5, w as f32 - 1.5), 0.5);
            for _ in 0..8 {
                if top_under(&rows, x) <= h as f32 - 2.0 {
                    break;
                }
                x = pick(rng, (1.5, w as f32 - 1.5), 0.5);
            }
            let drop = pick(rng, (0.0, 2.0), 0.5);
            let y = (top_under(&rows, x) + drop)
                .min(h as f32 - 2.0)
                .max(top_under(&rows, x));
            let (events, active) = script(rng, ladder);
            let idle = if rng.u32(0..4) != 0 {
                pick(rng, ranges::IDLE, 0.5)
            } else {
                0.0
            };
            ([x, y], events, (active + idle).max(1.0))
        }
    };
    let ends_idle = events.last().is_none_or(|e| duration - e.t >= 1.5);
    let expect = Expect {
        // A floor with no pit: nothing may fall through it (a quarter tile below its top is
        // beyond any controller's declared overlap).
        min_y: (!pits).then_some(0.75),
        stay_in_map: boxed && !pits,
        grounded_at_end: (ends_idle
            && !pits
            && !ladder
            && !steep
            && platforms.is_empty()
            && rows.iter().flatten().all(|c| *c != Cell::OneWay))
        .then_some(true),
    };
    Sketch {
        rows,
        platforms,
        spawn,
        duration,
        events,
        ride,
        expect,
    }
}

/// The height of the highest non-empty cell below the top row under the character's box at `x`
/// (0.8 wide) plus one: where its feet start when it spawns there before dropping.
fn top_under(rows: &[Vec<Cell>], x: f32) -> f32 {
    let w = rows[0].len();
    let lo = ((x - 0.4).floor().max(0.0)) as usize;
    let hi = ((x + 0.4).floor() as usize).min(w - 1);
    // The top row is left out: it is empty or a ceiling, which nobody spawns on.
    (0..rows.len() - 1)
        .rev()
        .find(|&j| rows[j][lo..=hi].iter().any(|c| *c != Cell::Empty))
        .map_or(0.0, |j| j as f32 + 1.0)
}

/// Places one ramp on the floor; returns whether it is steeper than the climb limit.
fn ramp(rng: &mut Rng, rows: &mut [Vec<Cell>]) -> bool {
    let w = rows[0].len();
    let kind = rng.u32(0..4);
    let rising_right = rng.bool();
    // (cells per row, rows): a straight ramp's tiles, bottom row first, left to right.
    let tiles: Vec<Vec<u8>> = match (kind, rising_right) {
        (0, true) => vec![vec![0]],
        (0, false) => vec![vec![1]],
        (1, true) => vec![vec![2, 3]],
        (1, false) => vec![vec![4, 5]],
        (2, true) => vec![vec![6], vec![7]],
        (2, false) => vec![vec![8], vec![9]],
        _ => vec![vec![10]],
    };
    let len = tiles[0].len();
    let steps = if kind == 2 { 1 } else { rng.usize(1..=2) };
    let span = len * steps + 1;
    if w < span + 3 {
        return false;
    }
    let start = rng.usize(1..w - span - 1);
    for s in 0..steps {
        // Each step of the ramp sits one row higher, with solid under it.
        for (dj, row) in tiles.iter().enumerate() {
            for (di, &k) in row.iter().enumerate() {
                let i = if rising_right {
                    start + s * len + di
                } else {
                    start + (steps - 1 - s) * len + di + 1
                };
                let j = 1 + s + dj;
                if j < rows.len() - 1 {
                    rows[j][i] = Cell::Ramp(k);
                    for row in rows.iter_mut().take(j).skip(1) {
                        if row[i] == Cell::Empty {
                            row[i] = Cell::Solid;
                        }
                    }
                }
            }
        }
    }
    // The top of the ramp: a solid column to walk onto.
    let top = if rising_right {
        start + steps * len
    } else {
        start
    };
    let height = (steps * tiles.len()).min(rows.len() - 2);
    for row in rows.iter_mut().take(height + 1).skip(1) {
        if row[top] == Cell::Empty {
            row[top] = Cell::Solid;
        }
    }
    kind == 2
}

/// A platform inside a `w` x `h` map.
fn platform(rng: &mut Rng, w: usize, h: usize) -> PlatformSketch {
    let size = [pick(rng, (1.0, 3.0), 1.0), 0.5];
    let x = pick(rng, (1.0, w as f32 - 1.0 - size[0]), 1.0);
    let y = pick(rng, (2.0, h as f32 - 3.0), 0.5);
    let motion = if rng.u32(0..3) == 0 {
        // Within the map: x from 1 to w - 1, y from 1.5 to h - 2.5.
        let room = [
            (x - 1.0).min(w as f32 - 1.0 - size[0] - x).max(0.0),
            (y - 1.5).min(h as f32 - 2.5 - y).max(0.0),
        ];
        Motion::Sine {
            amplitude: [
                pick(rng, (0.0, 2.0), 0.5).min(room[0]),
                pick(rng, (0.0, 1.5), 0.5).min(room[1]),
            ],
            period: pick(rng, ranges::SINE_PERIOD, 0.5),
        }
    } else {
        let (dx, dy) = match rng.u32(0..3) {
            0 => (pick(rng, (-3.0, 3.0), 1.0), 0.0),
            1 => (0.0, pick(rng, (-2.0, 2.0), 0.5)),
            _ => (pick(rng, (-2.0, 2.0), 1.0), pick(rng, (-1.5, 1.5), 0.5)),
        };
        let mut to = [
            (x + dx).clamp(1.0, w as f32 - 1.0 - size[0]),
            (y + dy).clamp(1.5, h as f32 - 2.5),
        ];
        if to == [x, y] {
            // A path of some length: a tile up, or down where there is no room above.
            to[1] = if y + 1.0 <= h as f32 - 2.5 {
                y + 1.0
            } else {
                y - 1.0
            };
        }
        Motion::Path {
            to,
            speed: pick(rng, ranges::PLATFORM_SPEED, 0.5),
        }
    };
    PlatformSketch {
        at: [x, y],
        size,
        motion,
        one_way: rng.u32(0..4) == 0,
    }
}

/// Whether two platforms' reaches (with their riders) do not meet.
fn apart(a: &PlatformSketch, b: &PlatformSketch) -> bool {
    let ((alo, ahi), (blo, bhi)) = (a.reach(), b.reach());
    alo[0] >= bhi[0] || blo[0] >= ahi[0] || alo[1] >= bhi[1] || blo[1] >= ahi[1]
}

/// Empties the cells the platform `p` sweeps, with the two rows above it where its rider
/// stands (the floor row stays).
fn clear_path(rows: &mut [Vec<Cell>], p: &PlatformSketch) {
    let (lo, hi) = p.reach();
    let (w, h) = (rows[0].len() as f32, rows.len());
    let i0 = lo[0].floor().max(0.0) as usize;
    let i1 = (hi[0].ceil().min(w)) as usize;
    let j0 = (lo[1].floor().max(1.0)) as usize;
    let j1 = (hi[1].ceil() as usize).min(h);
    for row in rows.iter_mut().take(j1).skip(j0) {
        for c in row.iter_mut().take(i1).skip(i0) {
            *c = Cell::Empty;
        }
    }
}

/// An input script: runs, jumps, drops through, climbs and stops, 0.5 to 4 s long; returns
/// the events and the time the last action ends.
fn script(rng: &mut Rng, ladder: bool) -> (Vec<Event>, f32) {
    let mut events = Vec::new();
    let mut t = pick(rng, (0.0, 0.5), 0.1);
    let end = pick(rng, ranges::ACTIVE, 0.25);
    let mut e = |t: f32, button, down| events.push(Event { t, button, down });
    while t < end {
        let hold = pick(rng, (0.1, 1.5), 0.1);
        let button = match rng.u32(0..10) {
            0..=2 => Button::Right,
            3..=5 => Button::Left,
            6 | 7 => Button::Jump,
            8 => Button::Down,
            _ if ladder => Button::Up,
            _ => Button::Right,
        };
        let hold = if button == Button::Jump {
            pick(rng, (0.05, 0.4), 0.05)
        } else {
            hold
        };
        e(t, button, true);
        // A jump may come while running: the run goes on under it.
        let overlap = button != Button::Jump && rng.u32(0..3) == 0;
        if overlap {
            e(t + hold / 2.0, Button::Jump, true);
            e(t + hold / 2.0 + 0.2, Button::Jump, false);
        }
        e(t + hold, button, false);
        t += hold + pick(rng, (0.0, 0.5), 0.1);
    }
    events.sort_by(|a, b| a.t.total_cmp(&b.t));
    let last = events.last().map_or(0.0, |e| e.t);
    (events, last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_case_is_the_same_for_the_same_seed_and_index() {
        assert_eq!(generate(7, 3), generate(7, 3));
        assert_ne!(generate(7, 3), generate(7, 4));
        assert_ne!(generate(7, 3), generate(8, 3));
    }

    #[test]
    fn every_generated_case_parses_within_the_ranges() {
        for i in 0..400 {
            let s = generate(1, i);
            let level = s
                .level("hunt_case")
                .unwrap_or_else(|e| panic!("case {i}: {e}\n{}", s.toml("hunt_case", &[])));
            let (w, h) = (level.width as usize, level.height as usize);
            assert!((ranges::WIDTH.0..=ranges::WIDTH.1).contains(&w), "case {i}");
            assert!(
                (ranges::HEIGHT.0..=ranges::HEIGHT.1).contains(&h),
                "case {i}"
            );
            let spec = &level.scenarios[0];
            // The active part ends at most a hold (1.5 s) past ACTIVE's end, then the idle.
            let longest = ranges::ACTIVE.1 + 1.5 + ranges::IDLE.1;
            assert!(
                spec.duration > 0.0 && spec.duration <= longest,
                "case {i}: {}",
                spec.duration
            );
            for p in &level.platforms {
                // Every platform's reach inside the map.
                let (lo, hi) = p.reach();
                assert!(lo.x >= 0.0 && hi.x <= w as f64, "case {i}: {lo} {hi}");
                assert!(lo.y >= 0.0 && hi.y <= h as f64, "case {i}: {lo} {hi}");
            }
        }
    }
}

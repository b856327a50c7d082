//! The shrinker: a failing case made smaller, one change at a time, keeping each change that
//! still fails the same invariant on the same configuration (greedy, to a fixed point or the
//! limit of tries): fewer platforms and input events, a shorter run, fewer rows and columns
//! (in blocks, then one by one), fewer tiles, rounder numbers.

use super::sketch::{Cell, Event, Motion, Sketch};

/// At most this many candidate cases are run to shrink one failure: enough for the passes to
/// reach a fixed point on the generator's largest case (20 x 10 tiles, about 60 events) in
/// practice, and a bound on the time one failure takes.
pub(crate) const MAX_TRIES: usize = 600;

/// How a shrink went.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Shrunk {
    /// The smallest failing case found.
    pub(crate) sketch: Sketch,
    /// Candidates run.
    pub(crate) tries: usize,
    /// Whether it stopped before a fixed point (the tries or the time ran out).
    pub(crate) cut_short: bool,
}

/// Shrinks `start`, which `fails`; `fails` runs a candidate and says whether it still breaks
/// the invariant. `stop` says when the time is up.
pub(crate) fn shrink(
    start: Sketch,
    fails: &mut dyn FnMut(&Sketch) -> bool,
    stop: &dyn Fn() -> bool,
) -> Shrunk {
    let mut s = Shrinker {
        best: start,
        tries: 0,
        cut_short: false,
        fails,
        stop,
    };
    loop {
        let before = s.best.clone();
        s.platforms();
        s.events();
        s.duration();
        s.rows();
        s.columns();
        s.tiles();
        s.round();
        if s.best == before || s.cut_short {
            break;
        }
    }
    Shrunk {
        sketch: s.best,
        tries: s.tries,
        cut_short: s.cut_short,
    }
}

struct Shrinker<'a> {
    best: Sketch,
    tries: usize,
    cut_short: bool,
    fails: &'a mut dyn FnMut(&Sketch) -> bool,
    stop: &'a dyn Fn() -> bool,
}

impl Shrinker<'_> {
    /// Tries `candidate`; keeps it when it still fails.
    fn attempt(&mut self, mut candidate: Sketch) -> bool {
        candidate.keep_premises();
        // The character's box starts inside the map's sides (rounding or removing columns
        // must not leave half of it outside).
        let w = candidate.width() as f32;
        if candidate.spawn[0] - 0.4 < 0.0 || candidate.spawn[0] + 0.4 > w {
            return false;
        }
        if self.cut_short || candidate == self.best {
            return false;
        }
        if self.tries >= MAX_TRIES || (self.stop)() {
            self.cut_short = true;
            return false;
        }
        self.tries += 1;
        if (self.fails)(&candidate) {
            self.best = candidate;
            true
        } else {
            false
        }
    }

    fn platforms(&mut self) {
        let mut k = self.best.platforms.len();
        while k > 0 {
            k -= 1;
            let mut c = self.best.clone();
            c.platforms.remove(k);
            c.ride = match c.ride {
                Some(r) if r == k => None,
                Some(r) if r > k => Some(r - 1),
                r => r,
            };
            self.attempt(c);
        }
    }

    fn events(&mut self) {
        // All at once, then halves, then one by one from the end.
        let mut c = self.best.clone();
        c.events.clear();
        self.attempt(c);
        let mut k = self.best.events.len();
        while k > 0 {
            k -= 1;
            if k >= self.best.events.len() {
                continue;
            }
            let mut c = self.best.clone();
            let e = c.events.remove(k);
            // A press goes with its release.
            if e.down {
                if let Some(r) = c.events[k..]
                    .iter()
                    .position(|o| o.button == e.button && !o.down)
                {
                    c.events.remove(k + r);
                }
            }
            self.attempt(c);
        }
    }

    fn duration(&mut self) {
        for cut in [0.5, 0.75, 0.9] {
            let mut c = self.best.clone();
            c.duration = ((c.duration * cut * 4.0).round() / 4.0).max(0.25);
            c.events.retain(|e| e.t < c.duration);
            self.attempt(c);
        }
        loop {
            let mut c = self.best.clone();
            c.duration -= 0.25;
            if c.duration < 0.25 {
                break;
            }
            c.events.retain(|e| e.t < c.duration);
            if !self.attempt(c) {
                break;
            }
        }
    }
}

/// `s` without row `j` (from the bottom): what lies above it comes down a tile; a row the
/// spawn or a platform is in stays.
fn without_row(s: &Sketch, j: usize) -> Option<Sketch> {
    let mut c = s.clone();
    if c.rows.len() <= 2 {
        return None;
    }
    let (lo, hi) = (j as f32, j as f32 + 1.0);
    let inside = |y: f32| y > lo && y < hi;
    // A row a platform sweeps stays (its reach would change).
    if inside(c.spawn[1])
        || c.platforms.iter().any(|p| {
            let (plo, phi) = p.reach();
            plo[1] < hi && phi[1] > lo
        })
    {
        return None;
    }
    c.rows.remove(j);
    let down = |y: &mut f32| {
        if *y >= hi {
            *y -= 1.0;
        }
    };
    down(&mut c.spawn[1]);
    for p in &mut c.platforms {
        down(&mut p.at[1]);
        if let Motion::Path { to, .. } = &mut p.motion {
            down(&mut to[1]);
        }
    }
    if let Some(y) = &mut c.expect.min_y {
        down(y);
    }
    Some(c)
}

/// `s` without column `i`: what lies right of it comes left a tile; a column the spawn or a
/// platform is in stays.
fn without_column(s: &Sketch, i: usize) -> Option<Sketch> {
    let mut c = s.clone();
    if c.width() <= 2 {
        return None;
    }
    let (lo, hi) = (i as f32, i as f32 + 1.0);
    let overlaps = |x0: f32, x1: f32| x0 < hi && x1 > lo;
    if overlaps(c.spawn[0] - 0.4, c.spawn[0] + 0.4)
        || c.platforms.iter().any(|p| {
            let (plo, phi) = p.reach();
            overlaps(plo[0], phi[0])
        })
    {
        return None;
    }
    for row in &mut c.rows {
        row.remove(i);
    }
    let left = |x: &mut f32| {
        if *x >= hi {
            *x -= 1.0;
        }
    };
    left(&mut c.spawn[0]);
    for p in &mut c.platforms {
        left(&mut p.at[0]);
        if let Motion::Path { to, .. } = &mut p.motion {
            left(&mut to[0]);
        }
    }
    Some(c)
}

impl Shrinker<'_> {
    fn rows(&mut self) {
        let mut j = self.best.height();
        while j > 0 {
            j -= 1;
            if let Some(c) = without_row(&self.best, j) {
                self.attempt(c);
            }
        }
    }

    fn columns(&mut self) {
        // Blocks of a quarter of the width from the right first, then single columns.
        let quarter = (self.best.width() / 4).max(2);
        let mut i = self.best.width();
        while i >= quarter {
            i -= quarter;
            let block = (i..i + quarter)
                .rev()
                .try_fold(self.best.clone(), |c, k| without_column(&c, k));
            if let Some(c) = block {
                self.attempt(c);
            }
        }
        let mut i = self.best.width();
        while i > 0 {
            i -= 1;
            if let Some(c) = without_column(&self.best, i) {
                self.attempt(c);
            }
        }
    }

    fn tiles(&mut self) {
        for j in (0..self.best.height()).rev() {
            for i in 0..self.best.width() {
                if self.best.rows.get(j).and_then(|r| r.get(i)) != Some(&Cell::Empty) {
                    let mut c = self.best.clone();
                    if let Some(cell) = c.rows.get_mut(j).and_then(|r| r.get_mut(i)) {
                        *cell = Cell::Empty;
                    }
                    self.attempt(c);
                }
            }
        }
    }

    fn round(&mut self) {
        let round = |v: f32, step: f32| (v / step).round() * step;
        for step in [1.0, 0.5] {
            let mut c = self.best.clone();
            c.spawn[0] = round(c.spawn[0], step).max(0.5);
            self.attempt(c);
            let mut c = self.best.clone();
            let t = |e: &Event| Event {
                t: round(e.t, step / 2.0),
                ..*e
            };
            c.events = c.events.iter().map(t).collect();
            c.events.sort_by(|a, b| a.t.total_cmp(&b.t));
            self.attempt(c);
            let mut c = self.best.clone();
            for p in &mut c.platforms {
                if let Motion::Path { speed, .. } = &mut p.motion {
                    *speed = round(*speed, step).max(step);
                }
            }
            self.attempt(c);
        }
    }
}

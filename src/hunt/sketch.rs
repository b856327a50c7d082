//! A generated case as hunt holds it ([`Sketch`]): a small tile grid, its moving platforms and
//! one scenario, written out as a level file in platbench's own TOML format ([`Sketch::toml`]).
//! Every run of a case parses that text ([`Sketch::level`]), so the file a finding is written
//! to is exactly the level that failed.

use std::fmt::Write;

use crate::level::{parse_level, Level, LevelError};

/// What one cell of a sketch holds: the built-in map characters and the ramps of [`RAMPS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Cell {
    /// `.`
    Empty,
    /// `#`
    Solid,
    /// `=`
    OneWay,
    /// `H`
    Ladder,
    /// A sloped tile: an index into [`RAMPS`].
    Ramp(u8),
}

/// The sloped tiles hunt places: (map character, legend value, what it is). Each ramp's tiles
/// come in the pairs a straight ramp of its angle needs.
pub(crate) const RAMPS: [(char, &str, &str); 11] = [
    ('/', "", "45 degrees rising right"),
    ('\\', "", "45 degrees rising left"),
    (
        'a',
        "{ line = [0.0, 0.5] }",
        "26.6 degrees rising right, lower half",
    ),
    (
        'b',
        "{ line = [0.5, 1.0] }",
        "26.6 degrees rising right, upper half",
    ),
    (
        'c',
        "{ line = [1.0, 0.5] }",
        "26.6 degrees rising left, upper half",
    ),
    (
        'd',
        "{ line = [0.5, 0.0] }",
        "26.6 degrees rising left, lower half",
    ),
    (
        'e',
        "{ line = [0.0, 2.0] }",
        "63.4 degrees rising right, lower tile",
    ),
    (
        'f',
        "{ line = [-1.0, 1.0] }",
        "63.4 degrees rising right, upper tile",
    ),
    (
        'g',
        "{ line = [2.0, 0.0] }",
        "63.4 degrees rising left, lower tile",
    ),
    (
        'h',
        "{ line = [1.0, -1.0] }",
        "63.4 degrees rising left, upper tile",
    ),
    (
        'k',
        "{ heights = [2, 2, 2, 2, 6, 6, 6, 6, 10, 10, 10, 10, 14, 14, 14, 14] }",
        "a height-array tile: four steps of a quarter tile",
    ),
];

impl Cell {
    fn char(self) -> char {
        match self {
            Cell::Empty => '.',
            Cell::Solid => '#',
            Cell::OneWay => '=',
            Cell::Ladder => 'H',
            Cell::Ramp(k) => RAMPS[k as usize].0,
        }
    }
}

/// How a sketched platform moves.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Motion {
    /// Back and forth between two points at a speed, in tiles and tiles/s.
    Path {
        /// The far end of the path (the near end is the rectangle's corner).
        to: [f32; 2],
        /// Speed along the path, tiles/s.
        speed: f32,
    },
    /// A sine about its corner: amplitude (tiles) and period (s).
    Sine {
        /// Amplitude on each axis, tiles.
        amplitude: [f32; 2],
        /// Period, s.
        period: f32,
    },
}

/// A sketched moving platform.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PlatformSketch {
    /// Lower-left corner, tiles.
    pub(crate) at: [f32; 2],
    /// Width and height, tiles.
    pub(crate) size: [f32; 2],
    /// Its motion.
    pub(crate) motion: Motion,
    /// Blocks only from above.
    pub(crate) one_way: bool,
}

impl PlatformSketch {
    /// The box the platform sweeps with two tiles above it for a rider: lower left, upper
    /// right, in tiles.
    pub(crate) fn reach(&self) -> ([f32; 2], [f32; 2]) {
        let (lo, hi) = match &self.motion {
            Motion::Path { to, .. } => (
                [self.at[0].min(to[0]), self.at[1].min(to[1])],
                [self.at[0].max(to[0]), self.at[1].max(to[1])],
            ),
            Motion::Sine { amplitude, .. } => (
                [self.at[0] - amplitude[0], self.at[1] - amplitude[1]],
                [self.at[0] + amplitude[0], self.at[1] + amplitude[1]],
            ),
        };
        (lo, [hi[0] + self.size[0], hi[1] + self.size[1] + 2.0])
    }
}

/// The buttons of an input event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Button {
    /// Left.
    Left,
    /// Right.
    Right,
    /// Up (ladders).
    Up,
    /// Down (ladders, dropping through one-way platforms).
    Down,
    /// Jump.
    Jump,
}

impl Button {
    fn key(self) -> &'static str {
        match self {
            Button::Left => "left",
            Button::Right => "right",
            Button::Up => "up",
            Button::Down => "down",
            Button::Jump => "jump",
        }
    }
}

/// One timed button change: time (s), button, pressed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Event {
    /// Time, s.
    pub(crate) t: f32,
    /// The button.
    pub(crate) button: Button,
    /// Pressed or released.
    pub(crate) down: bool,
}

/// What the generated scenario states should happen (its `[scenario.expect]` table).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Expect {
    /// The feet never below this height, tiles.
    pub(crate) min_y: Option<f32>,
    /// The feet never outside the map.
    pub(crate) stay_in_map: bool,
    /// Grounded on the last frame.
    pub(crate) grounded_at_end: Option<bool>,
}

/// A generated case: a grid (row 0 at the bottom), platforms and one scenario.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Sketch {
    /// Rows from the bottom, each `width` cells.
    pub(crate) rows: Vec<Vec<Cell>>,
    /// Moving platforms.
    pub(crate) platforms: Vec<PlatformSketch>,
    /// The character's feet at the start, tiles.
    pub(crate) spawn: [f32; 2],
    /// Length of the run, s.
    pub(crate) duration: f32,
    /// Input events, in time order.
    pub(crate) events: Vec<Event>,
    /// The platform the scenario rides (an index into `platforms`).
    pub(crate) ride: Option<usize>,
    /// What should happen.
    pub(crate) expect: Expect,
}

/// A number as the TOML is written: the shortest form that reads back the same f32.
fn num(v: f32) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

impl Sketch {
    /// Width in tiles.
    pub(crate) fn width(&self) -> usize {
        self.rows.first().map_or(0, Vec::len)
    }

    /// Height in tiles.
    pub(crate) fn height(&self) -> usize {
        self.rows.len()
    }

    /// Non-empty cells.
    pub(crate) fn tiles(&self) -> usize {
        self.rows
            .iter()
            .flatten()
            .filter(|c| **c != Cell::Empty)
            .count()
    }

    /// Drops the stated expectations whose premise the grid no longer holds (a shrunk case
    /// loses tiles): `min_y` and `grounded_at_end` need the whole floor, `stay_in_map` the
    /// walls at both sides and the ceiling, with the spawn between them.
    pub(crate) fn keep_premises(&mut self) {
        let floor = self
            .rows
            .first()
            .is_some_and(|r| r.iter().all(|c| *c == Cell::Solid));
        let w = self.width();
        let walled = floor
            && w >= 2
            && self
                .rows
                .iter()
                .all(|r| r[0] == Cell::Solid && r[w - 1] == Cell::Solid)
            && self
                .rows
                .last()
                .is_some_and(|r| r.iter().all(|c| *c == Cell::Solid));
        if !floor {
            self.expect.min_y = None;
            self.expect.grounded_at_end = None;
        }
        // ... and the spawn inside them, below the ceiling.
        let h = self.height() as f32;
        let inside = self.spawn[0] > 1.0
            && self.spawn[0] < w as f32 - 1.0
            && self.spawn[1] >= 1.0
            && self.spawn[1] < h - 1.0;
        if !walled || !inside {
            self.expect.stay_in_map = false;
        }
    }

    /// The level file: `header` lines (each written as a `# ` comment) and then the level named
    /// `name` with its one scenario, named `case`.
    pub(crate) fn toml(&self, name: &str, header: &[String]) -> String {
        let mut s = String::new();
        for line in header {
            let _ = writeln!(s, "# {line}");
        }
        let _ = writeln!(s, "name = {name:?}");
        let _ = writeln!(
            s,
            "description = \"Found by platbench hunt: {} x {} tiles, {} platform(s), {} input event(s)\"",
            self.width(),
            self.height(),
            self.platforms.len(),
            self.events.len()
        );
        s.push_str("\nmap = '''\n");
        for row in self.rows.iter().rev() {
            s.extend(row.iter().map(|c| c.char()));
            s.push('\n');
        }
        s.push_str("'''\n");
        let mut used: Vec<u8> = self
            .rows
            .iter()
            .flatten()
            .filter_map(|c| match c {
                Cell::Ramp(k) if !RAMPS[*k as usize].1.is_empty() => Some(*k),
                _ => None,
            })
            .collect();
        used.sort_unstable();
        used.dedup();
        if !used.is_empty() {
            s.push_str("\n[legend]\n");
            for k in used {
                let (c, value, what) = RAMPS[k as usize];
                let _ = writeln!(s, "\"{c}\" = {value}   # {what}");
            }
        }
        for p in &self.platforms {
            s.push_str("\n[[platform]]\n");
            let _ = writeln!(
                s,
                "rect = [{}, {}, {}, {}]",
                num(p.at[0]),
                num(p.at[1]),
                num(p.size[0]),
                num(p.size[1])
            );
            match &p.motion {
                Motion::Path { to, speed } => {
                    let _ = writeln!(
                        s,
                        "path = [[{}, {}], [{}, {}]]\nspeed = {}",
                        num(p.at[0]),
                        num(p.at[1]),
                        num(to[0]),
                        num(to[1]),
                        num(*speed)
                    );
                }
                Motion::Sine { amplitude, period } => {
                    let _ = writeln!(
                        s,
                        "sine = {{ amplitude = [{}, {}], period = {} }}",
                        num(amplitude[0]),
                        num(amplitude[1]),
                        num(*period)
                    );
                }
            }
            if p.one_way {
                s.push_str("one_way = true\n");
            }
        }
        s.push_str("\n[[scenario]]\nname = \"case\"\n");
        let _ = writeln!(
            s,
            "spawn = [{}, {}]",
            num(self.spawn[0]),
            num(self.spawn[1])
        );
        let _ = writeln!(s, "duration = {}", num(self.duration));
        let events: Vec<String> = self
            .events
            .iter()
            .map(|e| format!("{{ t = {}, {} = {} }}", num(e.t), e.button.key(), e.down))
            .collect();
        let _ = writeln!(s, "inputs = [ {} ]", events.join(", "));
        if let Some(k) = self.ride {
            let _ = writeln!(s, "ride = {k}");
        }
        let e = &self.expect;
        if e.min_y.is_some() || e.stay_in_map || e.grounded_at_end.is_some() {
            s.push_str("\n[scenario.expect]\n");
            if let Some(y) = e.min_y {
                let _ = writeln!(s, "min_y = {}", num(y));
            }
            if e.stay_in_map {
                s.push_str("stay_in_map = true\n");
            }
            if let Some(g) = e.grounded_at_end {
                let _ = writeln!(s, "grounded_at_end = {g}");
            }
        }
        s
    }

    /// The level, parsed from [`Sketch::toml`] as `platbench run` would read the file.
    pub(crate) fn level(&self, name: &str) -> Result<Level, LevelError> {
        parse_level(&self.toml(name, &[]), &format!("{name}.toml"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Sketch {
        let mut rows = vec![
            vec![Cell::Solid; 6],
            vec![Cell::Empty; 6],
            vec![Cell::Empty; 6],
        ];
        rows[1][3] = Cell::Ramp(2);
        rows[1][4] = Cell::Ramp(3);
        rows[1][0] = Cell::Ladder;
        rows[2][5] = Cell::OneWay;
        Sketch {
            rows,
            platforms: vec![PlatformSketch {
                at: [1.0, 2.0],
                size: [2.0, 0.5],
                motion: Motion::Path {
                    to: [3.0, 2.0],
                    speed: 1.5,
                },
                one_way: false,
            }],
            spawn: [1.5, 1.0],
            duration: 2.0,
            events: vec![Event {
                t: 0.25,
                button: Button::Right,
                down: true,
            }],
            ride: None,
            expect: Expect {
                min_y: Some(0.75),
                stay_in_map: true,
                grounded_at_end: Some(true),
            },
        }
    }

    #[test]
    fn the_written_level_reads_back_as_sketched() {
        let s = sample();
        let level = s.level("hunt_sample").expect("the sketch parses");
        assert_eq!((level.width, level.height), (6, 3));
        assert_eq!(level.platforms.len(), 1);
        let spec = &level.scenarios[0];
        assert_eq!(spec.inputs.len(), 1);
        assert_eq!(spec.inputs[0].right, Some(true));
        assert_eq!(spec.expect.min_y, Some(0.75));
        assert!(level.features.slopes && level.features.ladders && level.features.one_way);
        let text = s.toml("hunt_sample", &["a header".into()]);
        assert!(text.starts_with("# a header\n"), "{text}");
    }
}

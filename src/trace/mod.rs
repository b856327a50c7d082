//! Per-frame trace rows and their CSV form (DESIGN.md, "Traces and metrics"):
//! `frame,t,character,x,y,vx,vy,grounded,ground_nx,ground_ny,platform,ladder,crushed` (DESIGN.md's
//! columns, and `crushed` for the moving-platform crush event).
//!
//! Floats are written in Rust's shortest round-trip form, so reading a trace back gives the
//! same bits and two identical runs give byte-identical files.

use std::io::{Read, Write};

use serde::{Deserialize, Serialize};

use crate::backend::CharacterState;

pub mod store;
pub use store::{Frames, RowStore, Rows};

/// One character's state at one frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TraceRow {
    /// Frame index: 0 is the spawn, `k` the state after `k` steps.
    pub frame: u32,
    /// Time of the frame, in seconds.
    pub t: f32,
    /// Character index.
    pub character: u32,
    /// Feet x (bottom centre of the box), in tiles.
    pub x: f32,
    /// Feet y, in tiles.
    pub y: f32,
    /// Velocity x, in tiles/s.
    pub vx: f32,
    /// Velocity y, in tiles/s.
    pub vy: f32,
    /// 1 if standing on something, else 0.
    pub grounded: u8,
    /// Ground normal x (0 when airborne).
    pub ground_nx: f32,
    /// Ground normal y (0 when airborne).
    pub ground_ny: f32,
    /// Index of the moving platform ridden, empty if none.
    pub platform: Option<u32>,
    /// 1 if in the ladder state, else 0.
    pub ladder: u8,
    /// 1 if a moving platform crushed it against the level this frame, else 0.
    pub crushed: u8,
}

impl TraceRow {
    /// The row for a character's state.
    pub fn from_state(frame: u32, t: f32, character: u32, s: &CharacterState) -> Self {
        TraceRow {
            frame,
            t,
            character,
            x: s.pos.x,
            y: s.pos.y,
            vx: s.vel.x,
            vy: s.vel.y,
            grounded: s.grounded as u8,
            ground_nx: s.ground_normal.x,
            ground_ny: s.ground_normal.y,
            platform: s.platform,
            ladder: s.ladder as u8,
            crushed: s.crushed as u8,
        }
    }

    /// Whether the character stands on something.
    pub fn is_grounded(&self) -> bool {
        self.grounded != 0
    }
}

/// A whole run of one scenario on one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    /// Level name.
    pub level: String,
    /// Scenario name.
    pub scenario: String,
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// Rows in frame order.
    pub rows: Vec<TraceRow>,
}

impl Trace {
    /// File name of this trace inside `traces/`: `<level>.<scenario>.<backend>[.<config>].csv`
    /// (the default configuration keeps the DESIGN.md name).
    pub fn file_name(&self) -> String {
        if self.config == "default" {
            format!("{}.{}.{}.csv", self.level, self.scenario, self.backend)
        } else {
            let config: String = self
                .config
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            format!(
                "{}.{}.{}.{}.csv",
                self.level, self.scenario, self.backend, config
            )
        }
    }

    /// Rows of character `id`, in frame order.
    pub fn character(&self, id: u32) -> impl Iterator<Item = &TraceRow> {
        self.rows.iter().filter(move |r| r.character == id)
    }

    /// Writes the rows as CSV with a header.
    pub fn write_csv<W: Write>(&self, w: W) -> Result<(), csv::Error> {
        write_rows_csv(self.rows.iter().copied(), w)
    }

    /// Reads rows written by [`Trace::write_csv`].
    pub fn read_rows<R: Read>(r: R) -> Result<Vec<TraceRow>, csv::Error> {
        csv::Reader::from_reader(r).deserialize().collect()
    }
}

/// Writes `rows` as a trace's CSV with a header (see [`Trace::write_csv`]).
pub(crate) fn write_rows_csv<W: Write>(
    rows: impl IntoIterator<Item = TraceRow>,
    w: W,
) -> Result<(), csv::Error> {
    let mut wr = csv::Writer::from_writer(w);
    for r in rows {
        wr.serialize(r)?;
    }
    wr.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn csv_round_trip_is_bit_exact() {
        let s = CharacterState {
            pos: Vec2::new(1.0 / 3.0, 1e-7),
            vel: Vec2::new(-0.1, 12345.679),
            grounded: true,
            ground_normal: Vec2::Y,
            platform: Some(2),
            ladder: false,
            crushed: false,
        };
        let trace = Trace {
            level: "l".into(),
            scenario: "s".into(),
            backend: "sweep".into(),
            config: "default".into(),
            rows: vec![
                TraceRow::from_state(0, 0.0, 0, &s),
                TraceRow::from_state(1, 1.0 / 60.0, 0, &CharacterState::default()),
            ],
        };
        let mut buf = Vec::new();
        trace.write_csv(&mut buf).unwrap();
        let text = String::from_utf8(buf.clone()).unwrap();
        assert!(text.starts_with(
            "frame,t,character,x,y,vx,vy,grounded,ground_nx,ground_ny,platform,ladder,crushed\n"
        ));
        let back = Trace::read_rows(&buf[..]).unwrap();
        assert_eq!(back, trace.rows);
        assert_eq!(back[0].x.to_bits(), (1.0f32 / 3.0).to_bits());
    }
}

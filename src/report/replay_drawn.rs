//! A run reduced to what its replay draws ([`DrawnRun`]): the rows of the drawn frames, the
//! fault bits of the frames each stands for, and the box around every row. Built a row at a
//! time ([`DrawnBuilder`]), so a run read from a file row by row (`platbench review`'s traces)
//! takes memory for its drawn frames only, and the report's runs, held whole, are drawn by the
//! same code.

use glam::Vec2;

use super::replay::{drawn_frames, stride};
use crate::shape::CharacterShape;
use crate::trace::TraceRow;

/// The frames a scenario's replay draws, from the frame count of its longest run: every
/// `stride`-th and the last ([`super::replay::MAX_DRAWN_FRAMES`] at most).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Drawing {
    /// Frames between two drawn ones.
    pub(crate) stride: usize,
    /// The frames drawn, in order.
    pub(crate) picked: Vec<usize>,
}

impl Drawing {
    /// The drawing of a scenario whose longest run has `frames` frames.
    pub(crate) fn of(frames: usize) -> Drawing {
        let stride = stride(frames);
        Drawing {
            stride,
            picked: drawn_frames(frames, stride).collect(),
        }
    }

    /// A builder for one run of the scenario, whose character moves a box of `size` tiles.
    pub(crate) fn run(&self, size: Vec2) -> DrawnBuilder<'_> {
        DrawnBuilder {
            picked: &self.picked,
            size,
            rows: Vec::new(),
            row_at: 0,
            bounds: None,
            faults: vec![0; self.picked.len()],
            fault_at: 0,
            bucket: 0,
        }
    }
}

/// One run as its replay draws it.
pub(crate) struct DrawnRun {
    /// Backend name.
    pub(crate) backend: String,
    /// Configuration label, as the page names it.
    pub(crate) config: String,
    /// The character's collision shape.
    pub(crate) shape: CharacterShape,
    /// The outer size of the box the configuration moves, in tiles.
    pub(crate) size: Vec2,
    /// The rows of the drawn frames the run reaches (the first `rows.len()` of them).
    pub(crate) rows: Vec<TraceRow>,
    /// Per drawn frame, the fault bits of every frame it stands for (since the drawn frame
    /// before it), so subsampling the drawing never hides a fault.
    pub(crate) faults: Vec<u8>,
    /// The box around every row with a finite position, the character's width either side and
    /// its height above (`None`: no such row).
    pub(crate) bounds: Option<(Vec2, Vec2)>,
}

/// A [`DrawnRun`] being built: [`DrawnBuilder::row`] for each row of the drawn character in
/// frame order, [`DrawnBuilder::fault`] for each fault bit of the measured character's rows
/// ([`crate::metrics::faults`]) in frame order.
pub(crate) struct DrawnBuilder<'p> {
    picked: &'p [usize],
    size: Vec2,
    rows: Vec<TraceRow>,
    row_at: usize,
    bounds: Option<(Vec2, Vec2)>,
    faults: Vec<u8>,
    fault_at: usize,
    bucket: usize,
}

impl DrawnBuilder<'_> {
    /// The next row of the drawn character.
    pub(crate) fn row(&mut self, r: TraceRow) {
        if r.x.is_finite() && r.y.is_finite() {
            let (lo, hi) = (
                Vec2::new(r.x - self.size.x, r.y),
                Vec2::new(r.x + self.size.x, r.y + self.size.y),
            );
            self.bounds = Some(match self.bounds {
                None => (lo, hi),
                Some((a, b)) => (a.min(lo), b.max(hi)),
            });
        }
        if self.picked.get(self.rows.len()) == Some(&self.row_at) {
            self.rows.push(r);
        }
        self.row_at += 1;
    }

    /// The fault bits of the next row of the measured character: added to the drawn frame that
    /// stands for it (none past the last drawn frame).
    pub(crate) fn fault(&mut self, f: u8) {
        while self
            .picked
            .get(self.bucket)
            .is_some_and(|&p| p < self.fault_at)
        {
            self.bucket += 1;
        }
        if let Some(slot) = self.faults.get_mut(self.bucket) {
            *slot |= f;
        }
        self.fault_at += 1;
    }

    /// The run, named `backend` `config`, drawn as `shape`.
    pub(crate) fn finish(self, backend: &str, config: &str, shape: CharacterShape) -> DrawnRun {
        DrawnRun {
            backend: backend.to_string(),
            config: config.to_string(),
            shape,
            size: self.size,
            rows: self.rows,
            faults: self.faults,
            bounds: self.bounds,
        }
    }
}

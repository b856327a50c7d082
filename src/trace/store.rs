//! Trace rows held while a run is measured: in memory up to a limit, then spilled to an unlinked
//! temporary file and read back a block at a time, so that measuring a run of any length takes
//! memory bounded by the limit and two blocks, not by its frames.
//!
//! The metrics read rows through [`Frames`], a view that is the same whether the rows are a
//! slice in memory or a spilled file; the values read back are bit for bit those written, so a
//! spilled run measures exactly as one held in memory.

use std::cell::RefCell;
use std::fs::File;
use std::io::{self, BufWriter, Read, Seek, SeekFrom, Write};
use std::ops::Range;

use super::TraceRow;

/// Rows a run keeps in memory before its rows go to a temporary file: 65,536 rows, 3 MiB at
/// 48 bytes a row, about 18 minutes of game time at 60 Hz, so every built-in scenario and every
/// ordinary one is measured in memory and only a soak run spills.
pub const SPILL_ROWS: usize = 1 << 16;

/// Rows in one block read back from a spilled file: 4,096 rows, 192 KiB. Two blocks are kept,
/// so a metric that reads a frame against an earlier anchor (the idle drift) does not re-read.
pub(crate) const BLOCK_ROWS: usize = 4096;

/// Bytes of one row in a spilled file: ten 4-byte fields and four 1-byte flags.
const ROW_BYTES: usize = 44;

/// Rows being recorded; [`RowStore::finish`] makes them [`Rows`] to measure.
pub struct RowStore {
    mem: Vec<TraceRow>,
    limit: usize,
    block: usize,
    len: usize,
    file: Option<BufWriter<File>>,
    error: Option<io::Error>,
}

impl Default for RowStore {
    fn default() -> Self {
        RowStore::with_limits(SPILL_ROWS, BLOCK_ROWS)
    }
}

impl RowStore {
    /// A store that spills past `limit` rows and reads spilled rows back `block` rows at a time
    /// (the tests use small values to spill every built-in run; see [`SPILL_ROWS`]).
    pub fn with_limits(limit: usize, block: usize) -> Self {
        RowStore {
            mem: Vec::new(),
            limit,
            block: block.max(1),
            len: 0,
            file: None,
            error: None,
        }
    }

    /// Makes room for `n` more rows in memory, at most up to the limit (a run knows its frames
    /// before it starts: no regrowing in its steps).
    pub fn reserve(&mut self, n: usize) {
        if self.file.is_none() {
            let room = self.limit.saturating_sub(self.mem.len());
            self.mem.reserve(n.min(room));
        }
    }

    /// Appends a row. An error writing the temporary file is kept and returned by
    /// [`RowStore::finish`], as a `BufWriter` keeps its own.
    pub fn push(&mut self, row: TraceRow) {
        self.len += 1;
        if self.error.is_some() {
            return;
        }
        if self.file.is_none() && self.mem.len() < self.limit {
            self.mem.push(row);
            return;
        }
        if let Err(e) = self.spill(row) {
            self.error = Some(e);
        }
    }

    fn spill(&mut self, row: TraceRow) -> io::Result<()> {
        if self.file.is_none() {
            let mut w = BufWriter::with_capacity(64 * 1024, tempfile::tempfile()?);
            for r in &self.mem {
                w.write_all(&encode(r))?;
            }
            self.mem = Vec::new();
            self.file = Some(w);
        }
        match &mut self.file {
            Some(w) => w.write_all(&encode(&row)),
            None => unreachable!("created above"),
        }
    }

    /// Rows pushed so far.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no row was pushed.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The recorded rows, ready to read.
    pub fn finish(self) -> io::Result<Rows> {
        if let Some(e) = self.error {
            return Err(e);
        }
        match self.file {
            None => Ok(Rows::Memory(self.mem)),
            Some(w) => {
                let file = w.into_inner().map_err(|e| e.into_error())?;
                Ok(Rows::Spilled(Spilled {
                    len: self.len,
                    block: self.block,
                    reader: RefCell::new(Reader {
                        file,
                        blocks: [Block::default(), Block::default()],
                        newer: 0,
                        bytes: Vec::new(),
                        error: None,
                    }),
                }))
            }
        }
    }
}

/// Recorded rows: in memory, or in a temporary file (deleted when dropped: it is unlinked from
/// the start, so nothing is left behind even if the process is killed).
pub enum Rows {
    /// Held whole.
    Memory(Vec<TraceRow>),
    /// In a temporary file, read back a block at a time.
    Spilled(Spilled),
}

impl Rows {
    /// A view of every row.
    pub fn frames(&self) -> Frames<'_> {
        match self {
            Rows::Memory(v) => Frames::new(v),
            Rows::Spilled(s) => Frames {
                src: Src::Spilled(s),
                start: 0,
                len: s.len,
            },
        }
    }

    /// Whether the rows went to a temporary file.
    pub fn spilled(&self) -> bool {
        matches!(self, Rows::Spilled(_))
    }

    /// The first error reading a spilled file back, if any: a read that failed gave a row of
    /// NaNs, so metrics computed over it are void and the run must fail.
    pub fn take_error(&self) -> Option<io::Error> {
        match self {
            Rows::Memory(_) => None,
            Rows::Spilled(s) => s.reader.borrow_mut().error.take(),
        }
    }
}

/// Rows in a temporary file.
pub struct Spilled {
    len: usize,
    block: usize,
    reader: RefCell<Reader>,
}

struct Reader {
    file: File,
    blocks: [Block; 2],
    /// Index of the block read last (the other is evicted first).
    newer: usize,
    bytes: Vec<u8>,
    error: Option<io::Error>,
}

#[derive(Default)]
struct Block {
    first: usize,
    rows: Vec<TraceRow>,
}

impl Block {
    fn holds(&self, k: usize) -> bool {
        k >= self.first && k - self.first < self.rows.len()
    }
}

impl Spilled {
    fn at(&self, k: usize) -> TraceRow {
        let mut r = self.reader.borrow_mut();
        for b in 0..2 {
            if r.blocks[b].holds(k) {
                r.newer = b;
                return r.blocks[b].rows[k - r.blocks[b].first];
            }
        }
        let b = 1 - r.newer;
        let first = k - k % self.block;
        let n = self.block.min(self.len - first);
        match r.load(b, first, n) {
            Ok(()) => {
                r.newer = b;
                r.blocks[b].rows[k - first]
            }
            Err(e) => {
                r.blocks[b].rows.clear();
                r.error.get_or_insert(e);
                void_row(k)
            }
        }
    }
}

impl Reader {
    fn load(&mut self, b: usize, first: usize, n: usize) -> io::Result<()> {
        self.bytes.resize(n * ROW_BYTES, 0);
        self.file
            .seek(SeekFrom::Start((first * ROW_BYTES) as u64))?;
        self.file.read_exact(&mut self.bytes)?;
        let block = &mut self.blocks[b];
        block.first = first;
        block.rows.clear();
        block
            .rows
            .extend(self.bytes.chunks_exact(ROW_BYTES).map(decode));
        Ok(())
    }
}

/// The row a failed read gives: every measure over it is NaN.
fn void_row(k: usize) -> TraceRow {
    TraceRow {
        frame: k as u32,
        t: f32::NAN,
        character: 0,
        x: f32::NAN,
        y: f32::NAN,
        vx: f32::NAN,
        vy: f32::NAN,
        grounded: 0,
        ground_nx: f32::NAN,
        ground_ny: f32::NAN,
        platform: None,
        ladder: 0,
        crushed: 0,
    }
}

fn encode(r: &TraceRow) -> [u8; ROW_BYTES] {
    let mut out = [0u8; ROW_BYTES];
    let words = [
        r.frame,
        r.t.to_bits(),
        r.character,
        r.x.to_bits(),
        r.y.to_bits(),
        r.vx.to_bits(),
        r.vy.to_bits(),
        r.ground_nx.to_bits(),
        r.ground_ny.to_bits(),
        r.platform.unwrap_or(0),
    ];
    for (i, w) in words.iter().enumerate() {
        out[4 * i..4 * i + 4].copy_from_slice(&w.to_le_bytes());
    }
    out[40] = r.grounded;
    out[41] = r.ladder;
    out[42] = r.crushed;
    out[43] = r.platform.is_some() as u8;
    out
}

fn decode(b: &[u8]) -> TraceRow {
    let w = |i: usize| u32::from_le_bytes([b[4 * i], b[4 * i + 1], b[4 * i + 2], b[4 * i + 3]]);
    let f = |i: usize| f32::from_bits(w(i));
    TraceRow {
        frame: w(0),
        t: f(1),
        character: w(2),
        x: f(3),
        y: f(4),
        vx: f(5),
        vy: f(6),
        ground_nx: f(7),
        ground_ny: f(8),
        platform: (b[43] != 0).then(|| w(9)),
        grounded: b[40],
        ladder: b[41],
        crushed: b[42],
    }
}

#[derive(Clone, Copy)]
enum Src<'a> {
    Slice(&'a [TraceRow]),
    Spilled(&'a Spilled),
}

/// A run of consecutive rows, read by value: a slice in memory or a span of a spilled file.
/// Indices are relative to the view, as a slice's are.
#[derive(Clone, Copy)]
pub struct Frames<'a> {
    src: Src<'a>,
    start: usize,
    len: usize,
}

impl<'a> Frames<'a> {
    /// A view of rows in memory.
    pub fn new(rows: &'a [TraceRow]) -> Self {
        Frames {
            src: Src::Slice(rows),
            start: 0,
            len: rows.len(),
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it holds no row.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Row `k`. Panics if `k >= len()`, as indexing a slice does.
    pub fn at(&self, k: usize) -> TraceRow {
        assert!(k < self.len, "row {k} of a view of {} rows", self.len);
        match self.src {
            Src::Slice(s) => s[self.start + k],
            Src::Spilled(s) => s.at(self.start + k),
        }
    }

    /// Row `k`, if there is one.
    pub fn get(&self, k: usize) -> Option<TraceRow> {
        (k < self.len).then(|| self.at(k))
    }

    /// The last row.
    pub fn last(&self) -> Option<TraceRow> {
        self.len.checked_sub(1).map(|k| self.at(k))
    }

    /// The rows in order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = TraceRow> + ExactSizeIterator + 'a {
        let v = *self;
        (0..self.len).map(move |k| v.at(k))
    }

    /// The rows `range` of this view. Panics if it is out of bounds, as slicing does.
    pub fn slice(&self, range: Range<usize>) -> Frames<'a> {
        assert!(
            range.start <= range.end && range.end <= self.len,
            "rows {range:?} of a view of {} rows",
            self.len
        );
        Frames {
            src: self.src,
            start: self.start + range.start,
            len: range.end - range.start,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(k: u32) -> TraceRow {
        TraceRow {
            frame: k,
            t: k as f32 / 60.0,
            character: 0,
            x: 1.0 / (k as f32 + 3.0),
            y: -(k as f32) * 1e-7,
            vx: f32::MIN_POSITIVE,
            vy: -0.0,
            grounded: (k % 2) as u8,
            ground_nx: 0.5,
            ground_ny: f32::INFINITY,
            platform: k.is_multiple_of(3).then_some(k),
            ladder: k.is_multiple_of(5) as u8,
            crushed: 7,
        }
    }

    fn bits(r: &TraceRow) -> Vec<u32> {
        vec![
            r.frame,
            r.t.to_bits(),
            r.x.to_bits(),
            r.y.to_bits(),
            r.vx.to_bits(),
            r.vy.to_bits(),
            r.ground_nx.to_bits(),
            r.ground_ny.to_bits(),
            r.platform.map_or(u32::MAX, |p| p),
            r.grounded as u32,
            r.ladder as u32,
            r.crushed as u32,
        ]
    }

    #[test]
    fn a_spilled_store_reads_back_every_bit_in_any_order() {
        let rows: Vec<TraceRow> = (0..1000).map(row).collect();
        // Spills after 10 rows, blocks of 7: reads cross every block boundary.
        let mut store = RowStore::with_limits(10, 7);
        for r in &rows {
            store.push(*r);
        }
        let stored = store.finish().unwrap();
        assert!(stored.spilled());
        let f = stored.frames();
        assert_eq!(f.len(), rows.len());
        for k in (0..1000)
            .rev()
            .chain(0..1000)
            .chain((0..1000).map(|k| (k * 379) % 1000))
        {
            assert_eq!(bits(&f.at(k)), bits(&rows[k]), "row {k}");
        }
        // A frame read against a far anchor, alternately, as the idle drift does.
        for k in 500..600 {
            assert_eq!(bits(&f.at(3)), bits(&rows[3]));
            assert_eq!(bits(&f.at(k)), bits(&rows[k]));
        }
        let s = f.slice(990..1000);
        assert_eq!(s.len(), 10);
        assert_eq!(s.last().map(|r| r.frame), Some(999));
        assert_eq!(
            s.iter().map(|r| r.frame).collect::<Vec<_>>(),
            (990..1000).collect::<Vec<_>>()
        );
        assert!(stored.take_error().is_none());
    }

    #[test]
    fn a_store_under_its_limit_stays_in_memory() {
        let mut store = RowStore::with_limits(10, 7);
        for k in 0..10 {
            store.push(row(k));
        }
        let stored = store.finish().unwrap();
        assert!(!stored.spilled());
        assert_eq!(stored.frames().len(), 10);
        assert_eq!(stored.frames().get(10), None);
    }

    #[test]
    #[should_panic(expected = "row 5 of a view of 5 rows")]
    fn reading_past_the_end_panics_as_a_slice_does() {
        let rows: Vec<TraceRow> = (0..10).map(row).collect();
        Frames::new(&rows).slice(0..5).at(5);
    }
}

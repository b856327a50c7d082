//! Stability at the extremes: the invariants every controller should keep (nothing non-finite,
//! no penetration beyond its tolerance, no tunneling, a stable rest, no grounded flicker, carry
//! without drift, progress on flat seamed ground with no stuck step, a jump to its height),
//! checked one dimension at a time away from a base case (far from the origin, tiny and huge
//! time steps, fast movers, tiny and huge characters, and the sweep's epsilon down to where it
//! breaks: the seed's "try 0.001, and lower until unstable"), then on small grids of the pairs
//! of dimensions whose failures interact ([`pairs`]).
//!
//! The matrix is a list of independent [`Point`]s ([`points`]), each run alone ([`run_point`])
//! and collected in order, so that running them on several threads changes no row.

mod definition;
mod execution;
mod probes;
mod verdicts;
mod world;

pub use definition::{
    dimensions, format_setting, pair_offsets, pairs, Case, Dimension, BASE, F32_OFFSET_LIMIT,
    F64_OFFSETS, INVARIANTS, JUMP_TOLERANCE, PROGRESS_BAND, PROGRESS_MAX, PROGRESS_MIN,
};
pub(crate) use execution::carry_drift;
pub use execution::{
    points, points_with, run_point, stress_matrix, stress_matrix_on, stress_matrix_reporting,
    stress_matrix_with, Point, StressRow,
};
pub use probes::check_base_dt;
pub use probes::ProbeTimingError;
pub(crate) use probes::PROBE_TILES;
pub use verdicts::{cells, envelope, reach, verdicts, Cell, Edge, Envelope, Reach, Verdict};
pub(crate) use verdicts::{envelopes_by_key, value_key};
pub use world::{world_verdicts, WorldVerdict};

//! Regression compare of two run directories (DESIGN.md, "Regression compare"): every metric's
//! change against its tolerance, and for every trace the first frame where a character's
//! position differs by more than a position tolerance.
//!
//! Reading the two run directories (`read`, one row at a time) and matching their rows and
//! traces (`join`) is [`diff_runs`]'s; the rules that judge each pair (tolerances, distance
//! from ideal, divergence, what fails) are in `compare`; [`render()`] writes the result as
//! tables, Markdown or CSV.

mod compare;
mod csv_words;
mod join;
mod lines;
mod read;
mod render;
mod timing;

pub use compare::{
    default_tolerance, Change, ChangeCounts, FailOn, MetricDiff, RunDiff, Tolerance, TraceChange,
    TraceDiff,
};
pub(crate) use csv_words::{expected_of, worded};
pub use join::{diff_runs, diff_runs_each};
pub(crate) use lines::Lines;
pub(crate) use read::CsvRows;
pub use read::{read_metrics, read_metrics_where, read_runs, DiffError, MetricRecord, RunKey};
pub use render::{render, DiffFormat};

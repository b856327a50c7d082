//! The command line: every command's output, options, selection, exit status and what it writes; the report, the stress, the trade-off, and runs at scale.

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod error_places;
mod hunt;
mod report;
mod scale;
mod selection;
mod stress;
mod sweep_cli;
mod timing;
mod tradeoff;
mod verdict;

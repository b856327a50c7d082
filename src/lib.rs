//! platbench: run 2D platformer character controllers over the same levels and compare them.
//!
//! The pieces, in dependency order: [`level`] (the tile model, its text format and the Tiled import) ←
//! [`motion`], [`ladder`] and [`backend`] (shared game rules and the controller interface: the
//! [`backend::Backend`], [`backend::BackendSettings`] and [`backend::BackendKind`] traits) ← the
//! controllers ([`sweep`], [`rapier`] in f32 and f64, [`box2d`]), listed in one [`registry::Registry`] ← [`scenario`] (the
//! runner) and [`trace`] ← [`metrics`] ← [`report`], [`stress`], [`tradeoff`]. [`suite`] runs the
//! comparison from code; [`parallel`] fans independent runs out over threads; [`cli`] is the
//! `platbench` command line, which a user's crate gets with its own controller beside ours from
//! [`cli::main_with`] (see `examples/move_and_slide.rs`).

#![warn(missing_docs)]

pub mod backend;
pub mod box2d;
#[path = "../compare/builtin.rs"]
pub mod builtin;
pub mod cli;
pub mod ladder;
pub mod level;
pub mod limits;
pub mod metrics;
pub mod motion;
pub mod parallel;
pub mod rapier;
pub mod registry;
pub mod report;
pub mod scenario;
pub mod shape;
pub mod stress;
pub mod suite;
pub mod sweep;
pub mod trace;
pub mod tradeoff;

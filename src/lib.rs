//! platbench: run 2D platformer character controllers over the same levels and compare them.
//!
//! The pieces, in dependency order: [`level`] (the tile model, its text format and the Tiled import) ←
//! [`motion`], [`ladder`], [`backend`] and [`controller`] (shared game rules and the controller
//! interface: the one trait a controller implements, [`controller::Controller`]) ← the
//! controllers ([`sweep`], [`rapier`] in f32 and f64, [`box2d`]), listed in one [`registry::Registry`] ← [`scenario`] (the
//! runner) and [`trace`] ← [`metrics`] ← [`report`], [`stress`], [`tradeoff`]. [`suite`] runs the
//! comparison from code; [`parallel`] fans independent runs out over threads; [`cli`] is the
//! `platbench` command line, which a user's crate gets with its own controller beside ours from
//! [`cli::main_with`] (see `examples/box_mover.rs`, the README's plug-in example, and
//! `examples/move_and_slide.rs`).

//!
//! Cargo features, all on by default: `rapier` (rapier2d's controller, f32 and f64), `box2d`
//! (Box2D v3's mover, built from C), `tiled` (Tiled maps) and `ldtk` (LDtk projects). With
//! `default-features = false` the crate builds the harness, the sweep and a user's controller.

#![warn(missing_docs)]

pub mod backend;
#[cfg(feature = "box2d")]
pub mod box2d;
#[path = "../compare/builtin.rs"]
pub(crate) mod builtin;
pub mod cli;
pub mod config;
pub mod controller;
pub mod ladder;
pub mod level;
pub mod limits;
pub mod metrics;
pub mod motion;
pub mod oneway;
pub mod parallel;
pub mod prelude;
#[cfg(feature = "rapier")]
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

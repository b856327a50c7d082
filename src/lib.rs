//! platbench: run 2D platformer character controllers over the same levels and compare them.
//!
//! The pieces, in layers that point one way (ARCHITECTURE.md gives one row per module): the
//! tile model [`level`] ← the shared rules ([`motion`], [`ladder`], [`oneway`], [`shape`]) ← the
//! controller API ([`backend`], [`config`], [`controller`]: the one trait a controller
//! implements, [`controller::Controller`]) ← the controllers ([`sweep`], [`rapier`] in f32 and
//! f64, [`box2d`]) ← running ([`scenario`], [`trace`], [`parallel`]) ← [`metrics`] ←
//! [`registry`] ← analysis ([`stress`], [`tradeoff`]) ← [`report`] and [`suite`] ← [`cli`], the
//! `platbench` command line, which a user's crate gets with its own controller beside ours from
//! [`cli::main_with`] (see `examples/box_mover.rs`, the README's plug-in example). The names a
//! controller of one's own needs are in [`prelude`].
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
pub mod external;
pub mod hunt;
pub mod input;
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
pub(crate) mod rounding;
pub mod scenario;
pub mod shape;
pub mod stress;
pub mod suite;
pub mod sweep;
pub mod trace;
pub mod tradeoff;

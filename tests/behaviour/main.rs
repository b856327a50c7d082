//! What controllers do on the levels, read from their traces: the levels' own expectations and leaving the level, geometry, idling, integer positions, one-way platforms and ladders, moving platforms, slopes, the models' limits, the sweep on the built-in set, and the report's statements on a toy controller.

#[path = "../common/mod.rs"]
mod common;

mod expectations;
mod geometry;
mod idle;
mod integer;
mod models;
mod oneway_ladders;
mod platforms;
mod slopes;
mod statements;
mod sweep_builtin;

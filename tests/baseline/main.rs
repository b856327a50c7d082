//! `platbench baseline`, `check` and `review`, as a user's CI runs them: a baseline of a chosen
//! selection, a toy controller changed between two runs caught by `check` with the scenario
//! named, one change accepted into the baseline and every other byte of it unchanged.

#[path = "../common/mod.rs"]
mod common;

mod check;
mod guard;
mod review;
mod toy;

//! The report in headless Chromium: its replays play, step and link to their frames (skips loudly without Chromium).

#[path = "../common/mod.rs"]
mod common;

mod replay;

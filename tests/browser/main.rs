//! The report in headless Chromium: its replays play, step and link to their frames, and its page fits the window (skips loudly without Chromium).

#[path = "../common/mod.rs"]
mod common;

mod page;
mod replay;

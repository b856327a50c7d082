//! `platbench`: the command-line harness over the built-in backends. The CLI lives in the
//! library ([`platbench::cli`]), so a user's crate gets the same command with its own
//! controller beside ours from one call.

use std::path::PathBuf;
use std::process::ExitCode;

use platbench::cli::{main_with_harness, Harness};
use platbench::registry::Registry;

fn main() -> ExitCode {
    // The committed baseline (`PLATBENCH_BASELINE` overrides it, for tests).
    let baseline = std::env::var_os("PLATBENCH_BASELINE")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("compare/baseline"));
    main_with_harness(Harness {
        registry: Registry::builtin(),
        baseline,
    })
}

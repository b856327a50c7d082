//! Writes the level files docs/scale.md ("Running at scale") measures the harness on, into the folder
//! given (which must exist): `many.toml` (10,000 one-second walks), `long1000.toml`,
//! `long10000.toml` and `long100000.toml` (one soak scenario of that many seconds), each on a
//! 60 x 6 map of flat floor walled at both ends.
//!
//! ```text
//! cargo run --release --example scale_levels -- DIR
//! /usr/bin/time -f "%e s %M kB" target/release/platbench run DIR/long100000.toml --out OUT --traces none
//! ```

use std::fmt::Write as _;
use std::path::PathBuf;

/// The map: five rows of air between two walls over one row of floor.
fn map() -> String {
    let air = format!("#{}#", ".".repeat(58));
    let mut rows = vec![air; 5];
    rows.push("#".repeat(60));
    rows.join("\n")
}

/// A level named `name` with the scenarios `scenarios` (TOML `[[scenario]]` entries).
fn level(name: &str, scenarios: &str) -> String {
    format!(
        "name = \"{name}\"\nmap = \"\"\"\n{}\n\"\"\"\n\n{scenarios}",
        map()
    )
}

fn main() -> Result<(), String> {
    let dir: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .ok_or("usage: scale_levels DIR (an existing folder to write the level files into)")?;
    if !dir.is_dir() {
        return Err(format!("{} is not a folder", dir.display()));
    }
    let write = |file: &str, text: String| {
        let path = dir.join(file);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
    };
    for seconds in [1000, 10000, 100000] {
        let name = format!("long{seconds}");
        let soak = format!(
            "[[scenario]]\nname = \"soak\"\nspawn = [30.5, 1.0]\nduration = {seconds}.0\n\
             inputs = [ {{ t = 1.0, right = true }}, {{ t = 3.0, right = false, left = true }}, \
             {{ t = 7.0, left = false }}, {{ t = 8.0, jump = true }}, {{ t = 8.5, jump = false }} ]\n"
        );
        write(&format!("{name}.toml"), level(&name, &soak))?;
    }
    let mut many = String::new();
    for i in 0..10_000 {
        if i > 0 {
            many.push('\n');
        }
        let x = 5 + i % 50;
        let _ = write!(
            many,
            "[[scenario]]\nname = \"s{i}\"\nspawn = [{x}.5, 1.0]\nduration = 1.0\n\
             inputs = [ {{ t = 0.1, right = true }} ]\n"
        );
    }
    write("many.toml", level("many", &many))?;
    eprintln!(
        "wrote many.toml, long1000.toml, long10000.toml and long100000.toml to {}",
        dir.display()
    );
    Ok(())
}

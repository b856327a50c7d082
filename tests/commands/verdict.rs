//! The verdict's game profiles from the command line: a user's own profile file is judged, and
//! a bad one is refused with its file, line and column.

use crate::common::platbench;

// Beside Rapier: its configurations are built with the default features only.
#[cfg(feature = "rapier")]
#[test]
fn a_profile_of_ones_own_is_judged_and_printed_with_its_weights() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("mine.toml");
    std::fs::write(
        &file,
        "name = \"my-game\"\ntitle = \"seams above all\"\n[weights]\nseams = 5\nlanding = 1\n",
    )
    .unwrap();
    let out = platbench()
        .args([
            "run",
            "compare/levels/flat_seams.toml",
            "--backend",
            "sweep,rapier",
            "--profile",
        ])
        .arg(&file)
        .output()
        .unwrap();
    crate::common::assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    // Only the given profile, with its weights beside its verdict; the built-in ones are not.
    assert!(stdout.contains("\nmy-game: seams above all\n"), "{stdout}");
    assert!(stdout.contains("  weighs seams 5, landing 1\n"), "{stdout}");
    assert!(!stdout.contains("\npixel-precise: "), "{stdout}");
    let pick = stdout
        .lines()
        .find(|l| l.starts_with("  pick       "))
        .unwrap_or_else(|| panic!("no pick:\n{stdout}"));
    // On flat seams the sweep's weighted error is the lowest (3.8e-4 in this build: f32
    // rounding in the rest metrics, far below the 0.01-tile size that counts), the same for its
    // default and its continuous jump (no jump here): a tie, said as one; the runner-up is the
    // best configuration of the other backend.
    assert!(
        pick.starts_with("  pick       tie: sweep, sweep jump=continuous (error "),
        "{stdout}"
    );
    assert!(stdout.contains("  runner-up  rapier "), "{stdout}");
}

#[test]
fn a_bad_profile_is_refused_with_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(
        &file,
        "name = \"x\"\ntitle = \"t\"\nneeds = [\"wings\"]\n[weights]\nseams = 1\n",
    )
    .unwrap();
    let out = platbench()
        .args(["run", "compare/levels/flat_seams.toml", "--profile"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!(
            "{}:3:10: need \"wings\": expected one of",
            file.display()
        )),
        "{stderr}"
    );
    // Refused before the run: no scenario ran.
    assert!(!stderr.contains("ran in"), "{stderr}");
}

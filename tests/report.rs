//! The HTML report as a reader gets it: self-contained, one picture per scenario, every drawn
//! backend's path in each.

use std::process::Command;

#[test]
fn report_is_self_contained_with_one_picture_per_scenario() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_platbench"))
        .args(["report", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    let md = std::fs::read_to_string(dir.path().join("report.md")).unwrap();
    // The Markdown twin lists each scenario as "- level.scenario".
    let scenarios = md
        .lines()
        .filter(|l| {
            l.strip_prefix("- ")
                .is_some_and(|id| id.contains('.') && !id.contains(' '))
        })
        .count();
    let pictures = html.matches("<svg").count();
    assert!(pictures >= 60, "{pictures} pictures");
    assert_eq!(pictures, scenarios, "one picture per scenario listed");
    // Every picture holds the sweep's path and Rapier's.
    for svg in html.split("<svg").skip(1) {
        let svg = &svg[..svg.find("</svg>").unwrap()];
        assert!(svg.contains("class=\"path backend-sweep\""));
        assert!(svg.contains("class=\"path backend-rapier\""));
    }
    // No scripts and nothing fetched from the network (the SVG namespace is only a name).
    assert!(!html.contains("<script"));
    assert!(!html.contains("src=\"http") && !html.contains("href=\"http"));
    assert!(html.contains("Which backend for which game"));
    for section in [
        "Landing and resting",
        "Slopes",
        "Moving platforms",
        "Ladders",
    ] {
        assert!(html.contains(section) && md.contains(section), "{section}");
    }
}

//! The report's replays in a real browser: headless Chromium (the Debian package `chromium`,
//! which `.ci/run` installs) opens `report.html#selftest`; the inline script scrubs every replay,
//! plays one, ticks the picker, and writes what it saw into `<pre id="selftest">`, which the
//! test reads from the dumped DOM. Without the browser the test says loudly that it skipped
//! (`.ci/run` sets `PLATBENCH_REQUIRE_PROGRAMS=1`, which makes a missing browser a failure).
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{assert_success, platbench};

/// The Chromium binary: `PLATBENCH_CHROMIUM`, else `chromium` on the PATH; `None` (the test
/// says loudly that it skipped) when neither is there, unless `PLATBENCH_REQUIRE_PROGRAMS=1`.
fn chromium() -> Option<PathBuf> {
    common::outside_program(
        "tests/browser/replay.rs (the report's replays in headless Chromium)",
        "chromium",
        "PLATBENCH_CHROMIUM",
        "apt-get install -y chromium",
    )
}

/// The page's DOM after its scripts ran with `budget_ms` of virtual time.
fn dump_dom(chromium: &Path, page: &Path, fragment: &str, budget_ms: u32) -> String {
    let profile = tempfile::tempdir().unwrap();
    let url = format!("file://{}{fragment}", page.display());
    let out = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--virtual-time-budget={budget_ms}"))
        .arg("--dump-dom")
        .arg(url)
        .output()
        .expect("chromium runs");
    assert!(
        out.status.success(),
        "chromium failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_replays_play_scrub_and_pick_in_headless_chromium() {
    let Some(chromium) = chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Jumps: every scenario moves its characters; elevator: a moving platform.
    let out = platbench()
        .args([
            "report",
            "compare/levels/jumps.toml",
            "compare/levels/elevator.toml",
            "--out",
        ])
        .arg(dir.path().join("report"))
        .output()
        .unwrap();
    assert_success(&out);
    let page = dir.path().join("report/report.html");
    let html = std::fs::read_to_string(&page).unwrap();
    // Nothing fetched: no external script, style, image or link.
    for attr in ["src=\"http", "href=\"http", "src=\"//", "@import"] {
        assert!(!html.contains(attr), "{attr}");
    }
    let replays = html.matches("<div class=\"replay\"").count();
    assert_eq!(replays, 8, "7 jumps and 1 elevator scenario");
    // 5 s of virtual time: the self-test plays for 0.5 s after scrubbing every replay.
    let dom = dump_dom(&chromium, &page, "#selftest", 5000);
    let start = dom
        .find("<pre id=\"selftest\">")
        .unwrap_or_else(|| panic!("the self-test wrote no result"))
        + "<pre id=\"selftest\">".len();
    let text = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let text = text.replace("&amp;", "&");
    let r: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(r["errors"], serde_json::json!([]), "{r}");
    assert_eq!(r["replays"], replays, "{r}");
    // Every scenario here moves its characters, so the scrubber moves them in every replay.
    assert_eq!(r["scrub_moved"], replays, "{r}");
    assert_eq!(r["platforms"], 1, "{r}");
    assert_eq!(r["platforms_moved"], 1, "the elevator moves: {r}");
    // Half a second of play at real time is 30 frames at 60 Hz; more than 0 is "it runs".
    assert!(r["played_to"].as_u64().unwrap() > 0, "{r}");
    assert_eq!(r["played_drawn"], true, "{r}");
    assert!(!r["clock"].as_str().unwrap().starts_with("frame 0 "), "{r}");
    assert_eq!(r["picker"], true, "{r}");
}

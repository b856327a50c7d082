//! The report's replays in a real browser: headless Chromium (the Debian package `chromium`,
//! which `.ci/run` installs) opens `report.html#selftest`; the inline script scrubs every replay,
//! plays one, ticks the picker, steps with the arrow keys, zooms and follows, and writes what it
//! saw into `<pre id="selftest">`, which the test reads from the dumped DOM. Without the browser the test says loudly that it skipped
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
pub(crate) fn chromium() -> Option<PathBuf> {
    common::outside_program(
        "tests/browser/replay.rs (the report's replays in headless Chromium)",
        "chromium",
        "PLATBENCH_CHROMIUM",
        "apt-get install -y chromium",
    )
}

/// The page's DOM after its scripts ran with `budget_ms` of virtual time, in a window of
/// 1280 by 900 pixels.
pub(crate) fn dump_dom(chromium: &Path, page: &Path, fragment: &str, budget_ms: u32) -> String {
    let out = headless(
        chromium,
        page,
        fragment,
        budget_ms,
        (1280, 900),
        &["--dump-dom"],
    );
    String::from_utf8(out).unwrap()
}

/// Runs headless Chromium on `page` with `fragment` in a window of `size`, `budget_ms` of
/// virtual time and the `extra` arguments; returns its standard output.
pub(crate) fn headless(
    chromium: &Path,
    page: &Path,
    fragment: &str,
    budget_ms: u32,
    size: (u32, u32),
    extra: &[&str],
) -> Vec<u8> {
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
        .arg(format!("--window-size={},{}", size.0, size.1))
        .args(extra)
        .arg(url)
        .output()
        .expect("chromium runs");
    assert!(
        out.status.success(),
        "chromium failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The JSON the page's script wrote into `<pre id="{id}">`.
pub(crate) fn script_result(dom: &str, id: &str) -> serde_json::Value {
    let tag = format!("<pre id=\"{id}\">");
    let start = dom
        .find(&tag)
        .unwrap_or_else(|| panic!("the page's script wrote no {id} result"))
        + tag.len();
    let text = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    serde_json::from_str(&text.replace("&amp;", "&").replace("&quot;", "\"")).unwrap()
}

/// `platbench report` of `levels` (the built-in set when empty) into `dir`/report; its page.
pub(crate) fn report(dir: &Path, levels: &[&str]) -> PathBuf {
    let out = platbench()
        .arg("report")
        .args(levels)
        .arg("--out")
        .arg(dir.join("report"))
        .output()
        .unwrap();
    assert_success(&out);
    dir.join("report/report.html")
}

#[test]
fn the_replays_play_scrub_and_pick_in_headless_chromium() {
    let Some(chromium) = chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Jumps: every scenario moves its characters; elevator: a moving platform.
    let page = report(
        dir.path(),
        &["compare/levels/jumps.toml", "compare/levels/elevator.toml"],
    );
    let html = std::fs::read_to_string(&page).unwrap();
    // Nothing fetched: no external script, style, image or link.
    for attr in ["src=\"http", "href=\"http", "src=\"//", "@import"] {
        assert!(!html.contains(attr), "{attr}");
    }
    let replays = html.matches("<div class=\"replay\"").count();
    assert_eq!(replays, 8, "7 jumps and 1 elevator scenario");
    // 5 s of virtual time: the self-test plays for 0.5 s after scrubbing every replay.
    let dom = dump_dom(&chromium, &page, "#selftest", 5000);
    let r = script_result(&dom, "selftest");
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
    // The state table's first row (the first configuration at drawn frame 3, every frame drawn
    // in a jump of 150 frames) gives its trace's position.
    let x = r["state_x"].as_str().unwrap();
    assert!(r["state"][1].as_str().unwrap().starts_with(x), "{r}");
    assert!(
        r["state"][3].as_str().unwrap().starts_with("yes"),
        "standing at frame 3: {r}"
    );
    // From frame 5: right and left with the focus on the replay (6, 5), right with the mouse
    // over it (6), and nothing once the mouse left (6).
    assert_eq!(r["keys"], serde_json::json!([6, 5, 6, 6]), "{r}");
    // One zoom step is ZOOM_STEP (replay.js): 1.25 times.
    assert_eq!(r["zoom"], 1.25, "{r}");
    assert_eq!(r["followed"], true, "zoomed in and played to the end: {r}");
    assert_eq!(r["panned"], true, "dragged 40 px to the left: {r}");
    assert_eq!(r["fit"], true, "{r}");
}

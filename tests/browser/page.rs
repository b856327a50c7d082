//! The report page as a reader meets it, in headless Chromium (skipped loudly without it, as in
//! `replay.rs`): the built-in report does not scroll sideways at 1280 or 1400 px, its first
//! screen holds the table of contents and the first section, and a table value's link opens the
//! replay of its scenario at its frame. The page's script measures itself under `#measure`.
//!
//! The screenshot of the first screen in the docs is this file's
//! `the_first_screen_holds_the_contents`, run as
//! `PLATBENCH_SCREENSHOTS=1 cargo test --test browser first_screen`: it writes
//! `docs/img/report.png` (otherwise the picture goes to a temporary directory).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use super::replay::{chromium, dump_dom, headless, report, script_result};

/// The built-in report, made once for this file's tests (it runs every level: 6 s).
fn builtin_report() -> &'static Path {
    static PAGE: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &PAGE
        .get_or_init(|| {
            let dir = tempfile::tempdir().unwrap();
            let page = report(dir.path(), &[]);
            (dir, page)
        })
        .1
}

/// The page's `#measure` result in a window of `width` by `height`.
fn measure(chromium: &Path, page: &Path, width: u32, height: u32) -> serde_json::Value {
    let out = headless(
        chromium,
        page,
        "#measure",
        2000,
        (width, height),
        &["--dump-dom"],
    );
    script_result(&String::from_utf8(out).unwrap(), "measure")
}

#[test]
fn the_page_does_not_scroll_sideways() {
    let Some(chromium) = chromium() else {
        return;
    };
    let page = builtin_report();
    // 1280 px: the laptop width; 1400: a little wider, where the old page overflowed too.
    for width in [1280, 1400] {
        let m = measure(&chromium, page, width, 900);
        assert!(
            m["scroll_width"].as_f64().unwrap() <= m["inner_width"].as_f64().unwrap(),
            "{width} px: {m}"
        );
        eprintln!("page height at {width} px: {}", m["height"]);
    }
}

#[test]
fn the_first_screen_holds_the_verdict_and_the_scorecard_s_start() {
    let Some(chromium) = chromium() else {
        return;
    };
    let page = builtin_report();
    // The first screen of a 1280 by 800 window: the top 800 px of the page holds the verdict of
    // every profile and the scorecard's start (its heading and legend); the contents follow
    // the verdict section.
    let m = measure(&chromium, page, 1280, 800);
    let screen = 800.0;
    let at = |k: &str| {
        m[k].as_f64()
            .unwrap_or_else(|| panic!("no {k} on the page: {m}"))
    };
    assert!(at("verdict_table_bottom") <= screen, "{m}");
    assert!(at("scorecard_heading_bottom") <= screen, "{m}");
    assert!(at("toc_bottom") > at("verdict_bottom"), "{m}");
    // The screenshot of that first screen, for the docs.
    let target = if std::env::var("PLATBENCH_SCREENSHOTS").is_ok_and(|v| v == "1") {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/img/report.png")
    } else {
        std::env::temp_dir().join(format!("platbench-report-{}.png", std::process::id()))
    };
    std::fs::create_dir_all(target.parent().unwrap()).unwrap();
    let _ = std::fs::remove_file(&target);
    headless(
        &chromium,
        page,
        "",
        2000,
        (1280, 800),
        &[&format!("--screenshot={}", target.display())],
    );
    let png = std::fs::read(&target).unwrap();
    assert!(png.starts_with(b"\x89PNG"), "{}", target.display());
    eprintln!("wrote {} ({} bytes)", target.display(), png.len());
}

#[test]
fn a_worst_value_opens_its_replay_at_its_frame() {
    let Some(chromium) = chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let page = report(dir.path(), &["compare/levels/jumps.toml"]);
    let html = std::fs::read_to_string(&page).unwrap();
    // Every value of the behaviour tables links to a replay of the page, with a tooltip.
    let links: Vec<&str> = html.split("<a href=\"#view=").skip(1).collect();
    assert!(!links.is_empty());
    for l in &links {
        let id = &l[..l.find(['&', '"']).unwrap()];
        assert!(html.contains(&format!("id=\"replay-{id}\"")), "{id}");
        assert!(l.contains(&format!("title=\"{id} (")), "{l:.200}");
    }
    // Each metric name links to its definition.
    assert!(html.contains("<a href=\"#metric-apex_error\" title=\""));
    assert!(html.contains("<tr id=\"metric-apex_error\">"));
    // A link with a frame: that replay shows that frame (jump_1 draws all of its 150 frames).
    let dom = dump_dom(&chromium, &page, "#view=jumps.jump_1&frame=37", 2000);
    let at = dom.find("id=\"replay-jumps.jump_1\"").unwrap();
    let clock = &dom[at..][dom[at..].find("class=\"clock\">").unwrap()..];
    assert!(
        clock.starts_with("class=\"clock\">frame 37 of 150,"),
        "{:.80}",
        clock
    );
    // The other replays stay at their start.
    let other = dom.find("id=\"replay-jumps.jump_2\"").unwrap();
    assert!(dom[other..].contains("class=\"clock\">frame 0 of"));
    // A grade of the scorecard that is not ok links to its worst scenario at its frame (the
    // continuous jump falls short of every apex: its landing grade fails on a jump).
    let card = &html[html
        .find("<table class=\"scorecard\">")
        .expect("a scorecard")..];
    let cell = &card[card
        .find("<td class=\"g-fail\"><a href=\"")
        .expect("a failing grade")
        + "<td class=\"g-fail\"><a href=\"".len()..];
    let href = cell[..cell.find('"').unwrap()].replace("&amp;", "&");
    let id = &href["#view=".len()..href.find('&').unwrap()];
    let frame: u32 = href[href.find("&frame=").expect("the link names a frame") + 7..]
        .split('&')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let dom = dump_dom(&chromium, &page, &href, 2000);
    let at = dom.find(&format!("id=\"replay-{id}\"")).unwrap();
    let clock = &dom[at..][dom[at..].find("class=\"clock\">").unwrap()..];
    assert!(
        clock.starts_with(&format!("class=\"clock\">frame {frame} of ")),
        "{href}: {:.80}",
        clock
    );
}

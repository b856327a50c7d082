//! The README's and the book's (docs/) metric catalog, summary and figures, checked against the
//! code, and their relative links checked against the repository, so that no page states a figure
//! the code no longer gives or links to a file that is gone. Each check reads the file where its
//! text lives: README.md is the front door, docs/*.md the chapters.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use crate::common;

use common::{builtin_levels, evaluate_all};
use platbench::metrics::registry::METRICS;
use platbench::report::summary_table;

/// The text of a file of the repository (`README.md`, `docs/metrics.md`, ...).
fn doc(path: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path))
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn readme() -> String {
    doc("README.md")
}

/// Whitespace collapsed to single spaces, so a figure wrapped across lines still matches.
fn flat(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[test]
fn the_readme_lists_every_metric_of_the_registry_with_its_unit() {
    // The catalog lives in docs/metrics.md.
    let text = doc("docs/metrics.md");
    assert!(!METRICS.is_empty());
    for d in METRICS {
        let row = format!("| `{}` ({}) |", d.name, d.unit);
        assert!(text.contains(&row), "docs/metrics.md misses {row}");
    }
}

#[test]
fn integer_positions_are_compared_over_every_scenario() {
    // docs/comparison.md, summary: no "(over N of 64)" on the integer row. The integer mode models
    // moving platforms too (on the subpixel grid), so it runs all 64 scenarios of the built-in set,
    // as the float mode does; a configuration skipped anywhere would be marked.
    let levels = builtin_levels();
    let total: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    assert_eq!(total, 64);
    let mut rows = Vec::new();
    for run in [
        platbench::sweep::kind::run_default(),
        platbench::sweep::kind::run_integer(32),
    ] {
        for l in &levels {
            for s in &l.scenarios {
                rows.extend(
                    platbench::metrics::evaluate(l, s, &run)
                        .unwrap_or_else(|e| panic!("{}.{}: {e}", l.name, s.name))
                        .metrics,
                );
            }
        }
    }
    let summary = summary_table(&rows);
    assert!(
        summary.contains("| sweep positions=integer/32 "),
        "{summary}"
    );
    assert!(!summary.contains("(over"), "{summary}");
    // The same count the shared helper sees.
    let evals = evaluate_all(&levels, &platbench::sweep::kind::run_integer(32));
    assert_eq!(evals.len(), 64);
}

/// The rows of the committed `platbench sweep --out compare/tradeoff` run.
fn committed_tradeoff() -> Vec<platbench::tradeoff::TradeoffRow> {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compare/tradeoff/tradeoff.csv");
    csv::Reader::from_path(&path)
        .expect("compare/tradeoff/tradeoff.csv")
        .deserialize()
        .collect::<Result<_, _>>()
        .expect("parses")
}

#[test]
fn the_readme_trade_figures_are_the_committed_sweep_run() {
    use platbench::tradeoff::{scored_behaviours, ALL};
    let rows = committed_tradeoff();
    // The trade paragraph lives in docs/speed.md ("Speed versus accuracy"); the README's verdict
    // ("What it finds") quotes each backend's cheapest, dearest and error range from it.
    let speed = flat(&doc("docs/speed.md"));
    let front = flat(&readme());
    let all: Vec<_> = rows.iter().filter(|r| r.scope == ALL).collect();
    let of = |backend: &str| -> Vec<_> { all.iter().filter(|r| r.backend == backend).collect() };
    // Every backend of the built-in registry has its cheapest, dearest and error range in the
    // trade paragraph and in the README's verdict.
    for backend in ["sweep", "rapier", "box2d"] {
        let rs = of(backend);
        assert!(!rs.is_empty(), "{backend}");
        let cheapest = rs
            .iter()
            .min_by(|a, b| a.cost_us.total_cmp(&b.cost_us))
            .unwrap();
        let dearest = rs
            .iter()
            .max_by(|a, b| a.cost_us.total_cmp(&b.cost_us))
            .unwrap();
        let lo = rs.iter().map(|r| r.error).fold(f64::INFINITY, f64::min);
        let hi = rs.iter().map(|r| r.error).fold(0.0, f64::max);
        for figure in [
            format!("{:.1} ({})", cheapest.cost_us, cheapest.setting),
            format!("{:.1} ({})", dearest.cost_us, dearest.setting),
            format!("error scores {lo:.4} to {hi:.4}"),
        ] {
            assert!(speed.contains(&figure), "docs/speed.md lacks {figure:?}");
            assert!(front.contains(&figure), "README lacks {figure:?}");
        }
    }
    let text = speed;
    // "4 substeps buy a little accuracy (A to B for the per-tile capsule) at R times the cost".
    let setting = |s: &str| all.iter().find(|r| r.setting == s).expect(s);
    let (one, four) = (
        setting("per-tile capsule dt=1/60"),
        setting("per-tile capsule substeps=4"),
    );
    let figure = format!(
        "({:.4} to {:.4} for the per-tile capsule) at {:.1} times the cost",
        one.error,
        four.error,
        four.cost_us / one.cost_us
    );
    assert!(text.contains(&figure), "docs/speed.md lacks {figure:?}");
    // "Its most accurate setting is its advised feed (..., A, against B fed gravity every
    // step)".
    let fed = setting("per-tile capsule grounded=none-but-testbed-on-platforms");
    let best = all
        .iter()
        .filter(|r| r.backend == "rapier")
        .min_by(|a, b| a.error.total_cmp(&b.error))
        .expect("rapier rows");
    assert_eq!(best.setting, fed.setting);
    let figure = format!(
        "grounded=none-but-testbed-on-platforms`, {:.4}, against {:.4} fed gravity every step)",
        fed.error, one.error
    );
    assert!(text.contains(&figure), "docs/speed.md lacks {figure:?}");
    // "Per behaviour the fronts are the sweep's too": since integer positions run every
    // scenario, moving platforms included, their exact apex (error 0) at 12 us beats the four
    // Rapier settings that were on the jumping front beside the sweep before.
    for b in scored_behaviours() {
        let front: Vec<_> = rows
            .iter()
            .filter(|r| r.scope == b.key() && r.pareto)
            .collect();
        assert!(front.iter().any(|r| r.backend == "sweep"), "{}", b.key());
        let rapier: Vec<&str> = front
            .iter()
            .filter(|r| r.backend == "rapier")
            .map(|r| r.setting.as_str())
            .collect();
        let expected: &[&str] = &[];
        assert_eq!(rapier, expected, "{}", b.key());
    }
}

/// What `platbench` prints with `args`, as text.
fn printed(args: &[&str]) -> String {
    let out = common::platbench()
        .args(args)
        .output()
        .expect("platbench runs");
    common::assert_success(&out);
    String::from_utf8(out.stdout).expect("utf-8")
}

#[test]
fn the_readme_verdict_and_the_comparison_chapter_are_what_platbench_prints() {
    // The built-in comparison includes Godot 3's rows when `godot3-server` is installed, and
    // README and docs/comparison.md show them: without it this test cannot compare.
    if common::outside_program(
        "tests/docs/readme.rs (the verdict with Godot 3's rows)",
        "godot3-server",
        "PLATBENCH_GODOT3",
        "apt-get install -y godot3-server",
    )
    .is_none()
    {
        return;
    }
    // The README opens with the verdict: the block between its markers is what `platbench`
    // prints before the scorecard, line for line.
    let verdict = printed(&[]);
    let readme = readme();
    let start = readme
        .find("<!-- verdict: generated")
        .expect("README's verdict block");
    let block = &readme[start..];
    let block = &block[block.find("```\n").expect("its code fence") + 4..];
    let block = &block[..block.find("```").expect("its closing fence")];
    let head = &verdict[..verdict.find("\nScorecard:").expect("a scorecard") + 1];
    assert_eq!(
        block.trim_end(),
        head.trim_end(),
        "README's verdict differs from what platbench prints (regenerate it with the command in its marker)"
    );
    // docs/comparison.md, "The built-in comparison today": every line of the default output
    // (verdict, scorecard, capabilities) and of `--detail`'s worst values and statements
    // appears there as printed, so a change of behaviour that moves a number fails until the
    // page says so.
    let detail = printed(&["run", "--detail", "--controller", "godot3"]);
    let worst = &detail[detail
        .find("Worst value of each metric")
        .expect("--detail's tables")
        ..detail
            .find("Every metric of every scenario")
            .expect("--detail's scenario table")];
    let text = doc("docs/comparison.md");
    let lines: Vec<&str> = verdict
        .lines()
        // The heading is the chapter's own.
        .chain(worst.lines().skip(1))
        .filter(|l| !l.trim().is_empty())
        .collect();
    assert!(lines.len() > 60, "{verdict}{worst}");
    for l in &lines {
        assert!(
            text.contains(l),
            "docs/comparison.md lacks the printed line {l:?}"
        );
    }
    // The README's tour shows part of a table: every table line in its code blocks is a line
    // the command prints, as printed.
    let mut fence = false;
    let mut shown = 0;
    for l in readme.lines() {
        if l.starts_with("```") {
            fence = !fence;
        } else if fence && l.starts_with('|') {
            assert!(
                lines.contains(&l),
                "README shows a line platbench does not print: {l:?}"
            );
            shown += 1;
        }
    }
    assert!(shown > 5, "the README's table excerpt ({shown} lines)");
}

#[test]
fn the_committed_trade_off_scores_the_committed_baseline_with_the_default_score() {
    // Found by review: the README's trade figures come from compare/tradeoff/tradeoff.csv, which
    // the tests above check against the docs but nothing checked against the code: a change
    // of the default score left it stale. The grid's settings that are built-in configurations
    // (the sweep's dt=1/60 is its default; "X dt=1/60" is X) ran the same 64 scenarios, so the
    // default score of their baseline rows is their CSV error (1e-9: the CSV's f64 text).
    use platbench::metrics::registry;
    use platbench::metrics::score::Score;
    use platbench::metrics::MetricRow;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = platbench::report::diff::read_metrics(&root.join("compare/baseline"))
        .expect("compare/baseline/metrics.csv");
    let rows: Vec<MetricRow> = base
        .iter()
        .filter_map(|r| {
            let d = registry::get(&r.metric)?;
            Some(MetricRow {
                level: r.level.clone(),
                scenario: r.scenario.clone(),
                backend: r.backend.clone(),
                config: r.config.clone(),
                metric: d.name,
                value: r.value,
                unit: d.unit,
                reference: r.reference,
                error: r.error,
                frame: r.frame,
                q1: None,
                q3: None,
            })
        })
        .collect();
    let mut matched = 0;
    for t in committed_tradeoff()
        .iter()
        .filter(|t| t.scope == platbench::tradeoff::ALL)
    {
        let config = match (t.backend.as_str(), t.setting.as_str()) {
            ("sweep", "dt=1/60") => "default",
            (_, s) => s.strip_suffix(" dt=1/60").unwrap_or(s),
        };
        let of: Vec<MetricRow> = rows
            .iter()
            .filter(|r| r.backend == t.backend && r.config == config)
            .cloned()
            .collect();
        if of.is_empty() {
            continue;
        }
        matched += 1;
        let e = Score::default().error(&of);
        assert!(
            (e - t.error).abs() < 1e-9,
            "{} {}: the baseline scores {e}, the CSV says {}",
            t.backend,
            t.setting,
            t.error
        );
    }
    // The sweep's default, jump=continuous and integer/32; Rapier's per-tile capsule, merged
    // capsule, per-tile and merged cuboid, the advised feed
    // (`grounded=none-but-testbed-on-platforms`); Box2D's two buildings.
    assert!(matched >= 10, "{matched} settings matched a configuration");
}

#[test]
fn the_readme_box2d_figures_are_the_committed_baseline() {
    // Found by review: the Box2D section's slope figures stayed stale after a re-bless, and no
    // test read them. Each (scenario, configuration, metric) figure the chapter quotes is the
    // committed baseline's value, as docs/box2d.md prints it (four decimals).
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = platbench::report::diff::read_metrics(&root.join("compare/baseline"))
        .expect("compare/baseline/metrics.csv");
    // The chapter itself (docs/box2d.md; the summary in docs/comparison.md repeats some of these
    // values).
    let whole = doc("docs/box2d.md");
    let start = whole
        .find("# The Box2D backend")
        .expect("the Box2D chapter");
    let text = flat(&whole[start..]);
    // The last three: the sample's lost ride and the same ride carried by the advised and
    // the grid-best-spring rows (the chapter's table of set-ups).
    let figures: [(&str, &str, &str, &str); 9] = [
        (
            "slope_45",
            "walk_right",
            "per-tile capsule",
            "slope_gap_declared",
        ),
        (
            "slope_45",
            "walk_right",
            "merged capsule",
            "slope_gap_declared",
        ),
        (
            "slope_22_5",
            "walk_right",
            "per-tile capsule",
            "slope_gap_declared",
        ),
        (
            "slope_26_6",
            "walk_right",
            "per-tile capsule",
            "slope_gap_declared",
        ),
        (
            "drops",
            "drop_50",
            "per-tile capsule",
            "penetration_beyond_declared",
        ),
        (
            "elevator",
            "ride_turning_elevator",
            "per-tile capsule",
            "false_grounded",
        ),
        (
            "platforms",
            "ride_horizontal",
            "per-tile capsule",
            "carry_drift",
        ),
        (
            "platforms",
            "ride_horizontal",
            "per-tile capsule carry=ground pogo=7.8Hz",
            "carry_drift",
        ),
        (
            "platforms",
            "ride_horizontal",
            "per-tile capsule carry=ground pogo=20Hz",
            "carry_drift",
        ),
    ];
    for (level, scenario, config, metric) in figures {
        let r = base
            .iter()
            .find(|r| {
                (r.level.as_str(), r.scenario.as_str(), r.backend.as_str())
                    == (level, scenario, "box2d")
                    && r.config == config
                    && r.metric == metric
            })
            .unwrap_or_else(|| {
                panic!("{level}.{scenario} box2d {config} {metric} in the baseline")
            });
        let figure = if r.unit == "frames" {
            format!("`{metric}` {}", r.value)
        } else {
            format!("{:.4}", r.value)
        };
        assert!(
            text.contains(&figure),
            "docs/box2d.md lacks {figure:?} ({level}.{scenario} {config} {metric})"
        );
    }
}

/// GitHub's anchor for a Markdown heading: lower case, letters, digits, `-` and `_` kept,
/// spaces to `-`, everything else dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The lines of a Markdown text outside its fenced code blocks, with their line numbers.
fn prose(text: &str) -> Vec<(usize, &str)> {
    let mut fence = false;
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            if l.starts_with("```") {
                fence = !fence;
                return false;
            }
            !fence
        })
        .map(|(n, l)| (n + 1, l))
        .collect()
}

#[test]
fn every_relative_link_of_the_readme_and_the_book_resolves_to_a_file_of_the_repository() {
    // README.md and docs/*.md: every `](target)` outside code blocks that is not an http(s)
    // link names a file of the repository, relative to the linking file; an `#anchor` on a
    // Markdown file must name one of its headings.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    let mut book: Vec<_> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    book.sort();
    assert!(
        book.iter().any(|p| p.ends_with("docs/README.md")),
        "the book's table of contents, docs/README.md"
    );
    files.extend(book);
    let headings = |path: &std::path::Path| -> Vec<String> {
        let text = std::fs::read_to_string(path).unwrap();
        prose(&text)
            .iter()
            .filter(|(_, l)| l.starts_with('#'))
            .map(|(_, l)| anchor(l.trim_start_matches('#')))
            .collect()
    };
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let dir = file.parent().unwrap();
        for &(n, line) in &prose(&text) {
            let mut rest = line;
            while let Some(k) = rest.find("](") {
                let after = &rest[k + 2..];
                let end = after
                    .find(')')
                    .unwrap_or_else(|| panic!("{}: an unclosed link in {line:?}", file.display()));
                let target = &after[..end];
                rest = &after[end..];
                if target.starts_with("http://") || target.starts_with("https://") {
                    continue;
                }
                let (path, fragment) = target.split_once('#').unwrap_or((target, ""));
                let linked = if path.is_empty() {
                    file.clone()
                } else {
                    dir.join(path)
                };
                assert!(
                    linked.is_file()
                        && linked
                            .canonicalize()
                            .is_ok_and(|p| p.starts_with(root.canonicalize().unwrap())),
                    "{}:{n}: the link {target:?} names no file of the repository",
                    file.display(),
                );
                if !fragment.is_empty() && linked.extension().is_some_and(|e| e == "md") {
                    assert!(
                        headings(&linked).iter().any(|h| h == fragment),
                        "{}:{n}: the link {target:?} names no heading of {}",
                        file.display(),
                        linked.display()
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 50, "{checked} links");
}

#[test]
fn the_book_lists_every_chapter_and_nothing_points_outside_the_repository() {
    // docs/README.md is the table of contents: every chapter in docs/ is listed there. And no
    // page of the README or the book cites a file outside the repository (the links are held
    // inside it by the test above).
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let contents = doc("docs/README.md");
    let mut pages = vec!["README.md".to_string()];
    for e in std::fs::read_dir(root.join("docs")).expect("docs/") {
        let name = e.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".md") {
            if name != "README.md" {
                assert!(
                    contents.contains(&format!("]({name})")),
                    "docs/README.md does not list {name}"
                );
            }
            pages.push(format!("docs/{name}"));
        }
    }
    for page in pages {
        let text = doc(&page);
        // The notes the project started from lived beside the checkout, not in it: the facts
        // taken from them are in docs/ (docs/rapier-reference.md), so nothing cites them.
        for word in ["reference/rapier-kcc", "seeds/000_", "DESIGN.md"] {
            assert!(
                !text.contains(word),
                "{page} cites {word:?}, outside the repository"
            );
        }
    }
}

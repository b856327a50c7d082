//! README's CI section: every platbench command it shows (the three commands and the workflow's
//! steps) is one the CLI takes, and the workflow has the steps the section promises.

use crate::common;

/// README's "In CI" section, up to the next section.
fn ci_section() -> String {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("README.md");
    let start = readme.find("### In CI").expect("README has a CI section");
    let rest = &readme[start..];
    let end = rest.find("\n## ").unwrap_or(rest.len());
    rest[..end].to_string()
}

/// The arguments after `cargo run --release --` on each line of `text` that runs platbench,
/// with any trailing `# comment` removed.
fn platbench_commands(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter_map(|l| l.split_once("cargo run --release -- ").map(|(_, a)| a))
        .map(|a| a.split(" #").next().unwrap_or(a))
        .map(|a| a.split_whitespace().map(str::to_string).collect())
        .collect()
}

#[test]
fn every_platbench_command_of_the_ci_section_parses() {
    let section = ci_section();
    let commands = platbench_commands(&section);
    // baseline, check and review in the commands; check and report in the workflow.
    assert!(commands.len() >= 5, "{commands:?}");
    for c in &["baseline", "check", "review", "report"] {
        assert!(commands.iter().any(|a| a[0] == *c), "no `{c}` command");
    }
    for args in &commands {
        // `--backend mine` names the user's controller, which this harness does not have: the
        // sweep stands for it. `--help` after the arguments makes clap check every argument
        // before it and print the help instead of running.
        let args: Vec<&str> = args
            .iter()
            .map(|a| if a == "mine" { "sweep" } else { a.as_str() })
            .chain(["--help"])
            .collect();
        let out = common::platbench().args(&args).output().expect("runs");
        assert!(
            out.status.success(),
            "platbench {args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn the_workflow_caches_checks_uploads_and_comments() {
    let section = ci_section();
    let yaml = &section[section.find("```yaml").expect("a workflow")..];
    let yaml = &yaml[..yaml[3..].find("```").expect("its fence") + 3];
    for step in [
        "actions/checkout@",
        "Swatinem/rust-cache@",
        "-- check --baseline",
        "actions/upload-artifact@",
        "gh pr comment",
        "summary.md",
        "pull-requests: write",
    ] {
        assert!(yaml.contains(step), "the workflow lacks {step:?}");
    }
    // YAML indents with spaces only.
    assert!(!yaml.contains('\t'));
}

use super::*;
use crate::report::profile::parse_profile;

fn row(
    scenario: &str,
    backend: &str,
    metric: &'static str,
    value: f64,
    reference: f64,
) -> MetricRow {
    MetricRow {
        level: "l".into(),
        scenario: scenario.into(),
        backend: backend.into(),
        config: "default".into(),
        metric,
        value,
        unit: registry::unit(metric),
        reference,
        error: value - reference,
        frame: None,
        q1: None,
        q3: None,
    }
}

fn facts(backend: &str) -> Facts {
    Facts {
        label: backend.into(),
        backend: backend.into(),
        features: Features::ALL,
        precision: Precision::F32,
        capabilities: Capabilities::default(),
        why: String::new(),
    }
}

fn profile(text: &str) -> Profile {
    parse_profile(text, "test.toml").unwrap()
}

use crate::report::profile::Profile;

/// Two controllers on two scenarios: `a` catches on seams (stuck), `b` lands late.
fn rows(a_stuck: f64, b_late: f64) -> Vec<MetricRow> {
    vec![
        row("walk", "a", "stuck_frames", a_stuck, 0.0),
        row("walk", "b", "stuck_frames", 0.0, 0.0),
        row("drop", "a", "land_frame_error", 0.0, 0.0),
        row("drop", "b", "land_frame_error", b_late, 0.0),
    ]
}

#[test]
fn grades_follow_the_clearly_wrong_size_and_ten_times_it() {
    // 0.01 tiles is the error score's clearly-wrong size for a length, 0.1 ten times it, both
    // beyond the pixel of a 16-pixel tile (0.0625 tiles) the score does not charge.
    assert_eq!(Grade::of("tiles", 0.009), Grade::Keeps);
    assert_eq!(Grade::of("tiles", 0.05), Grade::Keeps);
    assert_eq!(Grade::of("tiles", 0.0725), Grade::Keeps);
    assert_eq!(Grade::of("tiles", 0.08), Grade::Minor);
    assert_eq!(Grade::of("tiles", 0.16), Grade::Minor);
    assert_eq!(Grade::of("tiles", 0.17), Grade::Fails);
    // A speed: one pixel per second (0.0625 tiles/s) is free; a ratio has no allowance.
    assert_eq!(Grade::of("tiles/s", 0.07), Grade::Keeps);
    assert_eq!(Grade::of("ratio", 0.05), Grade::Minor);
    // Frames: exact is kept, up to 3 frames (50 ms at 60 Hz) minor.
    assert_eq!(Grade::of("frames", 0.0), Grade::Keeps);
    assert_eq!(Grade::of("frames", -2.0), Grade::Minor);
    assert_eq!(Grade::of("frames", 4.0), Grade::Fails);
    assert_eq!(Grade::of("bool", -1.0), Grade::Fails);
    assert_eq!(Grade::of("tiles", f64::NAN), Grade::Fails);
}

#[test]
fn the_pick_moves_when_the_pick_is_made_worse_on_what_the_profile_weighs() {
    let seams = profile("name = \"s\"\ntitle = \"t\"\n[weights]\nseams = 3\nlanding = 1\n");
    let f = vec![facts("a"), facts("b")];
    // a: no stuck frames, b lands a frame late: a is picked.
    let card = VerdictRows::of(f.clone(), Vec::new(), &rows(0.0, 1.0));
    let v = pick(&card, &seams);
    assert_eq!(v.pick.map(|p| p.0), Some(0), "{v:?}");
    assert_eq!(v.runner_up.map(|p| p.0), Some(1));
    // The same rows with a catching on seams (what the profile weighs most): b is picked.
    let card = VerdictRows::of(f, Vec::new(), &rows(9.0, 1.0));
    let v = pick(&card, &seams);
    assert_eq!(v.pick.map(|p| p.0), Some(1), "{v:?}");
    assert_eq!(v.why[0].behaviour, Behaviour::Seams);
    assert_eq!(v.why[0].other, Some(Grade::Fails));
    // What b still gets wrong: landing, a frame late (minor), named with its scenario.
    assert_eq!(v.still_wrong.len(), 1, "{v:?}");
    let w = v.still_wrong[0].worst.as_ref().unwrap();
    assert_eq!((w.row.scenario.as_str(), w.grade), ("drop", Grade::Minor));
}

#[test]
fn a_configuration_that_skipped_what_a_profile_needs_is_not_picked() {
    let p = profile("name = \"s\"\ntitle = \"t\"\nneeds = [\"slopes\"]\n[weights]\nslopes = 1\n");
    // `b` is perfect on the one slope scenario it ran; `a` ran both, one a little off.
    let rows = vec![
        MetricRow {
            level: "ramp".into(),
            ..row("up", "a", "slope_airborne_frames", 1.0, 0.0)
        },
        MetricRow {
            level: "ramp".into(),
            ..row("up", "b", "slope_airborne_frames", 0.0, 0.0)
        },
        MetricRow {
            level: "steep".into(),
            ..row("up", "a", "slope_airborne_frames", 0.0, 0.0)
        },
    ];
    let card = VerdictRows::of(vec![facts("a"), facts("b")], Vec::new(), &rows);
    let v = pick(&card, &p);
    assert_eq!(v.pick.map(|p| p.0), Some(0), "{v:?}");
    assert_eq!(v.left_out.len(), 1);
    assert!(v.left_out[0].1.contains("skipped steep"), "{v:?}");
    // Without the need, b's skipped scenario still counts as clearly wrong, not as ideal.
    let p = profile("name = \"s\"\ntitle = \"t\"\n[weights]\nslopes = 1\n");
    let v = pick(&card, &p);
    assert_eq!(card.score(1, Behaviour::Slopes), Some(0.5));
    assert_eq!(v.pick.map(|p| p.0), Some(0), "{v:?}");
}

#[test]
fn a_declared_need_leaves_out_who_does_not_declare_it_and_cost_needs_timing() {
    let p =
        profile("name = \"s\"\ntitle = \"t\"\nneeds = [\"f64_positions\"]\n[weights]\nseams = 1\n");
    let mut f = vec![facts("a"), facts("b")];
    f[1].precision = Precision::F64;
    let card = VerdictRows::of(f, Vec::new(), &rows(9.0, 0.0));
    let v = pick(&card, &p);
    assert_eq!(v.pick.map(|p| p.0), Some(1));
    assert!(v.left_out[0].1.contains("does not declare f64_positions"));
    let crowd = profile("name = \"c\"\ntitle = \"t\"\n[weights]\ncost = 1\nseams = 1\n");
    let v = pick(&card, &crowd);
    assert_eq!(v.pick, None);
    assert!(v.no_pick.unwrap().contains("--timing"));
}

#[test]
fn every_line_fits_120_columns() {
    let long = "x".repeat(90);
    let mut f = vec![facts("a"), facts("b")];
    f[0].label = long.clone();
    let rows: Vec<MetricRow> = rows(9.0, 1.0)
        .into_iter()
        .map(|mut r| {
            if r.backend == "a" {
                r.config = long[2..].into();
                r.backend = "a".into();
            }
            r
        })
        .collect();
    let card = VerdictRows::of(f, Vec::new(), &rows);
    let profiles = crate::report::profile::builtin_profiles();
    let v: Vec<ProfileVerdict> = profiles.iter().map(|p| pick(&card, p)).collect();
    for text in [
        render_verdict(&card, &v, "Profiles: x."),
        render_scorecard(&card),
        render_capabilities(&card),
    ] {
        for line in text.lines() {
            assert!(render::columns(line) <= render::WIDTH, "{line}");
        }
    }
}

#[test]
fn a_tie_is_said_and_nothing_measured_picks_nothing() {
    let p = profile("name = \"s\"\ntitle = \"t\"\n[weights]\nseams = 1\n");
    // Both exact on the one scenario: a tie, not a win of the first in run order.
    let card = VerdictRows::of(vec![facts("a"), facts("b")], Vec::new(), &rows(0.0, 0.0));
    let v = pick(&card, &p);
    assert_eq!(v.tied, vec![1], "{v:?}");
    assert!(v.why.is_empty());
    let (text, runner) = render::pick_texts(&card, &v);
    assert!(text.starts_with("tie: a, b (error 0)"), "{text}");
    // The runner-up (another backend) is in the tie: not said twice.
    assert_eq!(runner, None);
    // A profile of what the run did not measure picks nothing.
    let p = profile("name = \"s\"\ntitle = \"t\"\n[weights]\nladders = 1\n");
    let v = pick(&card, &p);
    assert_eq!(v.pick, None);
    assert!(v.no_pick.unwrap().contains("nothing this profile weighs"));
}

#[test]
fn a_fail_ranks_below_a_lower_mean_and_a_platform_level_charges_its_feature() {
    let p = profile("name = \"s\"\ntitle = \"t\"\n[weights]\nlanding = 1\n");
    // a: one landing scenario 2 frames late (minor); b: one of ten scenarios clearly wrong
    // (FAIL), the others exact, so b's mean error (0.1) is below a's (1, capped).
    let mut r = vec![row("s0", "a", "land_frame_error", 2.0, 0.0)];
    for i in 0..10 {
        r.push(row(
            &format!("s{i}"),
            "b",
            "bounce_frames",
            if i == 0 { 9.0 } else { 0.0 },
            0.0,
        ));
        if i > 0 {
            r.push(row(&format!("s{i}"), "a", "land_frame_error", 0.0, 0.0));
        }
    }
    r.sort_by(|x, y| (&x.scenario, &x.backend).cmp(&(&y.scenario, &y.backend)));
    let card = VerdictRows::of(vec![facts("a"), facts("b")], Vec::new(), &r);
    let v = pick(&card, &p);
    assert_eq!(v.pick.map(|x| x.0), Some(0), "{v:?}");
    // On a level with moving platforms, a landing metric counts toward platforms.
    let plat = Features {
        moving_platforms: true,
        ..Features::NONE
    };
    assert_eq!(behaviour_of(Behaviour::Landing, plat), Behaviour::Platforms);
    assert_eq!(
        behaviour_of(Behaviour::Landing, Features::NONE),
        Behaviour::Landing
    );
    let card = VerdictRows::of(
        vec![facts("a"), facts("b")],
        vec![("l".to_string(), plat)],
        &rows(0.0, 9.0),
    );
    assert!(card.cards[1].cells.contains_key(&Behaviour::Platforms));
    assert!(!card.cards[1].cells.contains_key(&Behaviour::Landing));
}

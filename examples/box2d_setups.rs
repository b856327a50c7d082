//! Box2D set-ups side by side over the built-in set: the sample's mover, the user-side carry
//! its docs leave to the game (`GroundCarry::Ground`), the pogo spring scaled to the character
//! (`Box2dConfig::scaled_pogo_hertz`), the trade-off grid's best spring (20 Hz), and their
//! combinations. This is the command behind docs/box2d.md's choice of the advised row.
//!
//! `cargo run --example box2d_setups` prints one row per set-up: the default error score over
//! every built-in scenario, `carry_drift` on the horizontal, diagonal and circling rides,
//! `false_grounded` on the turning elevator and `apex_error` on `jumps.jump_1`.

#[path = "../compare/builtin.rs"]
mod builtin;

use platbench::box2d::kind::run_with;
use platbench::box2d::{advised_pogo_hertz, Box2dConfig, GroundCarry, STIFF_POGO_HERTZ};
use platbench::level::parse_level;
use platbench::metrics::{evaluate, score::Score, MetricRow};

fn main() {
    let levels: Vec<_> = builtin::LEVELS
        .iter()
        .map(|(f, t)| parse_level(t, f).expect("built-in level parses"))
        .collect();
    let mut setups = Vec::new();
    for carry in [GroundCarry::None, GroundCarry::Ground] {
        for hertz in [5.0, advised_pogo_hertz(), STIFF_POGO_HERTZ] {
            setups.push(Box2dConfig {
                carry,
                pogo_hertz: hertz,
                ..Default::default()
            });
        }
    }
    let watched = [
        ("platforms", "ride_horizontal", "carry_drift"),
        ("platforms", "diagonal", "carry_drift"),
        ("platforms", "circle", "carry_drift"),
        ("elevator", "ride_turning_elevator", "false_grounded"),
        ("jumps", "jump_1", "apex_error"),
    ];
    print!("| set-up | score |");
    for (l, s, m) in watched {
        print!(" {l}.{s} {m} |");
    }
    println!("\n|---|---|{}", "---|".repeat(watched.len()));
    for config in setups {
        let run = run_with(config);
        let mut rows: Vec<MetricRow> = Vec::new();
        for l in &levels {
            for s in &l.scenarios {
                rows.extend(evaluate(l, s, &run).expect("scenario runs").metrics);
            }
        }
        print!("| {} | {:.4} |", run.label, Score::default().error(&rows));
        for (l, s, m) in watched {
            let v = rows
                .iter()
                .find(|r| r.level == l && r.scenario == s && r.metric == m)
                .map_or(f64::NAN, |r| r.value);
            print!(" {v:.4} |");
        }
        println!();
    }
}

//! The Box2D backend against what Box2D's own `Mover` sample shows
//! (`samples/sample_character.cpp` at the revision boxdd 0.6 pins, 56edae79), and over every
//! built-in level.

use glam::Vec2;
use platbench::backend::{Backend, CharacterSpec};
use platbench::box2d::{Box2dBackend, Box2dConfig, ColliderBuilding};
use platbench::level::parse_level;
use platbench::motion::{Input, MotionParams};

const DT: f32 = 1.0 / 60.0;

/// The sample's mover stands on its pogo: a capsule of radius 0.3 with centres 0.5 above and
/// below its position, held by a spring (5 Hz, damping ratio 0.8) at a rest length of 3 radii
/// (0.9) below the lower centre, so the capsule's bottom floats 0.6 above the ground. A
/// character of the sample's size (0.6 wide, 2.2 tall: 0.6 of leg, 1.6 of capsule) gets the
/// sample's capsule, and after three seconds on flat ground it rests where Box2D's implicit
/// spring (`b2SpringDamper`) balances the gravity fed each grounded step: the spring's velocity
/// must be `g dt` upward, so its stretch is `x = -g dt (2 zeta + w dt) / w` with `w = 2 pi f`
/// (solving `v = (v - w (w dt) x) / (1 + 2 zeta w dt + (w dt)^2)` for `v = g dt`): the feet
/// sag 0.0338 tiles below the ground's top at 60 Hz. Box2D's shape cast stops one linear slop
/// (0.005) short of the surface (`target = max(linearSlop, totalRadius - linearSlop)` in its
/// `b2ShapeCast`), so the pogo reads its length 0.005 short and the feet rest 0.0288 below.
#[test]
fn the_sample_mover_rests_on_its_pogo_where_the_spring_balances_gravity() {
    let level = parse_level(
        "map = \"\"\"\n..........\n..........\n..........\n..........\n##########\n\"\"\"\n",
        "flat.toml",
    )
    .unwrap();
    let params = MotionParams::default();
    let config = Box2dConfig::default();
    let size = Vec2::new(0.6, 2.2);
    // The sample's capsule: radius 0.3, lower centre 0.9 above the feet (the pogo's rest
    // length), upper centre 1.9 (a segment of 1.0).
    let (r, c1, c2) = config.capsule(size);
    assert!((r - 0.3).abs() < 1e-6 && (c1 - 0.9).abs() < 1e-6 && (c2 - 1.9).abs() < 1e-6);
    for colliders in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
        let mut b = Box2dBackend::new(
            &level,
            params.clone(),
            Box2dConfig {
                colliders,
                ..config.clone()
            },
        )
        .unwrap();
        let id = b
            .add_character(CharacterSpec {
                spawn: Vec2::new(5.0, 1.5),
                size,
                velocity: Vec2::ZERO,
            })
            .unwrap();
        for _ in 0..180 {
            b.step(&[Input::default()], DT);
        }
        let s = b.state(id);
        assert!(s.grounded, "{colliders:?}: {s:?}");
        let w = 2.0 * std::f32::consts::PI * config.pogo_hertz;
        let sag = params.gravity * DT * (2.0 * config.pogo_damping_ratio + w * DT) / w;
        assert!((sag - 0.0338).abs() < 1e-4, "{sag}");
        // The ground's top is y = 1; 1e-4 tiles is f32 rounding over 180 steps of a converged
        // spring (damping 0.8 at 5 Hz decays by e^-25 in 3 s).
        let rest = 1.0 - sag + platbench::box2d::LINEAR_SLOP;
        assert!(
            (s.pos.y - rest).abs() < 1e-4,
            "{colliders:?}: {s:?}, rest {rest}"
        );
    }
}

/// Every built-in level builds on both collider buildings, and its first scenario runs.
#[test]
fn every_builtin_level_builds_and_runs_on_both_buildings() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/compare/levels");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let level = parse_level(&text, &path.to_string_lossy()).unwrap();
        for colliders in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
            let config = Box2dConfig {
                colliders,
                ..Default::default()
            };
            let mut b = Box2dBackend::new(&level, MotionParams::default(), config)
                .unwrap_or_else(|e| panic!("{}: {colliders:?}: {e}", level.name));
            if let Some(spec) = level.scenarios.first() {
                b.add_character(CharacterSpec {
                    spawn: spec.spawn,
                    size: spec.size,
                    velocity: spec.velocity,
                })
                .unwrap();
                for _ in 0..120 {
                    b.step(&[Input::default()], DT);
                }
            }
            n += 1;
        }
    }
    assert!(n >= 2 * 17, "{n}");
}

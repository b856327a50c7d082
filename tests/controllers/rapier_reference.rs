//! The figures measured on rapier2d 0.36.1's controller alone (no platbench), which
//! docs/rapier-reference.md records ("Walking on flat ground", "Corrections and additions"),
//! reproduced with the Rapier backend on the same scenes and with the same procedure: a
//! 0.8 x 0.9 character spawned 1% of its height above a floor whose top is y = 0, walked at
//! 6 tiles/s for 10 s; each frame `vy -= g dt`, desired `(vx dt, vy dt)`, `move_shape`, add the
//! translation, `vy = 0` when grounded. The level's `origin` places the floor where the
//! reference placed it (centred on x = 0), because Rapier's results depend on world coordinates.
// These tests read the built-in comparison (every controller) or a map importer: they run
// with the default features (`cargo test --no-default-features` leaves them out).
#![cfg(all(
    feature = "rapier",
    feature = "box2d",
    feature = "tiled",
    feature = "ldtk"
))]

use glam::Vec2;
use platbench::backend::CharacterSpec;
use platbench::level::{Level, Tile};
use platbench::motion::MotionParams;
use platbench::rapier::{CharacterShape, ColliderBuilding, Length, RapierBackend, RapierConfig};

const DT: f32 = 1.0 / 60.0;
const SIZE: Vec2 = Vec2::new(0.8, 0.9);

/// What one reference walk measured.
#[derive(Debug)]
struct Walk {
    /// Distance walked / distance commanded (60 tiles).
    ratio: f32,
    /// Deepest the feet went below the floor top, in tiles.
    sink: f32,
    /// Frames in which the character did not move along x.
    still: u32,
    /// Feet height above the floor at the end, in tiles.
    rest_gap: f32,
}

/// A one-row floor of `width` tiles whose top is at world y = 0 and whose left end is at world
/// x = `left`.
fn floor(width: u32, left: f32) -> Level {
    let mut tiles = vec![Tile::Solid; width as usize];
    tiles.extend(vec![Tile::Empty; width as usize * 3]);
    let mut level = Level::from_tiles("floor", width, 4, tiles);
    level.origin = Vec2::new(left, -1.0).as_dvec2();
    level
}

/// Walks the reference procedure from world x = `x`, 1% of the height above the floor, at
/// `speed` tiles/s for 10 s.
fn walk(level: &Level, config: RapierConfig, x: f32, speed: f32) -> Walk {
    walk_from(level, config, x, 0.01 * SIZE.y, speed)
}

/// As [`walk`], spawned `h` above the floor.
fn walk_from(level: &Level, config: RapierConfig, x: f32, h: f32, speed: f32) -> Walk {
    walk_fed(level, config, x, h, speed, false)
}

/// As [`walk_from`]; with `still_when_grounded`, a step after a grounded one asks for no
/// vertical move and gravity starts again only once the controller reports airborne (the
/// order of the official bevy_rapier character example).
fn walk_fed(
    level: &Level,
    config: RapierConfig,
    x: f32,
    h: f32,
    speed: f32,
    still_when_grounded: bool,
) -> Walk {
    let mut b = RapierBackend::new(level, MotionParams::default(), config).unwrap();
    let spawn = Vec2::new(x - level.origin_f32().x, 1.0 + h);
    let id = b
        .add_character(CharacterSpec {
            spawn,
            size: SIZE,
            velocity: Vec2::ZERO,
        })
        .expect("valid character");
    let (mut vy, mut sink, mut still) = (0.0f32, 0.0f32, 0u32);
    let mut grounded = false;
    for _ in 0..600 {
        let dy = if still_when_grounded && grounded {
            0.0
        } else {
            vy -= 30.0 * DT;
            vy * DT
        };
        let m = b.move_raw(id, Vec2::new(speed * DT, dy), DT);
        grounded = m.grounded;
        if m.grounded {
            vy = 0.0;
        }
        if m.translation.x == 0.0 {
            still += 1;
        }
        sink = sink.max(1.0 - b.state(id).pos.y);
    }
    let end = b.state(id).pos;
    Walk {
        ratio: (end.x - spawn.x) / (speed * 10.0),
        sink,
        still,
        rest_gap: end.y - 1.0,
    }
}

/// Starts near the stated one: x shifted by up to 0.1 tiles (and by 1), spawned 0.5%, 1% or 2%
/// of the height above the floor.
const STARTS: [(f32, f32); 15] = {
    let xs = [-0.1, 0.0, 0.05, 0.1, 1.0];
    let hs = [0.0045, 0.009, 0.018];
    let mut out = [(0.0, 0.0); 15];
    let mut i = 0;
    while i < 15 {
        out[i] = (xs[i / 3], hs[i % 3]);
        i += 1;
    }
    out
};

/// Rapier's result on these scenes depends on the exact start (f32 rounding in the shape
/// casts): the reference figure is one sample. Returns (median, min, max) of the ratio over
/// [`STARTS`], each walk starting `x0` + the shift.
fn spread(level: &Level, config: &RapierConfig, x0: f32) -> (f32, f32, f32) {
    let mut ratios: Vec<f32> = STARTS
        .iter()
        .map(|&(dx, h)| walk_from(level, config.clone(), x0 + dx, h, 6.0).ratio)
        .collect();
    ratios.sort_by(f32::total_cmp);
    (
        ratios[ratios.len() / 2],
        ratios[0],
        ratios[ratios.len() - 1],
    )
}

/// Asserts that the median over nearby starts is within 3 points of the reference and that the
/// reference lies in the measured spread (widened by one point).
fn assert_reference(what: &str, (median, min, max): (f32, f32, f32), reference: f32) {
    assert!(
        (median - reference).abs() <= 0.03 && reference >= min - 0.01 && reference <= max + 0.01,
        "{what}: median {median}, spread {min}..{max}, reference {reference}"
    );
}

fn rapier(colliders: ColliderBuilding, shape: CharacterShape) -> RapierConfig {
    RapierConfig {
        colliders,
        shape,
        // The reference spawns at the stated heights, some inside the offset band.
        lift_spawn: false,
        ..Default::default()
    }
}

/// "one 200-tile box": merged, centred on x = 0; the walk starts at x = 0.
fn on_200_box(shape: CharacterShape, colliders: ColliderBuilding) -> Walk {
    walk(&floor(200, -100.0), rapier(colliders, shape), 0.0, 6.0)
}

/// The reference's cuboid line on the 200-tile box, as a check that can fail.
fn cuboid_sticks_on_one_long_box(w: &Walk) -> Result<(), String> {
    // Reference: 0.044 of the distance, 573 of 600 frames without x motion, sink 0.008.
    // Tolerance: 3 points of the ratio, 3% of the frames, 0.001 of sink.
    if (w.ratio - 0.044).abs() > 0.03 {
        return Err(format!("ratio {} vs 0.044", w.ratio));
    }
    if (w.still as f32 - 573.0).abs() > 573.0 * 0.03 {
        return Err(format!("still frames {} vs 573", w.still));
    }
    if (w.sink - 0.008).abs() > 0.001 {
        return Err(format!("sink {} vs 0.008", w.sink));
    }
    Ok(())
}

#[test]
fn a_cuboid_sticks_on_one_long_merged_box() {
    let w = on_200_box(CharacterShape::Cuboid, ColliderBuilding::Merged);
    cuboid_sticks_on_one_long_box(&w).unwrap();
}

#[test]
fn the_cuboid_check_fails_for_another_shape_or_collider_building() {
    // The same check on the per-tile floor or with a capsule must fail: the figure belongs to
    // that shape on that floor, not to Rapier in general.
    let per_tile = on_200_box(CharacterShape::Cuboid, ColliderBuilding::PerTile);
    assert!(
        cuboid_sticks_on_one_long_box(&per_tile).is_err(),
        "{per_tile:?}"
    );
    let capsule = on_200_box(CharacterShape::Capsule, ColliderBuilding::Merged);
    assert!(
        cuboid_sticks_on_one_long_box(&capsule).is_err(),
        "{capsule:?}"
    );
}

#[test]
fn a_cuboid_on_a_2000_tile_box_covers_less_than_half() {
    let level = floor(2000, -1000.0);
    let config = rapier(ColliderBuilding::Merged, CharacterShape::Cuboid);
    // Reference: 0.44 (measured spread over nearby starts: 0.436 to 0.532).
    assert_reference("2000-tile box, cuboid", spread(&level, &config, 0.0), 0.44);
    // Reference sink 0.007, from the stated start; 0.002 tolerance.
    let w = walk(&level, config, 0.0, 6.0);
    assert!((w.sink - 0.007).abs() <= 0.002, "{w:?}");
}

#[test]
fn a_cuboid_walks_on_one_tile_cuboids() {
    // "85 one-tile cuboids": the floor runs from x = -10 to 75 (the reference does not say where;
    // the walk needs 55 tiles of floor ahead).
    let level = floor(85, -10.0);
    let config = rapier(ColliderBuilding::PerTile, CharacterShape::Cuboid);
    // Reference: 0.92 (measured spread 0.908 to 0.941).
    assert_reference("85 tiles, cuboid", spread(&level, &config, 0.0), 0.92);
    // Reference: no sink, rest gap 0.009 (the offset).
    let w = walk(&level, config.clone(), 0.0, 6.0);
    assert_eq!(w.sink, 0.0, "{w:?}");
    assert!((w.rest_gap - 0.009).abs() <= 2e-4, "{w:?}");
    let no_snap = RapierConfig {
        snap_to_ground: None,
        ..config
    };
    // Reference: 0.87 with snap-to-ground off (measured spread 0.847 to 0.918).
    assert_reference(
        "85 tiles, cuboid, no snap",
        spread(&level, &no_snap, 0.0),
        0.87,
    );
}

#[test]
fn rounded_shapes_walk_on_one_long_box() {
    let level = floor(200, -100.0);
    let capsule = rapier(ColliderBuilding::Merged, CharacterShape::Capsule);
    // Reference: 0.90.
    assert_reference("200-tile box, capsule", spread(&level, &capsule, 0.0), 0.90);
    let round = rapier(ColliderBuilding::Merged, CharacterShape::ROUND_CUBOID);
    // Reference: 0.96.
    assert_reference(
        "200-tile box, round cuboid",
        spread(&level, &round, 0.0),
        0.96,
    );
    let ball = rapier(ColliderBuilding::Merged, CharacterShape::Ball);
    // Reference: 0.875 (measured: 0.924 from the stated start, spread 0.875 to 0.925).
    assert_reference("200-tile box, ball", spread(&level, &ball, 0.0), 0.875);
    // Sinks from the stated start. Reference: capsule 0.0015, ball 0.0004, round cuboid 0.045.
    // A rounded shape's sink is also start-sensitive (0 to 0.012 measured nearby): bounded by
    // one offset; the round cuboid sinks by about its 0.05 border, within 0.005.
    let sink = |c: RapierConfig| walk(&level, c, 0.0, 6.0).sink;
    assert!(sink(capsule) <= 0.009);
    assert!(sink(ball) <= 0.009);
    let r = sink(round);
    assert!((r - 0.045).abs() <= 0.005, "round cuboid sink {r}");
}

#[test]
fn a_cuboid_on_one_long_box_mostly_sticks_wherever_it_starts() {
    // Reference: from x = -37.3, 0, 1, 7.3 and 33.3 at 2, 6 and 12 tiles/s, 13 of 15 runs
    // covered 2% to 13%. The reference walked "back and forth"; here each run walks right.
    let level = floor(200, -100.0);
    let mut stuck = 0;
    for x in [-37.3f32, 0.0, 1.0, 7.3, 33.3] {
        for speed in [2.0f32, 6.0, 12.0] {
            let w = walk(
                &level,
                rapier(ColliderBuilding::Merged, CharacterShape::Cuboid),
                x,
                speed,
            );
            stuck += (w.ratio <= 0.15) as u32;
        }
    }
    // At least 10 of 15 runs stuck (reference 13 of 15; the walks here are one-way).
    assert!(stuck >= 10, "{stuck} of 15 runs covered 15% or less");
}

#[test]
fn snap_setting_is_what_the_reference_used() {
    // The reference used Rapier's defaults: snap-to-ground 20% of the height.
    assert_eq!(
        RapierConfig::default().snap_to_ground,
        Some(Length::Relative(0.2))
    );
}

/// Median ratio of the cuboid's walk on a merged floor of `width` tiles over the reference's
/// five starts (x = -37.3, 0, 1, 7.3, 33.3, 1% of the height up, 6 tiles/s).
fn stuck_box_median(width: u32, config: RapierConfig, still_when_grounded: bool) -> f32 {
    let level = floor(width, -(width as f32) / 2.0);
    let mut ratios: Vec<f32> = [-37.3f32, 0.0, 1.0, 7.3, 33.3]
        .iter()
        .map(|&x| walk_fed(&level, config.clone(), x, 0.009, 6.0, still_when_grounded).ratio)
        .collect();
    ratios.sort_by(f32::total_cmp);
    ratios[2]
}

#[test]
fn the_stuck_box_and_its_remedies_match_the_reference() {
    // The reference's "Corrections and additions": a cuboid on one 200-tile box, median
    // progress over five starts, per way of feeding the grounded step and per documented
    // remedy. Tolerance 0.06 of the ratio: the reference does not say where it spawned the
    // character for the offset rows, and that moves the median (offset 0.02: 0.265 from the
    // stated 1% of the height, 0.257 from the offset, 0.187 from 0.05 up; reference 0.208).
    // The gap between the stuck and the freed set-ups is 0.3 or more, so the check still tells
    // them apart.
    let cuboid = rapier(ColliderBuilding::Merged, CharacterShape::Cuboid);
    let with = |f: &dyn Fn(&mut RapierConfig)| {
        let mut c = cuboid.clone();
        f(&mut c);
        c
    };
    let cases: [(&str, f32, RapierConfig, bool, f32); 7] = [
        ("gravity every step", 0.059, cuboid.clone(), false, 200.0),
        (
            "no vertical move while grounded",
            1.000,
            cuboid.clone(),
            true,
            200.0,
        ),
        (
            "no vertical move, 2,000 tiles",
            0.998,
            cuboid.clone(),
            true,
            2000.0,
        ),
        (
            "offset 0.02",
            0.208,
            with(&|c| c.offset = Length::Absolute(0.02)),
            false,
            200.0,
        ),
        (
            "offset 0.05",
            0.911,
            with(&|c| c.offset = Length::Absolute(0.05)),
            false,
            200.0,
        ),
        (
            "offset 0.1",
            0.895,
            with(&|c| c.offset = Length::Absolute(0.1)),
            false,
            200.0,
        ),
        (
            "normal nudge 1e-3",
            0.562,
            with(&|c| c.normal_nudge_factor = 1e-3),
            false,
            200.0,
        ),
    ];
    let mut report = Vec::new();
    for (what, reference, config, still, width) in cases {
        let median = stuck_box_median(width as u32, config, still);
        report.push(format!("{what}: {median:.3} (reference {reference})"));
        eprintln!("{}", report[report.len() - 1]);
        assert!((median - reference).abs() <= 0.06, "{}", report.join("; "));
    }
}

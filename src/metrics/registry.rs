//! The one registry of metric definitions: name, unit, behaviour, where it applies, the model
//! it measures against, and its default weight in the error score. The metrics (units), the
//! summary (tables and their order), the report (sections), `diff` (tolerances by unit) and
//! `sweep` (the error score) all read it; a metric added here appears everywhere.

/// The behaviour a metric measures: a section of the report, a part of a summary table, and a
/// front of its own in `platbench sweep`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Behaviour {
    /// Landing and resting on the ground.
    Landing,
    /// Jumping.
    Jumping,
    /// Walking over flat tiled ground and its seams.
    Seams,
    /// Slopes.
    Slopes,
    /// One-way platforms.
    OneWay,
    /// Ladders.
    Ladders,
    /// Moving platforms.
    Platforms,
    /// Walls hit at speed.
    Walls,
    /// Standing still with no input.
    Idle,
    /// Cost of a step (not part of the error score).
    Cost,
}

impl Behaviour {
    /// Every behaviour, in report order.
    pub const ALL: [Behaviour; 10] = [
        Behaviour::Landing,
        Behaviour::Jumping,
        Behaviour::Seams,
        Behaviour::Slopes,
        Behaviour::OneWay,
        Behaviour::Ladders,
        Behaviour::Platforms,
        Behaviour::Walls,
        Behaviour::Idle,
        Behaviour::Cost,
    ];

    /// The report's section title.
    pub fn title(self) -> &'static str {
        match self {
            Behaviour::Landing => "Landing and resting",
            Behaviour::Jumping => "Jumping",
            Behaviour::Seams => "Walking over tile seams",
            Behaviour::Slopes => "Slopes",
            Behaviour::OneWay => "One-way platforms",
            Behaviour::Ladders => "Ladders",
            Behaviour::Platforms => "Moving platforms",
            Behaviour::Walls => "Walls at speed",
            Behaviour::Idle => "Standing still",
            Behaviour::Cost => "Cost",
        }
    }

    /// A short lowercase name (`landing`, `seams`, `oneway`...), as the CLI and CSV files spell
    /// it.
    pub fn key(self) -> &'static str {
        match self {
            Behaviour::Landing => "landing",
            Behaviour::Jumping => "jumping",
            Behaviour::Seams => "seams",
            Behaviour::Slopes => "slopes",
            Behaviour::OneWay => "oneway",
            Behaviour::Ladders => "ladders",
            Behaviour::Platforms => "platforms",
            Behaviour::Walls => "walls",
            Behaviour::Idle => "idle",
            Behaviour::Cost => "cost",
        }
    }

    /// The summary table the behaviour's metrics are printed in (see [`SUMMARY_GROUPS`]).
    pub fn summary_group(self) -> &'static str {
        match self {
            Behaviour::Landing
            | Behaviour::Jumping
            | Behaviour::Seams
            | Behaviour::Walls
            | Behaviour::Idle => SUMMARY_GROUPS[0],
            Behaviour::Slopes | Behaviour::OneWay | Behaviour::Ladders => SUMMARY_GROUPS[1],
            Behaviour::Platforms => SUMMARY_GROUPS[2],
            Behaviour::Cost => SUMMARY_GROUPS[3],
        }
    }
}

/// The summary's tables, in print order.
pub const SUMMARY_GROUPS: [&str; 4] = [
    "landing, jumping, walking, walls, standing still",
    "slopes, one-way platforms, ladders",
    "moving platforms",
    "cost (run --timing)",
];

/// One metric's definition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetricDef {
    /// Its name, as `metrics.csv` spells it.
    pub name: &'static str,
    /// The unit of its values: `tiles`, `ratio`, `tiles/s`, `frames`, `count`, `bool` or `ns`.
    pub unit: &'static str,
    /// The behaviour it measures.
    pub behaviour: Behaviour,
    /// What it measures, in one sentence.
    pub meaning: &'static str,
    /// The scenarios it is reported for.
    pub applies: &'static str,
    /// The model it measures against (what "ideal" means), where controllers could differ by
    /// design.
    pub reference: &'static str,
    /// Its weight in the default error score of `platbench sweep` (0: not scored). The default
    /// charges no controller for its declared design: the touching-model geometric metrics
    /// (`rest_gap`, `max_penetration`, `slope_gap_max`, `slope_overlap`) weigh 0 and their
    /// declared-model twins (`rest_gap_declared`, `penetration_beyond_declared`) 1.
    pub weight: f64,
    /// Metrics that measure the same behaviour against different models share a group: the
    /// error score charges a scenario only the closest model's error (a controller following
    /// either model of slope speed is not wrong).
    pub model_group: Option<&'static str>,
}

impl MetricDef {
    /// The size of error that counts as clearly wrong in the error score, in the metric's unit:
    /// 0.01 tiles, 0.01 for ratios, 0.01 tiles/s, one frame, count or boolean. It is counted
    /// beyond the error the game cannot show ([`MetricDef::allowance`]).
    pub fn scale(&self) -> f64 {
        unit_scale(self.unit)
    }

    /// The part of an error in this metric's unit that is not charged at `pixels_per_tile`
    /// pixels per tile: one pixel for a length, one pixel per second for a speed, nothing for
    /// ratios, frames, counts and booleans (see [`unit_allowance`]).
    pub fn allowance(&self, pixels_per_tile: f64) -> f64 {
        unit_allowance(self.unit, pixels_per_tile)
    }

    /// How many clearly-wrong sizes error `error` is once the allowance is taken off:
    /// `max(0, |error| - allowance) / scale` (not capped; infinite for a NaN). The error score
    /// caps it at 1; the verdict grades it (1 or less: kept, 10 or less: minor).
    pub fn charged(&self, error: f64, pixels_per_tile: f64) -> f64 {
        charged(self.unit, error, pixels_per_tile)
    }
}

/// Pixels per tile the error score, `run --traces failing` and the verdict assume when not told
/// otherwise (`platbench sweep --pixels-per-tile`): a 16-pixel tile, common in pixel-art
/// platformers (at 8 pixels per tile the one-pixel allowance doubles in tiles).
pub const DEFAULT_PIXELS_PER_TILE: f64 = 16.0;

/// The "clearly wrong" size of an error in `unit` (see [`MetricDef::scale`]).
pub(crate) fn unit_scale(unit: &str) -> f64 {
    match unit {
        "tiles" | "ratio" | "tiles/s" => 0.01,
        _ => 1.0,
    }
}

/// The error in `unit` no game at `pixels_per_tile` pixels per tile can show, which the score
/// does not charge: one pixel (`1 / pixels_per_tile` tiles) for a length in tiles; one pixel per
/// second for a speed in tiles/s (a climb that far off its speed ends a pixel away from where it
/// should after a second of climbing: below that no frame shows the difference); 0 for ratios
/// (a ratio has no length: its error already scales with the distance walked), frames, counts,
/// booleans and costs. A `pixels_per_tile` that is not a positive number allows nothing.
pub fn unit_allowance(unit: &str, pixels_per_tile: f64) -> f64 {
    match unit {
        "tiles" | "tiles/s" if pixels_per_tile > 0.0 && pixels_per_tile.is_finite() => {
            1.0 / pixels_per_tile
        }
        _ => 0.0,
    }
}

/// [`MetricDef::charged`] for a value in `unit` (a metric this version may not define).
pub fn charged(unit: &str, error: f64, pixels_per_tile: f64) -> f64 {
    if error.is_nan() {
        return f64::INFINITY;
    }
    (error.abs() - unit_allowance(unit, pixels_per_tile)).max(0.0) / unit_scale(unit)
}

const fn def(
    name: &'static str,
    unit: &'static str,
    behaviour: Behaviour,
    meaning: &'static str,
    applies: &'static str,
    reference: &'static str,
    weight: f64,
) -> MetricDef {
    MetricDef {
        name,
        unit,
        behaviour,
        meaning,
        applies,
        reference,
        weight,
        model_group: match name.as_bytes() {
            b"slope_speed_ratio" | b"slope_surface_speed_ratio" => Some("slope_speed"),
            _ => None,
        },
    }
}

use Behaviour::*;

/// Every metric this version computes, in catalog order (tables list them in this order).
pub const METRICS: &[MetricDef] = &[
    def(
        "land_frame_error",
        "frames",
        Landing,
        "first grounded frame minus the frame the discrete integrator predicts",
        "a drop with no input and no horizontal speed onto flat static ground",
        "the shared symplectic-Euler fall, grounded on the step that reaches the floor",
        1.0,
    ),
    def(
        "rest_gap",
        "tiles",
        Landing,
        "signed gap from the character's shape down to the ground at the end of a rest (negative: sunk)",
        "scenarios ending with at least 0.5 s of idle input, not riding a platform",
        "touching (gap 0)",
        0.0,
    ),
    def(
        "rest_gap_declared",
        "tiles",
        Landing,
        "the rest_gap minus the gap of the stance the configuration declares (0: promise kept)",
        "scenarios ending with at least 0.5 s of idle input, not riding a platform",
        "the configuration's declared contact: Rapier's offset along the ground's normal; the seed's box on the surface under its centre",
        1.0,
    ),
    def(
        "max_penetration",
        "tiles",
        Landing,
        "deepest overlap of the character's shape with the level's solid tiles and slopes, or depth below a one-way top it stands on, over the run",
        "every scenario",
        "no overlap",
        0.0,
    ),
    def(
        "penetration_beyond_declared",
        "tiles",
        Landing,
        "deepest overlap with the level beyond what the configuration declares it may overlap",
        "every scenario",
        "the configuration's declared overlap: the sweep's epsilon, and the overlap its box has standing on the surface under its centre (the seed's overhang into a slope)",
        1.0,
    ),
    def(
        "rest_jitter",
        "tiles",
        Landing,
        "max minus min of the feet's height over the settled rest (its last 0.5 s, as stress judges it), leaving out frames a moving platform shoves",
        "scenarios ending with at least 0.5 s of idle input, not riding a platform",
        "a still rest",
        1.0,
    ),
    def(
        "bounce_frames",
        "frames",
        Landing,
        "frames airborne after the character first touched ground in its final idle span (a landing that bounces or lifts off again), leaving out frames a moving platform shoves",
        "scenarios ending with at least 0.5 s of idle input, not riding a platform",
        "staying down once landed",
        1.0,
    ),
    def(
        "grounded_flicker",
        "count",
        Landing,
        "grounded-to-airborne switches no jump explains while the ground is still under the feet",
        "every scenario",
        "no switch",
        1.0,
    ),
    def(
        "false_grounded",
        "frames",
        Landing,
        "frames reported grounded with no ground within 0.1 tiles below the shape",
        "every scenario",
        "grounded only on ground",
        1.0,
    ),
    def(
        "apex_error",
        "tiles",
        Jumping,
        "rise from take-off to the apex of the first jump minus the requested jump height",
        "a jump with no solid within its reach above",
        "the requested height",
        1.0,
    ),
    def(
        "progress_ratio",
        "ratio",
        Seams,
        "distance walked over distance commanded",
        "a walk over flat, open, supported tiled ground",
        "the shared motion model's commanded distance",
        1.0,
    ),
    def(
        "stuck_frames",
        "frames",
        Seams,
        "commanded, grounded steps that moved less than 1% of the commanded step with nothing blocking",
        "every scenario",
        "no stuck step",
        1.0,
    ),
    def(
        "slope_airborne_frames",
        "frames",
        Slopes,
        "frames airborne over a walkable slope while walking, without a jump",
        "a walk without a jump over a slope within the climb limit",
        "grounded all the way",
        1.0,
    ),
    def(
        "slope_gap_max",
        "tiles",
        Slopes,
        "signed gap between the shape and the surface farthest from touching over a walkable slope while grounded (negative: inside)",
        "a walk over, or a rest on, a slope within the climb limit",
        "touching (gap 0)",
        0.0,
    ),
    def(
        "slope_gap_declared",
        "tiles",
        Slopes,
        "slope_gap_max against the stance the configuration declares: the grounded gap over a walkable slope less the declared stance's gap, farthest from 0 (0: promise kept)",
        "a walk over, or a rest on, a slope within the climb limit",
        "the configuration's declared contact: Rapier's offset along the ground's normal; the seed's box on the surface under its centre",
        // Scored: a hover or sink beyond the declared contact is no configuration's declared
        // design (Rapier's is its offset; its snap-to-ground promises no more than that).
        1.0,
    ),
    def(
        "slope_overlap",
        "tiles",
        Slopes,
        "deepest overlap of the character's shape with a slope tile's solid part (penetration depth)",
        "every scenario on a level with slopes",
        "touching; the seed's centre-column rule overhangs a box by half its width times the gradient, by design",
        0.0,
    ),
    def(
        "slope_speed_ratio",
        "ratio",
        Slopes,
        "mean horizontal speed over a walkable slope at full run speed over the run speed",
        "a walk without a jump over a slope within the climb limit, not into a too-steep one",
        "constant horizontal speed (the seed)",
        1.0,
    ),
    def(
        "slope_surface_speed_ratio",
        "ratio",
        Slopes,
        "mean speed along the path over a walkable slope at full run speed over the run speed",
        "a walk without a jump over a slope within the climb limit, not into a too-steep one",
        "constant speed along the surface (Godot's floor_constant_speed)",
        1.0,
    ),
    def(
        "steep_blocked",
        "bool",
        Slopes,
        "1 if a slope above the climb limit stopped the climb, else 0",
        "a walk toward a slope steeper than the climb limit",
        "blocked",
        1.0,
    ),
    def(
        "oneway_result",
        "bool",
        OneWay,
        "1 if the character ended where the seed's rule puts it, else 0",
        "scenarios on levels with one-way platforms that state an expected end height",
        "the seed's one-way rule",
        1.0,
    ),
    def(
        "ladder_speed_error",
        "tiles/s",
        Ladders,
        "worst climbing speed on the ladder minus the configured ladder speed",
        "scenarios on levels with ladders that hold up or down",
        "the configured ladder speed",
        1.0,
    ),
    def(
        "ladder_result",
        "bool",
        Ladders,
        "1 if the character ended where the scenario says (top, bottom, floor), else 0",
        "scenarios on levels with ladders that state an expected end height",
        "the scenario's expected end",
        1.0,
    ),
    def(
        "carry_drift",
        "tiles",
        Platforms,
        "largest change of the rider's position relative to its platform over the idle ride",
        "scenarios that name a platform to ride",
        "carried rigidly",
        1.0,
    ),
    def(
        "carry_airborne_frames",
        "frames",
        Platforms,
        "frames airborne during the idle ride",
        "scenarios that name a platform to ride",
        "on the platform throughout",
        1.0,
    ),
    def(
        "push_penetration",
        "tiles",
        Platforms,
        "deepest overlap of the character's shape with a (not one-way) moving platform, outside a crush by design (a platform squeezing it against the level)",
        "levels with moving platforms",
        "no overlap",
        1.0,
    ),
    def(
        "crush_count",
        "count",
        Platforms,
        "times the character ended more than 0.25 tiles inside a moving platform against the crush rule: run through with room to be pushed, or squeezed against the level with no crush reported",
        "levels with moving platforms",
        "never run through; a squeeze against the level reported as a crush (the trace's crushed column)",
        1.0,
    ),
    def(
        "tunneled",
        "bool",
        Walls,
        "1 if the character passed wholly through a solid tile between two frames, else 0",
        "every scenario",
        "never",
        1.0,
    ),
    def(
        "idle_drift",
        "tiles",
        Idle,
        "largest displacement of a settled character with no input, off ladders, riding no platform and pushed by none, over each idle span",
        "every scenario with an idle step that rides no platform",
        "standing still",
        1.0,
    ),
    def(
        "left_level",
        "bool",
        Landing,
        "1 if the character left the level: its feet below the lowest thing that could catch it (the bottom of the lowest non-empty tile row or platform reach) while falling, or its box wholly beside or below the map; else 0",
        "every scenario",
        "never (above the map is not leaving it)",
        1.0,
    ),
    def(
        "expect_reach",
        "bool",
        Landing,
        "1 if the feet never entered the scenario's expect.reach region (tiles, bounds inclusive) by its deadline, else 0",
        "scenarios whose expect table states reach",
        "the level's stated expectation",
        1.0,
    ),
    def(
        "expect_grounded_at_end",
        "bool",
        Landing,
        "1 if the controller's grounded flag on the last frame is not the scenario's expect.grounded_at_end, else 0",
        "scenarios whose expect table states grounded_at_end",
        "the level's stated expectation",
        1.0,
    ),
    def(
        "expect_min_y",
        "bool",
        Landing,
        "1 if the feet ever went below the scenario's expect.min_y (tiles), else 0",
        "scenarios whose expect table states min_y",
        "the level's stated expectation",
        1.0,
    ),
    def(
        "expect_stay_in_map",
        "bool",
        Landing,
        "1 if the feet ever left the map (0 <= x <= width, 0 <= y <= height, tiles), else 0",
        "scenarios whose expect table sets stay_in_map = true",
        "the level's stated expectation",
        1.0,
    ),
    def(
        "expect_land_on",
        "bool",
        Platforms,
        "1 if the character never stood on the moving platform expect.land_on names (grounded, feet within 0.05 tiles of its top, overlapping it), else 0",
        "scenarios whose expect table states land_on",
        "the level's stated expectation",
        1.0,
    ),
    def(
        "ns_per_character_step",
        "ns",
        Cost,
        "nanoseconds per character step, median of 11 in-process samples on the thread's CPU clock (their quartiles in `q1` and `q3`)",
        "run --timing",
        "none (a cost, not an error)",
        0.0,
    ),
];

/// The definition of metric `name`, if this version defines it.
pub fn get(name: &str) -> Option<&'static MetricDef> {
    METRICS.iter().find(|d| d.name == name)
}

/// The catalog position of metric `name` (unknown metrics sort last).
pub fn position(name: &str) -> usize {
    METRICS
        .iter()
        .position(|d| d.name == name)
        .unwrap_or(usize::MAX)
}

/// The unit of metric `name` (empty if unknown).
pub fn unit(name: &str) -> &'static str {
    get(name).map_or("", |d| d.unit)
}

/// The metrics of one behaviour, in catalog order.
pub(crate) fn of_behaviour(b: Behaviour) -> impl Iterator<Item = &'static MetricDef> {
    METRICS.iter().filter(move |d| d.behaviour == b)
}

#[cfg(test)]
#[path = "registry_tests.rs"]
mod tests;

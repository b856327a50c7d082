//! The notes under the summary: a sentence explaining each effect the rows show, printed only
//! when the measurements show it; and [`RunNotes`], which gathers them from a stream of runs.

use std::collections::HashSet;

use crate::metrics::MetricRow;

/// Explanations of the differences `rows` show: each built-in controller's, then those about no
/// one controller, each printed only when the measurements show the effect it explains.
pub fn notes(rows: &[MetricRow]) -> Vec<String> {
    let mut out = sweep(rows);
    #[cfg(feature = "rapier")]
    out.extend(rapier(rows));
    #[cfg(feature = "box2d")]
    out.extend(box2d(rows));
    out.extend(general(rows));
    out
}

/// The notes that concern no one controller.
fn general(rows: &[MetricRow]) -> Vec<String> {
    let mut out = Vec::new();
    if rows
        .iter()
        .any(|r| r.metric == "apex_error" && r.config.contains("jump=continuous"))
    {
        out.push("jump=continuous is the seed's v = sqrt(2 g h): exact for continuous motion, short by up to v*dt/2 under symplectic Euler; the default solves the impulse for the discrete apex.".into());
    }
    out
}

/// The sweep's notes.
fn sweep(rows: &[MetricRow]) -> Vec<String> {
    use crate::sweep::kind::NAME;
    let mut out = Vec::new();
    if rows
        .iter()
        .any(|r| r.backend == NAME && r.metric == "slope_overlap" && r.value > 1e-3)
    {
        out.push("sweep slope_overlap: the seed's centre-column rule stands the box on the surface under its centre, so the box overhangs a ramp by half its width times the gradient (0.4 sin(angle) along the ramp's normal: 0.28 tiles at 45 degrees); by design, and counted in max_penetration, rest_gap and slope_gap_max too, as any shape inside a slope is.".into());
    }
    // A walk toward a too-steep slope (steep_blocked measured) that ends inside it beyond
    // the overhang a walkable ramp gives.
    let steep_walk = |r: &MetricRow| {
        rows.iter().any(|s| {
            s.metric == "steep_blocked"
                && (&s.level, &s.scenario, &s.backend, &s.config)
                    == (&r.level, &r.scenario, &r.backend, &r.config)
        })
    };
    if rows.iter().any(|r| {
        r.backend == NAME
            && r.metric == "penetration_beyond_declared"
            && r.value > 1e-3
            && steep_walk(r)
    }) {
        out.push("sweep penetration_beyond_declared at a too-steep slope: the climb limit is tested on the centre column, so the box stops with its centre at the foot of the steep rise and its leading half inside it (0.4 sin(63.4 degrees) = 0.36 tiles deep on the 63.4-degree ramp, 0.07 beyond the 0.28 a walkable ramp gives); the seed's alternative, colliding the higher side like a solid box, is not modelled.".into());
    }
    out
}

/// Rapier's notes.
#[cfg(feature = "rapier")]
fn rapier(rows: &[MetricRow]) -> Vec<String> {
    use crate::rapier::kind::NAME;
    fn rapier<'a>(rows: &'a [MetricRow], m: &'a str) -> impl Iterator<Item = &'a MetricRow> {
        rows.iter()
            .filter(move |r| r.backend == NAME && r.metric == m)
    }
    let rapier = |m| rapier(rows, m);
    let mut out = Vec::new();
    if rapier("rest_gap").any(|r| r.value > 1e-3) {
        out.push("rapier rest_gap is about its `offset` (1% of the character height, 0.009 tiles): Rapier keeps this gap on purpose and its docs say it must not be zero.".into());
    }
    if rapier("land_frame_error").any(|r| r.value < 0.0) {
        out.push("rapier lands early: it reports grounded while still within its ground prediction above the floor (its offset plus 0.05 tiles), then snaps down.".into());
    }
    if rapier("max_penetration").any(|r| r.value > 0.0 && r.config.starts_with("merged")) {
        out.push("rapier sinks into merged floors: a shape cast at a glancing angle can miss the offset band and start inside the floor (rapier #613).".into());
    }
    if rapier("false_grounded").any(|r| r.value > 0.0) {
        out.push("rapier false_grounded: rounded shapes sliding down a wall made of stacked tiles report grounded on the tile corners, which resets their fall.".into());
    }
    if rows.iter().any(|r| {
        r.backend == NAME
            && r.config.starts_with("merged cuboid")
            && r.metric == "progress_ratio"
            && r.value < 0.5
    }) {
        out.push("rapier shapes: on one long merged box a cuboid sticks (it misses the offset band at a glancing angle, starts inside the floor and every cast from there is blocked, rapier #613) while capsule, ball and round cuboid slide on; on per-tile floors every shape walks but catches on seams. A box character wants per-tile or short merged colliders; a rounded one can use merged floors, but not boxes thousands of tiles long, which rounded shapes sink into.".into());
    }
    if rapier("steep_blocked").any(|r| r.value == 0.0) {
        out.push("rapier climbs a too-steep slope that rises to the left, on every collider building: its 2D climb test uses a signed angle that is negative for such slopes (the same slope rising to the right blocks).".into());
    }
    if rapier("carry_airborne_frames").any(|r| r.value > 0.0) {
        out.push("rapier riders: the controller carries a rider by the velocity of the platform body it touches (the platforms move first, so it is this step's); on paths that turn (diagonal, circle) the rider loses the platform.".into());
    }
    if rapier("progress_ratio").any(|r| r.value < 0.99) {
        out.push("rapier loses progress on flat ground when fed gravity on every grounded step: the shape catches on tile seams; fed no vertical move while grounded (grounded=none-but-platforms) it walks.".into());
    }
    if rapier("idle_drift").any(|r| r.value > 1e-3) {
        out.push("rapier idle_drift: a standing Rapier character moves with no input: fed gravity every step, each cast hit adds the normal nudge (1e-4 tiles along the contact normal), which walks it down a slope at rest; and a wall sliding flush past its side pushes it away (moving_wall).".into());
    }
    out
}

/// Box2D's notes.
#[cfg(feature = "box2d")]
fn box2d(rows: &[MetricRow]) -> Vec<String> {
    use crate::box2d::kind::NAME;
    let b = |m: &'static str| {
        rows.iter()
            .filter(move |r| r.backend == NAME && r.metric == m)
    };
    let mut out = Vec::new();
    if b("rest_gap").any(|r| r.value.abs() > 1e-3) {
        out.push("box2d rest_gap: the sample's mover stands on a pogo spring (5 Hz, damping 0.8), not on a contact: fed gravity each step, the spring settles the feet where its push balances gravity, off the ground's top by the sag.".into());
    }
    if b("carry_airborne_frames").any(|r| r.value > 0.0) || b("carry_drift").any(|r| r.value > 1e-3)
    {
        out.push("box2d riders: the sample carries no rider and Box2D documents no remedy (docs/character.md and the sample at 56edae79 never read the ground body's velocity); a platform moves the mover only through its collision planes (push limited to 0.1 tiles, the sample's elevator) and the pogo, so a horizontal platform slides out from under it.".into());
    }
    if b("false_grounded").any(|r| r.value > 0.0) {
        out.push("box2d false_grounded: the sample's 5 Hz pogo spring follows moving ground at a steady lag (0.124 tiles above an elevator going down at 3 tiles/s), and the sample is on ground whenever the pogo's cast hits.".into());
    }
    if b("steep_blocked").any(|r| r.value == 0.0) {
        out.push("box2d climbs slopes steeper than the limit: the sample's pogo stands on any surface it touches (it has no slope limit).".into());
    }
    out
}

/// The notes of a stream of runs without holding every row: each run's rows are read as they
/// come and the rows of the first run that calls for each note are kept. A note is about the
/// rows of one run (a row past a threshold, or two rows of the same run), so the notes of the
/// kept runs are [`notes`] of every row, in the same order. Memory: one run's rows per distinct
/// note.
#[derive(Default)]
pub struct RunNotes {
    seen: HashSet<String>,
    rows: Vec<MetricRow>,
}

impl RunNotes {
    /// No run read yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Reads the rows of one run.
    pub fn push_run(&mut self, rows: &[MetricRow]) {
        let mut new = false;
        for n in notes(rows) {
            new |= self.seen.insert(n);
        }
        if new {
            self.rows.extend_from_slice(rows);
        }
    }

    /// The notes of every run read.
    pub fn notes(&self) -> Vec<String> {
        notes(&self.rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_notes_of_the_kept_runs_are_the_notes_of_every_row() {
        // The sweep's note on a too-steep slope needs a penetration row and a steep_blocked row
        // of the same run; here the run that has both comes between two that do not, and its
        // steep_blocked value is neither the lowest nor the highest (the summary drops it).
        let r = |scenario: &str, metric: &'static str, value: f64| MetricRow {
            level: "l".into(),
            scenario: scenario.into(),
            backend: "sweep".into(),
            config: "default".into(),
            metric,
            value,
            unit: "tiles",
            reference: 0.0,
            error: value,
            frame: None,
        };
        let runs = [
            vec![
                r("a", "penetration_beyond_declared", 0.0),
                r("a", "steep_blocked", 0.0),
            ],
            vec![
                r("b", "penetration_beyond_declared", 0.07),
                r("b", "steep_blocked", 0.5),
            ],
            vec![r("c", "penetration_beyond_declared", 0.2)],
            vec![r("d", "steep_blocked", 1.0)],
        ];
        let all: Vec<MetricRow> = runs.iter().flatten().cloned().collect();
        let mut kept = RunNotes::new();
        for run in &runs {
            kept.push_run(run);
        }
        let expected = notes(&all);
        assert!(
            expected.iter().any(|n| n.contains("too-steep slope")),
            "{expected:?}"
        );
        assert_eq!(kept.notes(), expected);
        // Only the run that called for a note is kept.
        assert_eq!(kept.rows.len(), 2);
    }
}

//! The range of every number a user gives platbench, checked before any work is done: a
//! value outside its range is an error that says what was found and what is expected, never a
//! hang, a runaway allocation or a silently meaningless run. The "Input ranges" table of docs/formats.md
//! lists the same numbers.
//!
//! Why these numbers: they are generous multiples of what the stress matrix exercises (offsets
//! to 1e7 tiles in f32 and 1e15 in f64, the level origin's limits; dt 1e-4 to 0.2 s, speeds to
//! 1000 tiles/s, widths 0.01 to 10 tiles), and
//! together they keep every quantity a run computes finite and its work proportional to the
//! frames and tiles asked for: a fall under the largest gravity for the longest duration
//! reaches `0.5 * 1e5 * 1e5^2 = 5e14` tiles, within f32 and far within the sweep's integer
//! positions (`i64` subpixels).

use std::path::Path;

/// Largest file read as a level, map, tileset or side file, in bytes (128 MiB): sixteen layers
/// of the largest map (the most a Tiled map's layers hold together) written as Tiled CSV take
/// about 32 MB. Only regular files are read
/// ([`crate::input`]): a device or named pipe (`/dev/zero`, a FIFO) is refused before it is
/// opened.
pub(crate) const MAX_INPUT_BYTES: u64 = 128 * 1024 * 1024;
/// Deepest nesting of group layers in a Tiled map: the `tiled` crate reads a group by
/// recursion, and 100,000 nested groups overflowed the stack. Tiled's editor makes a group per
/// folder of layers; 64 is far beyond any map made by hand.
#[cfg(feature = "tiled")]
pub(crate) const MAX_GROUP_DEPTH: usize = 64;
/// Deepest nesting of elements in a Tiled map, tileset or template (groups, class properties
/// within class properties), checked for the same reason.
#[cfg(feature = "tiled")]
pub(crate) const MAX_XML_DEPTH: usize = 128;
/// Most attributes one element of a Tiled map, tileset or template may have. The `tiled` crate
/// reads an element's attributes through quick-xml, which checks each against every one before
/// it for a duplicate: time grows with the square of their number (200,000 on `<map>` ran past
/// 120 s; 20,000 took 6.7 s). Tiled writes at most 19 (on `<map>`); 64 leaves room for other
/// tools' and hand-written ones.
#[cfg(feature = "tiled")]
pub(crate) const MAX_XML_ATTRIBUTES: usize = 64;
/// Longest chain of files a Tiled map reaches through references (the map, a tileset, a
/// template its tile uses, the template's tileset, and so on), the map included. A chain that
/// comes back to a file it has already passed is refused whatever its length.
#[cfg(feature = "tiled")]
pub(crate) const MAX_TILED_FILE_CHAIN: usize = 32;
/// Most tiles a level may have (width x height), TOML, Tiled or LDtk alike: what one thread of
/// a run holds within 2 GB ([`RUN_MEMORY`]) whatever the tiles are. It was 16,000,000, which no
/// run could hold: a backend's world costs hundreds of bytes a tile (one collider or shape per
/// tile and an engine's tree over them), and 16 million solid tiles took about 10 GB. Measured
/// as peak RSS of `platbench run MAP --out DIR --traces none --jobs 1` with every backend: a
/// solid 2000 x 1000 map 1.24 GB (622 bytes a tile), a 1000 x 1000 map of `/` slopes 675 MB,
/// and the most costly map, a 1000 x 1000 checkerboard of solid tiles, 1.38 GB (each solid
/// tile is its own rectangle, which Box2D's merged world makes a chain loop of four segments).
pub(crate) const MAX_TILES: u64 = 1_000_000;
/// Most cells all the tile layers of one Tiled map may hold together (the sum of each layer's
/// width x height), checked before any layer is read: every layer's cells are held while the
/// map is read, about 20 bytes a cell (peak RSS of `platbench inspect` on a 1000 x 1000 map:
/// 76 MB with one layer, 135 MB with four), so 20 layers of 16 million cells each aborted under
/// a 4 GiB cap. Sixteen layers of the largest map, about 330 MB, freed before the run.
#[cfg(feature = "tiled")]
pub(crate) const MAX_LAYER_CELLS: u64 = 16 * MAX_TILES;
/// Memory `platbench run` keeps its levels' worlds within, in bytes (2 GiB): the threads it
/// fans out over ([`jobs_within_memory`]) each build one backend's world of one level at a time.
pub(crate) const RUN_MEMORY: u64 = 2 << 30;
/// Peak memory one thread of a run takes per tile of the level it runs, in bytes: the most
/// costly map measured for [`MAX_TILES`], a checkerboard of solid tiles, 1.38 GB for 1,000,000
/// tiles, rounded up. Box2D's world is the largest (a shape is 444 bytes in its shape array,
/// grown by doubling, 46 in its tree and 43 in boxdd's own tables; a solid map's per-tile world
/// 540 MB a million tiles, a checkerboard's merged one of chain loops 1.38 GB), then Rapier's
/// (a collider 233 bytes, 199 in its broad phase) and the sweep's (boxes and BVH, about 170).
pub(crate) const THREAD_BYTES_PER_TILE: u64 = 1_400;
/// Most frames (duration / dt) one scenario may run.
pub const MAX_FRAMES: u64 = 10_000_000;
/// Most frames all the scenarios of one level may run together.
pub(crate) const MAX_LEVEL_FRAMES: u64 = 50_000_000;
/// Longest scenario, in seconds (about 28 hours of game time).
pub const MAX_DURATION: f64 = 1e5;
/// Smallest and largest time step, in seconds.
pub const DT_RANGE: (f64, f64) = (1e-6, 1.0);
/// Largest distance of a platform's corner or waypoint, a sine amplitude, a circle radius or an
/// `expect_y` from zero, in tiles: these are level coordinates, which every backend keeps in f32,
/// and beyond 1e7 an f32 position moves in whole tiles, where nothing a controller does means
/// anything.
pub(crate) const MAX_COORD: f64 = 1e7;
/// Largest distance of a level's origin from the world's origin, in tiles, on each axis: the
/// offsets `platbench stress` measures f64 configurations at (f64 spacing 1/8 tile there). The
/// origin is kept in f64, so anything up to this is placed exactly by an f64 configuration.
pub const MAX_ORIGIN: f64 = 1e15;
/// Largest distance of a level's origin from the world's origin, in tiles, at which an f32
/// configuration runs it ([`crate::controller::Controller::max_origin`]): beyond it an f32
/// position's spacing is over a tile (1 tile at 1e7, 8 at 1e8), every f32 configuration
/// measured has broken (`platbench stress`), and Rapier's f32 casts take seconds a step. Such a
/// level is skipped by f32 configurations and runs on f64 ones (`--precision f64`); the sweep's
/// integer positions, whose positions are whole subpixels, hold to 2^24 tiles (the level's
/// whole reach, origin plus size and platform paths, [`crate::level::Level::reach`]).
pub const MAX_F32_ORIGIN: f64 = 1e7;
/// Smallest and largest character width or height, in tiles.
pub(crate) const SIZE_RANGE: (f64, f64) = (1e-3, 1e3);
/// Largest speed (a run speed, an initial velocity component, a ladder or platform speed), in
/// tiles/s.
pub(crate) const MAX_SPEED: f64 = 1e4;
/// Largest acceleration (gravity, run acceleration), in tiles/s².
pub(crate) const MAX_ACCEL: f64 = 1e5;
/// Largest jump height, in tiles.
pub(crate) const MAX_JUMP_HEIGHT: f64 = 1e4;
/// Smallest platform period, in seconds (a period shorter than the smallest dt is noise).
pub(crate) const MIN_PERIOD: f64 = 1e-6;
/// Most waypoints of one platform path: a platform's place is found by walking its legs every
/// step, so a path's points cost every frame (real maps' paths hold a handful).
pub(crate) const MAX_PATH_POINTS: usize = 1_000;
/// Most changed metrics a diff lists of each change (worse, better, missing, added), and most
/// runs `check` lists that its new run lacks: every one is counted, and `diff --format csv`
/// and `check.csv` hold every one. A 1 GB baseline of 14 million rows the new run lacks listed
/// them all, in a summary of 150 MB per 100 MB, and aborted at 3.4 GB under
/// `prlimit --as=4294967296`; the built-in comparison has 18,883 rows.
pub const MAX_LISTED_CHANGES: usize = 1_000;

/// Rows of a metrics file `diff`, `check` and `review` read. The diff indexes the new run's rows
/// (about 280 bytes each) to stream the baseline past them: 1,000,000 extra rows took 285 MB and
/// a 1 GB file of 14 million would pass 4 GB. The built-in comparison writes 18,883 rows; 2
/// million keep the index near 600 MB.
pub const MAX_METRIC_ROWS: u64 = 2_000_000;

/// Bytes of one record of a CSV file `diff`, `check`, `review` and `report` read (a metrics row
/// or a trace frame: a few hundred bytes). A 1 GB field was read into one buffer and aborted
/// at 3 GB under `prlimit --as=4294967296`.
pub const MAX_CSV_RECORD_BYTES: u64 = 1024 * 1024;
/// Most rows of a trade-off CSV given to `report --tradeoff`: `platbench sweep` writes one row
/// per setting and scope, a few hundred (the built-in `compare/tradeoff/tradeoff.csv` holds 490),
/// and the report's chart draws an element per row, so 2.6 million rows (108 MiB) took 3.8 GB.
pub(crate) const MAX_TRADEOFF_ROWS: usize = 100_000;
/// Most rows of a stability.csv given to `report --stability`: `platbench stress` writes about
/// 4,000 (every backend, both precisions), and the report draws a table row per configuration
/// and dimension, so a file of rows each naming its own configuration costs a verdict, a table
/// row and their text per row: the 2.8 million such rows of a 128 MiB file reached 3.5 GB under
/// `prlimit --as=4294967296` (32 s); 100,000 take 0.9 s and 182 MB, 100,000 rows of a real run's
/// repeated 0.14 s and 47 MB. Refused at the first row past it.
pub(crate) const MAX_STABILITY_ROWS: usize = 100_000;
/// Most cells the combination grids of a stability.csv given to `report --stability` may hold
/// together, counted row by row as the file is read: a grid has a cell for every configuration
/// and first value times every second value, measured or not, so its size grows as the product
/// of the distinct values, not with the rows. `platbench stress` writes grids of about 250 cells
/// (the largest 27 x 4); 20,000 made-up rows of distinct values (2,222 of each) asked for 4.9
/// million cells, 241 MB of report and 980 MB of memory. 100,000 cells are about 5 MB of report.
pub(crate) const MAX_STABILITY_GRID_CELLS: u64 = 100_000;
/// Largest sweep epsilon, in tiles: an overlap tolerance of a whole tile tolerates everything.
pub(crate) const MAX_EPSILON: f64 = 1.0;
/// Most points of one Tiled polygon or polyline (a collision shape, a tile's collision
/// object, a platform's path), counted in the file before the `tiled` crate reads it: a ramp
/// has 3 or 4 corners and a hand-drawn outline some dozens, so 10,000 leaves room for traced
/// outlines while every shape is read in milliseconds (a 1,000,000-point polygon took 58 s
/// when a ramp was still found by a quadratic search).
#[cfg(feature = "tiled")]
pub(crate) const MAX_POLYGON_POINTS: usize = 10_000;
/// Most bytes of strings and member names in a Tiled JSON file (map, tileset or template), a
/// tile layer's `data` string aside, counted before serde_json reads it: the translation to TMX
/// escapes `&`, `<`, `>` and `"` (up to six bytes each) and holds several copies, so 120 MB of
/// `&` in one property aborted at 3.1 GB (about 27 bytes a byte of file). A map's names, types,
/// properties and image paths take kilobytes; 16 MiB keeps that worst case near 450 MB.
#[cfg(feature = "tiled")]
pub(crate) const MAX_JSON_TEXT_BYTES: u64 = 16 * 1024 * 1024;
/// Deepest nesting of arrays and objects in a Tiled JSON file (map, tileset or template):
/// serde_json, which reads it, stops at 128 with a bare "recursion limit exceeded", so the walk
/// before it (`level/tiled/json_walk.rs`) refuses what passes 127 with the line and column. A
/// group layer nests two (its object and its `layers`), so a tile layer's `data` array sits in at
/// most 61 groups of a JSON map (64 in a TMX map, [`MAX_GROUP_DEPTH`]).
#[cfg(feature = "tiled")]
pub(crate) const MAX_JSON_DEPTH: usize = 127;
/// Most JSON objects (`{...}`) in a Tiled JSON file, counted before serde_json reads the file
/// into a tree, where each takes a node of 632 bytes and more: 9.4 million polygon points
/// (`{"x":0,"y":0}`, a 126 MB map) took over 4 GB, and 940 polygons of 10,000 points each, every
/// one within [`MAX_POLYGON_POINTS`], as much. A layer, an object, a property, a tileset's tile
/// and a polygon's point are one object each; real maps hold some thousands. A file at every
/// JSON limit at once (16 layers of 1,000,000 cells, 490,000 points in 49 polygons, 3.4 million
/// more numbers) took 1.1 GB to import. A TMX map's elements (a layer's cells aside) count
/// against it too (`level/tiled/scan.rs`): 3 million `<object/>`s took 1.2 GB.
#[cfg(feature = "tiled")]
pub(crate) const MAX_JSON_OBJECTS: u64 = 500_000;
/// Most JSON values other than the cells of tile layers (which [`MAX_LAYER_CELLS`] bounds) in a
/// Tiled JSON file, counted with [`MAX_JSON_OBJECTS`]: serde_json's tree takes 32 bytes a value
/// and more (60 million numbers outside a layer's data took 2 GB). 5,000,000 take about 320 MB.
#[cfg(feature = "tiled")]
pub(crate) const MAX_JSON_VALUES: u64 = 5_000_000;
/// Longest level or scenario name, in bytes: a name is part of every trace file's name
/// (`LEVEL.SCENARIO.BACKEND.CONFIG.csv`), which a file system holds to 255 bytes, and is copied
/// into every run's rows; Tiled and LDtk name their objects in a few words.
pub(crate) const MAX_NAME_BYTES: usize = 64;
/// Most spawn points of one map (Tiled or LDtk): each spawn makes up to five probe scenarios
/// (27 s of game time, 1,620 frames at 60 Hz), and real maps hold a handful; 1,000 spawns make
/// 5,000 scenarios and 1.6 million frames per configuration, within [`MAX_LEVEL_FRAMES`].
pub(crate) const MAX_SPAWNS: usize = 1_000;
/// Largest TOML level or side file, in bytes (32 MiB), read no further: the largest map
/// [`MAX_TILES`] allows is a 1000 x 1000 string of about 1 MB, and the rest of a level is a few
/// kilobytes of legend, platforms and scenarios (the cap was set when maps could hold 16 million
/// tiles; [`MAX_TOML_ITEMS`] bounds what a file costs).
pub(crate) const MAX_TOML_BYTES: u64 = 32 * 1024 * 1024;
/// Most TOML items in a level or side file (each `=`, `,`, `.`, `[` and `{` outside strings and
/// comments), counted before the `toml` crate parses the file: it builds a tree of every value,
/// which costs some hundreds of bytes an item (an input event `{ t = 1.0, left = true }` about
/// 1.5 KB), so 127 MB of input events (3.9 million) took over 2 GB. 500,000 items keep a file's
/// tree near 250 MB (a map string is one item whatever its size) and hold a scenario of
/// [`MAX_INPUT_EVENTS`] events written out in full (about six items an event).
pub(crate) const MAX_TOML_ITEMS: usize = 500_000;
/// Deepest nesting in a TOML level or side file: a value's table header's parts, plus each open
/// `[` and `{` and each part of a dotted key on the way to it, counted before the `toml` crate
/// parses the file. A level nests at most four deep (`[[scenario]]`, `inputs = [{ t = 1.0 }]`);
/// the crate recurses once a level and refuses past about 80 (nested arrays) or 90 (key parts)
/// with a bare "recursion limit" at line 1, column 1.
pub(crate) const MAX_TOML_DEPTH: usize = 32;
/// Most input events of one scenario: a script written by hand holds tens, a recorded play a
/// change every few frames; 50,000 is one change a frame for 14 minutes at 60 Hz, and a
/// scenario of that many events written out in full (`{ t = 1.0, left = true }`, 5 items)
/// takes half of [`MAX_TOML_ITEMS`].
pub(crate) const MAX_INPUT_EVENTS: usize = 50_000;

/// The threads a run may fan out over when its largest level holds `tiles` tiles: `jobs`, or
/// as many as keep every thread's world within [`RUN_MEMORY`] ([`THREAD_BYTES_PER_TILE`]
/// each), at least one. The output is the same whatever the number of threads.
pub(crate) fn jobs_within_memory(jobs: usize, tiles: u64) -> usize {
    let per_thread = tiles.saturating_mul(THREAD_BYTES_PER_TILE).max(1);
    let fit = (RUN_MEMORY / per_thread).max(1);
    jobs.min(usize::try_from(fit).unwrap_or(usize::MAX)).max(1)
}

/// Whether `dt` (seconds) is within [`DT_RANGE`], compared in f32 as the runner stores it (so
/// `1e-6` read into an f32, a hair below 1e-6, is in).
pub(crate) fn dt_in_range(dt: f64) -> bool {
    dt.is_finite() && (dt as f32) >= DT_RANGE.0 as f32 && (dt as f32) <= DT_RANGE.1 as f32
}

/// `v` as an error message prints it: as Rust prints an f64, except from 1e16 on (past every
/// range here) in exponent form (`1e308`, not its 309 digits).
pub fn show(v: f64) -> String {
    if v.is_finite() && v.abs() >= 1e16 {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Whether `v` is finite and within `lo..=hi`.
pub fn within(v: f64, (lo, hi): (f64, f64)) -> bool {
    v.is_finite() && v >= lo && v <= hi
}

/// The number of frames a scenario of `duration` seconds runs at step `dt` (as the runner
/// counts them: `round(duration / dt)`), computed without overflow.
pub fn frames(duration: f64, dt: f64) -> f64 {
    (duration / dt).round()
}

/// What is wrong with a scenario's timing ([`check_timing`]), for the caller to place (file and
/// line, or a command-line flag).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TimingError {
    /// The time step is outside [`DT_RANGE`].
    #[error("dt is {dt}; expected a time step in seconds, {} <= dt <= {}", DT_RANGE.0, DT_RANGE.1)]
    Dt {
        /// The time step, seconds.
        dt: f64,
    },
    /// The duration is not a positive number of seconds within [`MAX_DURATION`].
    #[error("duration is {duration}; expected seconds, 0 < duration <= {MAX_DURATION}")]
    Duration {
        /// The duration, seconds.
        duration: f64,
    },
    /// The duration is under half a step: nothing would run.
    #[error("duration / dt = {duration} / {dt} rounds to 0 frames, so nothing would run; expected a duration of at least half a step")]
    NoFrame {
        /// The duration, seconds.
        duration: f64,
        /// The time step, seconds.
        dt: f64,
    },
    /// More frames than [`MAX_FRAMES`].
    #[error("duration / dt = {duration} / {dt} is {frames} frames; expected at most {MAX_FRAMES} (shorten the scenario or take a larger dt)")]
    TooManyFrames {
        /// The duration, seconds.
        duration: f64,
        /// The time step, seconds.
        dt: f64,
        /// The frames it would take.
        frames: f64,
    },
}

/// Checks a scenario's duration against its time step: the step within [`DT_RANGE`], the
/// duration within [`MAX_DURATION`], and between 1 and [`MAX_FRAMES`] frames. Returns the
/// number of frames.
pub fn check_timing(duration: f64, dt: f64) -> Result<u64, TimingError> {
    if !dt_in_range(dt) {
        return Err(TimingError::Dt { dt });
    }
    if !(duration.is_finite() && duration > 0.0 && duration <= MAX_DURATION) {
        return Err(TimingError::Duration { duration });
    }
    let n = frames(duration, dt);
    if n < 1.0 {
        return Err(TimingError::NoFrame { duration, dt });
    }
    if n > MAX_FRAMES as f64 {
        return Err(TimingError::TooManyFrames {
            duration,
            dt,
            frames: n,
        });
    }
    Ok(n as u64)
}

/// Reads a whole regular file of at most [`MAX_INPUT_BYTES`] ([`crate::input::read`]); the
/// error says why without the file's name, which the caller's own error gives.
pub(crate) fn read_capped(path: &Path) -> std::io::Result<Vec<u8>> {
    Ok(crate::input::read(path, MAX_INPUT_BYTES, "input file")?)
}

/// Reads a TOML level or side file of at most [`MAX_TOML_BYTES`] as UTF-8 text; the error says
/// why without the file's name, which the caller's own error gives.
#[cfg(feature = "tiled")]
pub(crate) fn read_toml_capped(path: &Path) -> std::io::Result<String> {
    Ok(crate::input::read_text(
        path,
        MAX_TOML_BYTES,
        "TOML level or side file",
    )?)
}

/// [`read_capped`] as UTF-8 text.
pub(crate) fn read_text_capped(path: &Path) -> std::io::Result<String> {
    Ok(crate::input::read_text(
        path,
        MAX_INPUT_BYTES,
        "input file",
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_takes_fewer_threads_on_a_large_level() {
        // Levels of a few thousand tiles (the built-in set) keep every thread asked for.
        assert_eq!(jobs_within_memory(8, 10_000), 8);
        // The largest level: one thread's world is up to 1.4 GB (THREAD_BYTES_PER_TILE), and
        // two would pass RUN_MEMORY (2 GiB).
        assert_eq!(jobs_within_memory(8, MAX_TILES), 1);
        // 500,000 tiles: 700 MB a thread, three within 2 GiB.
        assert_eq!(jobs_within_memory(8, 500_000), 3);
        // Never none, whatever is asked or however large.
        assert_eq!(jobs_within_memory(0, 0), 1);
        assert_eq!(jobs_within_memory(4, u64::MAX), 1);
    }

    #[test]
    fn timing_is_checked_before_anything_runs() {
        assert_eq!(check_timing(1.0, 0.01), Ok(100));
        // dt = 1e30 used to run zero steps; 1e-9 bypassed the frame cap.
        assert!(matches!(
            check_timing(1.0, 1e30),
            Err(TimingError::Dt { .. })
        ));
        assert!(matches!(
            check_timing(10.0, 1e-9),
            Err(TimingError::Dt { .. })
        ));
        let none = check_timing(0.001, 0.1).unwrap_err();
        assert!(matches!(none, TimingError::NoFrame { .. }));
        assert!(none.to_string().contains("0 frames"), "{none}");
        let many = check_timing(1e5, 1e-3).unwrap_err();
        assert!(matches!(many, TimingError::TooManyFrames { .. }));
        assert!(many.to_string().contains("at most"), "{many}");
        assert!(check_timing(f64::NAN, 0.1).is_err());
        assert!(check_timing(0.1, f64::INFINITY).is_err());
    }
}

//! No allocation in the per-step path: every built-in scenario stepped on the sweep in each of
//! its storage modes (f32, integer positions, f64) under a counting global allocator, which
//! counts the allocations made on this thread between the first step and the last.

#[path = "../common/mod.rs"]
mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use platbench::backend::{CharacterSpec, Precision};
use platbench::config::RunConfig;
use platbench::controller::Controller;
use platbench::scenario::{effective_params, input_script, Runner};
use platbench::sweep::SweepConfig;

/// Counts allocations (and reallocations) per thread, so the test harness's other threads do
/// not count.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: during a thread's teardown the counter may be gone; nothing is counted then.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every call forwards to the system allocator with the caller's arguments unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

/// The sweep's storage modes: its default (f32), integer positions and f64.
fn modes() -> Vec<RunConfig> {
    let mut runs: Vec<RunConfig> = SweepConfig::configs()
        .into_iter()
        .filter(|r| r.label == "default" || r.label.starts_with("positions="))
        .collect();
    let f64 = SweepConfig::default()
        .with_precision(Precision::F64)
        .expect("the sweep has an f64 build");
    runs.push(RunConfig::new("f64", f64));
    assert_eq!(
        runs.len(),
        3,
        "{:?}",
        runs.iter().map(|r| &r.label).collect::<Vec<_>>()
    );
    runs
}

#[test]
fn the_sweep_allocates_nothing_per_step_on_any_built_in_scenario() {
    // The counter counts: an allocation on this thread shows.
    let before = allocations();
    std::hint::black_box(vec![0u8; 64]);
    assert!(
        allocations() > before,
        "the counting allocator counts nothing"
    );
    let mut offenders = Vec::new();
    let mut stepped = 0;
    for level in common::builtin_levels() {
        let mut runner = Runner::new(&level);
        for spec in &level.scenarios {
            for run in modes() {
                let params = effective_params(&run.params, spec);
                let mut backend = runner
                    .build(&run, &params, &[CharacterSpec::of(spec)])
                    .expect("the sweep runs every built-in scenario");
                let script = input_script(spec);
                let inputs: Vec<_> = script.iter().copied().collect();
                let mut held = [inputs[0]];
                // The first step may set up what the later ones reuse; from the second on,
                // nothing is allocated.
                backend.step(&held, spec.dt);
                let before = allocations();
                for input in inputs.iter().skip(1) {
                    held[0] = *input;
                    backend.step(&held, spec.dt);
                    std::hint::black_box(backend.state(0));
                }
                let made = allocations() - before;
                stepped += inputs.len();
                if made > 0 {
                    offenders.push(format!(
                        "{}.{} {}: {made} allocation(s) over {} steps",
                        level.name,
                        spec.name,
                        run.label,
                        inputs.len() - 1
                    ));
                }
            }
        }
    }
    // Every built-in scenario in three modes (46,404 steps today): a test that stepped little
    // would prove little.
    assert!(stepped > 40_000, "{stepped}");
    assert!(offenders.is_empty(), "{}", offenders.join("\n"));
}

//! Cost of one character step on each built-in level (criterion). Benches measure; no test
//! asserts a time.

use criterion::{criterion_group, criterion_main, Criterion};
use platbench::backend::CharacterSpec;
use platbench::level::parse_level;
use platbench::scenario::{input_script, RunConfig};

#[path = "../compare/builtin.rs"]
mod builtin;

fn step_cost(c: &mut Criterion) {
    let run = RunConfig::sweep_default();
    for (file, text) in builtin::LEVELS {
        let level = parse_level(text, file).expect("built-in level parses");
        let spec = &level.scenarios[0];
        let script = input_script(spec);
        c.bench_function(&format!("sweep/{}.{}", level.name, spec.name), |b| {
            let mut backend = run
                .backend
                .build(&level, &run.params)
                .expect("backend builds");
            backend.add_character(CharacterSpec {
                spawn: spec.spawn,
                size: spec.size,
                velocity: spec.velocity,
            });
            let mut k = 0;
            b.iter(|| {
                // Replays the scenario's script in a loop; restarts are rare and cheap.
                if k == script.len() {
                    backend = run
                        .backend
                        .build(&level, &run.params)
                        .expect("backend builds");
                    backend.add_character(CharacterSpec {
                        spawn: spec.spawn,
                        size: spec.size,
                        velocity: spec.velocity,
                    });
                    k = 0;
                }
                backend.step(std::slice::from_ref(&script[k]), spec.dt);
                k += 1;
            });
        });
    }
}

criterion_group!(benches, step_cost);
criterion_main!(benches);

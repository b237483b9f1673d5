//! One robot's kernels (all 18, at the fast tier) obtained again and again in one process:
//! what the time to kernels is made of, load after load.
//!
//! ```text
//! cargo run --release -p rne-jit --example load_loop -- MODEL [LOADS] [--floating-base]
//! ```
//!
//! MODEL is a built-in robot's name or a URDF or TOML file. Each load prints its wall time,
//! the generator's part of it (symbolic recursion and optimisation, on two threads) and what
//! is left after the generator has ended (lowering and compiling what it built last, then
//! defining the module); the last line the best and median loads. `rne bench MODEL --jit-tier
//! fast --engines jit` measures the same in a fresh process, once.
//!
//! On a host whose speed changes from one second to the next (a cloud machine whose other
//! tenants come and go), times move by half between runs of the same binary; the number of
//! instructions executed does not. To see where the work goes, or whether a change removed
//! some, count them (docs/performance.md, "What a load is made of"):
//!
//! ```text
//! cargo build --release -p rne-jit --example load_loop
//! valgrind --tool=callgrind --callgrind-out-file=load.out target/release/examples/load_loop panda-arm 3
//! callgrind_annotate --inclusive=yes load.out | less
//! ```

use std::time::{Duration, Instant};

use rne_codegen_core::{GenerationOptions, Kernel, Scene};
use rne_jit::{JitModel, Tier};
use rne_models::builtin::RobotSource;
use rne_symbolic::model::Base;
use rne_symbolic::LoadOptions;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let floating = args.iter().any(|a| a == "--floating-base");
    let mut positional = args.iter().filter(|a| !a.starts_with("--"));
    let name = positional.next().map_or("panda-arm", String::as_str);
    let loads: usize = positional.next().map_or(Ok(20), |n| n.parse())?;
    let source = RobotSource::resolve(name);
    let mut model = source.load(&LoadOptions::default())?;
    if floating {
        model.set_base(Base::Floating);
    }
    model.constrain_mimic_joints()?;
    let options = GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        ..GenerationOptions::default()
    };
    let mut walls = Vec::with_capacity(loads);
    for load in 0..loads {
        let start = Instant::now();
        let jit = JitModel::compile_at(&model, &Scene::default(), &options, name, Tier::Fast)?;
        let wall = start.elapsed();
        let timings = jit.timings();
        println!(
            "load {load:3}: {:7.1} ms (generation {:6.1} ms, after it {:6.1} ms)",
            ms(wall),
            ms(timings.generation),
            ms(timings.compilation)
        );
        walls.push(wall);
    }
    walls.sort();
    if let (Some(best), Some(median)) = (walls.first(), walls.get(walls.len() / 2)) {
        println!(
            "{name}: {loads} loads, best {:.1} ms, median {:.1} ms",
            ms(*best),
            ms(*median)
        );
    }
    Ok(())
}

fn ms(time: Duration) -> f64 {
    time.as_secs_f64() * 1e3
}

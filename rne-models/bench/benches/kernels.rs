//! Every generated kernel of every built-in robot against the independent numeric reference
//! (spatial RNEA, CRBA and ABA), timed by criterion in one run, then summarised as ns per call
//! and as the ratio reference / generated.
//!
//! ```text
//! cargo bench -p rne-bench --bench kernels             # criterion options go after `--`
//! ```
//!
//! # What is timed
//!
//! Each criterion group `<robot>/<kernel>` holds the function `generated`, the kernel of the
//! robot's `Model` in [`rne_models::generated`] called through the `Dynamics` trait (statically
//! dispatched and inlined into the module's free function, as user code calls it), and, where the reference computes the same quantity, `reference`: the
//! allocation-free `Reference::*_into` method writing into a buffer allocated before the timed
//! loop, or `kinetic_energy` / `potential_energy`, which return an `f64`. The reference's calls
//! include its argument-length checks, which are part of its API. `coriolis_matrix` has no
//! reference counterpart (the reference forms C q̇ only, inside the bias), so only `generated`
//! is timed there.
//!
//! One criterion iteration is one call on the next state of the robot's input pool, cycled
//! through in order. The state reaches the kernel through `black_box` and so does the result,
//! so that neither the inputs nor the work can be folded away. Nothing allocates in the timed
//! loop.
//!
//! # Inputs
//!
//! For each robot, [`POOL`] states drawn from ChaCha8 seeded with [`SEED`]: |q| ≤ π, |q̇| ≤ 10,
//! |q̈| ≤ 10 (the ranges of the accuracy tests), and τ = RNEA(q, q̇, q̈) from the reference, so
//! that forward dynamics gets consistent torques. While the pool is made, the generated inverse
//! dynamics is checked against those torques, so a built-in name paired with the wrong
//! generated module fails before anything is timed.
//!
//! # Summary
//!
//! After criterion's runs, the median point estimate of each benchmark (criterion's
//! `<group>/<function>/new/estimates.json`, in ns per iteration, which is ns per call) is read
//! back from criterion's output directory, found as criterion finds it. Only estimates written by
//! this run count, so a run filtered to some benchmarks reports those alone, never stale figures.
//! The table gives, per robot and kernel, ns per call of each implementation, the ratio
//! reference / generated of the two medians, and the targets of issue 3 (inverse dynamics at
//! least 10× faster than the reference RNEA, mass matrix at least 5× faster than its CRBA). It
//! is printed and written to `summary.md` in criterion's output directory. On a shared machine
//! absolute times are noisy; the ratios within one run are what to report.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, SystemTime};
use std::{env, fs};

use criterion::measurement::WallTime;
use criterion::{Bencher, BenchmarkGroup, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::Dynamics;
use rne_models::{RobotSource, Visitor, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;

/// Number of states in each robot's input pool; a power of two, so cycling is a mask.
const POOL: usize = 1024;

/// Seed of every robot's input pool.
const SEED: u64 = 0x5eed_be4c;

/// Why the reference cannot reject the benchmark's arguments.
const SIZED: &str = "every array has the robot's number of joints";

/// Why a generated `Model` of a built-in robot returns every kernel.
const GENERATED: &str = "the built-in modules generate every kernel";

/// A criterion group that ran: (robot, kernel).
type Group = (&'static str, &'static str);

/// One input state; `tau` = RNEA(q, q̇, q̈).
struct State<const N: usize> {
    q: [f64; N],
    qd: [f64; N],
    qdd: [f64; N],
    tau: [f64; N],
}

fn main() {
    let started = SystemTime::now();
    // Modest settings, so that every robot runs in a few minutes on two loaded cores; the
    // command line (`--sample-size`, `--measurement-time`, `--quick`, ...) overrides them.
    let mut criterion = Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .nresamples(20_000)
        .without_plots()
        .configure_from_args();
    let mut groups = Vec::new();
    for robot in BUILTIN_ROBOTS {
        robot.visit(BenchRobot {
            criterion: &mut criterion,
            groups: &mut groups,
            robot: robot.name,
        });
    }
    criterion.final_summary();
    summarise(&groups, started);
}

/// The benchmarks of one built-in robot, run on its generated `Model`.
struct BenchRobot<'a> {
    criterion: &'a mut Criterion,
    groups: &'a mut Vec<Group>,
    robot: &'static str,
}

impl Visitor for BenchRobot<'_> {
    type Output = ();

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) {
        bench_robot(self.criterion, self.groups, self.robot, &model);
    }
}

/// Times every kernel of `robot`, whose generated `Model` is `g`, against its reference.
fn bench_robot<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    criterion: &mut Criterion,
    groups: &mut Vec<Group>,
    robot: &'static str,
    g: &D,
) {
    let spec = rne_models::builtin(robot).unwrap_or_else(|| panic!("`{robot}` is not built in"));
    let model = RobotSource::Builtin(spec)
        .load(&LoadOptions::default())
        .unwrap_or_else(|error| panic!("{error}"));
    let mut reference = Reference::new(&model.to_numeric());
    assert!(
        reference.joint_names() == D::JOINTS,
        "{robot}: the reference's joints {:?} are not the generated module's {:?}",
        reference.joint_names(),
        D::JOINTS
    );
    let pool = input_pool(robot, g, &mut reference);
    let mut bench = Bench {
        criterion,
        groups,
        robot,
        pool: &pool,
    };
    dynamics(&mut bench, g, &mut reference);
    coriolis_and_energies(&mut bench, g, &mut reference);
}

/// Inverse dynamics, M, the bias, forward dynamics and g: the generated kernel beside the
/// reference's.
fn dynamics<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    bench: &mut Bench<'_, N>,
    g: &D,
    reference: &mut Reference,
) {
    let mut v = [0.0; N];
    let mut m = [[0.0; N]; N];

    bench.compare(
        "inverse_dynamics",
        |s| g.inverse_dynamics(&s.q, &s.qd, &s.qdd),
        |s| {
            reference
                .inverse_dynamics_into(&s.q, &s.qd, &s.qdd, &mut v)
                .expect(SIZED);
            black_box(&v);
        },
    );
    bench.compare(
        "mass_matrix",
        |s| g.mass_matrix(&s.q),
        |s| {
            reference
                .mass_matrix_into(&s.q, m.as_flattened_mut())
                .expect(SIZED);
            black_box(&m);
        },
    );
    bench.compare(
        "bias_torques",
        |s| g.bias_torques(&s.q, &s.qd),
        |s| {
            reference
                .bias_torques_into(&s.q, &s.qd, &mut v)
                .expect(SIZED);
            black_box(&v);
        },
    );
    bench.compare(
        "forward_dynamics",
        |s| g.forward_dynamics(&s.q, &s.qd, &s.tau),
        |s| {
            reference
                .forward_dynamics_into(&s.q, &s.qd, &s.tau, &mut v)
                .expect(SIZED);
            black_box(&v);
        },
    );
    bench.compare(
        "gravity_torques",
        |s| g.gravity_torques(&s.q),
        |s| {
            reference.gravity_torques_into(&s.q, &mut v).expect(SIZED);
            black_box(&v);
        },
    );
}

/// C (generated only), then the kinetic and potential energies beside the reference's.
fn coriolis_and_energies<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    bench: &mut Bench<'_, N>,
    g: &D,
    reference: &mut Reference,
) {
    bench.generated("coriolis_matrix", |s| g.coriolis_matrix(&s.q, &s.qd));
    bench.compare(
        "kinetic_energy",
        |s| g.kinetic_energy(&s.q, &s.qd),
        |s| reference.kinetic_energy(&s.q, &s.qd).expect(SIZED),
    );
    bench.compare(
        "potential_energy",
        |s| g.potential_energy(&s.q),
        |s| reference.potential_energy(&s.q).expect(SIZED),
    );
}

/// `robot`'s input pool (see the crate docs), checking the generated inverse dynamics against
/// the reference's on every state (normwise, to 1e-12 of the largest torque or of 1 N·m).
fn input_pool<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    robot: &str,
    g: &D,
    reference: &mut Reference,
) -> Vec<State<N>> {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let mut uniform =
        |bound: f64| -> [f64; N] { std::array::from_fn(|_| rng.gen_range(-bound..=bound)) };
    (0..POOL)
        .map(|_| {
            let (q, qd, qdd) = (uniform(PI), uniform(10.0), uniform(10.0));
            let mut tau = [0.0; N];
            reference
                .inverse_dynamics_into(&q, &qd, &qdd, &mut tau)
                .expect(SIZED);
            let generated = g.inverse_dynamics(&q, &qd, &qdd).expect(GENERATED);
            let scale = tau.iter().fold(1.0, |s: f64, t| s.max(t.abs()));
            assert!(
                generated
                    .iter()
                    .zip(&tau)
                    .all(|(g, t)| (g - t).abs() <= 1e-12 * scale),
                "{robot}: generated τ {generated:?} ≠ reference τ {tau:?}: \
                 is the name paired with the right module?"
            );
            State { q, qd, qdd, tau }
        })
        .collect()
}

/// One robot's benchmarks: the criterion groups go to `criterion` and are recorded in `groups`.
struct Bench<'a, const N: usize> {
    criterion: &'a mut Criterion,
    groups: &'a mut Vec<Group>,
    robot: &'static str,
    pool: &'a [State<N>],
}

impl<const N: usize> Bench<'_, N> {
    /// The group `<robot>/<kernel>`, recorded for the summary.
    fn open(&mut self, kernel: &'static str) -> BenchmarkGroup<'_, WallTime> {
        self.groups.push((self.robot, kernel));
        self.criterion
            .benchmark_group(format!("{}/{kernel}", self.robot))
    }

    /// Times the generated kernel alone.
    fn generated<A>(&mut self, kernel: &'static str, mut generated: impl FnMut(&State<N>) -> A) {
        let pool = self.pool;
        let mut group = self.open(kernel);
        group.bench_function("generated", |b| time(b, pool, &mut generated));
        group.finish();
    }

    /// Times the generated kernel and the reference side by side.
    fn compare<A, B>(
        &mut self,
        kernel: &'static str,
        mut generated: impl FnMut(&State<N>) -> A,
        mut reference: impl FnMut(&State<N>) -> B,
    ) {
        let pool = self.pool;
        let mut group = self.open(kernel);
        group.bench_function("generated", |b| time(b, pool, &mut generated));
        group.bench_function("reference", |b| time(b, pool, &mut reference));
        group.finish();
    }
}

/// One call of `kernel` per iteration, on the next state of `pool`, inputs and result through
/// `black_box`.
fn time<const N: usize, R>(
    bencher: &mut Bencher<'_>,
    pool: &[State<N>],
    kernel: &mut impl FnMut(&State<N>) -> R,
) {
    let mut next = 0;
    bencher.iter(|| {
        let state = black_box(&pool[next]);
        next = (next + 1) % POOL;
        black_box(kernel(state))
    });
}

/// Prints the summary table of the `groups` that ran and writes it to `summary.md` in
/// criterion's output directory, from the estimates written since `started`.
fn summarise(groups: &[Group], started: SystemTime) {
    let home = criterion_home();
    let medians = medians_since(&home, started);
    if medians.is_empty() {
        println!(
            "no criterion estimates written in {} by this run (test or list mode, or \
             every benchmark filtered out): no summary",
            home.display()
        );
        return;
    }
    let median = |group: &str, function: &str| {
        medians
            .get(&(group.to_owned(), function.to_owned()))
            .copied()
    };
    let mut table = String::from(
        "| robot | kernel | generated (ns/call) | reference (ns/call) | reference / generated \
         | target |\n|---|---|---:|---:|---:|---|\n",
    );
    for &(robot, kernel) in groups {
        let group = format!("{robot}/{kernel}");
        let (generated, reference) = (median(&group, "generated"), median(&group, "reference"));
        if generated.is_none() && reference.is_none() {
            continue;
        }
        let ns = |t: Option<f64>| t.map_or("—".to_owned(), |t| format!("{t:.1}"));
        let ratio = generated.zip(reference).map(|(g, r)| r / g);
        let target = match (kernel, ratio) {
            ("inverse_dynamics", Some(ratio)) => verdict(ratio, 10.0),
            ("mass_matrix", Some(ratio)) => verdict(ratio, 5.0),
            _ => String::new(),
        };
        table += &format!(
            "| {robot} | {kernel} | {} | {} | {} | {target} |\n",
            ns(generated),
            ns(reference),
            ratio.map_or("—".to_owned(), |r| format!("{r:.1}×")),
        );
    }
    let path = home.join("summary.md");
    let written = fs::write(
        &path,
        format!(
            "# Generated kernels against the numeric reference\n\nMedian ns per call over \
             {POOL} seeded states (seed {SEED:#x}), criterion estimates of one run; ratio = \
             reference / generated.\n\n{table}"
        ),
    );
    println!("\nGenerated kernels against the numeric reference (median ns per call):\n\n{table}");
    match written {
        Ok(()) => println!("written to {}", path.display()),
        Err(error) => println!("could not write {}: {error}", path.display()),
    }
}

/// The target `≥ bound×` and whether `ratio` meets it.
fn verdict(ratio: f64, bound: f64) -> String {
    let met = if ratio >= bound { "met" } else { "missed" };
    format!("≥ {bound}×: {met}")
}

/// Criterion's output directory, found as criterion 0.5 finds it: `$CRITERION_HOME`, else
/// `criterion/` in `$CARGO_TARGET_DIR`, else in the target directory `cargo metadata` reports,
/// else `target/criterion`.
fn criterion_home() -> PathBuf {
    if let Some(home) = env::var_os("CRITERION_HOME") {
        return PathBuf::from(home);
    }
    if let Some(target) = env::var_os("CARGO_TARGET_DIR") {
        return Path::new(&target).join("criterion");
    }
    env::var_os("CARGO")
        .and_then(|cargo| {
            Command::new(cargo)
                .args(["metadata", "--format-version", "1", "--no-deps"])
                .output()
                .ok()
        })
        .and_then(|output| serde_json::from_slice::<serde_json::Value>(&output.stdout).ok())
        .and_then(|metadata| metadata["target_directory"].as_str().map(PathBuf::from))
        .map_or_else(
            || PathBuf::from("target/criterion"),
            |t| t.join("criterion"),
        )
}

/// The median point estimate (ns) of every benchmark under `home` whose estimates were written
/// since `started`, keyed by (group, function) as criterion's `benchmark.json` records them (so
/// that criterion's escaping of names into directory names does not matter).
fn medians_since(home: &Path, started: SystemTime) -> HashMap<(String, String), f64> {
    let read_json = |path: PathBuf| -> Option<serde_json::Value> {
        serde_json::from_slice(&fs::read(path).ok()?).ok()
    };
    let subdirectories = |dir: &Path| -> Vec<PathBuf> {
        fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|entry| entry.path())
            .filter(|path| path.is_dir())
            .collect()
    };
    let mut medians = HashMap::new();
    for benchmark in subdirectories(home).iter().flat_map(|g| subdirectories(g)) {
        let new = benchmark.join("new");
        let estimates = new.join("estimates.json");
        let fresh = fs::metadata(&estimates)
            .and_then(|m| m.modified())
            .is_ok_and(|modified| modified >= started);
        if !fresh {
            continue;
        }
        let (Some(id), Some(estimates)) =
            (read_json(new.join("benchmark.json")), read_json(estimates))
        else {
            continue;
        };
        if let (Some(group), Some(function), Some(median)) = (
            id["group_id"].as_str(),
            id["function_id"].as_str(),
            estimates["median"]["point_estimate"].as_f64(),
        ) {
            medians.insert((group.to_owned(), function.to_owned()), median);
        }
    }
    medians
}

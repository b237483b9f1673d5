//! States per second of the generic kernels in lanes: `f64`, `F64x4`, `F32x8`, and `F64x4`
//! on two threads, for UR5 and the Panda arm, inverse dynamics, mass matrix and forward
//! dynamics, through the runtime's batch helper on 1024 seeded states; and `F64x4 packed`,
//! the kernel alone on the same states already in lanes (what the helper's gathering and
//! scattering cost is the difference). A second table times inverse dynamics and the mass
//! matrices on 65 536 states, `f64`, `F64x4` and `F64x4` on two threads: the batches threads
//! are for.
//!
//! ```text
//! RUSTFLAGS="-C target-cpu=native" cargo bench -p rne-tests --bench lanes
//! ```
//! (without the flag, `F64x4` and `F32x8` run as pairs of 128-bit SSE2 instructions).
//!
//! The five ways of one kernel are timed by `rne bench`'s harness ([`time_interleaved`]): in
//! interleaved rounds, so that the ratios to `f64` — medians over rounds of the ratio within
//! a round — hold on a machine whose speed drifts, which timing one way after the other
//! (as a criterion group does) does not. It prints a markdown table; docs/performance.md has
//! the figures.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_bench::timing::{time_interleaved, Plan, Timed, Timing};
use rne_codegen::{batch, F32x8, F64x4, Real};
use std::hint::black_box;
use std::time::Duration;

rne_codegen::derive_dynamics! {
    mod ur5 {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
        scalar: generic,
    }
}

rne_codegen::derive_dynamics! {
    mod panda {
        robot: "../rne-models/robots/panda-arm.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
        scalar: generic,
    }
}

const STATES: usize = 1024;
const THREADS: usize = 2;
/// Batches of at least 5 ms (several passes over the states), 41 rounds.
const PLAN: Plan = Plan {
    batch: Duration::from_millis(5),
    rounds: 41,
};
/// The columns, in the order of each kernel's subjects.
const WAYS: [&str; 5] = ["f64", "F64x4", "F64x4 packed", "F64x4, 2 threads", "F32x8"];

/// One way of evaluating a kernel on all the states: a call is one pass.
struct Pass<'a>(Box<dyn FnMut() + 'a>);

impl Timed for Pass<'_> {
    fn run(&mut self, calls: u64) {
        for _ in 0..calls {
            (self.0)();
        }
    }
}

/// `count` seeded states (q, q̇, q̈ or τ) of an `N`-joint robot: |q| ≤ π, the rest ≤ 10.
fn states<const N: usize>(seed: u64, count: usize) -> Vec<([f64; N], [f64; N], [f64; N])> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut draw =
        |bound: f64| -> [f64; N] { std::array::from_fn(|_| rng.gen_range(-bound..=bound)) };
    (0..count)
        .map(|_| (draw(std::f64::consts::PI), draw(10.0), draw(10.0)))
        .collect()
}

/// A markdown row: states per second of each way (a pass being `count` states) and, beside
/// the lanes, the ratio to `f64` (the median over rounds of `f64`'s time over the way's).
fn row(label: &str, count: usize, timings: &[Timing]) -> String {
    let rate = |t: &Timing| count as f64 / t.median() * 1e3;
    let mut cells = vec![format!("{:.3} M/s", rate(&timings[0]))];
    for t in &timings[1..] {
        cells.push(format!(
            "{:.3} M/s ({:.2}×)",
            rate(t),
            timings[0].ratio_to(t)
        ));
    }
    format!("| {label} | {} |", cells.join(" | "))
}

/// Times the ways of one kernel together, each pass `count` states, and prints their row.
fn report(label: &str, count: usize, mut ways: Vec<Pass<'_>>) {
    let mut subjects: Vec<&mut dyn Timed> = ways.iter_mut().map(|w| w as &mut dyn Timed).collect();
    let timings = time_interleaved(&mut subjects, &PLAN);
    println!("{}", row(label, count, &timings));
}

/// The ways of a kernel of (q, q̇, x).
macro_rules! kernel_ways {
    ($all:ident, $single:ident, [$zero:expr], |($q:ident, $qd:ident, $x:ident)| $call:expr, $n:ident) => {{
        fn run<T: Real>($q: &[T; $n], $qd: &[T; $n], $x: &[T; $n]) -> [T; $n] {
            $call
        }
        let (all, single) = (&$all, &$single);
        let packed: Vec<([F64x4; $n], [F64x4; $n], [F64x4; $n])> = all
            .chunks(F64x4::LANES)
            .map(|group| batch::LaneData::gather(|i| &group[i]))
            .collect();
        let [mut out, mut out_lanes, mut out_threads] = [(); 3].map(|_| vec![$zero; STATES]);
        let mut packed_out = vec![[F64x4::splat(0.0); $n]; packed.len()];
        let mut out32 = vec![[0.0f32; $n]; STATES];
        vec![
            Pass(Box::new(move || {
                batch::evaluate(
                    black_box(all),
                    &mut out,
                    |s: &([f64; $n], [f64; $n], [f64; $n])| run(&s.0, &s.1, &s.2),
                )
            })),
            Pass(Box::new(move || {
                batch::evaluate(
                    black_box(all),
                    &mut out_lanes,
                    |s: &([F64x4; $n], [F64x4; $n], [F64x4; $n])| run(&s.0, &s.1, &s.2),
                )
            })),
            Pass(Box::new(move || {
                for (s, r) in black_box(&packed).iter().zip(packed_out.iter_mut()) {
                    *r = run(&s.0, &s.1, &s.2);
                }
            })),
            Pass(Box::new(move || {
                batch::evaluate_threaded(
                    black_box(all),
                    &mut out_threads,
                    |s: &([F64x4; $n], [F64x4; $n], [F64x4; $n])| run(&s.0, &s.1, &s.2),
                    THREADS,
                )
            })),
            Pass(Box::new(move || {
                batch::evaluate(
                    black_box(single),
                    &mut out32,
                    |s: &([F32x8; $n], [F32x8; $n], [F32x8; $n])| run(&s.0, &s.1, &s.2),
                )
            })),
        ]
    }};
}

/// The ways of the mass matrix.
macro_rules! mass_ways {
    ($all:ident, $single:ident, |$q:ident| $call:expr, $n:ident) => {{
        fn run<T: Real>($q: &[T; $n]) -> [[T; $n]; $n] {
            $call
        }
        let (all, single) = (&$all, &$single);
        let packed: Vec<[F64x4; $n]> = all
            .chunks(F64x4::LANES)
            .map(|group| batch::LaneData::gather(|i| &group[i]))
            .collect();
        let [mut out, mut out_lanes, mut out_threads] =
            [(); 3].map(|_| vec![[[0.0; $n]; $n]; STATES]);
        let mut packed_out = vec![[[F64x4::splat(0.0); $n]; $n]; packed.len()];
        let mut out32 = vec![[[0.0f32; $n]; $n]; STATES];
        vec![
            Pass(Box::new(move || {
                batch::evaluate(black_box(all), &mut out, |q: &[f64; $n]| run(q))
            })),
            Pass(Box::new(move || {
                batch::evaluate(black_box(all), &mut out_lanes, |q: &[F64x4; $n]| run(q))
            })),
            Pass(Box::new(move || {
                for (q, r) in black_box(&packed).iter().zip(packed_out.iter_mut()) {
                    *r = run(q);
                }
            })),
            Pass(Box::new(move || {
                batch::evaluate_threaded(
                    black_box(all),
                    &mut out_threads,
                    |q: &[F64x4; $n]| run(q),
                    THREADS,
                )
            })),
            Pass(Box::new(move || {
                batch::evaluate(black_box(single), &mut out32, |q: &[F32x8; $n]| run(q))
            })),
        ]
    }};
}

/// The rows of one robot.
macro_rules! robot_rows {
    ($name:literal, $module:ident, $seed:expr) => {{
        const N: usize = $module::NV;
        let all = states::<N>($seed, STATES);
        let single: Vec<([f32; N], [f32; N], [f32; N])> = all
            .iter()
            .map(|(q, qd, x)| {
                (
                    q.map(|v| v as f32),
                    qd.map(|v| v as f32),
                    x.map(|v| v as f32),
                )
            })
            .collect();
        let positions: Vec<[f64; N]> = all.iter().map(|s| s.0).collect();
        let positions32: Vec<[f32; N]> = single.iter().map(|s| s.0).collect();
        report(
            concat!($name, ", inverse dynamics"),
            STATES,
            kernel_ways!(
                all,
                single,
                [[0.0; N]],
                |(q, qd, x)| $module::inverse_dynamics(q, qd, x),
                N
            ),
        );
        report(
            concat!($name, ", forward dynamics"),
            STATES,
            kernel_ways!(
                all,
                single,
                [[0.0; N]],
                |(q, qd, x)| $module::forward_dynamics(q, qd, x),
                N
            ),
        );
        report(
            concat!($name, ", mass matrix"),
            STATES,
            mass_ways!(positions, positions32, |q| $module::mass_matrix(q), N),
        );
    }};
}

/// States of the second table.
const LARGE: usize = 65_536;

/// Inverse dynamics and the mass matrix of `LARGE` states: `f64`, `F64x4`, and `F64x4` on
/// `THREADS` threads.
macro_rules! large_batch_rows {
    ($name:literal, $module:ident, $seed:expr) => {{
        const N: usize = $module::NV;
        fn id<T: Real>(s: &([T; N], [T; N], [T; N])) -> [T; N] {
            $module::inverse_dynamics(&s.0, &s.1, &s.2)
        }
        fn mass<T: Real>(q: &[T; N]) -> [[T; N]; N] {
            $module::mass_matrix(q)
        }
        let all = states::<N>($seed, LARGE);
        let positions: Vec<[f64; N]> = all.iter().map(|s| s.0).collect();
        let (all, positions) = (&all, &positions);
        let [mut out, mut out_lanes, mut out_threads] = [(); 3].map(|_| vec![[0.0; N]; LARGE]);
        report(
            concat!($name, ", inverse dynamics"),
            LARGE,
            vec![
                Pass(Box::new(move || {
                    batch::evaluate(black_box(all), &mut out, id::<f64>)
                })),
                Pass(Box::new(move || {
                    batch::evaluate(black_box(all), &mut out_lanes, id::<F64x4>)
                })),
                Pass(Box::new(move || {
                    batch::evaluate_threaded(black_box(all), &mut out_threads, id::<F64x4>, THREADS)
                })),
            ],
        );
        let [mut out, mut out_lanes, mut out_threads] = [(); 3].map(|_| vec![[[0.0; N]; N]; LARGE]);
        report(
            concat!($name, ", mass matrix"),
            LARGE,
            vec![
                Pass(Box::new(move || {
                    batch::evaluate(black_box(positions), &mut out, mass::<f64>)
                })),
                Pass(Box::new(move || {
                    batch::evaluate(black_box(positions), &mut out_lanes, mass::<F64x4>)
                })),
                Pass(Box::new(move || {
                    batch::evaluate_threaded(
                        black_box(positions),
                        &mut out_threads,
                        mass::<F64x4>,
                        THREADS,
                    )
                })),
            ],
        );
    }};
}

fn main() {
    // `cargo test --benches` passes `--bench`-less arguments; time only under `cargo bench`.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    println!(
        "| robot, kernel | {} |\n|---|{}",
        WAYS.join(" | "),
        "---:|".repeat(WAYS.len())
    );
    robot_rows!("UR5", ur5, 81);
    robot_rows!("Panda arm", panda, 82);
    println!("\n{LARGE} states:\n\n| robot, kernel | f64 | F64x4 | F64x4, {THREADS} threads |\n|---|---:|---:|---:|");
    large_batch_rows!("UR5", ur5, 83);
    large_batch_rows!("Panda arm", panda, 84);
}

//! States per second of the generic kernels in lanes: `f64`, `F64x4`, `F32x8`, and `F64x4`
//! on two threads, for UR5 and the Panda arm, inverse dynamics, mass matrix and forward
//! dynamics, through the runtime's batch helper on 1024 seeded states; and `F64x4 packed`,
//! the kernel alone on the same states already in lanes (what the helper's gathering and
//! scattering cost is the difference).
//!
//! ```text
//! RUSTFLAGS="-C target-cpu=native" cargo bench -p rne-tests --bench lanes
//! ```
//! (without the flag, `F64x4` and `F32x8` run as pairs of 128-bit SSE2 instructions).
//! Criterion reports elements (states) per second; docs/performance.md has the figures.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::{batch, F32x8, F64x4, Real};
use std::hint::black_box;

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

/// `STATES` seeded states (q, q̇, q̈ or τ) of an `N`-joint robot: |q| ≤ π, the rest ≤ 10.
fn states<const N: usize>(seed: u64) -> Vec<([f64; N], [f64; N], [f64; N])> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut draw =
        |bound: f64| -> [f64; N] { std::array::from_fn(|_| rng.gen_range(-bound..=bound)) };
    (0..STATES)
        .map(|_| (draw(std::f64::consts::PI), draw(10.0), draw(10.0)))
        .collect()
}

/// The benchmarks of one robot: each kernel in `f64`, `F64x4`, `F32x8` and threads.
macro_rules! robot_benches {
    ($c:expr, $name:literal, $module:ident, $seed:expr) => {{
        const N: usize = $module::NV;
        let all = states::<N>($seed);
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

        let mut group = $c.benchmark_group(concat!($name, "/inverse_dynamics"));
        group.throughput(Throughput::Elements(STATES as u64));
        kernel_benches!(
            group,
            all,
            single,
            [[0.0; N]],
            |(q, qd, x)| $module::inverse_dynamics(q, qd, x),
            N
        );
        group.finish();

        let mut group = $c.benchmark_group(concat!($name, "/forward_dynamics"));
        group.throughput(Throughput::Elements(STATES as u64));
        kernel_benches!(
            group,
            all,
            single,
            [[0.0; N]],
            |(q, qd, x)| $module::forward_dynamics(q, qd, x),
            N
        );
        group.finish();

        let mut group = $c.benchmark_group(concat!($name, "/mass_matrix"));
        group.throughput(Throughput::Elements(STATES as u64));
        mass_benches!(
            group,
            positions,
            positions32,
            |q| $module::mass_matrix(q),
            N
        );
        group.finish();
    }};
}

/// One kernel of (q, q̇, x) in each scalar.
macro_rules! kernel_benches {
    ($group:ident, $all:ident, $single:ident, [$zero:expr], |($q:ident, $qd:ident, $x:ident)| $call:expr, $n:ident) => {{
        fn run<T: Real>($q: &[T; $n], $qd: &[T; $n], $x: &[T; $n]) -> [T; $n] {
            $call
        }
        let mut out = vec![$zero; STATES];
        $group.bench_function(BenchmarkId::new("f64", STATES), |b| {
            b.iter(|| {
                batch::evaluate(
                    black_box(&$all),
                    &mut out,
                    |s: &([f64; $n], [f64; $n], [f64; $n])| run(&s.0, &s.1, &s.2),
                )
            })
        });
        $group.bench_function(BenchmarkId::new("F64x4", STATES), |b| {
            b.iter(|| {
                batch::evaluate(
                    black_box(&$all),
                    &mut out,
                    |s: &([F64x4; $n], [F64x4; $n], [F64x4; $n])| run(&s.0, &s.1, &s.2),
                )
            })
        });
        let packed: Vec<([F64x4; $n], [F64x4; $n], [F64x4; $n])> = $all
            .chunks(F64x4::LANES)
            .map(|group| batch::LaneData::gather(|i| &group[i]))
            .collect();
        let mut packed_out = vec![[F64x4::splat(0.0); $n]; packed.len()];
        $group.bench_function(BenchmarkId::new("F64x4 packed", STATES), |b| {
            b.iter(|| {
                for (s, r) in black_box(&packed).iter().zip(packed_out.iter_mut()) {
                    *r = run(&s.0, &s.1, &s.2);
                }
            })
        });
        $group.bench_function(
            BenchmarkId::new(format!("F64x4 x{THREADS} threads"), STATES),
            |b| {
                b.iter(|| {
                    batch::evaluate_threaded(
                        black_box(&$all),
                        &mut out,
                        |s: &([F64x4; $n], [F64x4; $n], [F64x4; $n])| run(&s.0, &s.1, &s.2),
                        THREADS,
                    )
                })
            },
        );
        let mut out32 = vec![[0.0f32; $n]; STATES];
        $group.bench_function(BenchmarkId::new("F32x8", STATES), |b| {
            b.iter(|| {
                batch::evaluate(
                    black_box(&$single),
                    &mut out32,
                    |s: &([F32x8; $n], [F32x8; $n], [F32x8; $n])| run(&s.0, &s.1, &s.2),
                )
            })
        });
    }};
}

/// The mass matrix in each scalar.
macro_rules! mass_benches {
    ($group:ident, $all:ident, $single:ident, |$q:ident| $call:expr, $n:ident) => {{
        fn run<T: Real>($q: &[T; $n]) -> [[T; $n]; $n] {
            $call
        }
        let mut out = vec![[[0.0; $n]; $n]; STATES];
        $group.bench_function(BenchmarkId::new("f64", STATES), |b| {
            b.iter(|| batch::evaluate(black_box(&$all), &mut out, |q: &[f64; $n]| run(q)))
        });
        $group.bench_function(BenchmarkId::new("F64x4", STATES), |b| {
            b.iter(|| batch::evaluate(black_box(&$all), &mut out, |q: &[F64x4; $n]| run(q)))
        });
        let packed: Vec<[F64x4; $n]> = $all
            .chunks(F64x4::LANES)
            .map(|group| batch::LaneData::gather(|i| &group[i]))
            .collect();
        let mut packed_out = vec![[[F64x4::splat(0.0); $n]; $n]; packed.len()];
        $group.bench_function(BenchmarkId::new("F64x4 packed", STATES), |b| {
            b.iter(|| {
                for (q, r) in black_box(&packed).iter().zip(packed_out.iter_mut()) {
                    *r = run(q);
                }
            })
        });
        $group.bench_function(
            BenchmarkId::new(format!("F64x4 x{THREADS} threads"), STATES),
            |b| {
                b.iter(|| {
                    batch::evaluate_threaded(
                        black_box(&$all),
                        &mut out,
                        |q: &[F64x4; $n]| run(q),
                        THREADS,
                    )
                })
            },
        );
        let mut out32 = vec![[[0.0f32; $n]; $n]; STATES];
        $group.bench_function(BenchmarkId::new("F32x8", STATES), |b| {
            b.iter(|| batch::evaluate(black_box(&$single), &mut out32, |q: &[F32x8; $n]| run(q)))
        });
    }};
}

fn lanes(c: &mut Criterion) {
    robot_benches!(c, "ur5", ur5, 81);
    robot_benches!(c, "panda_arm", panda, 82);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = lanes
}
criterion_main!(benches);

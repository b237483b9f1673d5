//! The control and identification kernels (docs/design.md §4) of UR5 and the Panda arm, timed by
//! criterion: the derivatives of inverse and forward dynamics, M⁻¹, the Jacobians of every
//! frame, J̇q̇ and the regressor (rne-models' `control` variants, the modules `rne bench
//! --pinocchio` times), beside inverse dynamics (the default modules) for scale.
//!
//! ```text
//! cargo bench -p rne-bench --bench control
//! ```
//!
//! For the comparison with Pinocchio's analytical derivatives and its CppADCodeGen code, run
//! `tools/peers/run_cg.sh rne-models/robots/<robot>.urdf` right before or after
//! (same machine, same URDF; docs/performance.md quotes both with the ratios). Inputs: 64 states
//! per robot from ChaCha8 seeded with 0x5eed_c0de, |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10, |τ| ≤ 20,
//! cycled in order; inputs and outputs pass through `black_box`.

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use rne_models::generated::{panda_arm, ur5, variants};

/// 64 seeded states (q, q̇, q̈, τ).
fn states<const N: usize>() -> Vec<[[f64; N]; 4]> {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed_c0de);
    let bounds = [PI, 10.0, 10.0, 20.0];
    (0..64)
        .map(|_| bounds.map(|b| std::array::from_fn(|_| rng.gen_range(-b..=b))))
        .collect()
}

macro_rules! bench_robot {
    ($c:expr, $name:literal, $module:ident, $n:literal) => {{
        use variants::$module::control;
        let pool = states::<$n>();
        let mut group = $c.benchmark_group($name);
        let mut k = 0usize;
        let mut next = || {
            k = (k + 1) % pool.len();
            black_box(&pool[k])
        };
        group.bench_function("inverse_dynamics", |b| {
            b.iter(|| {
                let [q, v, a, _] = next();
                $module::inverse_dynamics(q, v, a)
            })
        });
        group.bench_function("inverse_dynamics_derivatives", |b| {
            b.iter(|| {
                let [q, v, a, _] = next();
                control::inverse_dynamics_derivatives(q, v, a)
            })
        });
        group.bench_function("forward_dynamics_derivatives", |b| {
            b.iter(|| {
                let [q, v, _, u] = next();
                control::forward_dynamics_derivatives(q, v, u)
            })
        });
        group.bench_function("mass_matrix_inverse", |b| {
            b.iter(|| control::mass_matrix_inverse(&next()[0]))
        });
        group.bench_function("frame_jacobians", |b| {
            b.iter(|| control::frame_jacobians(&next()[0]))
        });
        group.bench_function("frame_jacobian_dot_qd", |b| {
            b.iter(|| {
                let [q, v, _, _] = next();
                control::frame_jacobian_dot_qd(q, v)
            })
        });
        group.bench_function("regressor", |b| {
            b.iter(|| {
                let [q, v, a, _] = next();
                control::regressor(q, v, a)
            })
        });
        group.finish();
    }};
}

fn control(c: &mut Criterion) {
    bench_robot!(c, "ur5", ur5, 6);
    bench_robot!(c, "panda-arm", panda_arm, 7);
}

/// The group of this file, in a private module: `criterion_group!` writes an undocumented
/// `pub fn`.
mod group {
    criterion::criterion_group!(benches, super::control);
}

criterion_main!(group::benches);

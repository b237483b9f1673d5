//! Generic kernels evaluated in lanes: every lane of `F64x4` (`F32x8`) is, bit for bit, the
//! scalar `f64` (`f32`) kernel at that lane's state, and the batch helper gives each state
//! its own result whatever the number of states and threads.

mod common;

use rne_codegen::{batch, F32x8, F64x4, Lanes};

rne_codegen::derive_dynamics! {
    mod ur5 {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
        scalar: generic,
    }
}

const N: usize = ur5::NV;
type State<T> = ([T; N], [T; N], [T; N]);

/// Seeded UR5 states: |q| ≤ π, |q̇| ≤ 10, |q̈| (or τ) ≤ 10.
fn states(count: usize, seed: u64) -> Vec<State<f64>> {
    let mut rng = common::rng(seed);
    (0..count)
        .map(|_| {
            let (q, qd, qdd) = common::state(&mut rng, N);
            let array = |v: Vec<f64>| -> [f64; N] { v.try_into().expect("N values") };
            (array(q), array(qd), array(qdd))
        })
        .collect()
}

/// `[T; N]` arrays of lane `L` whose lane `i` is `states[i]`'s.
fn gather<L: Lanes>(
    states: &[State<L::Lane>],
    part: impl Fn(&State<L::Lane>) -> [L::Lane; N],
) -> [L; N] {
    std::array::from_fn(|j| L::from_fn(|i| part(&states[i])[j]))
}

fn bits(x: f64) -> u64 {
    x.to_bits()
}

#[test]
fn every_f64x4_lane_is_the_f64_kernel_at_its_state_bit_for_bit() {
    let all = states(400, 71);
    for group in all.chunks_exact(F64x4::LANES) {
        let (q, qd, qdd): State<F64x4> = (
            gather(group, |s| s.0),
            gather(group, |s| s.1),
            gather(group, |s| s.2),
        );
        let tau = ur5::inverse_dynamics(&q, &qd, &qdd);
        let m = ur5::mass_matrix(&q);
        let qdd_fd = ur5::forward_dynamics(&q, &qd, &qdd);
        for (i, (q, qd, x)) in group.iter().enumerate() {
            let expected_tau = ur5::inverse_dynamics(q, qd, x);
            let expected_m = ur5::mass_matrix(q);
            let expected_fd = ur5::forward_dynamics(q, qd, x);
            for j in 0..N {
                assert_eq!(
                    bits(tau[j].lane(i)),
                    bits(expected_tau[j]),
                    "τ{j}, lane {i}"
                );
                assert_eq!(
                    bits(qdd_fd[j].lane(i)),
                    bits(expected_fd[j]),
                    "q̈{j}, lane {i}"
                );
                for k in 0..N {
                    assert_eq!(
                        bits(m[j][k].lane(i)),
                        bits(expected_m[j][k]),
                        "M{j}{k}, lane {i}"
                    );
                }
            }
        }
    }
}

#[test]
fn every_f32x8_lane_is_the_f32_kernel_at_its_state_bit_for_bit() {
    let all: Vec<State<f32>> = states(400, 72)
        .iter()
        .map(|(q, qd, x)| {
            (
                q.map(|v| v as f32),
                qd.map(|v| v as f32),
                x.map(|v| v as f32),
            )
        })
        .collect();
    for group in all.chunks_exact(F32x8::LANES) {
        let (q, qd, qdd): State<F32x8> = (
            gather(group, |s| s.0),
            gather(group, |s| s.1),
            gather(group, |s| s.2),
        );
        let tau = ur5::inverse_dynamics(&q, &qd, &qdd);
        let m = ur5::mass_matrix(&q);
        let qdd_fd = ur5::forward_dynamics(&q, &qd, &qdd);
        for (i, (q, qd, x)) in group.iter().enumerate() {
            let expected_tau = ur5::inverse_dynamics(q, qd, x);
            let expected_m = ur5::mass_matrix(q);
            let expected_fd = ur5::forward_dynamics(q, qd, x);
            for j in 0..N {
                assert_eq!(
                    tau[j].lane(i).to_bits(),
                    expected_tau[j].to_bits(),
                    "τ{j}, lane {i}"
                );
                assert_eq!(
                    qdd_fd[j].lane(i).to_bits(),
                    expected_fd[j].to_bits(),
                    "q̈{j}, lane {i}"
                );
                for k in 0..N {
                    assert_eq!(
                        m[j][k].lane(i).to_bits(),
                        expected_m[j][k].to_bits(),
                        "M{j}{k}, lane {i}"
                    );
                }
            }
        }
    }
}

#[test]
fn batches_of_states_give_each_state_its_own_kernel_result() {
    // 4 · 9 + 3 states: full groups of 4 and of 8, then a tail.
    let all = states(39, 73);
    let scalar: Vec<[f64; N]> = all
        .iter()
        .map(|(q, qd, x)| ur5::inverse_dynamics(q, qd, x))
        .collect();
    let mut lanes = vec![[0.0; N]; all.len()];
    batch::evaluate(&all, &mut lanes, |(q, qd, x): &State<F64x4>| {
        ur5::inverse_dynamics(q, qd, x)
    });
    assert_eq!(lanes, scalar);
    let mut threaded = vec![[0.0; N]; all.len()];
    batch::evaluate_threaded(
        &all,
        &mut threaded,
        |(q, qd, x): &State<F64x4>| ur5::inverse_dynamics(q, qd, x),
        3,
    );
    assert_eq!(threaded, scalar);
    let mut masses = vec![[[0.0; N]; N]; all.len()];
    batch::evaluate(
        &all.iter().map(|s| s.0).collect::<Vec<_>>(),
        &mut masses,
        |q: &[F64x4; N]| ur5::mass_matrix(q),
    );
    for (m, s) in masses.iter().zip(&all) {
        assert_eq!(*m, ur5::mass_matrix(&s.0));
    }
}

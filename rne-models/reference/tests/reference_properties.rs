//! Consistency identities of the numeric reference on random robots (proptest) and on robots
//! built to pin one property each: fixed links, branched trees, energy conservation.

mod random_robots;

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use proptest::prelude::*;
use random_robots::*;
use rne_reference::Reference;
use rne_symbolic::model::NumericLink;
use rne_symbolic::NumericModel;

// ---------------------------------------------------------------------------------------------
// The identities

/// CRBA M equals the columns of RNEA(q, 0, e_j) − g(q).
fn mass_matrix_equals_rnea_columns(reference: &mut Reference, q: &[f64]) -> Result<(), String> {
    let n = reference.dof();
    let m = reference.mass_matrix(q).unwrap();
    let g = reference.gravity_torques(q).unwrap();
    let zero = vec![0.0; n];
    let mut columns = DMatrix::zeros(n, n);
    for j in 0..n {
        let mut unit = zero.clone();
        unit[j] = 1.0;
        let column = reference.inverse_dynamics(q, &zero, &unit).unwrap() - &g;
        columns.set_column(j, &column);
    }
    let error = max_difference(m.as_slice(), columns.as_slice());
    let scale = max_abs(m.as_slice()) + max_abs(g.as_slice());
    check(error <= 1e-12 * scale, || {
        format!("CRBA\n{m}\nRNEA columns\n{columns}")
    })
}

/// M is exactly symmetric and positive definite.
fn mass_matrix_is_symmetric_positive_definite(
    reference: &mut Reference,
    q: &[f64],
) -> Result<(), String> {
    let m = reference.mass_matrix(q).unwrap();
    check(m == m.transpose(), || format!("not symmetric\n{m}"))?;
    check(m.clone().cholesky().is_some(), || {
        format!("not positive definite\n{m}")
    })
}

/// τ = M q̈ + bias, with bias = C q̇ + g.
fn inverse_dynamics_splits_into_mass_matrix_and_bias(
    reference: &mut Reference,
    s: &State,
) -> Result<(), String> {
    let tau = reference.inverse_dynamics(&s.q, &s.qd, &s.qdd).unwrap();
    let m = reference.mass_matrix(&s.q).unwrap();
    let bias = reference.bias_torques(&s.q, &s.qd).unwrap();
    let split = &m * DVector::from_column_slice(&s.qdd) + &bias;
    let scale = max_abs(tau.as_slice()) + max_abs(split.as_slice()) + max_abs(bias.as_slice());
    let error = max_difference(tau.as_slice(), split.as_slice());
    check(error <= 1e-12 * scale, || {
        format!("RNEA {tau} vs M qdd + bias {split}")
    })
}

/// The ABA equals M⁻¹ (τ − bias) and the RNEA of its result gives τ back. The tolerances
/// follow the forward error of a linear solve, `ε (cond(M) |q̈| + |τ − bias| / λ_min(M))`, and
/// its residual, `ε (|τ| + |bias| + |M| |q̈|)`.
fn forward_dynamics_inverts_inverse_dynamics(
    reference: &mut Reference,
    s: &State,
) -> Result<(), String> {
    let tau = reference.inverse_dynamics(&s.q, &s.qd, &s.qdd).unwrap();
    let qdd = reference
        .forward_dynamics(&s.q, &s.qd, tau.as_slice())
        .unwrap();
    let m = reference.mass_matrix(&s.q).unwrap();
    let bias = reference.bias_torques(&s.q, &s.qd).unwrap();
    let eigenvalues = m.clone().symmetric_eigenvalues();
    let (largest, smallest) = (eigenvalues.max(), eigenvalues.min());
    let solved = m.clone().cholesky().unwrap().solve(&(&tau - &bias));
    let error = max_difference(qdd.as_slice(), solved.as_slice());
    let bound = largest / smallest * max_abs(solved.as_slice())
        + (max_abs(tau.as_slice()) + max_abs(bias.as_slice())) / smallest;
    check(error <= 1e-13 * bound, || {
        format!(
            "ABA {qdd} vs M^-1 (tau - bias) {solved}, eigenvalues of M {smallest:e} to {largest:e}"
        )
    })?;
    let again = reference
        .inverse_dynamics(&s.q, &s.qd, qdd.as_slice())
        .unwrap();
    let error = max_difference(again.as_slice(), tau.as_slice());
    let scale = max_abs(tau.as_slice())
        + max_abs(bias.as_slice())
        + max_abs(m.as_slice()) * max_abs(qdd.as_slice());
    check(error <= 1e-12 * scale, || {
        format!("RNEA(ABA(tau)) {again} vs tau {tau}")
    })
}

/// T = ½ q̇ᵀ M q̇.
fn kinetic_energy_is_the_mass_matrix_quadratic_form(
    reference: &mut Reference,
    s: &State,
) -> Result<(), String> {
    let m = reference.mass_matrix(&s.q).unwrap();
    let qd = DVector::from_column_slice(&s.qd);
    let quadratic = 0.5 * qd.dot(&(&m * &qd));
    let kinetic = reference.kinetic_energy(&s.q, &s.qd).unwrap();
    check(
        (kinetic - quadratic).abs() <= 1e-12 * quadratic.abs(),
        || format!("T = {kinetic} vs ½ qdᵀ M qd = {quadratic}"),
    )
}

/// d(T + V)/dt = q̇ᵀ τ along q(t) = q + q̇ t + ½ q̈ t², by a fourth-order central difference
/// (truncation and rounding errors near 1e-10 of the energies; an absolute floor of 1e-9 W for
/// states where everything is near zero).
fn power_balance_holds(reference: &mut Reference, s: &State) -> Result<(), String> {
    let h = 1e-3;
    let mut energy = |t: f64| {
        let q: Vec<f64> = (0..s.q.len())
            .map(|k| s.q[k] + s.qd[k] * t + 0.5 * s.qdd[k] * t * t)
            .collect();
        let qd: Vec<f64> = (0..s.q.len()).map(|k| s.qd[k] + s.qdd[k] * t).collect();
        reference.kinetic_energy(&q, &qd).unwrap() + reference.potential_energy(&q).unwrap()
    };
    let scale = energy(0.0).abs() + energy(h).abs();
    let derivative =
        (-energy(2.0 * h) + 8.0 * energy(h) - 8.0 * energy(-h) + energy(-2.0 * h)) / (12.0 * h);
    let tau = reference.inverse_dynamics(&s.q, &s.qd, &s.qdd).unwrap();
    let power = DVector::from_column_slice(&s.qd).dot(&tau);
    check(
        (derivative - power).abs() <= 1e-7 * (scale + power.abs()) + 1e-9,
        || format!("d(T+V)/dt = {derivative} vs qdᵀ tau = {power}"),
    )
}

fn check(condition: bool, message: impl FnOnce() -> String) -> Result<(), String> {
    if condition {
        Ok(())
    } else {
        Err(message())
    }
}

fn all_identities(model: &NumericModel, s: &State) -> Result<(), String> {
    let mut reference = Reference::new(model);
    mass_matrix_equals_rnea_columns(&mut reference, &s.q)?;
    mass_matrix_is_symmetric_positive_definite(&mut reference, &s.q)?;
    inverse_dynamics_splits_into_mass_matrix_and_bias(&mut reference, s)?;
    forward_dynamics_inverts_inverse_dynamics(&mut reference, s)?;
    kinetic_energy_is_the_mass_matrix_quadratic_form(&mut reference, s)?;
    power_balance_holds(&mut reference, s)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_robots_satisfy_the_consistency_identities((model, state) in robot_and_state()) {
        if let Err(message) = all_identities(&model, &state) {
            return Err(TestCaseError::fail(message));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Fixed links

/// The inertia of two bodies about their common COM, in the first body's axes: the second is
/// placed by rotation `r` and origin `t`.
fn merge(
    (m1, c1, i1): (f64, Vector3<f64>, Matrix3<f64>),
    (m2, c2, i2): (f64, Vector3<f64>, Matrix3<f64>),
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let mass = m1 + m2;
    let c2 = t + r * c2;
    let com = (c1 * m1 + c2 * m2) / mass;
    let shift =
        |m: f64, d: Vector3<f64>| (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m;
    let inertia = i1 + shift(m1, c1 - com) + r * i2 * r.transpose() + shift(m2, c2 - com);
    (mass, com, inertia)
}

fn matrix(rows: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| rows[r][c])
}

fn inertial(link: &NumericLink) -> (f64, Vector3<f64>, Matrix3<f64>) {
    (link.mass, Vector3::from(link.com), matrix(&link.inertia))
}

/// A random 6-link chain q0, q1, [fixed, with mass], q2, [fixed, massless], q3 with the fixed
/// links removed and merged by hand: the heavy one into its parent, and the placements of the
/// links after each fixed one composed with the fixed placement.
#[test]
fn fixed_link_with_mass_equals_its_inertia_merged_into_the_parent() {
    let mut specs = sample_link_specs(6);
    for (spec, kind) in specs.iter_mut().zip([0, 2, 3, 1, 4, 0]) {
        spec.kind = kind;
        spec.parent_choice = 0.0;
    }
    let with_fixed = robot(&specs, 0, [1.0, -2.0, -9.0]);
    let l = &with_fixed.links;
    let (heavy, flange) = (&l[2], &l[4]);
    let (mass, com, inertia) = merge(
        inertial(&l[1]),
        inertial(heavy),
        &matrix(&heavy.rotation),
        &Vector3::from(heavy.translation),
    );
    let after = |fixed: &NumericLink, child: &NumericLink, parent: usize| NumericLink {
        parent: Some(parent),
        rotation: rows(&(matrix(&fixed.rotation) * matrix(&child.rotation))),
        translation: (Vector3::from(fixed.translation)
            + matrix(&fixed.rotation) * Vector3::from(child.translation))
        .into(),
        ..child.clone()
    };
    let merged = NumericModel {
        links: vec![
            l[0].clone(),
            NumericLink {
                mass,
                com: com.into(),
                inertia: rows(&inertia),
                ..l[1].clone()
            },
            after(heavy, &l[3], 1),
            after(flange, &l[5], 2),
        ],
        ..with_fixed.clone()
    };
    let (mut a, mut b) = (Reference::new(&with_fixed), Reference::new(&merged));
    let (q, qd, qdd) = (
        &[0.4, -0.3, 1.9, -2.5],
        &[1.1, -0.6, 0.8, 1.7],
        &[-0.9, 2.2, 0.5, -1.4],
    );
    let pairs = [
        (
            a.inverse_dynamics(q, qd, qdd).unwrap(),
            b.inverse_dynamics(q, qd, qdd).unwrap(),
        ),
        (a.gravity_torques(q).unwrap(), b.gravity_torques(q).unwrap()),
        (
            a.bias_torques(q, qd).unwrap(),
            b.bias_torques(q, qd).unwrap(),
        ),
        (
            a.forward_dynamics(q, qd, qdd).unwrap(),
            b.forward_dynamics(q, qd, qdd).unwrap(),
        ),
        (
            DVector::from_column_slice(a.mass_matrix(q).unwrap().as_slice()),
            DVector::from_column_slice(b.mass_matrix(q).unwrap().as_slice()),
        ),
        (
            DVector::from_vec(vec![
                a.kinetic_energy(q, qd).unwrap(),
                a.potential_energy(q).unwrap(),
            ]),
            DVector::from_vec(vec![
                b.kinetic_energy(q, qd).unwrap(),
                b.potential_energy(q).unwrap(),
            ]),
        ),
    ];
    for (fixed, hand_merged) in pairs {
        let error = max_difference(fixed.as_slice(), hand_merged.as_slice());
        assert!(
            error <= 1e-12 * max_abs(hand_merged.as_slice()),
            "{fixed} vs {hand_merged}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Branched trees

/// A trunk joint carrying two 2-joint arms: M couples each arm with the trunk but never the two
/// arms with each other (exact zeros), and the identities hold.
#[test]
fn branched_tree_has_zero_inertia_coupling_between_branches() {
    let mut specs = sample_link_specs(5);
    // Trunk, arm A (links 1, 2), arm B (links 3, 4). A parent choice of 0.8 at link 3 picks
    // ⌊(0.8 − 0.7) / 0.3 · 4⌋ − 1 = 0, the trunk.
    for (spec, (kind, parent_choice)) in
        specs
            .iter_mut()
            .zip([(0, 0.0), (1, 0.0), (2, 0.0), (0, 0.8), (1, 0.0)])
    {
        spec.kind = kind;
        spec.parent_choice = parent_choice;
    }
    let tree = robot(&specs, 0, [0.0, 0.0, -9.81]);
    let parents: Vec<_> = tree.links.iter().map(|l| l.parent).collect();
    assert_eq!(parents, [None, Some(0), Some(1), Some(0), Some(3)]);
    let state = State {
        q: vec![0.3, -1.2, 0.7, 2.1, -0.4],
        qd: vec![0.5, -1.0, 0.3, 0.8, -0.2],
        qdd: vec![1.0, 0.4, -2.0, 0.6, 1.5],
    };
    let m = Reference::new(&tree).mass_matrix(&state.q).unwrap();
    for (a, b) in [(1, 3), (1, 4), (2, 3), (2, 4)] {
        assert_eq!(m[(a, b)], 0.0, "{m}");
        assert_eq!(m[(b, a)], 0.0, "{m}");
    }
    assert!(
        m[(0, 1)] != 0.0 && m[(0, 3)] != 0.0 && m[(3, 4)] != 0.0,
        "{m}"
    );
    all_identities(&tree, &state).unwrap();
}

// ---------------------------------------------------------------------------------------------
// Energy along a simulated trajectory

/// With τ = 0 and no friction, T + V stays constant along a trajectory integrated with the ABA
/// (classical Runge–Kutta, 1 ms steps, 1 s).
#[test]
fn total_energy_is_conserved_along_an_unactuated_trajectory() {
    let (model, state) = sample_robot_and_state(4);
    let mut reference = Reference::new(&model);
    let n = reference.dof();
    let zero = vec![0.0; n];
    let mut derivative = |x: &[f64]| -> Vec<f64> {
        let qdd = reference.forward_dynamics(&x[..n], &x[n..], &zero).unwrap();
        x[n..].iter().chain(qdd.iter()).copied().collect()
    };
    let mut x: Vec<f64> = state.q.iter().chain(&state.qd).copied().collect();
    let dt = 1e-3;
    let axpy = |x: &[f64], a: f64, k: &[f64]| -> Vec<f64> {
        x.iter().zip(k).map(|(x, k)| x + a * k).collect()
    };
    let mut trajectory = vec![x.clone()];
    for _ in 0..1000 {
        let k1 = derivative(&x);
        let k2 = derivative(&axpy(&x, dt / 2.0, &k1));
        let k3 = derivative(&axpy(&x, dt / 2.0, &k2));
        let k4 = derivative(&axpy(&x, dt, &k3));
        x = (0..2 * n)
            .map(|k| x[k] + dt / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]))
            .collect();
        trajectory.push(x.clone());
    }
    let mut reference = Reference::new(&model);
    let energies: Vec<(f64, f64)> = trajectory
        .iter()
        .map(|x| {
            (
                reference.kinetic_energy(&x[..n], &x[n..]).unwrap(),
                reference.potential_energy(&x[..n]).unwrap(),
            )
        })
        .collect();
    let total: Vec<f64> = energies.iter().map(|(t, v)| t + v).collect();
    let swing = energies.iter().map(|(t, _)| *t).fold(0.0, f64::max);
    let drift = total
        .iter()
        .fold(0.0_f64, |m, e| m.max((e - total[0]).abs()));
    eprintln!("energy drift {drift:e} over a kinetic-energy swing of {swing:e}");
    assert!(swing > 1.0, "the robot should move: {swing}");
    assert!(
        drift <= 1e-8 * swing,
        "drift {drift} over a swing of {swing}"
    );
}

//! Consistency identities of the numeric reference on random robots (proptest) and on robots
//! built to pin one property each: fixed links, branched trees, energy conservation, NaN input,
//! argument checking.

use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Unit, Vector3};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use rne_reference::{Reference, ReferenceError};
use rne_symbolic::model::Base;
use rne_symbolic::model::NumericLink;
use rne_symbolic::{JointKind, NumericModel};

// ---------------------------------------------------------------------------------------------
// Random robots

/// A unit vector from spherical angles (polar, azimuth).
fn direction([polar, azimuth]: [f64; 2]) -> Vector3<f64> {
    Vector3::new(
        polar.sin() * azimuth.cos(),
        polar.sin() * azimuth.sin(),
        polar.cos(),
    )
}

/// A rotation from an axis (spherical angles) and an angle.
fn rotation(axis: [f64; 2], angle: f64) -> Matrix3<f64> {
    Rotation3::from_axis_angle(&Unit::new_unchecked(direction(axis)), angle).into_inner()
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[(r, c)]))
}

/// The raw numbers of one random link.
#[derive(Clone, Debug)]
struct LinkSpec {
    /// Below 0.7: the previous link (a chain); above: any earlier link or the base.
    parent_choice: f64,
    /// 0, 1: revolute; 2: prismatic; 3: fixed with mass; 4: fixed, massless.
    kind: u8,
    rotation_axis: [f64; 2],
    rotation_angle: f64,
    translation: [f64; 3],
    joint_axis: [f64; 2],
    mass: f64,
    com: [f64; 3],
    /// Second moments of mass along the principal axes, per kg: `I = m diag(b+c, a+c, a+b)`
    /// satisfies the triangle inequality.
    moments: [f64; 3],
    principal_axis: [f64; 2],
    principal_angle: f64,
}

fn angles() -> impl Strategy<Value = [f64; 2]> {
    [0.0..std::f64::consts::PI, -3.2..3.2]
}

fn link_spec() -> impl Strategy<Value = LinkSpec> {
    (
        (
            0.0..1.0,
            0u8..5,
            angles(),
            -3.2..3.2,
            [-0.6..0.6, -0.6..0.6, -0.6..0.6],
            angles(),
        ),
        (
            0.1..5.0,
            [-0.3..0.3, -0.3..0.3, -0.3..0.3],
            [0.001..0.05, 0.001..0.05, 0.001..0.05],
        ),
        (angles(), -3.2..3.2),
    )
        .prop_map(|(geometry, inertia, principal)| {
            let (parent_choice, kind, rotation_axis, rotation_angle, translation, joint_axis) =
                geometry;
            let (mass, com, moments) = inertia;
            let (principal_axis, principal_angle) = principal;
            LinkSpec {
                parent_choice,
                kind,
                rotation_axis,
                rotation_angle,
                translation,
                joint_axis,
                mass,
                com,
                moments,
                principal_axis,
                principal_angle,
            }
        })
}

/// A robot from link specs; joint indices are assigned in link order, shifted cyclically by
/// `shift` so that the reference cannot rely on any particular numbering.
fn robot(specs: &[LinkSpec], shift: usize, gravity: [f64; 3]) -> NumericModel {
    let dof = specs.iter().filter(|s| s.kind < 3).count();
    let mut next_joint = 0;
    let links = specs
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let parent = if s.parent_choice < 0.7 {
                i.checked_sub(1)
            } else {
                let pick = ((s.parent_choice - 0.7) / 0.3 * (i + 1) as f64) as usize;
                pick.min(i).checked_sub(1)
            };
            let (kind, joint) = match s.kind {
                0 | 1 => (JointKind::Revolute, Some((next_joint + shift) % dof)),
                2 => (JointKind::Prismatic, Some((next_joint + shift) % dof)),
                _ => (JointKind::Fixed, None),
            };
            next_joint += usize::from(joint.is_some());
            let mass = if s.kind == 4 { 0.0 } else { s.mass };
            let [a, b, c] = s.moments;
            let principal = rotation(s.principal_axis, s.principal_angle);
            let inertia = principal
                * Matrix3::from_diagonal(&Vector3::new(b + c, a + c, a + b))
                * principal.transpose()
                * mass;
            NumericLink {
                name: format!("link{i}"),
                parent,
                kind,
                joint,
                rotation: rows(&rotation(s.rotation_axis, s.rotation_angle)),
                translation: s.translation,
                axis: direction(s.joint_axis).into(),
                mass,
                com: s.com,
                inertia: rows(&inertia),
                coupling: None,
                friction: None,
                armature: None,
            }
        })
        .collect();
    NumericModel {
        name: "random".into(),
        gravity,
        base: Base::Fixed,
        links,
        joint_names: (0..dof).map(|k| format!("q{k}")).collect(),
    }
}

/// A random robot with 1–8 joints and up to 10 links, and a state for it.
fn robot_and_state() -> impl Strategy<Value = (NumericModel, State)> {
    (
        prop::collection::vec(link_spec(), 1..=10).prop_filter("1 to 8 joints", |specs| {
            (1..=8).contains(&specs.iter().filter(|s| s.kind < 3).count())
        }),
        0usize..8,
        [-10.0..10.0, -10.0..10.0, -10.0..10.0],
        prop::array::uniform8(-3.2..3.2),
        prop::array::uniform8(-2.0..2.0),
        prop::array::uniform8(-5.0..5.0),
    )
        .prop_map(|(specs, shift, gravity, q, qd, qdd)| {
            let model = robot(&specs, shift, gravity);
            let n = model.dof();
            let state = State {
                q: q[..n].to_vec(),
                qd: qd[..n].to_vec(),
                qdd: qdd[..n].to_vec(),
            };
            (model, state)
        })
}

/// One sample of [`robot_and_state`] for the deterministic tests.
fn sample_robot_and_state(min_dof: usize) -> (NumericModel, State) {
    let mut runner = TestRunner::deterministic();
    let strategy = robot_and_state().prop_filter("enough joints", move |(m, _)| m.dof() >= min_dof);
    strategy.new_tree(&mut runner).unwrap().current()
}

/// `count` link specs drawn deterministically, for tests that then fix kinds and parents.
fn sample_link_specs(count: usize) -> Vec<LinkSpec> {
    let mut runner = TestRunner::deterministic();
    let strategy = prop::collection::vec(link_spec(), count);
    strategy.new_tree(&mut runner).unwrap().current()
}

#[derive(Clone, Debug)]
struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

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

// ---------------------------------------------------------------------------------------------
// Non-finite input and argument checking

/// A serial chain with all-NaN input gives NaN outputs, and no panic. Of M only the
/// off-diagonal entries are asserted: each passes through the transform of its column's joint,
/// while some diagonal entries (the last, `S_nᵀ I_n S_n`) do not depend on q at all.
#[test]
fn nan_input_gives_nan_output() {
    let mut specs = sample_link_specs(4);
    for (spec, kind) in specs.iter_mut().zip([0, 2, 1, 0]) {
        spec.kind = kind;
        spec.parent_choice = 0.0;
    }
    let mut reference = Reference::new(&robot(&specs, 0, [0.0, 0.0, -9.81]));
    let (finite, nan) = ([0.1, 0.2, 0.3, 0.4], [f64::NAN; 4]);
    let all_nan = |v: DVector<f64>| v.iter().all(|x| x.is_nan());
    assert!(all_nan(
        reference.inverse_dynamics(&nan, &finite, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.inverse_dynamics(&finite, &nan, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.inverse_dynamics(&finite, &finite, &nan).unwrap()
    ));
    assert!(all_nan(reference.gravity_torques(&nan).unwrap()));
    assert!(all_nan(reference.bias_torques(&finite, &nan).unwrap()));
    assert!(all_nan(
        reference.forward_dynamics(&nan, &finite, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.forward_dynamics(&finite, &nan, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.forward_dynamics(&finite, &finite, &nan).unwrap()
    ));
    assert!(reference.kinetic_energy(&finite, &nan).unwrap().is_nan());
    assert!(reference.kinetic_energy(&nan, &finite).unwrap().is_nan());
    assert!(reference.potential_energy(&nan).unwrap().is_nan());
    let m = reference.mass_matrix(&nan).unwrap();
    for (r, c) in (0..4).flat_map(|r| (0..4).map(move |c| (r, c))) {
        assert!(r == c || m[(r, c)].is_nan(), "{m}");
    }
}

#[test]
fn wrong_lengths_are_errors_naming_the_argument() {
    let (model, _) = sample_robot_and_state(3);
    let mut reference = Reference::new(&model);
    let n = reference.dof();
    let (ok, short) = (vec![0.0; n], vec![0.0; n - 1]);
    let wrong = |argument, expected, found| {
        Err::<(), _>(ReferenceError::WrongLength {
            argument,
            expected,
            found,
        })
    };
    assert_eq!(
        reference.inverse_dynamics(&ok, &ok, &short).map(drop),
        wrong("qdd", n, n - 1)
    );
    assert_eq!(
        reference.inverse_dynamics_into(&ok, &ok, &ok, &mut vec![0.0; n + 1]),
        wrong("tau", n, n + 1)
    );
    assert_eq!(
        reference.mass_matrix(&short).map(drop),
        wrong("q", n, n - 1)
    );
    assert_eq!(
        reference.mass_matrix_into(&ok, &mut vec![0.0; n]),
        wrong("out", n * n, n)
    );
    assert_eq!(
        reference.gravity_torques(&short).map(drop),
        wrong("q", n, n - 1)
    );
    assert_eq!(
        reference.bias_torques(&ok, &short).map(drop),
        wrong("qd", n, n - 1)
    );
    assert_eq!(
        reference.forward_dynamics(&ok, &ok, &short).map(drop),
        wrong("tau", n, n - 1)
    );
    assert_eq!(
        reference.kinetic_energy(&ok, &short).map(drop),
        wrong("qd", n, n - 1)
    );
    assert_eq!(reference.potential_energy(&[]).map(drop), wrong("q", n, 0));
}

#[test]
fn into_variants_equal_the_allocating_ones() {
    let (model, s) = sample_robot_and_state(3);
    let mut reference = Reference::new(&model);
    let n = reference.dof();
    let mut out = vec![0.0; n];
    reference
        .inverse_dynamics_into(&s.q, &s.qd, &s.qdd, &mut out)
        .unwrap();
    assert_eq!(
        out,
        reference
            .inverse_dynamics(&s.q, &s.qd, &s.qdd)
            .unwrap()
            .as_slice()
    );
    reference.gravity_torques_into(&s.q, &mut out).unwrap();
    assert_eq!(out, reference.gravity_torques(&s.q).unwrap().as_slice());
    reference.bias_torques_into(&s.q, &s.qd, &mut out).unwrap();
    assert_eq!(out, reference.bias_torques(&s.q, &s.qd).unwrap().as_slice());
    reference
        .forward_dynamics_into(&s.q, &s.qd, &s.qdd, &mut out)
        .unwrap();
    assert_eq!(
        out,
        reference
            .forward_dynamics(&s.q, &s.qd, &s.qdd)
            .unwrap()
            .as_slice()
    );
    let mut matrix = vec![0.0; n * n];
    reference.mass_matrix_into(&s.q, &mut matrix).unwrap();
    assert_eq!(matrix, reference.mass_matrix(&s.q).unwrap().as_slice());
}

#[test]
fn invalid_models_are_rejected_with_the_link_and_field() {
    let (model, _) = sample_robot_and_state(3);
    let field_of = |model: &NumericModel| match Reference::try_new(model) {
        Err(ReferenceError::InvalidModel { link, field, .. }) => (link, field),
        other => panic!("expected an invalid-model error, got {other:?}"),
    };
    let last = model.links.len() - 1;
    let name = model.links[last].name.clone();

    let mut bad = model.clone();
    bad.links[0].parent = Some(last);
    assert_eq!(field_of(&bad), (model.links[0].name.clone(), "parent"));

    let moving = model.links.iter().position(|l| l.joint.is_some()).unwrap();
    let mut bad = model.clone();
    bad.links[moving].axis = [0.0, 0.0, 2.0];
    bad.links[moving].kind = JointKind::Prismatic;
    assert_eq!(field_of(&bad), (model.links[moving].name.clone(), "axis"));

    let mut bad = model.clone();
    bad.links[last].rotation = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(field_of(&bad), (name.clone(), "rotation"));

    let mut bad = model.clone();
    bad.links[last].inertia[0][1] += 0.5;
    assert_eq!(field_of(&bad), (name, "inertia"));

    let mut bad = model.clone();
    bad.joint_names.push("extra".into());
    assert_eq!(field_of(&bad), ("joint_names".to_string(), "joint"));

    let second = model.links.iter().rposition(|l| l.joint.is_some()).unwrap();
    let mut bad = model.clone();
    bad.links[second].joint = model.links[moving].joint;
    assert_eq!(field_of(&bad), (model.links[second].name.clone(), "joint"));
}

//! Derivatives of the dynamics by dual numbers, against central finite differences in the
//! tangent space (Pinocchio's `integrate` for the base), and the identities they obey.

mod common;

use common::{
    coupled, fixture, floating, floating_three_body, matrix_rel_err, rel_err, rng, rotation_of,
    state, with_fixed_payload, with_friction_and_armature, Mimic, FIXTURES,
};
use nalgebra::{DMatrix, DVector, Rotation3, Vector3};
use rne_reference::Reference;
use rne_symbolic::NumericModel;

/// Step of the central differences.
const H: f64 = 1e-6;

/// Fixed-base fixtures, floating robots, a coupled one and one with friction and armature.
fn models() -> Vec<NumericModel> {
    let mut models: Vec<NumericModel> = FIXTURES.iter().map(|f| fixture(f)).collect();
    models.push(floating_three_body());
    models.push(floating(&fixture("panda-arm.urdf")));
    let mimic = Mimic {
        follower: 2,
        leader: 0,
        multiplier: -1.4,
        offset: 0.2,
    };
    models.push(coupled(&floating(&fixture("ur5.urdf")), mimic).0);
    models.push(with_friction_and_armature(&floating_three_body()));
    models.push(with_fixed_payload(&floating(&fixture("puma560.toml"))));
    models
}

/// The central difference of `f` along every tangent direction of q (columns), with
/// `q ⊕ ±h e_j` by the reference's `integrate`.
fn differentiate_q(
    reference: &Reference,
    q: &[f64],
    mut f: impl FnMut(&[f64]) -> DVector<f64>,
) -> DMatrix<f64> {
    let n = reference.nv();
    let columns: Vec<DVector<f64>> = (0..n)
        .map(|j| {
            let mut step = vec![0.0; n];
            step[j] = H;
            let plus = reference.integrate(q, &step).unwrap();
            step[j] = -H;
            let minus = reference.integrate(q, &step).unwrap();
            (f(plus.as_slice()) - f(minus.as_slice())) / (2.0 * H)
        })
        .collect();
    DMatrix::from_columns(&columns)
}

/// The central difference of `f` along every entry of a vector `x`.
fn differentiate(x: &[f64], mut f: impl FnMut(&[f64]) -> DVector<f64>) -> DMatrix<f64> {
    let columns: Vec<DVector<f64>> = (0..x.len())
        .map(|j| {
            let (mut plus, mut minus) = (x.to_vec(), x.to_vec());
            plus[j] += H;
            minus[j] -= H;
            (f(&plus) - f(&minus)) / (2.0 * H)
        })
        .collect();
    DMatrix::from_columns(&columns)
}

/// Relative to the largest entry of the matrix (and at least 1).
fn scaled_error(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    matrix_rel_err(a, b, 1.0)
}

/// A dual-number derivative against a central difference of `f`, relative to the largest entry
/// of the matrix or of `f` itself, whichever is larger: rounding in the difference quotient is
/// `ε |f| / h`, so a derivative small against the function it comes from is known to that
/// scale only.
fn difference_error(dual: &DMatrix<f64>, difference: &DMatrix<f64>, value: &DVector<f64>) -> f64 {
    matrix_rel_err(dual, difference, value.amax().max(1.0))
}

#[test]
fn inverse_dynamics_derivatives_agree_with_central_differences() {
    let mut rng = rng(21);
    for model in models() {
        let mut reference = Reference::new(&model).with_friction(true);
        let mut other = Reference::new(&model).with_friction(true);
        for _ in 0..5 {
            let (q, v, a) = state(&mut rng, &model);
            let (dq, dv) = reference.inverse_dynamics_derivatives(&q, &v, &a).unwrap();
            let fd_q = differentiate_q(&reference, &q, |q| {
                other.inverse_dynamics(q, &v, &a).unwrap()
            });
            let fd_v = differentiate(&v, |v| other.inverse_dynamics(&q, v, &a).unwrap());
            let tau = other.inverse_dynamics(&q, &v, &a).unwrap();
            assert!(
                difference_error(&dq, &fd_q, &tau) < 1e-6,
                "{}: ∂τ/∂q\n{dq}{fd_q}",
                model.name
            );
            assert!(
                difference_error(&dv, &fd_v, &tau) < 1e-6,
                "{}: ∂τ/∂q̇\n{dv}{fd_v}",
                model.name
            );
        }
    }
}

#[test]
fn the_acceleration_derivative_of_inverse_dynamics_is_the_mass_matrix() {
    let mut rng = rng(22);
    for model in models() {
        let mut reference = Reference::new(&model);
        let (q, v, a) = state(&mut rng, &model);
        let tau = reference.inverse_dynamics(&q, &v, &a).unwrap();
        let m = reference.mass_matrix(&q).unwrap();
        for j in 0..model.nv() {
            let mut moved = a.clone();
            moved[j] += 1.0;
            let column = reference.inverse_dynamics(&q, &v, &moved).unwrap() - &tau;
            let expected = m.column(j).into_owned();
            assert!(
                rel_err(column.as_slice(), expected.as_slice(), 1.0) < 1e-11,
                "{}",
                model.name
            );
        }
    }
}

#[test]
fn forward_dynamics_derivatives_agree_with_central_differences_and_with_minus_m_inverse_dtau() {
    let mut rng = rng(23);
    for model in models() {
        let mut reference = Reference::new(&model).with_friction(true);
        let mut other = Reference::new(&model).with_friction(true);
        for _ in 0..5 {
            let (q, v, tau) = state(&mut rng, &model);
            let derivatives = reference
                .forward_dynamics_derivatives(&q, &v, &tau)
                .unwrap();
            let (dq, dv) = (derivatives.dqdd_dq, derivatives.dqdd_dqd);
            let m_inverse = derivatives.mass_matrix_inverse;
            let fd_q = differentiate_q(&reference, &q, |q| {
                other.forward_dynamics(q, &v, &tau).unwrap()
            });
            let fd_v = differentiate(&v, |v| other.forward_dynamics(&q, v, &tau).unwrap());
            let qdd = reference.forward_dynamics(&q, &v, &tau).unwrap();
            assert!(
                difference_error(&dq, &fd_q, &qdd) < 1e-6,
                "{}: ∂q̈/∂q\n{dq}{fd_q}",
                model.name
            );
            assert!(
                difference_error(&dv, &fd_v, &qdd) < 1e-6,
                "{}: ∂q̈/∂q̇\n{dv}{fd_v}",
                model.name
            );
            // ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ).
            let (dtau_q, dtau_v) = reference
                .inverse_dynamics_derivatives(&q, &v, qdd.as_slice())
                .unwrap();
            assert!(
                scaled_error(&dq, &(-&m_inverse * dtau_q)) < 1e-9,
                "{}",
                model.name
            );
            assert!(
                scaled_error(&dv, &(-&m_inverse * dtau_v)) < 1e-9,
                "{}",
                model.name
            );
        }
    }
}

#[test]
fn the_mass_matrix_inverse_times_the_mass_matrix_is_the_identity() {
    let mut rng = rng(24);
    for model in models() {
        let mut reference = Reference::new(&model);
        for _ in 0..10 {
            let (q, _, _) = state(&mut rng, &model);
            let product =
                reference.mass_matrix_inverse(&q).unwrap() * reference.mass_matrix(&q).unwrap();
            let identity = DMatrix::identity(model.nv(), model.nv());
            assert!((product - identity).abs().max() < 1e-9, "{}", model.name);
        }
    }
}

#[test]
fn integrate_moves_the_base_along_the_se3_exponential_of_its_body_twist() {
    // Under a constant body twist the orientation is R Exp(ω t) and the origin moves by
    // ∫ R Exp(ω s) v_lin ds (Simpson's rule here); joints add their rates.
    let model = floating_three_body();
    let reference = Reference::new(&model);
    let mut rng = rng(25);
    for _ in 0..20 {
        let (q, v, _) = state(&mut rng, &model);
        let moved = reference.integrate(&q, &v).unwrap();
        let r = rotation_of(&q);
        let (w, v_lin) = (
            Vector3::new(v[3], v[4], v[5]),
            Vector3::new(v[0], v[1], v[2]),
        );
        let expected_rotation = r * Rotation3::new(w).into_inner();
        assert!((rotation_of(moved.as_slice()) - expected_rotation).norm() < 1e-13);
        let steps = 2000;
        let sample = |s: f64| r * Rotation3::new(w * s).into_inner() * v_lin;
        let mut integral = sample(0.0) + sample(1.0);
        for k in 1..steps {
            let weight = if k % 2 == 1 { 4.0 } else { 2.0 };
            integral += sample(k as f64 / steps as f64) * weight;
        }
        let expected = Vector3::new(q[0], q[1], q[2]) + integral / (3.0 * steps as f64);
        let position = Vector3::new(moved[0], moved[1], moved[2]);
        assert!(
            (position - expected).norm() < 1e-10,
            "{position} vs {expected}"
        );
        for k in 7..model.nq() {
            assert_eq!(moved[k], q[k] + v[k - 1]);
        }
    }
}

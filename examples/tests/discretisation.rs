//! The discrete dynamics the swing-up optimises over: the Runge–Kutta step's Jacobians, built
//! from the generated ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ by the chain rule, are those of the step itself;
//! the angle convention of the hanging and upright states; the errors of a bad setup.

use nalgebra::{SMatrix, SVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::Kernel;
use rne_examples::{planar_elbow, Discretisation, Error, Rk4, HANGING, TORQUE_LIMIT, UPRIGHT};

rne_codegen::derive_dynamics! {
    /// The planar elbow without the derivative kernel.
    mod elbow_without_derivatives {
        robot: "robots/planar-elbow.toml",
        outputs: [forward_dynamics],
    }
}

/// Central differences of the step: column j of ∂f/∂x is (f(x + ε e_j) − f(x − ε e_j)) / 2ε.
fn central_differences(
    rk4: &Rk4<planar_elbow::Model, 2>,
    x: &SVector<f64, 4>,
    u: &SVector<f64, 2>,
) -> (SMatrix<f64, 4, 4>, SMatrix<f64, 4, 2>) {
    let eps = 1e-6;
    let mut fx = SMatrix::<f64, 4, 4>::zeros();
    let mut fu = SMatrix::<f64, 4, 2>::zeros();
    for j in 0..4 {
        let mut e = SVector::<f64, 4>::zeros();
        e[j] = eps;
        let column = (rk4.step(&(x + e), u) - rk4.step(&(x - e), u)) / (2.0 * eps);
        fx.set_column(j, &column);
    }
    for j in 0..2 {
        let mut e = SVector::<f64, 2>::zeros();
        e[j] = eps;
        let column = (rk4.step(x, &(u + e)) - rk4.step(x, &(u - e))) / (2.0 * eps);
        fu.set_column(j, &column);
    }
    (fx, fu)
}

/// max |a − b| over the largest entry of b (at least 1).
fn relative<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> f64 {
    (a - b).amax() / b.amax().max(1.0)
}

/// Property: ∂f/∂x and ∂f/∂u of the Runge–Kutta step, assembled from the generated derivative
/// kernel at the four stages, equal central differences of the step to 1e-7 relative (the
/// differences' own error is ~1e-9), for random states, torques within the limits, and both
/// step lengths of the example. A wrong stage weight or a missing chain-rule factor makes an
/// error of order h, 10⁻² or more.
#[test]
fn rk4_jacobians_from_the_generated_derivatives_match_central_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x11c5_e1b0);
    for h in [0.01, 0.05] {
        let rk4 = Rk4::new(planar_elbow::Model, h).unwrap();
        let mut states = Vec::new();
        let mut controls = Vec::new();
        for _ in 0..50 {
            let x: SVector<f64, 4> = SVector::from_fn(|i, _| {
                let bound = if i < 2 { std::f64::consts::PI } else { 6.0 };
                rng.gen_range(-bound..bound)
            });
            let u: SVector<f64, 2> =
                SVector::from_fn(|_, _| rng.gen_range(-TORQUE_LIMIT..TORQUE_LIMIT));
            states.push(x);
            controls.push(u);
        }
        let linearisation = rk4.linearise(&states, &controls);
        assert_eq!(linearisation.fx.len(), 50);
        assert_eq!(
            linearisation.derivative_kernel_calls, 200,
            "4 stages per step"
        );
        for ((x, u), (fx, fu)) in states
            .iter()
            .zip(&controls)
            .zip(linearisation.fx.iter().zip(&linearisation.fu))
        {
            let (dx, du) = central_differences(&rk4, x, u);
            assert!(relative(fx, &dx) < 1e-7, "h {h}, x {x}: ∂f/∂x {fx} vs {dx}");
            assert!(relative(fu, &du) < 1e-7, "h {h}, x {x}: ∂f/∂u {fu} vs {du}");
        }
    }
}

/// Property: the thesis's angle convention (gravity along −y, q₁ from the x axis): hanging
/// q = (−π/2, 0) is the potential energy's minimum and upright (π/2, 0) its maximum, both
/// equilibria (g(q) = 0), and the upright state at rest with zero torque stays put under the
/// discrete dynamics.
#[test]
fn hanging_and_upright_are_the_potential_energys_minimum_and_maximum() {
    let hanging = [HANGING[0], HANGING[1]];
    let upright = [UPRIGHT[0], UPRIGHT[1]];
    let (low, high) = (
        planar_elbow::potential_energy(&hanging),
        planar_elbow::potential_energy(&upright),
    );
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..1000 {
        let q = [rng.gen_range(-4.0..4.0), rng.gen_range(-4.0..4.0)];
        let v = planar_elbow::potential_energy(&q);
        assert!(low <= v + 1e-12 && v <= high + 1e-12, "V({q:?}) = {v}");
    }
    assert!(high - low > 80.0, "lifting 30 kg through 0.6 m");
    for q in [hanging, upright] {
        assert!(planar_elbow::gravity_torques(&q)
            .iter()
            .all(|t| t.abs() < 1e-12));
    }
    let rk4 = Rk4::new(planar_elbow::Model, 0.05).unwrap();
    let x: SVector<f64, 4> = UPRIGHT.into();
    assert!((rk4.step(&x, &SVector::zeros()) - x).amax() < 1e-12);
}

#[test]
fn a_module_without_the_derivative_kernel_is_refused() {
    let error = Rk4::<_, 2>::new(elbow_without_derivatives::Model, 0.01).unwrap_err();
    assert!(matches!(
        error,
        Error::MissingKernel {
            robot: "planar-elbow",
            kernel: Kernel::ForwardDynamicsDerivatives
        }
    ));
    assert!(error
        .to_string()
        .contains("no `forward_dynamics_derivatives`"));
    for step in [0.0, -0.01, f64::NAN] {
        let error = Rk4::new(planar_elbow::Model, step).unwrap_err();
        assert!(matches!(error, Error::InvalidTimeStep { .. }), "{step}");
    }
}

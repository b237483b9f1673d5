//! The control and identification kernels (docs/design.md §4) of every built-in robot against the
//! independent numeric reference, over 1000 seeded states each: ∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q,
//! ∂q̈/∂q̇, M⁻¹, frame placements, Jacobians, J̇q̇, the regressor and the base regressor.
//!
//! The kernels are evaluated as the optimised straight-line programs the generator emits
//! ([`Program::eval`], operation for operation what the generated function computes: the
//! compiled modules of `control_kernels.rs` check that equality bit for bit), which lets this
//! test cover every robot without compiling a module per robot. A third truth for the
//! derivatives: central differences of the inverse and forward dynamics evaluated in
//! double-double arithmetic (≈32 digits, so the differences carry no rounding of note).

mod common;

use common::{rng, state, uniform};
use nalgebra::DMatrix;
use rne_codegen_core::{build_kernel_with, Kernel, KernelSetup, Program, Scene};
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{DoubleDouble, Real, Symbol, SymbolicDynamics};

const SAMPLES: usize = 1000;

/// The programs of one robot's kernels.
struct Kernels {
    dynamics: SymbolicDynamics,
    setup: KernelSetup,
    programs: Vec<(Kernel, Program)>,
}

impl Kernels {
    /// The programs of `kernels`, the derivatives built in lanes when `lanes` is set (as
    /// `derivatives: lanes` builds them).
    fn new(dynamics: SymbolicDynamics, kernels: &[Kernel], lanes: bool) -> Kernels {
        let setup = KernelSetup {
            derivative_lanes: lanes,
            ..KernelSetup::new(&dynamics, kernels)
        };
        let programs = kernels
            .iter()
            .map(|&k| (k, build_kernel_with(&dynamics, k, &setup).program))
            .collect();
        Kernels {
            dynamics,
            setup,
            programs,
        }
    }

    /// `kernel` at (q, v, a, u) in scalar `T`.
    fn eval<T: Real>(&self, kernel: Kernel, q: &[T], v: &[T], a: &[T], u: &[T]) -> Vec<T> {
        let program = &self.programs.iter().find(|(k, _)| *k == kernel).unwrap().1;
        let model = &self.dynamics.model;
        program.eval(|s| match s {
            Symbol::Position(k) => q[k as usize],
            Symbol::Velocity(k) => v[k as usize],
            Symbol::Acceleration(k) => a[k as usize],
            Symbol::Force(k) => u[k as usize],
            Symbol::Parameter(_) => T::from_f64(model.parameter_value(s).unwrap()),
            Symbol::Lane(_) => unreachable!("`Program::eval` gives a lane its value"),
        })
    }

    fn f64(&self, kernel: Kernel, q: &[f64], v: &[f64], a: &[f64], u: &[f64]) -> Vec<f64> {
        self.eval(kernel, q, v, a, u)
    }

    /// `base_parameters(standard)`: its program reads π_i as `Symbol::Parameter(i)`.
    fn base_parameters(&self, standard: &[f64]) -> Vec<f64> {
        let program = &self
            .programs
            .iter()
            .find(|(k, _)| *k == Kernel::BaseParameters)
            .unwrap()
            .1;
        program.eval(|s| match s {
            Symbol::Parameter(i) => standard[i as usize],
            other => panic!("base_parameters reads {other:?}"),
        })
    }
}

/// max |a − b| / max(max |b|, floor): the error relative to the largest entry of the reference.
fn scaled_error(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(floor, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// A row-major copy of a matrix.
fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// The robot's model as the generator sees it with the default scene.
fn scene_model(robot: &'static rne_models::builtin::BuiltinRobot) -> rne_symbolic::RobotModel {
    let model = RobotSource::Builtin(robot)
        .load(&LoadOptions::default())
        .unwrap();
    Scene::default().apply(&model).unwrap()
}

#[test]
fn derivative_kernels_agree_with_the_reference_on_every_builtin_robot() {
    let kernels = [
        Kernel::InverseDynamicsDerivatives,
        Kernel::ForwardDynamicsDerivatives,
        Kernel::MassMatrixInverse,
        Kernel::MassMatrix,
    ];
    for (robot, lanes) in BUILTIN_ROBOTS.iter().flat_map(|r| [(r, false), (r, true)]) {
        let model = scene_model(robot);
        let programs = Kernels::new(SymbolicDynamics::new(&model), &kernels, lanes);
        let mut reference = Reference::new(&model.to_numeric());
        let n = reference.nv();
        let mut random = rng(0x5eed_d0d0);
        let mut worst = [0.0f64; 6];
        for _ in 0..SAMPLES {
            let (q, v, a) = state(&mut random, n);
            let u = uniform(&mut random, n, 20.0);
            let id = programs.f64(Kernel::InverseDynamicsDerivatives, &q, &v, &a, &[]);
            let (dq, dv) = reference.inverse_dynamics_derivatives(&q, &v, &a).unwrap();
            worst[0] = worst[0].max(scaled_error(&id[..n * n], &rows(&dq), 1e-300));
            worst[1] = worst[1].max(scaled_error(&id[n * n..], &rows(&dv), 1e-300));

            let fd = programs.f64(Kernel::ForwardDynamicsDerivatives, &q, &v, &[], &u);
            let expected = reference.forward_dynamics_derivatives(&q, &v, &u).unwrap();
            let nn = n * n;
            worst[2] = worst[2].max(scaled_error(&fd[..nn], &rows(&expected.dqdd_dq), 1e-300));
            worst[3] = worst[3].max(scaled_error(
                &fd[nn..2 * nn],
                &rows(&expected.dqdd_dqd),
                1e-300,
            ));
            let inverse = programs.f64(Kernel::MassMatrixInverse, &q, &[], &[], &[]);
            worst[4] = worst[4].max(scaled_error(
                &inverse,
                &rows(&expected.mass_matrix_inverse),
                1e-300,
            ));
            assert_eq!(&fd[2 * nn..], &inverse[..], "the third output is M⁻¹");

            // M⁻¹ M = I.
            let m = programs.f64(Kernel::MassMatrix, &q, &[], &[], &[]);
            let m = DMatrix::from_row_slice(n, n, &m);
            let product = DMatrix::from_row_slice(n, n, &inverse) * m;
            let identity = DMatrix::<f64>::identity(n, n);
            worst[5] = worst[5].max((product - identity).amax());
        }
        let names = ["∂τ/∂q", "∂τ/∂q̇", "∂q̈/∂q", "∂q̈/∂q̇", "M⁻¹", "M⁻¹M − I"];
        let bars = [1e-12, 1e-12, 1e-12, 1e-12, 1e-12, 1e-13];
        for ((name, error), bar) in names.iter().zip(worst).zip(bars) {
            assert!(
                error <= bar,
                "{} (lanes: {lanes}): {name} error {error:e} exceeds {bar:e}",
                robot.name
            );
        }
    }
}

/// Central differences of `kernel` in double-double along each input entry of `which`
/// (0: q, 1: v), at (q, v, a, u), as an NV × NV row-major matrix of f64.
fn central_differences(
    programs: &Kernels,
    kernel: Kernel,
    which: usize,
    [q, v, a, u]: [&[f64]; 4],
) -> Vec<f64> {
    let dd =
        |x: &[f64]| -> Vec<DoubleDouble> { x.iter().map(|&x| DoubleDouble::from(x)).collect() };
    let n = v.len();
    let h = DoubleDouble::from(1e-9);
    let mut columns = Vec::new();
    for k in 0..n {
        let mut inputs = [dd(q), dd(v), dd(a), dd(u)];
        let at = |inputs: &[Vec<DoubleDouble>; 4]| {
            programs.eval(kernel, &inputs[0], &inputs[1], &inputs[2], &inputs[3])
        };
        inputs[which][k] += h;
        let plus = at(&inputs);
        inputs[which][k] -= h + h;
        let minus = at(&inputs);
        columns.push(
            plus.iter()
                .zip(&minus)
                .map(|(&p, &m)| ((p - m) / (h + h)).to_f64())
                .collect::<Vec<f64>>(),
        );
    }
    (0..n)
        .flat_map(|i| columns.iter().map(move |c| c[i]))
        .collect()
}

#[test]
fn derivative_kernels_agree_with_double_double_central_differences() {
    let kernels = [
        Kernel::InverseDynamics,
        Kernel::ForwardDynamics,
        Kernel::InverseDynamicsDerivatives,
        Kernel::ForwardDynamicsDerivatives,
    ];
    for (robot, lanes) in BUILTIN_ROBOTS.iter().flat_map(|r| [(r, false), (r, true)]) {
        let model = scene_model(robot);
        let programs = Kernels::new(SymbolicDynamics::new(&model), &kernels, lanes);
        let n = model.state_layout().nv();
        let mut random = rng(0x5eed_d0d1);
        for _ in 0..20 {
            let (q, v, a) = state(&mut random, n);
            let u = uniform(&mut random, n, 20.0);
            let id = programs.f64(Kernel::InverseDynamicsDerivatives, &q, &v, &a, &[]);
            let fd = programs.f64(Kernel::ForwardDynamicsDerivatives, &q, &v, &[], &u);
            let nn = n * n;
            let cases = [
                ("∂τ/∂q", Kernel::InverseDynamics, 0, &id[..nn]),
                ("∂τ/∂q̇", Kernel::InverseDynamics, 1, &id[nn..]),
                ("∂q̈/∂q", Kernel::ForwardDynamics, 0, &fd[..nn]),
                ("∂q̈/∂q̇", Kernel::ForwardDynamics, 1, &fd[nn..2 * nn]),
            ];
            for (name, kernel, which, generated) in cases {
                let expected = central_differences(&programs, kernel, which, [&q, &v, &a, &u]);
                let error = scaled_error(generated, &expected, 1e-300);
                assert!(
                    error <= 1e-8,
                    "{} (lanes: {lanes}): {name} differs from double-double central \
                     differences by {error:e}",
                    robot.name
                );
            }
        }
    }
}

#[test]
fn kinematics_kernels_agree_with_the_reference_on_every_builtin_robot() {
    let kernels = [
        Kernel::FramePlacements,
        Kernel::FrameJacobians,
        Kernel::FrameJacobianDotQd,
    ];
    for robot in BUILTIN_ROBOTS {
        let model = scene_model(robot);
        let programs = Kernels::new(SymbolicDynamics::new(&model), &kernels, false);
        let mut reference = Reference::new(&model.to_numeric());
        let n = reference.nv();
        // The generator's frames (every link of the file) by name in the reference's links.
        let frames: Vec<usize> = programs
            .setup
            .frames
            .iter()
            .map(|&f| {
                let name = &programs.dynamics.frames()[f].name;
                reference
                    .link_names()
                    .iter()
                    .position(|l| l == name)
                    .unwrap_or_else(|| panic!("{}: frame {name} in the reference", robot.name))
            })
            .collect();
        let mut random = rng(0x5eed_d0d2);
        let mut worst = [0.0f64; 3];
        for _ in 0..SAMPLES {
            let (q, v, _) = state(&mut random, n);
            let placements = programs.f64(Kernel::FramePlacements, &q, &[], &[], &[]);
            let jacobians = programs.f64(Kernel::FrameJacobians, &q, &[], &[], &[]);
            let jdot_qd = programs.f64(Kernel::FrameJacobianDotQd, &q, &v, &[], &[]);
            let expected_placements = reference.frame_placements(&q).unwrap();
            let expected_jacobians = reference.frame_jacobians(&q).unwrap();
            let expected_jdot = reference.frame_jacobian_dot_qd(&q, &v).unwrap();
            for (i, &f) in frames.iter().enumerate() {
                let (rotation, origin) = &expected_placements[f];
                let mut expected: Vec<f64> =
                    rows(&DMatrix::from_column_slice(3, 3, rotation.as_slice()));
                expected.extend(origin.iter());
                worst[0] = worst[0].max(scaled_error(
                    &placements[12 * i..12 * (i + 1)],
                    &expected,
                    1.0,
                ));
                let j = &jacobians[6 * n * i..6 * n * (i + 1)];
                worst[1] = worst[1].max(scaled_error(j, &rows(&expected_jacobians[f]), 1.0));
                let jd = &jdot_qd[6 * i..6 * (i + 1)];
                worst[2] = worst[2].max(scaled_error(jd, expected_jdot[f].as_slice(), 1.0));
            }
        }
        for (name, error) in ["placements", "Jacobians", "J̇q̇"].iter().zip(worst) {
            assert!(error <= 1e-12, "{}: {name} error {error:e}", robot.name);
        }
    }
}

#[test]
fn regressor_kernels_agree_with_the_reference_and_reproduce_the_torques() {
    let kernels = [
        Kernel::InverseDynamics,
        Kernel::Regressor,
        Kernel::BaseRegressor,
        Kernel::BaseParameters,
    ];
    for robot in BUILTIN_ROBOTS {
        let model = scene_model(robot);
        let dynamics = SymbolicDynamics::new(&model);
        let names = dynamics.parameter_names();
        let programs = Kernels::new(dynamics, &kernels, false);
        let mut reference = Reference::new(&model.to_numeric());
        assert_eq!(
            names,
            reference.parameter_names(),
            "{}: columns",
            robot.name
        );
        let standard = reference.standard_parameters();
        let base = programs.base_parameters(&standard);
        let np = standard.len();
        let nb = base.len();
        assert_eq!(nb, programs.setup.base_parameters.as_ref().unwrap().len());
        let n = reference.nv();
        let mut random = rng(0x5eed_d0d3);
        let (mut worst_y, mut worst_tau, mut worst_base) = (0.0f64, 0.0f64, 0.0f64);
        for _ in 0..SAMPLES {
            let (q, v, a) = state(&mut random, n);
            let y = programs.f64(Kernel::Regressor, &q, &v, &a, &[]);
            let expected = rows(&reference.regressor(&q, &v, &a).unwrap());
            worst_y = worst_y.max(scaled_error(&y, &expected, 1.0));
            let tau = programs.f64(Kernel::InverseDynamics, &q, &v, &a, &[]);
            let product = |m: &[f64], x: &[f64], columns: usize| -> Vec<f64> {
                m.chunks(columns)
                    .map(|row| row.iter().zip(x).map(|(y, p)| y * p).sum())
                    .collect()
            };
            worst_tau = worst_tau.max(scaled_error(&product(&y, &standard, np), &tau, 1.0));
            let yb = programs.f64(Kernel::BaseRegressor, &q, &v, &a, &[]);
            worst_base = worst_base.max(scaled_error(&product(&yb, &base, nb), &tau, 1.0));
        }
        assert!(worst_y <= 1e-12, "{}: Y error {worst_y:e}", robot.name);
        assert!(worst_tau <= 1e-12, "{}: Y π − τ {worst_tau:e}", robot.name);
        assert!(
            worst_base <= 1e-11,
            "{}: Y_b π_b − τ {worst_base:e}",
            robot.name
        );
    }
}

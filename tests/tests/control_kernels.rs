//! Compiled modules with the control and identification kernels (docs/design.md §4): the emitted
//! functions compute bit for bit what their programs do (so `derivatives_vs_reference.rs`,
//! which evaluates the programs, speaks for the generated code), the `Kinematics` and
//! `Identification` handles, a floating base (tangent-space derivatives), and friction with
//! armature and a mimic coupling (`friction: include`) against the independent reference.

mod common;

use common::{rng, uniform};
use nalgebra::DMatrix;
use rne_codegen::{Dynamics, Identification, Kinematics};
use rne_codegen_core::{build_kernel_with, GenerationOptions, Kernel, KernelSetup, Program, Scene};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

rne_codegen::derive_dynamics! {
    /// UR5 with every control and identification kernel, two frames.
    mod ur5 {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, inverse_dynamics_derivatives, forward_dynamics_derivatives,
                  mass_matrix_inverse, frame_placements, frame_jacobians, frame_jacobian_dot_qd,
                  regressor, base_regressor],
        frames: [ee_link, "wrist_1_link"],
    }
}

rne_codegen::derive_dynamics! {
    /// UR5's derivatives built in lanes.
    mod ur5_lanes {
        robot: "fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives],
        derivatives: lanes,
    }
}

rne_codegen::derive_dynamics! {
    /// The floating hopper's derivatives built in lanes.
    mod hopper_lanes {
        robot: "fixtures/robots/hopper-floating.toml",
        outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives],
        derivatives: lanes,
    }
}

rne_codegen::derive_dynamics! {
    /// The floating hopper's derivatives and kinematics.
    mod hopper {
        robot: "fixtures/robots/hopper-floating.toml",
        outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, frame_jacobians,
                  frame_jacobian_dot_qd],
    }
}

rne_codegen::derive_dynamics! {
    /// The geared arm with its friction in the dynamics.
    mod geared {
        robot: "fixtures/robots/geared-arm.toml",
        outputs: [inverse_dynamics, forward_dynamics, friction_torques,
                  inverse_dynamics_derivatives, regressor, base_regressor],
        friction: include,
    }
}

fn fixture(name: &str) -> RobotModel {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/robots")
        .join(name);
    let model =
        read_robot(Description::file(&path), &LoadOptions::default()).expect("the fixture loads");
    Scene::default().apply(&model).unwrap()
}

/// ‖a − b‖∞ / max(‖b‖∞, 1): these kernels' entries are of order one or larger.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    common::rel_err_floor(a, b, 1.0)
}

fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

fn flat<const R: usize, const C: usize>(m: &[[f64; C]; R]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

/// `kernel`'s program for `model` with the frames given, evaluated in f64.
fn program(model: &RobotModel, kernel: Kernel, frames: &[&str]) -> Program {
    program_with(model, kernel, frames, false)
}

/// [`program`], the derivatives built in lanes when `lanes` is set (`derivatives: lanes`).
fn program_with(model: &RobotModel, kernel: Kernel, frames: &[&str], lanes: bool) -> Program {
    let dynamics = SymbolicDynamics::new(model);
    let options = GenerationOptions {
        frames: Some(frames.iter().map(|f| (*f).to_owned()).collect()),
        ..GenerationOptions::default()
    };
    let setup = KernelSetup {
        frames: options.frame_indices(dynamics.frames()).unwrap(),
        derivative_lanes: lanes,
        ..KernelSetup::new(&dynamics, &[kernel])
    };
    build_kernel_with(&dynamics, kernel, &setup).program
}

/// `program` at (q, v, a), `a` standing for the accelerations or, in forward dynamics'
/// derivatives, the torques.
fn eval(program: &Program, q: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
    program.eval(|s| match s {
        Symbol::Position(k) => q[k as usize],
        Symbol::Velocity(k) => v[k as usize],
        Symbol::Acceleration(k) | Symbol::Force(k) => a[k as usize],
        other => panic!("unexpected input {other:?}"),
    })
}

/// UR5's forward-dynamics derivatives are large enough to be compiled for AVX and AVX2 too
/// (`rne-codegen/core/src/dispatch.rs`): on a processor with both the function runs that copy,
/// which must give the program's bits as the baseline copy does.
#[test]
fn emitted_control_kernels_compute_exactly_their_programs() {
    let model = fixture("ur5.urdf");
    let frames = ["ee_link", "wrist_1_link"];
    let dq = program(&model, Kernel::InverseDynamicsDerivatives, &frames);
    let dfd = program(&model, Kernel::ForwardDynamicsDerivatives, &frames);
    assert!(
        dfd.instrs.len() >= rne_codegen_core::DISPATCH_FROM,
        "∂FD is compiled for AVX2 too"
    );
    let jacobians = program(&model, Kernel::FrameJacobians, &frames);
    let jdot = program(&model, Kernel::FrameJacobianDotQd, &frames);
    let regressor = program(&model, Kernel::Regressor, &frames);
    let mut random = rng(0x5eed_c0de);
    for _ in 0..200 {
        let q: [f64; 6] = uniform(&mut random, 6, 3.0).try_into().unwrap();
        let v: [f64; 6] = uniform(&mut random, 6, 2.0).try_into().unwrap();
        let a: [f64; 6] = uniform(&mut random, 6, 5.0).try_into().unwrap();
        let bits = |x: Vec<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
        let (dtau_dq, dtau_dv) = ur5::inverse_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dtau_dq), flat(&dtau_dv)].concat();
        assert_eq!(bits(emitted), bits(eval(&dq, &q, &v, &a)), "∂τ");
        let (dqdd_dq, dqdd_dv, minv) = ur5::forward_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dqdd_dq), flat(&dqdd_dv), flat(&minv)].concat();
        assert_eq!(bits(emitted), bits(eval(&dfd, &q, &v, &a)), "∂q̈");
        let j: Vec<f64> = ur5::frame_jacobians(&q).iter().flat_map(flat).collect();
        assert_eq!(bits(j), bits(eval(&jacobians, &q, &v, &a)), "J");
        let jd: Vec<f64> = ur5::frame_jacobian_dot_qd(&q, &v)
            .iter()
            .flat_map(|r| *r)
            .collect();
        assert_eq!(bits(jd), bits(eval(&jdot, &q, &v, &a)), "J̇q̇");
        let y = flat(&ur5::regressor(&q, &v, &a));
        assert_eq!(bits(y), bits(eval(&regressor, &q, &v, &a)), "Y");
    }
}

/// With `derivatives: lanes`, the emitted derivatives compute four directions per vector
/// instruction and still give their programs' bits — programs that do compute with lanes,
/// and fewer instructions than the scalar sweeps' — also on a free-flyer, whose tangent
/// directions seed the base position and quaternion together.
#[test]
fn derivatives_in_lanes_compute_exactly_their_programs() {
    let model = fixture("ur5.urdf");
    let dq = program_with(&model, Kernel::InverseDynamicsDerivatives, &[], true);
    let dfd = program_with(&model, Kernel::ForwardDynamicsDerivatives, &[], true);
    for (lanes, kernel) in [
        (&dq, Kernel::InverseDynamicsDerivatives),
        (&dfd, Kernel::ForwardDynamicsDerivatives),
    ] {
        let scalar = program(&model, kernel, &[]);
        assert!(lanes.has_lanes(), "{kernel} computes with lanes");
        assert!(
            lanes.instrs.len() < scalar.instrs.len(),
            "{kernel}: {} instructions in lanes, {} without",
            lanes.instrs.len(),
            scalar.instrs.len()
        );
    }
    let hopper = fixture("hopper-floating.toml");
    let floating_dq = program_with(&hopper, Kernel::InverseDynamicsDerivatives, &[], true);
    let floating_dfd = program_with(&hopper, Kernel::ForwardDynamicsDerivatives, &[], true);
    assert!(floating_dq.has_lanes() && floating_dfd.has_lanes());
    let mut random = rng(0x5eed_1a7e);
    for _ in 0..200 {
        let q: [f64; 6] = uniform(&mut random, 6, 3.0).try_into().unwrap();
        let v: [f64; 6] = uniform(&mut random, 6, 2.0).try_into().unwrap();
        let a: [f64; 6] = uniform(&mut random, 6, 5.0).try_into().unwrap();
        let bits = |x: Vec<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
        let (dtau_dq, dtau_dv) = ur5_lanes::inverse_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dtau_dq), flat(&dtau_dv)].concat();
        assert_eq!(bits(emitted), bits(eval(&dq, &q, &v, &a)), "∂τ");
        let (dqdd_dq, dqdd_dv, minv) = ur5_lanes::forward_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dqdd_dq), flat(&dqdd_dv), flat(&minv)].concat();
        assert_eq!(bits(emitted), bits(eval(&dfd, &q, &v, &a)), "∂q̈");
        let mut q: [f64; 9] = uniform(&mut random, 9, 1.0).try_into().unwrap();
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let v: [f64; 8] = uniform(&mut random, 8, 2.0).try_into().unwrap();
        let a: [f64; 8] = uniform(&mut random, 8, 3.0).try_into().unwrap();
        let (dtau_dq, dtau_dv) = hopper_lanes::inverse_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dtau_dq), flat(&dtau_dv)].concat();
        assert_eq!(
            bits(emitted),
            bits(eval(&floating_dq, &q, &v, &a)),
            "floating ∂τ"
        );
        let (dqdd_dq, dqdd_dv, minv) = hopper_lanes::forward_dynamics_derivatives(&q, &v, &a);
        let emitted = [flat(&dqdd_dq), flat(&dqdd_dv), flat(&minv)].concat();
        assert_eq!(
            bits(emitted),
            bits(eval(&floating_dfd, &q, &v, &a)),
            "floating ∂q̈"
        );
    }
}

/// The origin of frame `f`, for any robot whose module has frame placements.
fn frame_origin<const NQ: usize, const NV: usize, const NF: usize, K>(
    robot: &K,
    q: &[f64; NQ],
    f: usize,
) -> [f64; 3]
where
    K: Kinematics<NQ, NV, NF> + Dynamics<NQ, NV, Scalar = f64>,
{
    robot.frame_placements(q).expect("generated")[f].1
}

#[test]
fn kinematics_and_identification_handles_carry_the_module() {
    assert_eq!(ur5::FRAMES, ["ee_link", "wrist_1_link"]);
    assert_eq!(<ur5::Model as Kinematics<6, 6, 2>>::FRAMES, ur5::FRAMES);
    assert_eq!(ur5::NP, 60);
    assert_eq!(ur5::PARAMETERS[0], "shoulder_link.m");
    assert_eq!(ur5::PARAMETERS[9], "shoulder_link.Izz");
    const { assert!(ur5::NB < ur5::NP) };
    assert_eq!(
        <ur5::Model as Identification<6, 6, 60, { ur5::NB }>>::BASE_PARAMETERS,
        ur5::BASE_PARAMETERS
    );
    let q = [0.1, -0.7, 1.2, 0.3, -0.4, 0.9];
    let placements = ur5::frame_placements(&q);
    assert_eq!(frame_origin(&ur5::Model, &q, 0), placements[0].1);
    assert!(
        ur5::Model.has(Kernel::BaseParameters),
        "added with the base regressor"
    );
    assert!(!ur5::Model.has(Kernel::FrictionTorques));
    assert_eq!(ur5::Model.friction_torques(&q), None);
    let model = fixture("ur5.urdf");
    let mut reference = Reference::new(&model.to_numeric());
    let standard: [f64; 60] = reference.standard_parameters().try_into().unwrap();
    let base = ur5::base_parameters(&standard);
    let tau = ur5::inverse_dynamics(&q, &[0.3; 6], &[-0.2; 6]);
    let yb = ur5::base_regressor(&q, &[0.3; 6], &[-0.2; 6]);
    let from_base: Vec<f64> = yb
        .iter()
        .map(|row| row.iter().zip(&base).map(|(y, p)| y * p).sum())
        .collect();
    assert!(relative(&from_base, &tau) < 1e-12, "Y_b π_b = τ");
    let expected = reference
        .inverse_dynamics(&q, &[0.3; 6], &[-0.2; 6])
        .unwrap();
    assert!(relative(&tau, expected.as_slice()) < 1e-12);
}

#[test]
fn floating_base_derivatives_and_jacobians_agree_with_the_reference() {
    let model = fixture("hopper-floating.toml");
    let mut reference = Reference::new(&model.to_numeric());
    let mut random = rng(0x5eed_f10b);
    for _ in 0..200 {
        let mut q: [f64; 9] = uniform(&mut random, 9, 1.0).try_into().unwrap();
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let v: [f64; 8] = uniform(&mut random, 8, 2.0).try_into().unwrap();
        let a: [f64; 8] = uniform(&mut random, 8, 3.0).try_into().unwrap();
        let u: [f64; 8] = uniform(&mut random, 8, 10.0).try_into().unwrap();
        let (edq, edv) = reference.inverse_dynamics_derivatives(&q, &v, &a).unwrap();
        let expected = reference.forward_dynamics_derivatives(&q, &v, &u).unwrap();
        let scalar = (
            hopper::inverse_dynamics_derivatives(&q, &v, &a),
            hopper::forward_dynamics_derivatives(&q, &v, &u),
        );
        let lanes = (
            hopper_lanes::inverse_dynamics_derivatives(&q, &v, &a),
            hopper_lanes::forward_dynamics_derivatives(&q, &v, &u),
        );
        for ((dq, dv), (fq, fv, _)) in [scalar, lanes] {
            assert!(relative(&flat(&dq), &rows(&edq)) < 1e-12, "∂τ/∂q");
            assert!(relative(&flat(&dv), &rows(&edv)) < 1e-12, "∂τ/∂v");
            assert!(
                relative(&flat(&fq), &rows(&expected.dqdd_dq)) < 1e-11,
                "∂q̈/∂q"
            );
            assert!(
                relative(&flat(&fv), &rows(&expected.dqdd_dqd)) < 1e-11,
                "∂q̈/∂v"
            );
        }
        let minv = scalar.1 .2;
        assert!(
            relative(&flat(&minv), &rows(&expected.mass_matrix_inverse)) < 1e-11,
            "M⁻¹"
        );
        let jacobians = hopper::frame_jacobians(&q);
        let expected = reference.frame_jacobians(&q).unwrap();
        let jdot = hopper::frame_jacobian_dot_qd(&q, &v);
        let expected_jdot = reference.frame_jacobian_dot_qd(&q, &v).unwrap();
        for (f, name) in hopper::FRAMES.iter().enumerate() {
            let r = reference
                .link_names()
                .iter()
                .position(|l| l == name)
                .unwrap();
            assert!(
                relative(&flat(&jacobians[f]), &rows(&expected[r])) < 1e-12,
                "J {name}"
            );
            assert!(
                relative(&jdot[f], expected_jdot[r].as_slice()) < 1e-12,
                "J̇q̇ {name}"
            );
        }
    }
}

#[test]
fn included_friction_and_armature_agree_with_the_reference_and_the_regressor() {
    let model = fixture("geared-arm.toml");
    assert_eq!(geared::JOINTS, ["q1", "q2", "q4"], "the wrist follows q2");
    let mut reference = Reference::new(&model.to_numeric()).with_friction(true);
    assert_eq!(geared::PARAMETERS.to_vec(), reference.parameter_names());
    assert!(geared::PARAMETERS.contains(&"wrist.fc"));
    assert!(geared::PARAMETERS.contains(&"slide.Ia"));
    let standard = reference.standard_parameters();
    let mut random = rng(0x5eed_9ea2);
    for k in 0..1000 {
        let q: [f64; 3] = uniform(&mut random, 3, 3.0).try_into().unwrap();
        let mut v: [f64; 3] = uniform(&mut random, 3, 2.0).try_into().unwrap();
        if k % 10 == 0 {
            v[k % 3] = 0.0; // sign(0) = 0: no Coulomb friction at rest
        }
        let a: [f64; 3] = uniform(&mut random, 3, 3.0).try_into().unwrap();
        let tau = geared::inverse_dynamics(&q, &v, &a);
        let expected = reference.inverse_dynamics(&q, &v, &a).unwrap();
        assert!(
            relative(&tau, expected.as_slice()) < 1e-12,
            "τ with friction"
        );
        let friction = geared::friction_torques(&v);
        let expected_friction = reference.friction_torques(&v).unwrap();
        assert!(
            relative(&friction, expected_friction.as_slice()) < 1e-14,
            "τ_f"
        );
        let back = geared::forward_dynamics(&q, &v, &tau);
        assert!(relative(&back, &a) < 1e-10, "FD(ID(q̈)) = q̈ with friction");
        let y = geared::regressor(&q, &v, &a);
        let y_pi: Vec<f64> = y
            .iter()
            .map(|row| row.iter().zip(&standard).map(|(y, p)| y * p).sum())
            .collect();
        assert!(
            relative(&y_pi, &tau) < 1e-12,
            "Y π = τ with friction and armature"
        );
        let (_, dv) = geared::inverse_dynamics_derivatives(&q, &v, &a);
        let (_, expected_dv) = reference.inverse_dynamics_derivatives(&q, &v, &a).unwrap();
        assert!(
            relative(&flat(&dv), &rows(&expected_dv)) < 1e-12,
            "∂τ/∂q̇ with f_v"
        );
    }
}

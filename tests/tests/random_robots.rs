//! Random robots (1–8 joints, mixed revolute / prismatic, random DH geometry and physically
//! valid inertias, written as TOML specs): the symbolic dynamics, evaluated from the
//! expression graph, agree with the independent numeric reference, and satisfy the
//! structural properties of (3.1).

mod common;

use std::fmt::Write;

use common::{mat_vec, rel_err, rel_err_floor, rows};
use proptest::prelude::*;
use rne_codegen::Kernel;
use rne_interpreted::{Interpreted, StateRef};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};

/// One random link: DH geometry, joint kind, mass, COM and principal moments with a rotation.
#[derive(Clone, Debug)]
struct RandomLink {
    prismatic: bool,
    a: f64,
    alpha: f64,
    d: f64,
    theta: f64,
    mass: f64,
    com: [f64; 3],
    /// Principal moments, made to satisfy the triangle inequality.
    moments: [f64; 3],
    /// Roll-pitch-yaw of the principal axes.
    axes: [f64; 3],
}

fn link() -> impl Strategy<Value = RandomLink> {
    (
        prop::bool::weighted(0.3),
        (-0.5..0.5f64, -3.2..3.2f64, -0.5..0.5f64, -3.2..3.2f64),
        0.1..20.0f64,
        prop::array::uniform3(-0.3..0.3f64),
        prop::array::uniform3(0.01..1.0f64),
        prop::array::uniform3(-3.2..3.2f64),
    )
        .prop_map(|(prismatic, (a, alpha, d, theta), mass, com, raw, axes)| {
            // Moments (x + y, y + z, z + x) of positive x, y, z obey the triangle inequality.
            let moments =
                [raw[0] + raw[1], raw[1] + raw[2], raw[2] + raw[0]].map(|m| m * mass * 0.01);
            RandomLink {
                prismatic,
                a,
                alpha,
                d,
                theta,
                mass,
                com,
                moments,
                axes,
            }
        })
}

fn rotation(rpy: [f64; 3]) -> [[f64; 3]; 3] {
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// The spec text of a random serial robot in standard DH.
fn spec(links: &[RandomLink], gravity: [f64; 3]) -> String {
    let mut text = format!(
        "name = \"random\"\ngravity = [{}, {}, {}]\n",
        gravity[0], gravity[1], gravity[2]
    );
    for (i, l) in links.iter().enumerate() {
        let r = rotation(l.axes);
        let inertia = |a: usize, b: usize| {
            (0..3)
                .map(|k| r[a][k] * l.moments[k] * r[b][k])
                .sum::<f64>()
        };
        let joint = if l.prismatic { "prismatic" } else { "revolute" };
        writeln!(text, "\n[[link]]\nname = \"link{i}\"\njoint = \"{joint}\"").unwrap();
        writeln!(
            text,
            "dh = {{ a = {}, alpha = {}, d = {}, theta = {} }}",
            l.a, l.alpha, l.d, l.theta
        )
        .unwrap();
        writeln!(
            text,
            "mass = {}\ncom = [{}, {}, {}]",
            l.mass, l.com[0], l.com[1], l.com[2]
        )
        .unwrap();
        writeln!(
            text,
            "inertia = {{ xx = {}, yy = {}, zz = {}, xy = {}, xz = {}, yz = {} }}",
            inertia(0, 0),
            inertia(1, 1),
            inertia(2, 2),
            inertia(0, 1),
            inertia(0, 2),
            inertia(1, 2)
        )
        .unwrap();
    }
    text
}

fn robot() -> impl Strategy<Value = (Vec<RandomLink>, [f64; 3])> {
    (
        prop::collection::vec(link(), 1..=8),
        prop::array::uniform3(-10.0..10.0f64),
    )
}

fn state(n: usize) -> impl Strategy<Value = (Vec<f64>, Vec<f64>, Vec<f64>)> {
    (
        prop::collection::vec(-3.2..3.2f64, n),
        prop::collection::vec(-5.0..5.0f64, n),
        prop::collection::vec(-5.0..5.0f64, n),
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn symbolic_and_numeric_dynamics_agree_on_random_robots(
        (links, gravity) in robot(),
        states in prop::collection::vec(state(8), 4),
    ) {
        let text = spec(&links, gravity);
        let model = read_robot(Description::toml(&text, "random.toml"), &LoadOptions::default())
            .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let n = model.dof();
        let symbolic = Interpreted::new(&model);
        let mut reference = Reference::new(&model.to_numeric());
        let mut weightless = model.to_numeric();
        weightless.gravity = [0.0; 3];
        let mut weightless = Reference::new(&weightless);
        for (q, qd, qdd) in states {
            let (q, qd, qdd) = (&q[..n], &qd[..n], &qdd[..n]);
            // A torque that vanishes by symmetry is rounding noise in either implementation,
            // so errors are relative to at least the robot's own torque scale here: the
            // largest entry of M (torque per unit acceleration) or of g.
            let m_ref: Vec<f64> = reference.mass_matrix(q).unwrap().transpose().data.into();
            let g_ref: Vec<f64> = reference.gravity_torques(q).unwrap().data.into();
            let floor = m_ref.iter().chain(&g_ref).fold(0.0f64, |m, x| m.max(x.abs()));
            let err = |a: &[f64], b: &[f64]| rel_err_floor(a, b, floor);
            let tau = symbolic.evaluate(Kernel::InverseDynamics, StateRef { q, qd, qdd, tau: &[] }).unwrap();
            let tau_ref: Vec<f64> = reference.inverse_dynamics(q, qd, qdd).unwrap().data.into();
            prop_assert!(err(&tau, &tau_ref) < 1e-12, "tau {:?} vs {:?}", tau, tau_ref);
            let m = rows(symbolic.evaluate(Kernel::MassMatrix, StateRef { q, qd: &[], qdd: &[], tau: &[] }).unwrap(), n);
            prop_assert!(err(&m.concat(), &m_ref) < 1e-12, "M");
            let g = symbolic.evaluate(Kernel::GravityTorques, StateRef { q, qd: &[], qdd: &[], tau: &[] }).unwrap();
            prop_assert!(err(&g, &g_ref) < 1e-12, "g");
            let c = rows(symbolic.evaluate(Kernel::CoriolisMatrix, StateRef { q, qd, qdd: &[], tau: &[] }).unwrap(), n);
            let c_qd = mat_vec(&c, qd);
            let c_qd_ref: Vec<f64> = weightless.bias_torques(q, qd).unwrap().data.into();
            prop_assert!(err(&c_qd, &c_qd_ref) < 1e-12, "C qd");

            // τ = M q̈ + C q̇ + g.
            let rebuilt: Vec<f64> = mat_vec(&m, qdd).iter().zip(&c_qd).zip(&g).map(|((a, b), c)| a + b + c).collect();
            prop_assert!(err(&rebuilt, &tau) < 1e-12, "tau = M qdd + C qd + g");
            // M symmetric positive definite (Cholesky succeeds).
            for (i, row) in m.iter().enumerate() {
                for (j, &entry) in row.iter().enumerate() {
                    prop_assert_eq!(entry, m[j][i]);
                }
            }
            prop_assert!(nalgebra::DMatrix::from_row_slice(n, n, &m.concat()).cholesky().is_some(), "M not SPD");
            // Ṁ = C + Cᵀ (Ṁ − 2C skew), with Ṁ by a central difference of the reference CRBA.
            let h = 1e-6;
            let shifted = |s: f64| -> Vec<f64> { q.iter().zip(qd).map(|(q, v)| q + s * v).collect() };
            let mdot = (reference.mass_matrix(&shifted(h)).unwrap() - reference.mass_matrix(&shifted(-h)).unwrap())
                / (2.0 * h);
            let scale = mdot.amax().max(1.0);
            for i in 0..n {
                for j in 0..n {
                    prop_assert!((mdot[(i, j)] - c[i][j] - c[j][i]).abs() < 1e-6 * scale, "Mdot - 2C not skew");
                }
            }
            // Forward dynamics inverts inverse dynamics, to the accuracy the data allow: the
            // rounding in τ and in the bias (relative 1e-16 of their size) moves q̈ by up to
            // that size over the smallest eigenvalue of M.
            let back = symbolic.evaluate(Kernel::ForwardDynamics, StateRef { q, qd, qdd: &[], tau: &tau }).unwrap();
            let bias = symbolic.evaluate(Kernel::BiasTorques, StateRef { q, qd, qdd: &[], tau: &[] }).unwrap();
            let lambda_min = nalgebra::DMatrix::from_row_slice(n, n, &m.concat()).symmetric_eigenvalues().min();
            let size = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let bound = 1e-12 * (size(qdd) + (size(&tau) + size(&bias)) / lambda_min);
            let error = back.iter().zip(qdd).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            prop_assert!(error <= bound, "fd(id(qdd)) != qdd: error {error:e} > {bound:e}");
        }
    }
}

/// Regression: the LᵀDL factorisation walked each row from the first column, so with three
/// joints (a dense 3 × 3 M, no zeros to hide it) it read already-scaled entries of L and
/// forward dynamics was wrong.
#[test]
fn forward_dynamics_of_three_coaxial_joints_with_a_dense_mass_matrix() {
    let link = |name: &str| {
        format!(
            "[[link]]\nname = \"{name}\"\njoint = \"revolute\"\ndh = {{ a = 0.1 }}\nmass = 0.1\n\
             inertia = {{ xx = 2e-5, yy = 2e-5, zz = 2e-5 }}\n"
        )
    };
    let text = format!(
        "name = \"coaxial\"\ngravity = [0, 0, 0]\n{}{}{}",
        link("a"),
        link("b"),
        link("c")
    );
    let model = read_robot(
        Description::toml(&text, "coaxial.toml"),
        &LoadOptions::default(),
    )
    .unwrap();
    let symbolic = Interpreted::new(&model);
    let mut reference = Reference::new(&model.to_numeric());
    let (q, qd, tau) = ([0.1, 0.2, 0.3], [1.0, 2.0, 3.0], [2e-5, 1e-5, 3e-5]);
    let expected: Vec<f64> = reference
        .forward_dynamics(&q, &qd, &tau)
        .unwrap()
        .data
        .into();
    assert!(
        rel_err(
            &symbolic
                .evaluate(
                    Kernel::ForwardDynamics,
                    StateRef {
                        q: &q,
                        qd: &qd,
                        qdd: &[],
                        tau: &tau
                    }
                )
                .unwrap(),
            &expected
        ) < 1e-13
    );
}

proptest! {
    // Eight robots a run: each generates and compiles all 18 kernels of up to 8 joints.
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// The JIT computes every kernel of a random robot (all 18, fma off) with the bits of its
    /// program (the one `derive_dynamics!` emits) evaluated operation by operation, at random
    /// states.
    #[test]
    fn the_jit_is_the_programs_bit_for_bit_on_random_robots(
        (links, gravity) in robot(),
        states in prop::collection::vec(state(8), 3),
    ) {
        let text = spec(&links, gravity);
        let model = read_robot(Description::toml(&text, "random.toml"), &LoadOptions::default())
            .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let n = model.dof();
        let options = rne_codegen_core::GenerationOptions {
            outputs: Kernel::ALL.to_vec(),
            ..rne_codegen_core::GenerationOptions::default()
        };
        let scene = rne_codegen::Scene::default();
        let jit = rne_jit::JitModel::compile(&model, &scene, &options, "random.toml")
            .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        for (q, qd, qdd) in &states {
            let tau: Vec<f64> = qdd.iter().map(|x| 3.0 * x).collect();
            let state = rne_jit::State { q: &q[..n], qd: &qd[..n], qdd: &qdd[..n], tau: &tau[..n] };
            let input = |symbol: rne_symbolic::Symbol| match symbol {
                rne_symbolic::Symbol::Position(k) => q[k as usize],
                rne_symbolic::Symbol::Velocity(k) => qd[k as usize],
                rne_symbolic::Symbol::Acceleration(k) => qdd[k as usize],
                rne_symbolic::Symbol::Force(k) => tau[k as usize],
                _ => f64::NAN,
            };
            for kp in &jit.programs().kernels {
                let kernel = kp.kernel;
                if kernel == Kernel::BaseParameters {
                    continue;
                }
                let got = jit.evaluate_vec(kernel, state).unwrap();
                let expected = kp.program.eval_f64(&input);
                let same = got.len() == expected.len()
                    && got.iter().zip(&expected).all(|(a, b)| a.to_bits() == b.to_bits());
                prop_assert!(same, "{kernel}: {got:?} != {expected:?}\n{text}");
            }
        }
    }
}

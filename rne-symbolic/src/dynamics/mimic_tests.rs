//! Mimic joints and armature: the constrained model is the free one seen through the chain
//! rule (M ← Jᵀ M J, τ ← Jᵀ τ), and armature adds I_a to M's diagonal and I_a q̈ to τ.

use super::SymbolicDynamics;
use crate::expr::{Id, Symbol};
use crate::model::{Mimic, RobotModel};
use crate::spec::{parse_str, LoadOptions};

/// A gripper: a revolute wrist, a prismatic finger, and a second finger (a revolute joint)
/// whose coordinate follows the first finger's: `q_f2 = −2 q_f1 + 0.3` when constrained.
pub(super) fn gripper(constrained: bool) -> RobotModel {
    let text = r#"
name = "gripper"
[[link]]
name = "wrist"
q = "w"
joint = "revolute"
origin = { xyz = [0, 0, 0.1], rpy = [0.3, 0, 0] }
axis = [0, 0.6, 0.8]
mass = 1.2
com = [0.01, 0.02, 0.05]
inertia = { xx = 0.01, yy = 0.012, zz = 0.008, xy = 0.001 }
[[link]]
name = "finger1"
parent = "wrist"
q = "f1"
joint = "prismatic"
origin = { xyz = [0.05, 0, 0.1] }
axis = [1, 0, 0]
mass = 0.2
com = [0, 0, 0.03]
inertia = { xx = 0.001, yy = 0.001, zz = 0.0005 }
[[link]]
name = "finger2"
parent = "wrist"
q = "f2"
joint = "revolute"
origin = { xyz = [-0.05, 0, 0.1] }
axis = [0, 1, 0]
mass = 0.3
com = [0, 0, 0.04]
inertia = { xx = 0.002, yy = 0.002, zz = 0.0007 }
"#;
    let mut model = parse_str(text, "gripper.toml", &LoadOptions::default()).expect("valid spec");
    let g = &mut model.graph;
    model.links[2].mimic = Some(Mimic {
        leader: "f1".into(),
        multiplier: g.constant(-2.0),
        offset: g.constant(0.3),
    });
    if constrained {
        model.constrain_mimic_joints().expect("no loop");
    }
    model
}

fn eval(d: &SymbolicDynamics, ids: &[Id], q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    d.model.graph.eval::<f64>(ids, |sym| match sym {
        Symbol::Position(k) => q[k as usize],
        Symbol::Velocity(k) => qd[k as usize],
        Symbol::Acceleration(k) => qdd[k as usize],
        _ => f64::NAN,
    })
}

#[test]
fn a_constrained_follower_enters_through_the_chain_rule() {
    let mut free = SymbolicDynamics::new(&gripper(false));
    let mut constrained = SymbolicDynamics::new(&gripper(true));
    assert_eq!(constrained.dof(), 2);
    let (tau_f, m_f, g_f) = (
        free.inverse_dynamics(),
        free.mass_matrix().concat(),
        free.gravity_torques(),
    );
    let (tau_c, m_c, g_c) = (
        constrained.inverse_dynamics(),
        constrained.mass_matrix().concat(),
        constrained.gravity_torques(),
    );
    // J maps (w, f1) to (w, f1, f2): f2 = −2 f1 + 0.3.
    let j = [[1.0, 0.0], [0.0, 1.0], [0.0, -2.0]];
    for k in 0..30 {
        let f = |a: f64| ((k as f64 + 1.0) * a).fract() * 2.0 - 1.0;
        let (q, qd, qdd) = (
            [2.0 * f(0.37), 0.05 * f(0.71)],
            [3.0 * f(0.13), 0.5 * f(0.29)],
            [4.0 * f(0.47), 2.0 * f(0.83)],
        );
        let lift = |x: [f64; 2], offset: f64| [x[0], x[1], -2.0 * x[1] + offset];
        let (qf, qdf, qddf) = (lift(q, 0.3), lift(qd, 0.0), lift(qdd, 0.0));
        let t_free = eval(&free, &tau_f, &qf, &qdf, &qddf);
        let m_free = eval(&free, &m_f, &qf, &qdf, &qddf);
        let g_free = eval(&free, &g_f, &qf, &qdf, &qddf);
        let t_con = eval(&constrained, &tau_c, &q, &qd, &qdd);
        let m_con = eval(&constrained, &m_c, &q, &qd, &qdd);
        let g_con = eval(&constrained, &g_c, &q, &qd, &qdd);
        for a in 0..2 {
            let jt = |x: &[f64]| (0..3).map(|i| j[i][a] * x[i]).sum::<f64>();
            assert!(
                (t_con[a] - jt(&t_free)).abs() < 1e-12,
                "τ[{a}] at state {k}"
            );
            assert!(
                (g_con[a] - jt(&g_free)).abs() < 1e-12,
                "g[{a}] at state {k}"
            );
            for b in 0..2 {
                let jmj: f64 = (0..3)
                    .flat_map(|i| (0..3).map(move |l| (i, l)))
                    .map(|(i, l)| j[i][a] * m_free[i * 3 + l] * j[l][b])
                    .sum();
                assert!((m_con[a * 2 + b] - jmj).abs() < 1e-12, "M[{a}][{b}]");
            }
        }
    }
}

#[test]
fn locking_a_leader_fixes_its_followers_too() {
    let mut model = gripper(true);
    model.lock_joint("f1", 0.02).expect("f1 is a variable");
    assert_eq!(model.joint_names(), ["w"]);
    assert!(!model.has_couplings(), "the follower is fixed, not coupled");
    let mut locked = SymbolicDynamics::new(&model);
    let mut full = SymbolicDynamics::new(&gripper(true));
    let (a, b) = (locked.mass_matrix(), full.mass_matrix());
    let m_locked = eval(&locked, &[a[0][0]], &[0.4], &[0.0], &[0.0])[0];
    let m_full = eval(&full, &[b[0][0]], &[0.4, 0.02], &[0.0; 2], &[0.0; 2])[0];
    assert!((m_locked - m_full).abs() < 1e-15);
}

#[test]
fn armature_adds_to_the_diagonal_and_to_the_torque() {
    let plain = gripper(true);
    let mut geared = plain.clone();
    geared.links[2].armature = Some(geared.graph.constant(0.05));
    let (mut d0, mut d1) = (
        SymbolicDynamics::new(&plain),
        SymbolicDynamics::new(&geared),
    );
    let (m0, m1) = (d0.mass_matrix().concat(), d1.mass_matrix().concat());
    let (t0, t1) = (d0.inverse_dynamics(), d1.inverse_dynamics());
    let (k0, k1) = (d0.kinetic_energy(), d1.kinetic_energy());
    let (q, qd, qdd) = ([0.3, 0.01], [0.7, -0.2], [1.1, 0.4]);
    let (a, b) = (eval(&d0, &m0, &q, &qd, &qdd), eval(&d1, &m1, &q, &qd, &qdd));
    // The follower's rotor turns at −2 q̇_f1: I_a m² = 0.05 · 4 on the leader's diagonal.
    for i in 0..4 {
        let expected = if i == 3 { a[i] + 0.2 } else { a[i] };
        assert!((b[i] - expected).abs() < 1e-15, "M entry {i}");
    }
    let (x, y) = (eval(&d0, &t0, &q, &qd, &qdd), eval(&d1, &t1, &q, &qd, &qdd));
    assert!((y[0] - x[0]).abs() < 1e-15);
    assert!((y[1] - x[1] - 0.2 * qdd[1]).abs() < 1e-14);
    let (e0, e1) = (
        eval(&d0, &[k0], &q, &qd, &qdd)[0],
        eval(&d1, &[k1], &q, &qd, &qdd)[0],
    );
    assert!((e1 - e0 - 0.5 * 0.2 * qd[1] * qd[1]).abs() < 1e-15);
}

/// Y π reproduces inverse dynamics with mimic joints and armature (the standard parameters
/// taken from the model's own links).
#[test]
fn the_regressor_times_the_standard_parameters_is_the_torque() {
    let mut model = gripper(true);
    model.links[1].armature = Some(model.graph.constant(0.07));
    model.links[2].armature = Some(model.graph.constant(0.05));
    let mut d = SymbolicDynamics::new(&model);
    let tau = d.inverse_dynamics();
    let y = d.regressor();
    let pi = d.standard_parameters();
    assert_eq!(pi.len(), 3 * 10 + 2);
    let flat: Vec<Id> = y.concat();
    for k in 0..20 {
        let f = |a: f64| ((k as f64 + 1.0) * a).fract() * 2.0 - 1.0;
        let (q, qd, qdd) = (
            [2.0 * f(0.37), 0.05 * f(0.71)],
            [3.0 * f(0.13), 0.5 * f(0.29)],
            [4.0 * f(0.47), 2.0 * f(0.83)],
        );
        let t = eval(&d, &tau, &q, &qd, &qdd);
        let yy = eval(&d, &flat, &q, &qd, &qdd);
        let p = eval(&d, &pi, &q, &qd, &qdd);
        for i in 0..2 {
            let y_pi: f64 = (0..pi.len()).map(|c| yy[i * pi.len() + c] * p[c]).sum();
            assert!(
                (y_pi - t[i]).abs() < 1e-12 * t[i].abs().max(1.0),
                "row {i}: {y_pi} vs {}",
                t[i]
            );
        }
    }
}

/// The base parameters of the planar elbow: six (ZZ₁ + m₂ l₁², m₁ c₁ₓ + m₂ l₁, m₁ c₁ᵧ, ZZ₂,
/// m₂ c₂ₓ, m₂ c₂ᵧ for a planar 2R arm with gravity in its plane), the base regressor has full
/// column rank, and Y_b π_b = τ at states the search never saw.
#[test]
fn the_planar_elbows_base_parameters_reproduce_the_torque() {
    use super::base_parameters::BaseParameters;
    let mut d = SymbolicDynamics::new(&super::tests::planar_elbow());
    let tau = d.inverse_dynamics();
    let y = d.regressor();
    let pi = d.standard_parameters();
    let base = BaseParameters::find(&d.model, &y, 40);
    assert_eq!(base.len(), 6, "kept: {:?}", base.independent);
    // Kept: ZZ₁ (column 9), MX₁, MY₁ (1, 2) of link 1; MX₂, MY₂, ZZ₂ (11, 12, 19).
    assert_eq!(base.independent, [1, 2, 9, 11, 12, 19]);
    // m₂ regroups onto MX₁ with l₁ and onto ZZ₁ with l₁², the f64 nearest to the exact
    // coefficients (K refined in double-double), not values a few ulps off.
    let mut coefficients: Vec<f64> = base.k.concat().into_iter().filter(|&k| k != 0.0).collect();
    coefficients.sort_by(f64::total_cmp);
    assert_eq!(coefficients, [0.09, 0.3]);
    let values = |ids: &[Id], q: [f64; 2], qd: [f64; 2], qdd: [f64; 2]| {
        d.model.graph.eval::<f64>(ids, |s| match s {
            Symbol::Position(k) => q[k as usize],
            Symbol::Velocity(k) => qd[k as usize],
            Symbol::Acceleration(k) => qdd[k as usize],
            Symbol::Parameter(_) => d.model.parameter_value(s).unwrap_or(f64::NAN),
            Symbol::Force(_) | Symbol::Lane(_) => f64::NAN,
        })
    };
    let pi_values = values(&pi, [0.0; 2], [0.0; 2], [0.0; 2]);
    let pi_b = base.of(&pi_values);
    let kept: Vec<Id> = y
        .iter()
        .flat_map(|row| base.independent.iter().map(move |&c| row[c]))
        .collect();
    for k in 0..10 {
        let x = 0.37 * k as f64;
        let (q, qd, qdd) = ([x.sin(), 2.0 * x.cos()], [1.0 - x, x], [0.5 * x, -x]);
        let t = values(&tau, q, qd, qdd);
        let yb = values(&kept, q, qd, qdd);
        for i in 0..2 {
            let predicted: f64 = (0..6).map(|b| yb[i * 6 + b] * pi_b[b]).sum();
            assert!(
                (predicted - t[i]).abs() < 1e-10 * t[i].abs().max(1.0),
                "τ{i}"
            );
        }
    }
}

/// The articulated-body algorithm gives the same accelerations as M + LᵀDL on a branched,
/// mixed revolute/prismatic model, and declines mimic couplings.
#[test]
fn articulated_body_forward_dynamics_equals_the_factorised_one() {
    let mut d = SymbolicDynamics::new(&gripper(false));
    let factorised = d.forward_dynamics();
    let articulated = d
        .forward_dynamics_articulated()
        .expect("fixed base, no couplings");
    for k in 0..20 {
        let f = |a: f64| ((k as f64 + 1.0) * a).fract() * 2.0 - 1.0;
        let q = [2.0 * f(0.37), 0.05 * f(0.71), f(0.19)];
        let qd = [3.0 * f(0.13), 0.5 * f(0.29), 2.0 * f(0.61)];
        let u = [f(0.47), 2.0 * f(0.83), 0.3 * f(0.53)];
        let values = |ids: &[Id]| {
            d.model.graph.eval::<f64>(ids, |s| match s {
                Symbol::Position(k) => q[k as usize],
                Symbol::Velocity(k) => qd[k as usize],
                Symbol::Force(k) => u[k as usize],
                _ => f64::NAN,
            })
        };
        let (a, b) = (values(&factorised), values(&articulated));
        for i in 0..3 {
            assert!(
                (a[i] - b[i]).abs() < 1e-11 * a[i].abs().max(1.0),
                "q̈{i}: {a:?} {b:?}"
            );
        }
    }
    let mut coupled = SymbolicDynamics::new(&gripper(true));
    assert!(coupled.forward_dynamics_articulated().is_none());
}

/// On a 24-joint chain with skewed axes the articulated-body algorithm needs fewer
/// multiplications than M + LᵀDL (linear against cubic growth).
#[test]
fn articulated_body_forward_dynamics_is_cheaper_on_long_chains() {
    let mut text = String::from("name = \"snake\"\n");
    for k in 0..24 {
        let parent = if k == 0 {
            String::new()
        } else {
            format!("parent = \"l{}\"\n", k - 1)
        };
        let axis = ["[0.6, 0, 0.8]", "[0, 1, 0]", "[0.36, 0.48, 0.8]"][k % 3];
        text.push_str(&format!(
            "[[link]]\nname = \"l{k}\"\n{parent}joint = \"revolute\"\n\
             origin = {{ xyz = [0.1, 0.02, 0.05], rpy = [0.1, 0.2, 0.3] }}\naxis = {axis}\n\
             mass = 1\ncom = [0.05, 0.01, 0.02]\n\
             inertia = {{ xx = 0.01, yy = 0.012, zz = 0.009, xy = 0.001 }}\n"
        ));
    }
    let model = parse_str(&text, "snake.toml", &LoadOptions::default()).expect("valid spec");
    let mut d = SymbolicDynamics::new(&model);
    let factorised = d.forward_dynamics();
    let articulated = d.forward_dynamics_articulated().expect("a chain");
    let (ldlt, aba) = (
        d.model.graph.op_count(&factorised),
        d.model.graph.op_count(&articulated),
    );
    println!("24 joints: ABA {aba:?}, M + LTDL {ldlt:?}");
    assert!(
        aba.mul < ldlt.mul,
        "ABA {} multiplications, M + LᵀDL {}",
        aba.mul,
        ldlt.mul
    );
}

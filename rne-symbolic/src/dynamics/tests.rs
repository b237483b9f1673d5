//! The recursion and the extraction checked on the planar elbow built by hand (independent
//! of the spec reader) against the thesis's closed forms (4.45)–(4.47).

use super::SymbolicDynamics;
use crate::expr::{ExprGraph, Id, Symbol, SymbolTable};
use crate::model::{JointKind, JointVariable, Link, Parameter, RobotModel};

const NAMES: [&str; 9] = ["m1", "m2", "l1", "l2", "lc1", "lc2", "I1", "I2", "g"];

/// Table 6.1: m = 15, l = 0.3, lc = l/2, I = m (l² + w²)/12 with w = sqrt(m / (ρ l)).
fn table_6_1() -> [f64; 9] {
    let (m, l) = (15.0, 0.3);
    let w2 = m / (7850.0 * l);
    let inertia = m * (l * l + w2) / 12.0;
    [m, m, l, l, l / 2.0, l / 2.0, inertia, inertia, 9.81]
}

/// The planar elbow of chapter 4 with every parameter a symbol.
pub(super) fn planar_elbow() -> RobotModel {
    let mut graph = ExprGraph::new(SymbolTable::with_joints(["q1", "q2"]));
    let p: Vec<Id> = NAMES
        .iter()
        .map(|name| {
            let s = graph.symbols_mut().push_parameter(*name);
            graph.symbol(s)
        })
        .collect();
    let (z, o) = (graph.zero(), graph.one());
    let identity = graph.identity();
    let axis = [z, z, o];
    let inertia = |g: &mut ExprGraph, izz: Id| {
        let z = g.zero();
        [[z, z, z], [z, z, z], [z, z, izz]]
    };
    let link1 = Link {
        name: "link1".into(),
        parent: None,
        kind: JointKind::Revolute,
        joint: Some(0),
        rotation: identity,
        translation: [z, z, z],
        axis,
        mass: p[0],
        com: [p[4], z, z],
        inertia: inertia(&mut graph, p[6]),
        mimic: None,
        coupling: None,
        friction: None,
        armature: None,
    };
    let link2 = Link {
        name: "link2".into(),
        parent: Some(0),
        kind: JointKind::Revolute,
        joint: Some(1),
        rotation: identity,
        translation: [p[2], z, z],
        axis,
        mass: p[1],
        com: [p[5], z, z],
        inertia: inertia(&mut graph, p[7]),
        mimic: None,
        coupling: None,
        friction: None,
        armature: None,
    };
    let minus_g = graph.neg(p[8]);
    let values = table_6_1();
    RobotModel {
        name: "planar-elbow".into(),
        graph,
        parameters: NAMES
            .iter()
            .zip(values)
            .map(|(n, v)| Parameter {
                name: n.to_string(),
                value: v,
            })
            .collect(),
        gravity: [z, minus_g, z],
        links: vec![link1, link2],
        joints: vec![
            JointVariable {
                name: "q1".into(),
                link: 0,
            },
            JointVariable {
                name: "q2".into(),
                link: 1,
            },
        ],
        base: crate::model::Base::Fixed,
        warnings: Vec::new(),
    }
}

struct State {
    q: [f64; 2],
    qd: [f64; 2],
    qdd: [f64; 2],
    u: [f64; 2],
}

fn states() -> impl Iterator<Item = State> {
    // A fixed low-discrepancy sequence: deterministic, spread over the state space.
    (1..200).map(|k| {
        let f = |a: f64| ((k as f64) * a).fract() * 2.0 - 1.0;
        State {
            q: [3.0 * f(0.754877666), 3.0 * f(0.569840291)],
            qd: [5.0 * f(0.430159709), 5.0 * f(0.3247179572)],
            qdd: [4.0 * f(0.1378), 4.0 * f(0.8611)],
            u: [30.0 * f(0.2718), 30.0 * f(0.3141)],
        }
    })
}

fn eval(d: &SymbolicDynamics, ids: &[Id], s: &State) -> Vec<f64> {
    d.model.graph.eval::<f64>(ids, |sym| match sym {
        Symbol::Position(k) => s.q[k as usize],
        Symbol::Velocity(k) => s.qd[k as usize],
        Symbol::Acceleration(k) => s.qdd[k as usize],
        Symbol::Force(k) => s.u[k as usize],
        Symbol::Parameter(_) => d.model.parameter_value(sym).unwrap_or(f64::NAN),
        Symbol::Lane(_) => f64::NAN,
    })
}

/// (4.45), (4.46) and (4.47) with table 6.1's values.
fn closed_form(s: &State) -> ([[f64; 2]; 2], [f64; 2], [f64; 2]) {
    let [m1, m2, l1, _, lc1, lc2, i1, i2, g] = table_6_1();
    let (c1, c2, s2) = (s.q[0].cos(), s.q[1].cos(), s.q[1].sin());
    let c12 = (s.q[0] + s.q[1]).cos();
    let h = m2 * l1 * lc2 * s2;
    let m12 = m2 * l1 * lc2 * c2 + m2 * lc2 * lc2 + i2;
    let m = [
        [
            2.0 * m2 * l1 * lc2 * c2 + m2 * lc2 * lc2 + m2 * l1 * l1 + m1 * lc1 * lc1 + i1 + i2,
            m12,
        ],
        [m12, i2 + m2 * lc2 * lc2],
    ];
    let [qd1, qd2] = s.qd;
    let c_qd = [-2.0 * h * qd2 * qd1 - h * qd2 * qd2, h * qd1 * qd1];
    let gravity = [
        m2 * l1 * g * c1 + m1 * lc1 * g * c1 + m2 * lc2 * g * c12,
        m2 * lc2 * g * c12,
    ];
    (m, c_qd, gravity)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

#[test]
fn planar_elbow_matches_the_closed_forms_4_45_to_4_47() {
    let mut d = SymbolicDynamics::new(&planar_elbow());
    let tau = d.inverse_dynamics();
    let m: Vec<Id> = d.mass_matrix().concat();
    let g = d.gravity_torques();
    let bias = d.bias_torques();
    for s in states() {
        let (m_ref, c_qd_ref, g_ref) = closed_form(&s);
        let m_val = eval(&d, &m, &s);
        let g_val = eval(&d, &g, &s);
        let bias_val = eval(&d, &bias, &s);
        let tau_val = eval(&d, &tau, &s);
        for i in 0..2 {
            for j in 0..2 {
                assert!(close(m_val[2 * i + j], m_ref[i][j]), "M[{i}][{j}]");
            }
            assert!(close(g_val[i], g_ref[i]), "g[{i}]");
            assert!(close(bias_val[i], c_qd_ref[i] + g_ref[i]), "bias[{i}]");
            let expected = m_ref[i][0] * s.qdd[0] + m_ref[i][1] * s.qdd[1] + c_qd_ref[i] + g_ref[i];
            assert!(close(tau_val[i], expected), "tau[{i}]");
        }
    }
}

#[test]
fn christoffel_matrix_reproduces_the_bias_and_makes_mdot_minus_2c_skew() {
    let mut d = SymbolicDynamics::new(&planar_elbow());
    let c: Vec<Id> = d.coriolis_matrix().concat();
    let mdot: Vec<Id> = d.mass_matrix_derivative().concat();
    for s in states() {
        let (_, c_qd_ref, _) = closed_form(&s);
        let c_val = eval(&d, &c, &s);
        let mdot_val = eval(&d, &mdot, &s);
        for i in 0..2 {
            let c_qd = c_val[2 * i] * s.qd[0] + c_val[2 * i + 1] * s.qd[1];
            assert!(close(c_qd, c_qd_ref[i]), "(C qd)[{i}]");
            for j in 0..2 {
                let n_ij = mdot_val[2 * i + j] - 2.0 * c_val[2 * i + j];
                let n_ji = mdot_val[2 * j + i] - 2.0 * c_val[2 * j + i];
                assert!(
                    (n_ij + n_ji).abs() < 1e-12,
                    "Mdot - 2C not skew at ({i},{j})"
                );
            }
        }
    }
}

#[test]
fn forward_dynamics_inverts_inverse_dynamics() {
    let mut d = SymbolicDynamics::new(&planar_elbow());
    let tau = d.inverse_dynamics();
    let fd = d.forward_dynamics();
    for s in states() {
        let u = eval(&d, &tau, &s);
        let solved = State {
            u: [u[0], u[1]],
            ..s
        };
        let qdd = eval(&d, &fd, &solved);
        for i in 0..2 {
            assert!(
                close(qdd[i], s.qdd[i]),
                "qdd[{i}]: {} vs {}",
                qdd[i],
                s.qdd[i]
            );
        }
    }
}

#[test]
fn energies_match_the_mass_matrix_and_the_gravity_torques() {
    let mut d = SymbolicDynamics::new(&planar_elbow());
    let t = d.kinetic_energy();
    let v = d.potential_energy();
    let m: Vec<Id> = d.mass_matrix().concat();
    let g = d.gravity_torques();
    let dv: Vec<Id> = (0..2)
        .map(|k| d.model.graph.derivative(v, Symbol::Position(k)))
        .collect();
    for s in states() {
        let tv = eval(&d, &[t], &s)[0];
        let m_val = eval(&d, &m, &s);
        let quadratic: f64 = (0..2)
            .map(|i| {
                (0..2)
                    .map(|j| s.qd[i] * m_val[2 * i + j] * s.qd[j])
                    .sum::<f64>()
            })
            .sum();
        assert!(close(tv, 0.5 * quadratic), "T = 1/2 qd' M qd");
        let dv_val = eval(&d, &dv, &s);
        let g_val = eval(&d, &g, &s);
        for i in 0..2 {
            assert!(close(dv_val[i], g_val[i]), "dV/dq = g");
        }
    }
}

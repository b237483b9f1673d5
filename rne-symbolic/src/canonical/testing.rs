//! Thesis-sized expressions for the tests: the Newton–Euler recursion of the thesis's
//! chapter 3 written out directly on an [`ExprGraph`], for the planar elbow manipulator
//! (chapter 4, Appendix B) and the first three joints of the IRB 140 (chapter 5, Appendix B).

use crate::expr::{ExprGraph, Id, Mat3, Symbol, SymbolTable, Vec3};

/// One link of a serial chain, in the thesis's convention: frame i has the orientation of
/// link i and the origin of frame i−1, and every vector is expressed in frame i.
pub(super) struct ChainLink {
    /// R_i^{i−1}(q_i).
    pub rotation: Mat3,
    /// b_i, the joint axis.
    pub axis: Vec3,
    /// r_{i−1,i}, to the next joint.
    pub to_joint: Vec3,
    /// r_{i−1,ci}, to the centre of mass.
    pub to_com: Vec3,
    /// m_i.
    pub mass: Id,
    /// I_i about the centre of mass.
    pub inertia: Mat3,
}

/// The joint torques u_i = b_iᵀ τ_i of a chain of revolute joints, by (3.27)–(3.38) with
/// the errata of docs/design.md §7.
pub(super) fn newton_euler(g: &mut ExprGraph, links: &[ChainLink], gravity: Vec3) -> Vec<Id> {
    let n = links.len();
    let (mut omega, mut alpha, mut a_e, mut g_i) =
        (g.zero_vec(), g.zero_vec(), g.zero_vec(), gravity);
    let mut state = Vec::with_capacity(n);
    for (i, link) in links.iter().enumerate() {
        let qd = g.symbol(Symbol::Velocity(i as u16));
        let qdd = g.symbol(Symbol::Acceleration(i as u16));
        let b_qd = g.vscale(qd, link.axis);
        let b_qdd = g.vscale(qdd, link.axis);
        let w = g.mat_t_vec(&link.rotation, omega);
        omega = g.vadd(w, b_qd);
        let a = g.mat_t_vec(&link.rotation, alpha);
        let a = g.vadd(a, b_qdd);
        let coriolis = g.cross(omega, b_qd);
        alpha = g.vadd(a, coriolis);
        let a_prev = g.mat_t_vec(&link.rotation, a_e);
        let point = |g: &mut ExprGraph, r: Vec3| {
            let tangential = g.cross(alpha, r);
            let wr = g.cross(omega, r);
            let centripetal = g.cross(omega, wr);
            let sum = g.vadd(a_prev, tangential);
            g.vadd(sum, centripetal)
        };
        let a_c = point(g, link.to_com);
        a_e = point(g, link.to_joint);
        g_i = g.mat_t_vec(&link.rotation, g_i);
        state.push((omega, alpha, a_c, g_i));
    }
    let (mut f_next, mut tau_next) = (g.zero_vec(), g.zero_vec());
    let mut torques = vec![g.zero(); n];
    for i in (0..n).rev() {
        let link = &links[i];
        let (omega, alpha, a_c, g_i) = state[i];
        let (rf, rt) = match links.get(i + 1) {
            Some(next) => (
                g.mat_vec(&next.rotation, f_next),
                g.mat_vec(&next.rotation, tau_next),
            ),
            None => (g.zero_vec(), g.zero_vec()),
        };
        let inertial = g.vsub(a_c, g_i);
        let inertial = g.vscale(link.mass, inertial);
        let f = g.vadd(rf, inertial);
        let r_com_from_joint = g.vsub(link.to_com, link.to_joint);
        let t1 = g.cross(f, link.to_com);
        let t2 = g.cross(rf, r_com_from_joint);
        let i_alpha = g.mat_vec(&link.inertia, alpha);
        let i_omega = g.mat_vec(&link.inertia, omega);
        let gyro = g.cross(omega, i_omega);
        let tau = g.vsub(rt, t1);
        let tau = g.vadd(tau, t2);
        let tau = g.vadd(tau, i_alpha);
        let tau = g.vadd(tau, gyro);
        torques[i] = g.dot(link.axis, tau);
        (f_next, tau_next) = (f, tau);
    }
    torques
}

/// A graph with these joints and parameters.
pub(super) fn graph(joints: &[&str], parameters: &[&str]) -> ExprGraph {
    let mut symbols = SymbolTable::with_joints(joints.iter().copied());
    for p in parameters {
        symbols.push_parameter(*p);
    }
    ExprGraph::new(symbols)
}

/// The parameter named `name` as a node.
pub(super) fn parameter(g: &mut ExprGraph, name: &str) -> Id {
    let symbol = g.symbols().parameter(name).expect("declared parameter");
    g.symbol(symbol)
}

/// R_z(angle).
pub(super) fn rot_z(g: &mut ExprGraph, angle: Id) -> Mat3 {
    let (c, s) = (g.cos(angle), g.sin(angle));
    let (z, o, ns) = (g.zero(), g.one(), g.neg(s));
    [[c, ns, z], [s, c, z], [z, z, o]]
}

/// A constant matrix.
pub(super) fn constant(g: &mut ExprGraph, m: [[f64; 3]; 3]) -> Mat3 {
    m.map(|row| row.map(|x| g.constant(x)))
}

/// diag(a, b, c).
pub(super) fn diagonal(g: &mut ExprGraph, d: [Id; 3]) -> Mat3 {
    let z = g.zero();
    [[d[0], z, z], [z, d[1], z], [z, z, d[2]]]
}

/// Parameters of the planar elbow, in the order the thesis introduces them.
pub(super) const ELBOW_PARAMETERS: [&str; 8] = ["m1", "m2", "l1", "lc1", "lc2", "I1", "I2", "g"];

/// The planar elbow manipulator of chapter 4 with symbolic parameters: (τ1, τ2).
pub(super) fn planar_elbow(g: &mut ExprGraph) -> Vec<Id> {
    let p = |g: &mut ExprGraph, name: &str| parameter(g, name);
    let z = g.zero();
    let axis = g.const_vec([0.0, 0.0, 1.0]);
    let (l1, lc1, lc2) = (p(g, "l1"), p(g, "lc1"), p(g, "lc2"));
    let mut links = Vec::new();
    for (k, to_joint, to_com, mass, inertia) in [(0, l1, lc1, "m1", "I1"), (1, z, lc2, "m2", "I2")]
    {
        let q = g.symbol(Symbol::Position(k));
        let rotation = rot_z(g, q);
        let (mass, izz) = (p(g, mass), p(g, inertia));
        let inertia = diagonal(g, [z, z, izz]);
        links.push(ChainLink {
            rotation,
            axis,
            to_joint: [to_joint, z, z],
            to_com: [to_com, z, z],
            mass,
            inertia,
        });
    }
    let gravity = p(g, "g");
    let down = g.neg(gravity);
    newton_euler(g, &links, [z, down, z])
}

/// Parameters of the IRB 140's first three links, as in the thesis's Maple code.
pub(super) const IRB140_PARAMETERS: [&str; 21] = [
    "m1", "m2", "m3", "l1x", "l1y", "l2", "l3", "lc1x", "lc1y", "lc2", "lc3", "I1xx", "I1yy",
    "I1zz", "I2xx", "I2yy", "I2zz", "I3xx", "I3yy", "I3zz", "g",
];

/// The first three joints of the IRB 140 (chapter 5, Appendix B) with symbolic parameters:
/// R_1^0 = R_z(q1) R_x(π/2) R_z(π/2), R_2^1 = R_z(q2 − π/2), R_3^2 = R_z(q3).
pub(super) fn irb140(g: &mut ExprGraph) -> Vec<Id> {
    let p = |g: &mut ExprGraph, name: &str| parameter(g, name);
    let z = g.zero();
    let q: Vec<Id> = (0..3).map(|k| g.symbol(Symbol::Position(k))).collect();
    let rz1 = rot_z(g, q[0]);
    let rx = constant(g, [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]);
    let rz = constant(g, [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    let r1 = g.mat_mul(&rz1, &rx);
    let r1 = g.mat_mul(&r1, &rz);
    let half_pi = g.constant(std::f64::consts::FRAC_PI_2);
    let q2 = g.sub(q[1], half_pi);
    let r2 = rot_z(g, q2);
    let r3 = rot_z(g, q[2]);
    let (x, zaxis) = (g.const_vec([1.0, 0.0, 0.0]), g.const_vec([0.0, 0.0, 1.0]));
    let (l1x, l1y, l2, l3) = (p(g, "l1x"), p(g, "l1y"), p(g, "l2"), p(g, "l3"));
    let (lc1x, lc1y, lc2, lc3) = (p(g, "lc1x"), p(g, "lc1y"), p(g, "lc2"), p(g, "lc3"));
    let (nl1y, nlc1y) = (g.neg(l1y), g.neg(lc1y));
    let frames = [
        (r1, x, [l1x, nl1y, z], [lc1x, nlc1y, z], "1"),
        (r2, zaxis, [z, l2, z], [z, lc2, z], "2"),
        (r3, zaxis, [l3, z, z], [lc3, z, z], "3"),
    ];
    let mut links = Vec::new();
    for (rotation, axis, to_joint, to_com, k) in frames {
        let mass = p(g, &format!("m{k}"));
        let d = ["xx", "yy", "zz"].map(|a| p(g, &format!("I{k}{a}")));
        let inertia = diagonal(g, d);
        links.push(ChainLink {
            rotation,
            axis,
            to_joint,
            to_com,
            mass,
            inertia,
        });
    }
    let gravity = p(g, "g");
    let down = g.neg(gravity);
    newton_euler(g, &links, [z, z, down])
}

/// (4.42) for τ1, and M21 q̈1 + M22 q̈2 + C21 q̇1 + g2 from (4.45)–(4.47) for τ2.
pub(super) const THESIS_TAU: [&str; 2] = [
    "(+ (* (+ (* 2 m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) (* m2 l1 l1) (* m1 lc1 lc1) I1 I2) DDq1)
        (* (+ (* m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) I2) DDq2)
        (- (* 2 m2 l1 lc2 (sin q2) Dq1 Dq2))
        (- (* m2 l1 lc2 (sin q2) Dq2 Dq2))
        (* m2 l1 g (cos q1)) (* m1 lc1 g (cos q1)) (* m2 lc2 g (cos (+ q1 q2))))",
    "(+ (* (+ (* m2 lc2 lc2) I2 (* m2 l1 lc2 (cos q2))) DDq1) (* (+ I2 (* m2 lc2 lc2)) DDq2)
        (* m2 l1 lc2 (sin q2) Dq1 Dq1) (* m2 lc2 g (cos (+ q1 q2))))",
];

/// (4.45) as printed in the thesis, row by row.
pub(super) const THESIS_M: [[&str; 2]; 2] = [
    [
        "(+ (* 2 m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) (* m2 l1 l1) (* m1 lc1 lc1) I1 I2)",
        "(+ (* m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) I2)",
    ],
    [
        "(+ (* m2 lc2 lc2) I2 (* m2 l1 lc2 (cos q2)))",
        "(+ I2 (* m2 lc2 lc2))",
    ],
];

/// M = Σ m_i J_ciᵀ J_ci + I, with the centres of mass at (lc1 c1, lc1 s1) and
/// (l1 c1 + lc2 c12, l1 s1 + lc2 s12): (4.45) written with the angle sums unexpanded.
const JACOBIAN_M: [[&str; 2]; 2] = [
    [
        "(+ (* m1 lc1 lc1) I1 I2
            (* m2 (+ (* (+ (* l1 (cos q1)) (* lc2 (cos (+ q1 q2)))) (+ (* l1 (cos q1)) (* lc2 (cos (+ q1 q2)))))
                     (* (+ (* l1 (sin q1)) (* lc2 (sin (+ q1 q2)))) (+ (* l1 (sin q1)) (* lc2 (sin (+ q1 q2))))))))",
        "(+ I2 (* m2 lc2 (+ (* (cos (+ q1 q2)) (+ (* l1 (cos q1)) (* lc2 (cos (+ q1 q2)))))
                             (* (sin (+ q1 q2)) (+ (* l1 (sin q1)) (* lc2 (sin (+ q1 q2))))))))",
    ],
    [
        "(+ I2 (* m2 lc2 (+ (* (sin (+ q1 q2)) (+ (* l1 (sin q1)) (* lc2 (sin (+ q1 q2)))))
                             (* (cos (+ q1 q2)) (+ (* l1 (cos q1)) (* lc2 (cos (+ q1 q2))))))))",
        "(+ I2 (* m2 lc2 lc2 (+ (* (cos (+ q1 q2)) (cos (+ q1 q2))) (* (sin (+ q1 q2)) (sin (+ q1 q2))))))",
    ],
];

/// M11, M22, M23, M33 of the IRB 140 as printed in Appendix B, (25), and g2, g3 of (27),
/// transcribed with the thesis's `ll_y` read as `l1y` and `ll_xx` as `I1xx`.
const APPENDIX_B_M: [(usize, usize, &str); 4] = [
    (
        0,
        0,
        "(+ (* 0.5 (- I3yy I3xx) (cos (+ (* 2 q3) (* 2 q2)))) (* 0.5 I2xx) (* m2 l1y l1y) (* 0.5 m2 lc2 lc2)
            (* 0.5 m3 l2 l2) (* 0.5 m3 lc3 lc3) (* 0.5 I2yy) (* 0.5 I2yy (cos (* 2 q2))) I1xx
            (* 2 m3 lc3 (cos (+ q3 q2)) l1y) (- (* m3 lc3 l2 (sin (+ q3 (* 2 q2))))) (- (* 0.5 I2xx (cos (* 2 q2))))
            (* lc3 m3 (sin q3) l2) (* m1 lc1y lc1y) (* 0.5 I3xx) (- (* 0.5 m3 l2 l2 (cos (* 2 q2)))) (* m3 l1y l1y)
            (- (* 2 (sin q2) lc2 m2 l1y)) (- (* 2 (sin q2) m3 l1y l2)) (* 0.5 I3yy)
            (* 0.5 m3 lc3 lc3 (cos (+ (* 2 q3) (* 2 q2)))) (- (* 0.5 m2 lc2 lc2 (cos (* 2 q2)))))",
    ),
    (1, 1, "(+ (* m3 l2 l2) I3zz (* m2 lc2 lc2) (* 2 lc3 m3 (sin q3) l2) (* m3 lc3 lc3) I2zz)"),
    (1, 2, "(+ (* lc3 m3 (sin q3) l2) (* m3 lc3 lc3) I3zz)"),
    (2, 2, "(+ (* m3 lc3 lc3) I3zz)"),
];

/// g2 and g3 of Appendix B, (27); g1 = 0.
const APPENDIX_B_G: [&str; 3] = [
    "0",
    "(+ (* lc3 m3 (cos (+ q3 q2)) g) (- (* m3 g (sin q2) l2)) (- (* lc2 m2 (sin q2) g)))",
    "(* lc3 m3 (cos (+ q3 q2)) g)",
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::{Atom, Monomial, Polynomial};

    fn parse(g: &mut ExprGraph, text: &str) -> Polynomial {
        let id = g.parse_sexpr(text).unwrap();
        Polynomial::from_expr(g, id).unwrap()
    }

    /// M_ij: the coefficient of q̈_j in τ_i.
    fn mass_matrix_entry(tau: &[Polynomial], i: usize, j: usize) -> Polynomial {
        let key = Monomial::atom(Atom::Symbol(Symbol::Acceleration(j as u16)));
        tau[i].coefficient(&key, Atom::is_joint_rate)
    }

    fn elbow() -> (ExprGraph, Vec<Polynomial>) {
        let mut g = graph(&["q1", "q2"], &ELBOW_PARAMETERS);
        let tau = planar_elbow(&mut g);
        let tau = Polynomial::from_exprs(&g, &tau).unwrap();
        (g, tau)
    }

    fn irb() -> (ExprGraph, Vec<Polynomial>) {
        let mut g = graph(&["q1", "q2", "q3"], &IRB140_PARAMETERS);
        let tau = irb140(&mut g);
        let tau = Polynomial::from_exprs(&g, &tau).unwrap();
        (g, tau)
    }

    #[test]
    fn planar_elbow_torques_equal_the_thesis() {
        let (mut g, tau) = elbow();
        for (i, thesis) in THESIS_TAU.iter().enumerate() {
            assert_eq!(tau[i], parse(&mut g, thesis), "tau{}", i + 1);
        }
    }

    #[test]
    fn mass_matrix_written_two_ways_is_one_polynomial() {
        let (mut g, tau) = elbow();
        for i in 0..2 {
            for j in 0..2 {
                let thesis = parse(&mut g, THESIS_M[i][j]);
                let jacobian = parse(&mut g, JACOBIAN_M[i][j]);
                assert_eq!(thesis, jacobian, "M[{},{}]", i + 1, j + 1);
                assert_eq!(
                    mass_matrix_entry(&tau, i, j),
                    thesis,
                    "M[{},{}]",
                    i + 1,
                    j + 1
                );
            }
        }
    }

    #[test]
    fn irb140_mass_matrix_and_gravity_equal_appendix_b() {
        let (mut g, tau) = irb();
        for (i, j, thesis) in APPENDIX_B_M {
            let thesis = parse(&mut g, thesis);
            assert_eq!(
                mass_matrix_entry(&tau, i, j),
                thesis,
                "M[{},{}]",
                i + 1,
                j + 1
            );
            assert_eq!(
                mass_matrix_entry(&tau, j, i),
                thesis,
                "M[{},{}]",
                j + 1,
                i + 1
            );
        }
        for j in 1..3 {
            assert!(mass_matrix_entry(&tau, 0, j).is_zero(), "M[1,{}]", j + 1);
        }
        for (i, thesis) in APPENDIX_B_G.iter().enumerate() {
            let gravity = tau[i].coefficient(&Monomial::one(), Atom::is_joint_rate);
            assert_eq!(gravity, parse(&mut g, thesis), "g{}", i + 1);
        }
    }

    #[test]
    fn irb140_mass_matrix_is_symmetric() {
        let (_, tau) = irb();
        for i in 0..3 {
            for j in 0..i {
                assert_eq!(
                    mass_matrix_entry(&tau, i, j),
                    mass_matrix_entry(&tau, j, i),
                    "M[{},{}]",
                    i + 1,
                    j + 1
                );
            }
        }
    }
}

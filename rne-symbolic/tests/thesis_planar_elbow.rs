//! The planar elbow of chapter 4, derived with symbolic parameters, equals the thesis's
//! closed forms exactly (as canonical trigonometric polynomials, not by sampling): M (4.45),
//! g (4.47) and C q̇ of (4.46). The thesis's C is shown not to make Ṁ − 2C skew-symmetric;
//! the Christoffel C that rne generates does, exactly.

use rne_symbolic::canonical::Polynomial;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{ExprGraph, Id, SymbolicDynamics};

fn planar_elbow() -> SymbolicDynamics {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/robots/planar-elbow.toml"
    );
    let model = read_robot(
        Description::file(path.as_ref()),
        &LoadOptions {
            symbolic_parameters: true,
            ..LoadOptions::default()
        },
    )
    .unwrap();
    SymbolicDynamics::new(&model)
}

fn poly(graph: &ExprGraph, id: Id) -> Polynomial {
    Polynomial::from_expr(graph, id).unwrap()
}

/// Parses a formula of the thesis written as an s-expression over the spec's names.
fn thesis(graph: &mut ExprGraph, sexpr: &str) -> Polynomial {
    let id = graph.parse_sexpr(sexpr).unwrap();
    poly(graph, id)
}

/// (4.45)
const M: [[&str; 2]; 2] = [
    [
        "(+ (* 2 m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) (* m2 l1 l1) (* m1 lc1 lc1) I1 I2)",
        "(+ (* m2 l1 lc2 (cos q2)) (* m2 lc2 lc2) I2)",
    ],
    [
        "(+ (* m2 lc2 lc2) I2 (* m2 l1 lc2 (cos q2)))",
        "(+ I2 (* m2 lc2 lc2))",
    ],
];

/// (4.46)
const C_THESIS: [[&str; 2]; 2] = [
    [
        "(* -2 m2 l1 lc2 (sin q2) Dq2)",
        "(* -1 m2 l1 lc2 (sin q2) Dq2)",
    ],
    ["(* m2 l1 lc2 (sin q2) Dq1)", "0"],
];

/// (4.47)
const G: [&str; 2] = [
    "(+ (* m2 l1 g (cos q1)) (* m1 lc1 g (cos q1)) (* m2 lc2 g (cos (+ q1 q2))))",
    "(* m2 lc2 g (cos (+ q1 q2)))",
];

#[test]
fn mass_matrix_equals_4_45_exactly() {
    let mut d = planar_elbow();
    let m = d.mass_matrix();
    let g = &mut d.model.graph;
    for i in 0..2 {
        for j in 0..2 {
            let ours = poly(g, m[i][j]);
            assert_eq!(ours, thesis(g, M[i][j]), "M[{i}][{j}]");
        }
    }
}

#[test]
fn gravity_torques_equal_4_47_exactly() {
    let mut d = planar_elbow();
    let gravity = d.gravity_torques();
    let g = &mut d.model.graph;
    for i in 0..2 {
        assert_eq!(poly(g, gravity[i]), thesis(g, G[i]), "g[{i}]");
    }
}

#[test]
fn coriolis_times_velocity_equals_that_of_4_46_exactly() {
    let mut d = planar_elbow();
    let c = d.coriolis_matrix();
    let g = &mut d.model.graph;
    let dq = [thesis(g, "Dq1"), thesis(g, "Dq2")];
    for i in 0..2 {
        let ours = &(&poly(g, c[i][0]) * &dq[0]) + &(&poly(g, c[i][1]) * &dq[1]);
        let theirs =
            &(&thesis(g, C_THESIS[i][0]) * &dq[0]) + &(&thesis(g, C_THESIS[i][1]) * &dq[1]);
        assert_eq!(ours, theirs, "(C qd)[{i}]");
    }
}

#[test]
fn mdot_minus_2c_is_skew_for_the_christoffel_c_but_not_for_the_thesis_c() {
    let mut d = planar_elbow();
    let c = d.coriolis_matrix();
    let mdot = d.mass_matrix_derivative();
    let g = &mut d.model.graph;
    let mdot: Vec<Vec<Polynomial>> = mdot
        .iter()
        .map(|row| row.iter().map(|&x| poly(g, x)).collect())
        .collect();
    let ours: Vec<Vec<Polynomial>> = c
        .iter()
        .map(|row| row.iter().map(|&x| poly(g, x)).collect())
        .collect();
    let theirs: Vec<Vec<Polynomial>> = C_THESIS
        .iter()
        .map(|row| row.iter().map(|s| thesis(g, s)).collect())
        .collect();
    // N = Ṁ − 2C is skew iff N + Nᵀ = 2 Ṁ − 2 (C + Cᵀ) = 0, i.e. Ṁ = C + Cᵀ.
    let skew_defect =
        |c: &[Vec<Polynomial>], i: usize, j: usize| &(&mdot[i][j] - &c[i][j]) - &c[j][i];
    for i in 0..2 {
        for j in 0..2 {
            assert!(
                skew_defect(&ours, i, j).is_zero(),
                "Christoffel C: Mdot - C - C' at ({i},{j}) is not zero"
            );
        }
    }
    let defect = skew_defect(&theirs, 0, 0);
    assert!(
        !defect.is_zero(),
        "the thesis's C would make Mdot - 2C skew"
    );
    // (Ṁ − C − Cᵀ)₁₁ = −2 h q̇2 + 4 h q̇2 = 2 h q̇2 with h = m2 l1 lc2 sin q2.
    assert_eq!(defect, thesis(g, "(* 2 m2 l1 lc2 (sin q2) Dq2)"));
}

#[test]
fn torques_are_m_qdd_plus_c_qd_plus_g_exactly() {
    let mut d = planar_elbow();
    let tau = d.inverse_dynamics();
    let m = d.mass_matrix();
    let c = d.coriolis_matrix();
    let gravity = d.gravity_torques();
    let g = &mut d.model.graph;
    let ddq = [thesis(g, "DDq1"), thesis(g, "DDq2")];
    let dq = [thesis(g, "Dq1"), thesis(g, "Dq2")];
    for i in 0..2 {
        let mut sum = poly(g, gravity[i]);
        for j in 0..2 {
            sum += &(&poly(g, m[i][j]) * &ddq[j]);
            sum += &(&poly(g, c[i][j]) * &dq[j]);
        }
        assert_eq!(poly(g, tau[i]), sum, "tau[{i}]");
    }
}

#[test]
fn joint_reactions_of_the_planar_arm_have_no_out_of_plane_torque_section_4_5() {
    let mut d = planar_elbow();
    let reactions = d.joint_reactions();
    let tau = d.inverse_dynamics();
    let g = &mut d.model.graph;
    for (i, r) in reactions.iter().enumerate() {
        // "Both τ1 and τ2 are zero in the x-direction and y-direction" (section 4.5) and no
        // force along z: the planar arm loads its joints only in the plane.
        assert!(poly(g, r.torque[0]).is_zero(), "tau_{} x", i + 1);
        assert!(poly(g, r.torque[1]).is_zero(), "tau_{} y", i + 1);
        assert!(poly(g, r.force[2]).is_zero(), "f_{} z", i + 1);
        assert_eq!(
            poly(g, r.torque[2]),
            poly(g, tau[i]),
            "the z component is the joint torque"
        );
    }
}

//! The numeric reference against closed forms and published values: the thesis's planar elbow
//! (4.45)–(4.47), the PUMA 560 check value published with SymPyBotics, and two hand-derived robots with
//! prismatic joints.

use std::f64::consts::FRAC_PI_2;

use nalgebra::{DMatrix, Matrix3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_reference::Reference;
use rne_symbolic::model::Base;
use rne_symbolic::model::NumericLink;
use rne_symbolic::{JointKind, NumericModel};

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// A link with identity `E`, zero placement and no mass; tests fill in the rest.
fn link(name: &str, parent: Option<usize>, kind: JointKind, joint: Option<usize>) -> NumericLink {
    NumericLink {
        name: name.into(),
        parent,
        kind,
        joint,
        rotation: IDENTITY,
        translation: [0.0; 3],
        axis: Z,
        mass: 0.0,
        com: [0.0; 3],
        inertia: [[0.0; 3]; 3],
        coupling: None,
        friction: None,
        armature: None,
    }
}

fn diagonal(x: f64, y: f64, z: f64) -> [[f64; 3]; 3] {
    [[x, 0.0, 0.0], [0.0, y, 0.0], [0.0, 0.0, z]]
}

/// `max |a − b| / max |b|`: the error relative to the size of the expected quantity.
fn relative_error(actual: &[f64], expected: &[f64]) -> f64 {
    assert_eq!(actual.len(), expected.len());
    rne_figures::relative_error(actual, expected)
}

fn scientific(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|v| format!("{v:.2e}")).collect();
    parts.join(", ")
}

// ---------------------------------------------------------------------------------------------
// Planar elbow (thesis chapter 4, table 6.1)

const ELBOW_MASS: f64 = 15.0;
const ELBOW_LENGTH: f64 = 0.3;
const ELBOW_COM: f64 = 0.15;
const G: f64 = 9.81;

/// `I = m (l² + w²) / 12` about z, `w = sqrt(m / (ρ l))`.
fn elbow_inertia() -> f64 {
    let w2 = ELBOW_MASS / (7850.0 * ELBOW_LENGTH);
    ELBOW_MASS * (ELBOW_LENGTH * ELBOW_LENGTH + w2) / 12.0
}

/// Body frame i has the orientation of the thesis's frame i and its origin at joint i:
/// `R_1^0 = Rz(q1)`, `R_2^1 = Rz(q2)`, `r_{0,1} = [l1, 0, 0]`, COM `[lc, 0, 0]`. The links are
/// uniform boxes l × w × w.
fn planar_elbow() -> NumericModel {
    let (m, l, w2) = (
        ELBOW_MASS,
        ELBOW_LENGTH,
        ELBOW_MASS / (7850.0 * ELBOW_LENGTH),
    );
    let inertia = diagonal(m * 2.0 * w2 / 12.0, elbow_inertia(), elbow_inertia());
    let com = [ELBOW_COM, 0.0, 0.0];
    let revolute = JointKind::Revolute;
    NumericModel {
        name: "planar-elbow".into(),
        gravity: [0.0, -G, 0.0],
        base: Base::Fixed,
        links: vec![
            NumericLink {
                mass: m,
                com,
                inertia,
                ..link("link1", None, revolute, Some(0))
            },
            NumericLink {
                translation: [l, 0.0, 0.0],
                mass: m,
                com,
                inertia,
                ..link("link2", Some(0), revolute, Some(1))
            },
        ],
        joint_names: vec!["q1".into(), "q2".into()],
    }
}

#[test]
fn planar_elbow_matches_the_thesis_closed_forms_4_45_to_4_47_and_its_potential_energy() {
    let (m, l, lc, i) = (ELBOW_MASS, ELBOW_LENGTH, ELBOW_COM, elbow_inertia());
    let mut reference = Reference::new(&planar_elbow());
    // Without gravity the bias is C q̇ alone, not a difference bias − g that would cancel.
    let mut weightless = Reference::new(&NumericModel {
        gravity: [0.0; 3],
        base: Base::Fixed,
        ..planar_elbow()
    });
    let mut rng = ChaCha8Rng::seed_from_u64(445);
    let mut worst = [0.0_f64; 3];
    for _ in 0..2000 {
        let q: [f64; 2] = [rng.gen_range(-3.2..3.2), rng.gen_range(-3.2..3.2)];
        let qd = [rng.gen_range(-3.0..3.0), rng.gen_range(-3.0..3.0)];
        let (c2, h) = (q[1].cos(), m * l * lc * q[1].sin());
        // (4.45), with m1 = m2 = m, l1 = l, lc1 = lc2 = lc, I1 = I2 = I.
        let m11 = 2.0 * m * l * lc * c2 + m * lc * lc + m * l * l + m * lc * lc + 2.0 * i;
        let m12 = m * l * lc * c2 + m * lc * lc + i;
        let m22 = i + m * lc * lc;
        // (4.47)
        let g1 =
            m * l * G * q[0].cos() + m * lc * G * q[0].cos() + m * lc * G * (q[0] + q[1]).cos();
        let g2 = m * lc * G * (q[0] + q[1]).cos();
        // (4.46) times q̇.
        let cqd = [
            -2.0 * h * qd[1] * qd[0] - h * qd[1] * qd[1],
            h * qd[0] * qd[0],
        ];

        let mass = reference.mass_matrix(&q).unwrap();
        let gravity = reference.gravity_torques(&q).unwrap();
        let coriolis = weightless.bias_torques(&q, &qd).unwrap();
        // Potential energy, zero at the base origin: both COM heights times m g.
        let (s1, s12) = (q[0].sin(), (q[0] + q[1]).sin());
        let potential = m * G * lc * s1 + m * G * (l * s1 + lc * s12);
        let v = reference.potential_energy(&q).unwrap();
        assert!(
            (v - potential).abs() <= 1e-13 * m * G * (l + lc),
            "V = {v} vs {potential}"
        );
        let errors = [
            relative_error(mass.as_slice(), &[m11, m12, m12, m22]),
            relative_error(gravity.as_slice(), &[g1, g2]),
            relative_error(coriolis.as_slice(), &cqd),
        ];
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    eprintln!(
        "planar elbow, worst relative error of M, g, C q̇: {}",
        scientific(&worst)
    );
    assert!(worst.iter().all(|&e| e <= 1e-12), "{worst:?}");
}

// ---------------------------------------------------------------------------------------------
// PUMA 560 (Corke & Armstrong-Hélouvry 1994, standard DH)

fn rx(angle: f64) -> Matrix3<f64> {
    let (s, c) = angle.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[(r, c)]))
}

/// One row of a standard DH table with its link's inertia: d, a, α, mass, COM in DH frame j,
/// and Ixx, Iyy, Izz about the COM in DH frame j's axes.
type DhRow = (f64, f64, f64, f64, [f64; 3], [f64; 3]);

/// The PUMA 560 of Corke & Armstrong-Hélouvry (ICRA 1994).
#[rustfmt::skip]
const PUMA_DH: [DhRow; 6] = [
    (0.0,     0.0,    FRAC_PI_2,  0.0,  [0.0, 0.0, 0.0],            [0.0, 0.35, 0.0]),
    (0.0,     0.4318, 0.0,        17.4, [-0.3638, 0.006, 0.2275],   [0.13, 0.524, 0.539]),
    (0.15005, 0.0203, -FRAC_PI_2, 4.8,  [-0.0203, -0.0141, 0.070],  [0.066, 0.086, 0.0125]),
    (0.4318,  0.0,    FRAC_PI_2,  0.82, [0.0, 0.019, 0.0],          [1.8e-3, 1.3e-3, 1.8e-3]),
    (0.0,     0.0,    -FRAC_PI_2, 0.34, [0.0, 0.0, 0.0],            [0.3e-3, 0.4e-3, 0.3e-3]),
    (0.0,     0.0,    0.0,        0.09, [0.0, 0.0, 0.032],          [0.15e-3, 0.15e-3, 0.04e-3]),
];

/// Body frame B_i = DH frame i−1 followed by Rz(θ_i) Tz(d_i): `E_i = Rx(α_{i−1})`,
/// `t_i = [a_{i−1}, 0, 0] + Rx(α_{i−1}) [0, 0, d_i]`, axis z; a COM `c` and inertia `I` given
/// in DH frame i become `[a_i, 0, 0] + Rx(α_i) c` and `Rx(α_i) I Rx(α_i)ᵀ` in B_i.
fn puma560() -> NumericModel {
    let links = (0..6)
        .map(|j| {
            let (d, a, alpha, mass, com, inertia) = PUMA_DH[j];
            let (a_prev, alpha_prev) = if j == 0 {
                (0.0, 0.0)
            } else {
                (PUMA_DH[j - 1].1, PUMA_DH[j - 1].2)
            };
            let e = rx(alpha_prev);
            let t = Vector3::new(a_prev, 0.0, 0.0) + e * Vector3::new(0.0, 0.0, d);
            let r = rx(alpha);
            let com = Vector3::new(a, 0.0, 0.0) + r * Vector3::from(com);
            let inertia = r * Matrix3::from_diagonal(&Vector3::from(inertia)) * r.transpose();
            NumericLink {
                name: format!("link{}", j + 1),
                parent: j.checked_sub(1),
                kind: JointKind::Revolute,
                joint: Some(j),
                rotation: rows(&e),
                translation: t.into(),
                axis: Z,
                mass,
                com: com.into(),
                inertia: rows(&inertia),
                coupling: None,
                friction: None,
                armature: None,
            }
        })
        .collect();
    NumericModel {
        name: "puma560".into(),
        gravity: [0.0, 0.0, -G],
        base: Base::Fixed,
        links,
        joint_names: (1..=6).map(|j| format!("q{j}")).collect(),
    }
}

const PUMA_Q: [f64; 6] = [
    0.7504516826728697,
    0.8395156106908136,
    0.16851233582594916,
    0.3849629637427072,
    0.5252993946810777,
    0.6701207256444748,
];
const PUMA_QD: [f64; 6] = [
    0.24721855939629367,
    0.9805915670454258,
    0.9895299755642817,
    0.7861135739668947,
    0.273842245476577,
    0.17182358900767503,
];
const PUMA_QDD: [f64; 6] = [
    0.707405815485141,
    0.25295715193420953,
    0.9763909835998361,
    0.8412822676113918,
    0.4867768296473465,
    0.11480270540937143,
];

#[test]
fn puma560_inverse_dynamics_reproduces_the_published_check_value() {
    let tau_published = [
        0.986185688341252,
        16.1055550633721,
        -6.54839494827661,
        0.00626452648190803,
        -0.0208972707132494,
        5.59805923645945e-5,
    ];
    let mut reference = Reference::new(&puma560());
    let tau = reference
        .inverse_dynamics(&PUMA_Q, &PUMA_QD, &PUMA_QDD)
        .unwrap();
    let per_joint: Vec<f64> = tau
        .iter()
        .zip(tau_published)
        .map(|(t, p)| ((t - p) / p).abs())
        .collect();
    eprintln!("PUMA 560 tau = {:?}", tau.as_slice());
    eprintln!("relative error per joint: {}", scientific(&per_joint));
    assert!(per_joint.iter().all(|&e| e <= 1e-12), "{per_joint:?}");
}

/// The same source (SymPyBotics' test against Corke's Robotics Toolbox, `tests/test_results.py`)
/// publishes g, C q̇ and M at the check state; the 1e-20 entries of its M are rounding noise,
/// so these are compared relative to the largest entry.
#[test]
fn puma560_gravity_coriolis_and_mass_matrix_match_the_same_source() {
    let g_published = [
        1.0295354054077e-15,
        16.8135891283022,
        -7.29033633567802,
        0.00449992182015992,
        -0.026719893613902,
        0.0,
    ];
    let c_published = [
        -0.240237883763956,
        -1.0843848843681,
        0.365583586254475,
        -0.000123404998742911,
        0.00359951257553373,
        1.1075729558421e-5,
    ];
    let m_published = DMatrix::from_row_slice(
        6,
        6,
        &[
            2.05591694561963,
            -0.607149114401804,
            -0.0772414386669633,
            0.00110264316988551,
            0.000264135330891356,
            2.74006873318143e-6, //
            -0.607149114401804,
            2.00048563124708,
            0.306870038373922,
            -0.000227846077158843,
            0.000780985328855223,
            7.53260796283046e-6, //
            -0.0772414386669632,
            0.306870038373922,
            0.361368447500762,
            -0.000267122764221431,
            0.00156301630001611,
            7.53260796283046e-6, //
            0.00110264316988551,
            -0.000227846077158844,
            -0.000267122764221432,
            0.00169083802882858,
            1.45380752747483e-20,
            3.4606953693396e-5, //
            0.000264135330891356,
            0.000780985328855223,
            0.00156301630001611,
            2.33135442795155e-20,
            0.00064216,
            2.44929359829471e-21, //
            2.74006873318143e-6,
            7.53260796283046e-6,
            7.53260796283046e-6,
            3.4606953693396e-5,
            2.44929359829471e-21,
            4.0e-5,
        ],
    );
    let mut reference = Reference::new(&puma560());
    let g = reference.gravity_torques(&PUMA_Q).unwrap();
    let c = reference.bias_torques(&PUMA_Q, &PUMA_QD).unwrap() - &g;
    let m = reference.mass_matrix(&PUMA_Q).unwrap();
    let errors = [
        relative_error(g.as_slice(), &g_published),
        relative_error(c.as_slice(), &c_published),
        relative_error(m.as_slice(), m_published.as_slice()),
    ];
    eprintln!(
        "PUMA 560 relative error of g, C q̇, M: {}",
        scientific(&errors)
    );
    assert!(errors.iter().all(|&e| e <= 1e-12), "{errors:?}");
}

// ---------------------------------------------------------------------------------------------
// Prismatic joints

/// A cart of mass `mc` on a prismatic rail along x (joint x), carrying a pendulum (joint θ,
/// about z) with COM `l` below the pivot at θ = 0 and inertia `I` about it; gravity −g y.
/// Lagrange: `M = [mc + mp, mp l cos θ; mp l cos θ, mp l² + I]`,
/// `bias = [−mp l sin θ θ̇², mp g l sin θ]`.
#[test]
fn cart_pole_with_a_prismatic_rail_matches_its_lagrangian_closed_form() {
    let (mc, mp, l, i) = (2.5, 0.8, 0.45, 0.03);
    let model = NumericModel {
        name: "cart-pole".into(),
        gravity: [0.0, -G, 0.0],
        base: Base::Fixed,
        links: vec![
            NumericLink {
                translation: [0.3, -0.5, 0.0],
                axis: [1.0, 0.0, 0.0],
                mass: mc,
                com: [0.05, 0.0, 0.0],
                inertia: diagonal(0.1, 0.2, 0.3),
                ..link("cart", None, JointKind::Prismatic, Some(0))
            },
            NumericLink {
                translation: [0.2, 0.1, 0.0],
                mass: mp,
                com: [0.0, -l, 0.0],
                inertia: diagonal(i, 0.001, i),
                ..link("pole", Some(0), JointKind::Revolute, Some(1))
            },
        ],
        joint_names: vec!["x".into(), "theta".into()],
    };
    let mut reference = Reference::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..500 {
        let q: [f64; 2] = [rng.gen_range(-2.0..2.0), rng.gen_range(-3.2..3.2)];
        let qd = [rng.gen_range(-2.0..2.0), rng.gen_range(-3.0..3.0)];
        let qdd = [rng.gen_range(-2.0..2.0), rng.gen_range(-3.0..3.0)];
        let (s, c) = q[1].sin_cos();
        let mass = [mc + mp, mp * l * c, mp * l * c, mp * l * l + i];
        let bias = [-mp * l * s * qd[1] * qd[1], mp * G * l * s];
        let tau = [
            mass[0] * qdd[0] + mass[1] * qdd[1] + bias[0],
            mass[2] * qdd[0] + mass[3] * qdd[1] + bias[1],
        ];
        let m = reference.mass_matrix(&q).unwrap();
        assert!(
            relative_error(m.as_slice(), &mass) <= 1e-13,
            "{m} vs {mass:?}"
        );
        let b = reference.bias_torques(&q, &qd).unwrap();
        assert!(
            relative_error(b.as_slice(), &bias) <= 1e-13,
            "{b} vs {bias:?}"
        );
        let t = reference.inverse_dynamics(&q, &qd, &qdd).unwrap();
        assert!(
            relative_error(t.as_slice(), &tau) <= 1e-13,
            "{t} vs {tau:?}"
        );
    }
}

/// A rotating arm (joint θ about z, inertia I1) carrying a slider of mass m on a prismatic joint
/// along its x axis (joint r, inertia I2 about its COM at the slider origin); gravity −g y.
/// Lagrange: `τ_θ = (I1 + I2 + m r²) θ̈ + 2 m r ṙ θ̇ + m g r cos θ`,
/// `f_r = m r̈ − m r θ̇² + m g sin θ` — the `2 ω × b q̇` Coriolis term of a prismatic joint.
#[test]
fn slider_on_a_rotating_arm_has_the_prismatic_coriolis_term() {
    let (i1, i2, m) = (0.4, 0.05, 1.7);
    let model = NumericModel {
        name: "r-theta".into(),
        gravity: [0.0, -G, 0.0],
        base: Base::Fixed,
        links: vec![
            NumericLink {
                inertia: diagonal(i1, i1, i1),
                ..link("arm", None, JointKind::Revolute, Some(0))
            },
            NumericLink {
                axis: [1.0, 0.0, 0.0],
                mass: m,
                inertia: diagonal(i2, i2, i2),
                ..link("slider", Some(0), JointKind::Prismatic, Some(1))
            },
        ],
        joint_names: vec!["theta".into(), "r".into()],
    };
    let mut reference = Reference::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for _ in 0..500 {
        let q: [f64; 2] = [rng.gen_range(-3.2..3.2), rng.gen_range(-1.5..1.5)];
        let qd = [rng.gen_range(-3.0..3.0), rng.gen_range(-2.0..2.0)];
        let qdd = [rng.gen_range(-3.0..3.0), rng.gen_range(-2.0..2.0)];
        let (s, c) = q[0].sin_cos();
        let r = q[1];
        let expected = [
            (i1 + i2 + m * r * r) * qdd[0] + 2.0 * m * r * qd[1] * qd[0] + m * G * r * c,
            m * qdd[1] - m * r * qd[0] * qd[0] + m * G * s,
        ];
        let tau = reference.inverse_dynamics(&q, &qd, &qdd).unwrap();
        assert!(
            relative_error(tau.as_slice(), &expected) <= 1e-13,
            "{tau} vs {expected:?}"
        );
        let qdd_aba = reference.forward_dynamics(&q, &qd, &expected).unwrap();
        assert!(
            relative_error(qdd_aba.as_slice(), &qdd) <= 1e-12,
            "{qdd_aba} vs {qdd:?}"
        );
    }
}

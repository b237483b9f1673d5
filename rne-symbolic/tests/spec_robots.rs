//! The spec files of rne-models/robots read into models, checked against the thesis's frames
//! and closed forms, against the PUMA 560's published torques in all four frame conventions,
//! and the spec reader's tree, parameter and prismatic handling.

use std::f64::consts::FRAC_PI_2;
use std::path::PathBuf;

use rne_symbolic::model::NumericModel;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{Id, JointKind, RobotModel};

fn robot_path(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/robots")
        .join(file)
}

fn load(file: &str, symbolic_parameters: bool) -> RobotModel {
    let options = LoadOptions {
        symbolic_parameters,
        ..LoadOptions::default()
    };
    read_robot(Description::file(&robot_path(file)), &options).unwrap_or_else(|e| panic!("{e}"))
}

fn parse(text: &str) -> RobotModel {
    read_robot(
        Description::toml(text, "test.toml"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Exact constant values of expressions (panics on a non-constant).
fn constants(model: &RobotModel, ids: &[Id]) -> Vec<f64> {
    ids.iter()
        .map(|&id| {
            model
                .graph
                .as_const(id)
                .unwrap_or_else(|| panic!("{}", model.graph.to_sexpr(id)))
        })
        .collect()
}

fn sexprs(model: &RobotModel, ids: &[Id]) -> Vec<String> {
    ids.iter().map(|&id| model.graph.to_sexpr(id)).collect()
}

fn parameter(model: &RobotModel, name: &str) -> f64 {
    model
        .parameters
        .iter()
        .find(|p| p.name == name)
        .map(|p| p.value)
        .unwrap()
}

fn assert_close(actual: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(actual.len(), expected.len());
    for (a, e) in actual.iter().zip(expected) {
        assert!(
            (a - e).abs() <= tolerance * (1.0 + e.abs()),
            "{actual:?} != {expected:?}"
        );
    }
}

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(s: f64, a: V3) -> V3 {
    a.map(|x| s * x)
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn mv(m: &M3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn mtv(m: &M3, v: V3) -> V3 {
    [0, 1, 2].map(|j| m[0][j] * v[0] + m[1][j] * v[1] + m[2][j] * v[2])
}

fn mm(a: &M3, b: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]))
}

/// Rotation by `angle` about the unit vector `u` (Rodrigues).
fn rot(u: V3, angle: f64) -> M3 {
    let (s, c) = angle.sin_cos();
    let k = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| f64::from(u8::from(i == j)) * c + (1.0 - c) * u[i] * u[j] + s * k[i][j])
    })
}

/// Recursive Newton–Euler on the model's body frames (a reference for these tests only):
/// R_i = E_i Rot(u_i, q_i), origin t_i (+ E_i u_i q_i for a prismatic joint).
fn inverse_dynamics(model: &NumericModel, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    let n = model.links.len();
    let mut rotation = vec![[[0.0; 3]; 3]; n];
    let mut origin = vec![[0.0; 3]; n];
    let mut omega = vec![[0.0; 3]; n];
    let mut alpha = vec![[0.0; 3]; n];
    let mut accel = vec![[0.0; 3]; n];
    let mut force = vec![[0.0; 3]; n];
    let mut torque = vec![[0.0; 3]; n];
    for (i, link) in model.links.iter().enumerate() {
        let (w0, a0, acc0) = match link.parent {
            Some(p) => (omega[p], alpha[p], accel[p]),
            None => ([0.0; 3], [0.0; 3], scale(-1.0, model.gravity)),
        };
        let (qi, qdi, qddi) = link
            .joint
            .map_or((0.0, 0.0, 0.0), |k| (q[k], qd[k], qdd[k]));
        let u = link.axis;
        let (r, p) = match link.kind {
            JointKind::Revolute => (mm(&link.rotation, &rot(u, qi)), link.translation),
            JointKind::Prismatic => (
                link.rotation,
                add(link.translation, mv(&link.rotation, scale(qi, u))),
            ),
            JointKind::Fixed => (link.rotation, link.translation),
            JointKind::FreeFlyer => unreachable!("the specs read here have a fixed base"),
        };
        let parent_accel = add(acc0, add(cross(a0, p), cross(w0, cross(w0, p))));
        let w_in = mtv(&r, w0);
        let (w, al, mut acc) = (w_in, mtv(&r, a0), mtv(&r, parent_accel));
        let (w, al) = match link.kind {
            JointKind::Revolute => (
                add(w, scale(qdi, u)),
                add(add(al, scale(qddi, u)), cross(w_in, scale(qdi, u))),
            ),
            _ => (w, al),
        };
        if link.kind == JointKind::Prismatic {
            acc = add(acc, add(scale(qddi, u), cross(scale(2.0 * qdi, w), u)));
        }
        let c = link.com;
        let acc_c = add(acc, add(cross(al, c), cross(w, cross(w, c))));
        force[i] = scale(link.mass, acc_c);
        let iw = mv(&link.inertia, w);
        torque[i] = add(add(mv(&link.inertia, al), cross(w, iw)), cross(c, force[i]));
        rotation[i] = r;
        origin[i] = p;
        omega[i] = w;
        alpha[i] = al;
        accel[i] = acc;
    }
    let mut tau = vec![0.0; model.dof()];
    for i in (0..n).rev() {
        let link = &model.links[i];
        if let Some(k) = link.joint {
            tau[k] = match link.kind {
                JointKind::Prismatic => dot(link.axis, force[i]),
                _ => dot(link.axis, torque[i]),
            };
        }
        if let Some(p) = link.parent {
            let f = mv(&rotation[i], force[i]);
            let t = add(mv(&rotation[i], torque[i]), cross(origin[i], f));
            force[p] = add(force[p], f);
            torque[p] = add(torque[p], t);
        }
    }
    tau
}

#[test]
fn planar_elbow_frames_follow_chapter_4() {
    let model = load("planar-elbow.toml", false);
    assert_eq!(model.name, "planar-elbow");
    assert_eq!(model.joint_names(), ["q1", "q2"]);
    assert_eq!(model.graph.symbols().joints(), ["q1", "q2"]);
    let [link1, link2] = [&model.links[0], &model.links[1]];
    assert_eq!(link2.parent, Some(0));
    assert_eq!(constants(&model, &link1.axis), [0.0, 0.0, 1.0]);
    assert_eq!(constants(&model, &link2.axis), [0.0, 0.0, 1.0]);
    assert_eq!(constants(&model, &link1.translation), [0.0; 3]);
    assert_eq!(constants(&model, &link2.translation), [0.3, 0.0, 0.0]); // r_{0,1}
    assert_eq!(constants(&model, &link1.com), [0.15, 0.0, 0.0]); // r_{0,c1}
    assert_eq!(constants(&model, &model.gravity), [0.0, -9.81, 0.0]);
    let w = (15.0_f64 / (7850.0 * 0.3)).sqrt();
    assert!((parameter(&model, "w") - 0.0798).abs() < 5e-5);
    let izz = constants(&model, &[link2.inertia[2][2]])[0];
    assert!((izz - 15.0 * (0.09 + w * w) / 12.0).abs() < 1e-15);
}

#[test]
fn planar_elbow_keeps_the_thesis_symbols() {
    let model = load("planar-elbow.toml", true);
    let names: Vec<&str> = model.parameters.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        ["m", "l", "rho", "w", "lc", "I", "m1", "m2", "l1", "l2", "lc1", "lc2", "I1", "I2", "g"]
    );
    assert_eq!(model.graph.symbols().parameters(), names.as_slice());
    assert_eq!(parameter(&model, "I2"), parameter(&model, "I"));
    let [link1, link2] = [&model.links[0], &model.links[1]];
    assert_eq!(sexprs(&model, &link2.translation), ["l1", "0", "0"]);
    assert_eq!(sexprs(&model, &link1.com), ["lc1", "0", "0"]);
    assert_eq!(sexprs(&model, &link2.com), ["lc2", "0", "0"]);
    assert_eq!(model.graph.to_sexpr(link1.mass), "m1");
    assert_eq!(model.graph.to_sexpr(link1.inertia[2][2]), "I1");
    assert_eq!(sexprs(&model, &model.gravity), ["0", "(- g)", "0"]);
}

/// M (4.45) and g (4.47) of the planar elbow, from inverse dynamics of the loaded model.
#[test]
fn planar_elbow_reproduces_the_closed_forms() {
    let model = load("planar-elbow.toml", false);
    let numeric = model.to_numeric();
    let p = |name| parameter(&model, name);
    let (m1, m2, l1, lc1, lc2, i1, i2, g) = (
        p("m1"),
        p("m2"),
        p("l1"),
        p("lc1"),
        p("lc2"),
        p("I1"),
        p("I2"),
        p("g"),
    );
    for q in [[0.3_f64, -1.1], [2.0, 0.7], [-0.4, 2.9]] {
        let c2 = q[1].cos();
        let m = [
            [
                2.0 * m2 * l1 * lc2 * c2 + m2 * lc2 * lc2 + m2 * l1 * l1 + m1 * lc1 * lc1 + i1 + i2,
                m2 * l1 * lc2 * c2 + m2 * lc2 * lc2 + i2,
            ],
            [
                m2 * lc2 * lc2 + i2 + m2 * l1 * lc2 * c2,
                i2 + m2 * lc2 * lc2,
            ],
        ];
        let gravity = [
            (m2 * l1 + m1 * lc1) * g * q[0].cos() + m2 * lc2 * g * (q[0] + q[1]).cos(),
            m2 * lc2 * g * (q[0] + q[1]).cos(),
        ];
        let g_rnea = inverse_dynamics(&numeric, &q, &[0.0; 2], &[0.0; 2]);
        assert_close(&g_rnea, &gravity, 1e-12);
        for j in 0..2 {
            let mut qdd = [0.0; 2];
            qdd[j] = 1.0;
            let column = inverse_dynamics(&numeric, &q, &[0.0; 2], &qdd);
            let column: Vec<f64> = column.iter().zip(&g_rnea).map(|(t, g)| t - g).collect();
            assert_close(&column, &[m[0][j], m[1][j]], 1e-12);
        }
    }
}

#[test]
fn irb140_frames_follow_chapter_5() {
    let model = load("irb140-3dof.toml", false);
    assert_eq!(model.joint_names(), ["q1", "q2", "q3"]);
    let [link1, link2, link3] = [&model.links[0], &model.links[1], &model.links[2]];
    assert_eq!(constants(&model, &link1.axis), [1.0, 0.0, 0.0]); // b_1, (5.17)
    assert_eq!(constants(&model, &link2.axis), [0.0, 0.0, 1.0]); // b_2, (5.18)
    assert_eq!(constants(&model, &link3.axis), [0.0, 0.0, 1.0]); // b_3, (5.19)
                                                                 // E_1 = Rx(pi/2) Rz(pi/2): R_1^0 at q1 = 0, (5.12).
    assert_eq!(
        constants(&model, &link1.rotation.concat()),
        [0.0, -1.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0]
    );
    // E_2 = Rz(-pi/2), (5.13) at q2 = 0.
    assert_eq!(
        constants(&model, &link2.rotation.concat()),
        [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    );
    assert_eq!(constants(&model, &link2.translation), [0.352, -0.070, 0.0]); // r_{0,1}
    assert_eq!(constants(&model, &link3.translation), [0.0, 0.360, 0.0]); // r_{1,2}
    assert_eq!(constants(&model, &link1.com), [0.176, -0.035, 0.0]); // r_{0,c1}
    assert_eq!(constants(&model, &link2.com), [0.0, 0.18, 0.0]);
    assert_eq!(constants(&model, &link3.com), [0.19, 0.0, 0.0]);
    assert_eq!(constants(&model, &model.gravity), [0.0, 0.0, -9.81]);
    let i1 = constants(
        &model,
        &[
            link1.inertia[0][0],
            link1.inertia[1][1],
            link1.inertia[2][2],
        ],
    );
    assert_close(
        &i1,
        &[
            23.0 * 0.18 / 12.0,
            23.0 * (0.352f64.powi(2) + 0.09) / 12.0,
            23.0 * (0.352f64.powi(2) + 0.09) / 12.0,
        ],
        1e-15,
    );
}

/// E_i Rot(u_i, q_i) of the model equals the thesis's R_i^{i−1}(q) at any q.
#[test]
fn irb140_rotations_factor_exactly() {
    let numeric = load("irb140-3dof.toml", false).to_numeric();
    let rz = |a: f64| rot([0.0, 0.0, 1.0], a);
    let rx = |a: f64| rot([1.0, 0.0, 0.0], a);
    for q in [0.3, -2.0, 1.234] {
        let thesis = [
            mm(&mm(&rz(q), &rx(FRAC_PI_2)), &rz(FRAC_PI_2)),
            rz(q - FRAC_PI_2),
            rz(q),
        ];
        for (link, expected) in numeric.links.iter().zip(thesis) {
            let factored = mm(&link.rotation, &rot(link.axis, q));
            assert_close(&factored.concat(), &expected.concat(), 1e-15);
        }
    }
}

#[test]
fn irb140_keeps_the_thesis_symbols() {
    let model = load("irb140-3dof.toml", true);
    let [link1, link2, link3] = [&model.links[0], &model.links[1], &model.links[2]];
    assert_eq!(sexprs(&model, &link2.translation), ["l1x", "(- l1y)", "0"]);
    assert_eq!(sexprs(&model, &link3.translation), ["0", "l2", "0"]);
    assert_eq!(sexprs(&model, &link1.com), ["lc1x", "(- lc1y)", "0"]);
    assert_eq!(sexprs(&model, &link3.com), ["lc3", "0", "0"]);
    assert_eq!(model.graph.to_sexpr(link2.inertia[1][1]), "I2yy");
    assert_eq!(constants(&model, &link1.axis), [1.0, 0.0, 0.0]);
    assert_eq!(sexprs(&model, &model.gravity), ["0", "0", "(- g)"]);
    assert!((parameter(&model, "I1xx") - 23.0 * 0.18 / 12.0).abs() < 1e-15);
}

/// The PUMA 560 table of Corke & Armstrong-Hélouvry (ICRA 1994): (d, a, alpha, mass, com,
/// diagonal inertia).
const PUMA: [(f64, f64, f64, f64, V3, V3); 6] = [
    (0.0, 0.0, FRAC_PI_2, 0.0, [0.0, 0.0, 0.0], [0.0, 0.35, 0.0]),
    (
        0.0,
        0.4318,
        0.0,
        17.4,
        [-0.3638, 0.006, 0.2275],
        [0.13, 0.524, 0.539],
    ),
    (
        0.15005,
        0.0203,
        -FRAC_PI_2,
        4.8,
        [-0.0203, -0.0141, 0.070],
        [0.066, 0.086, 0.0125],
    ),
    (
        0.4318,
        0.0,
        FRAC_PI_2,
        0.82,
        [0.0, 0.019, 0.0],
        [1.8e-3, 1.3e-3, 1.8e-3],
    ),
    (
        0.0,
        0.0,
        -FRAC_PI_2,
        0.34,
        [0.0, 0.0, 0.0],
        [0.3e-3, 0.4e-3, 0.3e-3],
    ),
    (
        0.0,
        0.0,
        0.0,
        0.09,
        [0.0, 0.0, 0.032],
        [0.15e-3, 0.15e-3, 0.04e-3],
    ),
];

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
const PUMA_TAU: [f64; 6] = [
    0.986185688341252,
    16.1055550633721,
    -6.54839494827661,
    0.00626452648190803,
    -0.0208972707132494,
    5.59805923645945e-5,
];

fn puma_torques(model: &RobotModel) -> Vec<f64> {
    inverse_dynamics(&model.to_numeric(), &PUMA_Q, &PUMA_QD, &PUMA_QDD)
}

#[test]
fn puma560_file_gives_the_published_torques() {
    let model = load("puma560.toml", false);
    assert_eq!(model.dof(), 6);
    assert_close(&puma_torques(&model), &PUMA_TAU, 1e-12);
}

fn puma_link_header(j: usize) -> String {
    format!("[[link]]\nname = \"link{}\"\njoint = \"revolute\"\n", j + 1)
}

fn toml_vec(v: V3) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

fn diagonal_inertia(i: V3) -> String {
    format!("{{ xx = {:?}, yy = {:?}, zz = {:?} }}", i[0], i[1], i[2])
}

/// The same robot in the thesis's convention: R_i^{i−1} = Rz(q) Rx(alpha) and
/// r_{i−1,i} = Rx(alpha)ᵀ [a, 0, d] in frame i; inertials in frame i as in DH.
#[test]
fn puma560_in_the_thesis_convention() {
    let mut text = String::from("name = \"puma-thesis\"\n[parameters]\nhalf = \"pi/2\"\n");
    for (j, (d, a, alpha, m, com, inertia)) in PUMA.iter().enumerate() {
        let alpha_text = match alpha {
            x if *x == FRAC_PI_2 => "half".to_owned(),
            x if *x == -FRAC_PI_2 => "-half".to_owned(),
            _ => "0".to_owned(),
        };
        text += &puma_link_header(j);
        text += &format!("rotation = \"Rz(q{}) * Rx({alpha_text})\"\n", j + 1);
        text += &format!(
            "position = {}\n",
            toml_vec([*a, d * alpha.sin(), d * alpha.cos()])
        );
        text += &format!(
            "mass = {m:?}\ncom = {}\ninertia = {}\n",
            toml_vec(*com),
            diagonal_inertia(*inertia)
        );
        text += if j == 2 {
            "triangle_inequality = false\n"
        } else {
            ""
        };
    }
    assert_close(&puma_torques(&parse(&text)), &PUMA_TAU, 1e-12);
}

/// Modified DH: link j's table holds alpha_{j−1}, a_{j−1} and d_j; frame j is DH's body frame,
/// in which the inertials become com' = Rx(alpha_j) com + [a_j, 0, 0] and I' = Rx I Rxᵀ,
/// written as a full 3×3 array.
#[test]
fn puma560_in_modified_dh_with_inertia_arrays() {
    let mut text = String::from("name = \"puma-mdh\"\n");
    for (j, (d, a, alpha, m, com, inertia)) in PUMA.iter().enumerate() {
        let (a_prev, alpha_prev) = if j == 0 {
            (0.0, 0.0)
        } else {
            (PUMA[j - 1].1, PUMA[j - 1].2)
        };
        let rx = rot([1.0, 0.0, 0.0], *alpha);
        let diag = [
            [inertia[0], 0.0, 0.0],
            [0.0, inertia[1], 0.0],
            [0.0, 0.0, inertia[2]],
        ];
        let i_body = mm(
            &mm(&rx, &diag),
            &[0, 1, 2].map(|r| [0, 1, 2].map(|c| rx[c][r])),
        );
        // Symmetrise exactly: rounding may differ in the last bit between the two triangles.
        let i_body =
            [0, 1, 2].map(|r| [0, 1, 2].map(|c| if r <= c { i_body[r][c] } else { i_body[c][r] }));
        text += &puma_link_header(j);
        text += &format!("mdh = {{ a = {a_prev:?}, alpha = {alpha_prev:?}, d = {d:?} }}\n");
        text += &format!(
            "mass = {m:?}\ncom = {}\n",
            toml_vec(add(mv(&rx, *com), [*a, 0.0, 0.0]))
        );
        text += &format!(
            "inertia = [{}, {}, {}]\n",
            toml_vec(i_body[0]),
            toml_vec(i_body[1]),
            toml_vec(i_body[2])
        );
        text += if j == 2 {
            "triangle_inequality = false\n"
        } else {
            ""
        };
    }
    assert_close(&puma_torques(&parse(&text)), &PUMA_TAU, 1e-12);
}

/// URDF origins: frame j = Trans([a_{j−1}, −d_j sin alpha_{j−1}, d_j cos alpha_{j−1}]) ·
/// Rx(alpha_{j−1}), about z; inertials in the body frame as for modified DH, via `com` and
/// products of inertia in a table.
#[test]
fn puma560_with_urdf_origins() {
    let mut text = String::from("name = \"puma-urdf\"\n");
    for (j, (d, a, alpha, m, com, inertia)) in PUMA.iter().enumerate() {
        let (a_prev, alpha_prev) = if j == 0 {
            (0.0, 0.0)
        } else {
            (PUMA[j - 1].1, PUMA[j - 1].2)
        };
        let rx = rot([1.0, 0.0, 0.0], *alpha);
        let diag = [
            [inertia[0], 0.0, 0.0],
            [0.0, inertia[1], 0.0],
            [0.0, 0.0, inertia[2]],
        ];
        let i_body = mm(
            &mm(&rx, &diag),
            &[0, 1, 2].map(|r| [0, 1, 2].map(|c| rx[c][r])),
        );
        let xyz = [a_prev, -d * alpha_prev.sin(), d * alpha_prev.cos()];
        text += &puma_link_header(j);
        text += &format!(
            "origin = {{ xyz = {}, rpy = [{alpha_prev:?}, 0, 0] }}\naxis = [0, 0, 1]\n",
            toml_vec(xyz)
        );
        text += &format!(
            "mass = {m:?}\ncom = {}\n",
            toml_vec(add(mv(&rx, *com), [*a, 0.0, 0.0]))
        );
        text += &format!(
            "inertia = {{ xx = {:?}, yy = {:?}, zz = {:?}, xy = {:?}, xz = {:?}, yz = {:?} }}\n",
            i_body[0][0], i_body[1][1], i_body[2][2], i_body[0][1], i_body[0][2], i_body[1][2]
        );
        text += if j == 2 {
            "triangle_inequality = false\n"
        } else {
            ""
        };
    }
    assert_close(&puma_torques(&parse(&text)), &PUMA_TAU, 1e-12);
}

#[test]
fn links_are_ordered_depth_first_and_joints_named_in_file_order() {
    let link = |name: &str, parent: &str, joint: &str| {
        format!(
            "[[link]]\nname = \"{name}\"\nparent = \"{parent}\"\njoint = \"{joint}\"\ndh = {{ a = 1 }}\nmass = 1\n\
             inertia = {{ xx = 1, yy = 1, zz = 1 }}\n"
        )
    };
    let text = format!(
        "name = \"tree\"\n{}{}{}{}{}",
        link("a", "base", "revolute"),
        link("b", "a", "revolute"),
        link("c", "base", "prismatic"),
        link("tool", "b", "fixed"),
        link("d", "a", "revolute"),
    );
    let model = parse(&text);
    let names: Vec<&str> = model.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["a", "b", "tool", "d", "c"]);
    let parents: Vec<Option<usize>> = model.links.iter().map(|l| l.parent).collect();
    assert_eq!(parents, [None, Some(0), Some(1), Some(0), None]);
    // Default names count movable joints in file order; indices follow the model order.
    assert_eq!(model.joint_names(), ["q1", "q2", "q4", "q3"]);
    assert_eq!(model.graph.symbols().joints(), ["q1", "q2", "q4", "q3"]);
    let joints: Vec<Option<usize>> = model.links.iter().map(|l| l.joint).collect();
    assert_eq!(joints, [Some(0), Some(1), None, Some(2), Some(3)]);
    let links: Vec<usize> = model.joints.iter().map(|j| j.link).collect();
    assert_eq!(links, [0, 1, 3, 4]);
    assert_eq!(model.links[2].kind, JointKind::Fixed);
    // Children of a DH link hang from its frame: t = [a, 0, 0] of the parent.
    assert_eq!(
        constants(&model, &model.links[1].translation),
        [1.0, 0.0, 0.0]
    );
    assert_eq!(
        constants(&model, &model.links[0].translation),
        [0.0, 0.0, 0.0]
    );
}

#[test]
fn prismatic_joints_in_the_thesis_convention() {
    let text = r#"
        name = "slider"
        gravity = [0, 0, -10]
        [[link]]
        name = "carriage"
        joint = "prismatic"
        q = "s"
        rotation = "Rx(pi)"
        position = [0.5, 0, "s + 0.25"]
        mass = 2
        com = [0, 0, -0.1]
        inertia = { box = [0.1, 0.2, 0.3] }
        [[link]]
        name = "pendulum"
        joint = "revolute"
        rotation = "Rz(q2)"
        position = [1, 0, 0]
        mass = 1
        com = [-0.5, 0, 0]
        inertia = { xx = 0, yy = 0.1, zz = 0.1 }
    "#;
    let model = parse(text);
    assert_eq!(model.joint_names(), ["s", "q2"]);
    let [carriage, pendulum] = [&model.links[0], &model.links[1]];
    assert_eq!(constants(&model, &carriage.axis), [0.0, 0.0, 1.0]);
    assert_eq!(constants(&model, &pendulum.translation), [0.5, 0.0, 0.25]); // position at s = 0
    assert_eq!(constants(&model, &carriage.com), [0.5, 0.0, 0.15]);
    assert_eq!(constants(&model, &pendulum.com), [0.5, 0.0, 0.0]);
    let inertia = constants(
        &model,
        &[
            carriage.inertia[0][0],
            carriage.inertia[1][1],
            carriage.inertia[2][2],
        ],
    );
    assert_close(
        &inertia,
        &[2.0 * 0.13 / 12.0, 2.0 * 0.1 / 12.0, 2.0 * 0.05 / 12.0],
        1e-15,
    );
    // The carriage is turned upside down: moving up along its z moves it down in the world,
    // so holding it still against gravity takes a force of -(m1 + m2) g along its axis.
    let tau = inverse_dynamics(&model.to_numeric(), &[0.3, 0.0], &[0.0; 2], &[0.0; 2]);
    assert_close(&tau, &[-30.0, 0.0], 1e-12);
}

#[test]
fn parameters_are_defined_in_any_order() {
    let text = r#"
        name = "p"
        [parameters]
        area = "side^2"
        side = "2 * half"
        half = 0.5
        [[link]]
        name = "l"
        joint = "revolute"
        axis = [0, 0, 1]
        mass = "area"
        inertia = { xx = "area", yy = "area", zz = "area" }
    "#;
    let numeric = parse(text);
    assert_eq!(constants(&numeric, &[numeric.links[0].mass]), [1.0]);
    assert!(numeric.graph.symbols().parameters().is_empty());
    let symbolic = read_robot(
        Description::toml(text, "p.toml"),
        &LoadOptions {
            symbolic_parameters: true,
            ..LoadOptions::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        symbolic.graph.symbols().parameters(),
        ["area", "side", "half"]
    );
    assert_eq!(symbolic.graph.to_sexpr(symbolic.links[0].mass), "area");
    let values: Vec<f64> = symbolic.parameters.iter().map(|p| p.value).collect();
    assert_eq!(values, [1.0, 1.0, 0.5]);
}

#[test]
fn gravity_defaults_to_minus_z() {
    let model = parse(
        "name = \"g\"\n[[link]]\nname = \"l\"\njoint = \"fixed\"\norigin = {}\nmass = 0\n\
         inertia = { xx = 0, yy = 0, zz = 0 }\n",
    );
    assert_eq!(constants(&model, &model.gravity), [0.0, 0.0, -9.81]);
    assert_eq!(model.dof(), 0);
}

#[test]
fn urdf_axes_are_normalised_and_default_to_x() {
    let text = r#"
        name = "u"
        [[link]]
        name = "a"
        joint = "revolute"
        origin = { xyz = [0, 0, 1] }
        mass = 1
        inertia = { xx = 1, yy = 1, zz = 1 }
        [[link]]
        name = "b"
        joint = "revolute"
        axis = [0, 3, 4]
        mass = 1
        inertia = { xx = 1, yy = 1, zz = 1 }
    "#;
    let model = parse(text);
    assert_eq!(constants(&model, &model.links[0].axis), [1.0, 0.0, 0.0]);
    assert_eq!(
        constants(&model, &model.links[0].translation),
        [0.0, 0.0, 1.0]
    );
    assert_eq!(constants(&model, &model.links[1].axis), [0.0, 0.6, 0.8]);
}

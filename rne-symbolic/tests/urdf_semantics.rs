//! URDF import against an independent reading of URDF semantics (`urdf_oracle`): for each edge
//! case of issue 4 and each built-in URDF robot, M(q) and g(q) of the symbolic dynamics equal
//! those of forward kinematics written straight from the URDF specification, at seeded states.
//! Also the tree order, the base, fixed links and the branch-induced zeros of M.

mod urdf_oracle;

use std::path::{Path, PathBuf};

use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{JointKind, RobotModel, Symbol, SymbolicDynamics};
use urdf_oracle::Oracle;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/urdf_fixtures")
        .join(name)
}

fn builtin(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/robots")
        .join(name)
}

fn load(path: &Path) -> RobotModel {
    read_robot(Description::file(path), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A small seeded generator of states in [−2, 2).
struct States(u64);

impl States {
    fn next(&mut self, n: usize) -> Vec<f64> {
        (0..n)
            .map(|_| {
                self.0 ^= self.0 << 13;
                self.0 ^= self.0 >> 7;
                self.0 ^= self.0 << 17;
                4.0 * (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 2.0
            })
            .collect()
    }
}

/// M(q) and g(q) of the symbolic dynamics, evaluated.
fn symbolic(dynamics: &mut SymbolicDynamics, q: &[f64]) -> (Vec<Vec<f64>>, Vec<f64>) {
    let n = dynamics.dof();
    let m = dynamics.mass_matrix();
    let g = dynamics.gravity_torques();
    let mut outputs: Vec<_> = m.iter().flatten().copied().collect();
    outputs.extend(&g);
    let values = dynamics.model.graph.eval::<f64>(&outputs, |s| match s {
        Symbol::Position(k) => q[k as usize],
        _ => f64::NAN,
    });
    let m = values[..n * n].chunks(n).map(<[f64]>::to_vec).collect();
    (m, values[n * n..].to_vec())
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// The file's M and g against the oracle's at 20 seeded states (finite differences: 1e-7
/// relative to the largest entry).
fn agrees_with_the_oracle(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    let model = load(path);
    let oracle = Oracle::new(&text, &model.joint_names());
    let mut dynamics = SymbolicDynamics::new(&model);
    let mut states = States(0x2545_f491_4f6c_dd1d);
    for _ in 0..20 {
        let q = states.next(model.dof());
        let (m, g) = symbolic(&mut dynamics, &q);
        let m_oracle = oracle.mass_matrix(&q);
        let g_oracle = oracle.gravity_torques(&q);
        let flat: Vec<f64> = m.iter().flatten().copied().collect();
        let flat_oracle: Vec<f64> = m_oracle.iter().flatten().copied().collect();
        let scale = max_abs(&flat_oracle).max(1e-3);
        for (k, (a, b)) in flat.iter().zip(&flat_oracle).enumerate() {
            assert!(
                (a - b).abs() <= 1e-7 * scale,
                "{}: M[{}][{}] = {a} but the oracle gives {b} at q = {q:?}",
                path.display(),
                k / model.dof(),
                k % model.dof()
            );
        }
        let scale = max_abs(&g_oracle).max(1e-3);
        for (k, (a, b)) in g.iter().zip(&g_oracle).enumerate() {
            assert!(
                (a - b).abs() <= 1e-7 * scale,
                "{}: g[{k}] = {a} but the oracle gives {b} at q = {q:?}",
                path.display()
            );
        }
    }
}

#[test]
fn rpy_on_every_joint() {
    agrees_with_the_oracle(&fixture("rpy_every_joint.urdf"));
}

#[test]
fn negative_and_unnormalised_axes() {
    let path = fixture("negative_axes.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    let half = std::f64::consts::FRAC_1_SQRT_2;
    let axes: Vec<Vec<f64>> = model
        .links
        .iter()
        .map(|l| {
            l.axis
                .iter()
                .map(|&a| model.graph.as_const(a).unwrap())
                .collect()
        })
        .collect();
    // The root link, fixed, has no axis.
    assert_eq!(axes[0], [0.0, 0.0, 0.0]);
    assert_eq!(axes[1], [0.0, 0.0, -1.0]);
    assert_eq!(axes[2], [0.0, -1.0, 0.0]);
    assert_eq!(axes[3], [-1.0, 0.0, 0.0]);
    for (a, b) in axes[4].iter().zip([0.0, -half, half]) {
        assert!((a - b).abs() < 1e-15, "{:?}", axes[4]);
    }
    let length: f64 = axes[5].iter().map(|a| a * a).sum::<f64>().sqrt();
    assert!((length - 1.0).abs() < 1e-15);
}

#[test]
fn fixed_link_with_mass_and_rotated_inertia() {
    let path = fixture("fixed_link.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    let kinds: Vec<JointKind> = model.links.iter().map(|l| l.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Fixed,
            JointKind::Revolute,
            JointKind::Revolute,
            JointKind::Fixed,
            JointKind::Revolute
        ]
    );
    // The root and the fixed link are kept in the model, the bracket between l2 and l3; the
    // dynamics drop the root and merge the bracket.
    assert_eq!(model.links[0].name, "base");
    assert_eq!(model.links[3].name, "bracket");
    assert_eq!(model.links[4].parent, Some(3));
    assert_eq!(model.joint_names(), ["f1", "f2", "f3"]);
    assert_eq!(SymbolicDynamics::new(&model).model.links.len(), 3);
}

#[test]
fn branch() {
    let path = fixture("branch.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    // Depth-first from the root, children in file order.
    assert_eq!(
        model.joint_names(),
        ["left1", "left2", "thumb", "right1", "right2"]
    );
    let parents: Vec<Option<usize>> = model.links.iter().map(|l| l.parent).collect();
    assert_eq!(parents, [None, Some(0), Some(1), Some(1), Some(0), Some(4)]);
    assert_eq!(model.links[0].name, "torso");
    // Joints on different branches share no body: M has structural zeros there.
    let mut dynamics = SymbolicDynamics::new(&model);
    let m = dynamics.mass_matrix();
    let graph = &dynamics.model.graph;
    for (i, j) in [(1, 2), (0, 3), (0, 4), (1, 3), (1, 4), (2, 3), (2, 4)] {
        assert!(
            graph.is_zero(m[i][j]),
            "M[{i}][{j}] is not structurally zero"
        );
    }
    assert!(!graph.is_zero(m[0][1]) && !graph.is_zero(m[3][4]));
}

#[test]
fn massless_intermediate_link() {
    let path = fixture("massless_link.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    let gimbal = &model.links[2];
    assert_eq!(gimbal.name, "gimbal");
    assert!(model.graph.is_zero(gimbal.mass));
    assert!(gimbal
        .inertia
        .iter()
        .flatten()
        .all(|&i| model.graph.is_zero(i)));
}

#[test]
fn prismatic_joints() {
    let path = fixture("prismatic.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    let kinds: Vec<JointKind> = model.links.iter().map(|l| l.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Fixed,
            JointKind::Prismatic,
            JointKind::Revolute,
            JointKind::Prismatic,
            JointKind::Revolute,
            JointKind::Prismatic
        ]
    );
}

#[test]
fn the_handwritten_robot() {
    agrees_with_the_oracle(&fixture("handwritten.urdf"));
    let model = load(&fixture("handwritten.urdf"));
    assert_eq!(
        model.joint_names(),
        ["shoulder", "elbow", "slide", "camera_pan", "camera_tilt"]
    );
}

#[test]
fn ur5() {
    let path = builtin("ur5.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    assert_eq!(model.name, "ur5");
    assert_eq!(
        model.joint_names(),
        [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint"
        ]
    );
    // world (the root) and base_link (fixed to it) are fixed links the dynamics drop; ee_link
    // is a fixed link behind wrist_3_link.
    let names: Vec<&str> = model.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "world",
            "base_link",
            "shoulder_link",
            "upper_arm_link",
            "forearm_link",
            "wrist_1_link",
            "wrist_2_link",
            "wrist_3_link",
            "ee_link"
        ]
    );
    assert_eq!(model.links[0].parent, None);
    assert_eq!(model.links[0].kind, JointKind::Fixed);
    assert_eq!(model.links[1].kind, JointKind::Fixed);
    assert_eq!(model.links[8].kind, JointKind::Fixed);
    assert_eq!(SymbolicDynamics::new(&model).model.links.len(), 6);
    assert!(model.parameters.is_empty());
}

#[test]
fn panda_with_hand_and_fingers() {
    let path = builtin("panda.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    let mut joints: Vec<String> = (1..=7).map(|k| format!("panda_joint{k}")).collect();
    joints.extend(["panda_finger_joint1".into(), "panda_finger_joint2".into()]);
    assert_eq!(model.joint_names(), joints);
    // Both fingers hang off the hand, a fixed link on the fixed flange.
    let index = |name: &str| model.links.iter().position(|l| l.name == name).unwrap();
    let hand = index("panda_hand");
    assert_eq!(model.links[hand].kind, JointKind::Fixed);
    assert_eq!(model.links[hand].parent, Some(index("panda_link8")));
    assert_eq!(model.links[index("panda_leftfinger")].parent, Some(hand));
    assert_eq!(model.links[index("panda_rightfinger")].parent, Some(hand));
    // The fingers are on different branches: M[7][8] is structurally zero.
    let mut dynamics = SymbolicDynamics::new(&model);
    assert_eq!(dynamics.model.links.len(), 9);
    let m = dynamics.mass_matrix();
    assert!(dynamics.model.graph.is_zero(m[7][8]));
}

#[test]
fn panda_arm() {
    let path = builtin("panda-arm.urdf");
    agrees_with_the_oracle(&path);
    let model = load(&path);
    assert_eq!(model.dof(), 7);
    assert_eq!(
        model.links.last().map(|l| l.name.as_str()),
        Some("panda_link8")
    );
}

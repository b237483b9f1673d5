//! A URDF and the same robot written another way give the same dynamics:
//! - `handwritten.urdf` and `handwritten.toml` (issue 4): the same expressions, node for node,
//!   for the model and for every quantity the kernels are generated from, in the same graph;
//! - `fixed_link.urdf` and the same robot with its fixed link merged into its parent by hand
//!   (mass, COM, parallel-axis inertia, re-placed child, computed here in plain f64): the same
//!   numbers.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{ExprGraph, Id, Node, RobotModel, Symbol, SymbolicDynamics};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/urdf_fixtures")
        .join(name)
}

fn load(path: &Path) -> RobotModel {
    read_robot(Description::file(path), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Whether `a` in `ga` and `b` in `gb` are the same expression, node for node (memoised on
/// pairs, so shared subexpressions are compared once).
struct SameExpression<'g> {
    ga: &'g ExprGraph,
    gb: &'g ExprGraph,
    memo: HashMap<(Id, Id), bool>,
}

impl SameExpression<'_> {
    fn same(&mut self, a: Id, b: Id) -> bool {
        if let Some(&known) = self.memo.get(&(a, b)) {
            return known;
        }
        let result = match (self.ga.node(a), self.gb.node(b)) {
            (Node::Const(x), Node::Const(y)) => x.value().to_bits() == y.value().to_bits(),
            (Node::Symbol(x), Node::Symbol(y)) => x == y,
            (Node::Add(a1, a2), Node::Add(b1, b2))
            | (Node::Mul(a1, a2), Node::Mul(b1, b2))
            | (Node::Div(a1, a2), Node::Div(b1, b2)) => self.same(a1, b1) && self.same(a2, b2),
            (Node::Neg(x), Node::Neg(y))
            | (Node::Sin(x), Node::Sin(y))
            | (Node::Cos(x), Node::Cos(y))
            | (Node::Sqrt(x), Node::Sqrt(y))
            | (Node::Sign(x), Node::Sign(y)) => self.same(x, y),
            _ => false,
        };
        self.memo.insert((a, b), result);
        result
    }

    fn all(&mut self, what: &str, a: &[Id], b: &[Id]) {
        assert_eq!(a.len(), b.len(), "{what}");
        for (k, (&x, &y)) in a.iter().zip(b).enumerate() {
            assert!(
                self.same(x, y),
                "{what}[{k}] differs: {x} in the URDF's graph, {y} in the TOML's"
            );
        }
    }
}

/// Every expression of a model link, in a fixed order.
fn link_expressions(model: &RobotModel) -> Vec<Id> {
    let mut ids = model.gravity.to_vec();
    for link in &model.links {
        ids.extend(link.rotation.iter().flatten());
        ids.extend(link.translation);
        ids.extend(link.axis);
        ids.push(link.mass);
        ids.extend(link.com);
        ids.extend(link.inertia.iter().flatten());
    }
    ids
}

/// τ, M, C, g, the bias, forward dynamics and the energies: what the kernels are made of.
fn dynamics_expressions(dynamics: &mut SymbolicDynamics) -> Vec<Id> {
    let mut ids = dynamics.inverse_dynamics();
    ids.extend(dynamics.mass_matrix().into_iter().flatten());
    ids.extend(dynamics.coriolis_matrix().into_iter().flatten());
    ids.extend(dynamics.gravity_torques());
    ids.extend(dynamics.bias_torques());
    ids.extend(dynamics.forward_dynamics());
    ids.push(dynamics.kinetic_energy());
    ids.push(dynamics.potential_energy());
    ids
}

#[test]
fn a_handwritten_urdf_and_the_same_robot_as_a_toml_spec_give_identical_kernels() {
    let urdf = load(&fixture("handwritten.urdf"));
    let toml = load(&fixture("handwritten.toml"));
    assert_eq!(urdf.name, toml.name);
    assert_eq!(urdf.joint_names(), toml.joint_names());
    assert_eq!(urdf.joints, toml.joints);
    let structure = |m: &RobotModel| -> Vec<_> {
        m.links
            .iter()
            .map(|l| (l.name.clone(), l.parent, l.kind, l.joint))
            .collect()
    };
    assert_eq!(structure(&urdf), structure(&toml));
    let mut same = SameExpression {
        ga: &urdf.graph,
        gb: &toml.graph,
        memo: HashMap::new(),
    };
    same.all("model", &link_expressions(&urdf), &link_expressions(&toml));

    let mut urdf_dynamics = SymbolicDynamics::new(&urdf);
    let mut toml_dynamics = SymbolicDynamics::new(&toml);
    let a = dynamics_expressions(&mut urdf_dynamics);
    let b = dynamics_expressions(&mut toml_dynamics);
    let mut same = SameExpression {
        ga: &urdf_dynamics.model.graph,
        gb: &toml_dynamics.model.graph,
        memo: HashMap::new(),
    };
    same.all("dynamics", &a, &b);
    // Stronger: the two graphs are the same, node for node and id for id, so the code
    // generated from them is too.
    assert_eq!(a, b);
    let (ga, gb) = (&urdf_dynamics.model.graph, &toml_dynamics.model.graph);
    assert_eq!(ga.len(), gb.len());
    for id in ga.reachable(&a) {
        assert_eq!(ga.node(id), gb.node(id), "node {id}");
    }
}

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

fn rpy(r: f64, p: f64, y: f64) -> M3 {
    let (sr, cr) = r.sin_cos();
    let (sp, cp) = p.sin_cos();
    let (sy, cy) = y.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

fn mat_mul(a: &M3, b: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn mat_vec(a: &M3, v: V3) -> V3 {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn transpose(a: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

/// Roll, pitch, yaw of a rotation `Rz(y) Ry(p) Rx(r)` (away from pitch ±π/2).
fn to_rpy(r: &M3) -> V3 {
    [
        r[2][1].atan2(r[2][2]),
        (-r[2][0]).asin(),
        r[1][0].atan2(r[0][0]),
    ]
}

fn tensor(i: &urdf_rs::Inertia) -> M3 {
    [
        [i.ixx, i.ixy, i.ixz],
        [i.ixy, i.iyy, i.iyz],
        [i.ixz, i.iyz, i.izz],
    ]
}

/// Inertia about `point` of a body of mass `m` with inertia `inertia` about its COM `com`.
fn shifted(inertia: &M3, m: f64, com: V3, point: V3) -> M3 {
    let d = [0, 1, 2].map(|k| com[k] - point[k]);
    let d2: f64 = d.iter().map(|x| x * x).sum();
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let delta = if i == j { d2 } else { 0.0 };
            inertia[i][j] + m * (delta - d[i] * d[j])
        })
    })
}

/// `fixed_link.urdf` with the link `bracket` (behind the fixed joint `bracket_joint`) merged
/// into its parent `l2` by hand, and `l3` re-attached to `l2`.
fn merged_by_hand(text: &str) -> String {
    let mut robot = urdf_rs::read_from_string(text).unwrap();
    let link = |robot: &urdf_rs::Robot, name: &str| {
        robot.links.iter().position(|l| l.name == name).unwrap()
    };
    let joint = |robot: &urdf_rs::Robot, name: &str| {
        robot.joints.iter().position(|j| j.name == name).unwrap()
    };
    let (l2, bracket) = (link(&robot, "l2"), link(&robot, "bracket"));
    let (fixed, f3) = (joint(&robot, "bracket_joint"), joint(&robot, "f3"));
    // The bracket's frame in l2's frame.
    let o = robot.joints[fixed].origin.clone();
    let r_b = rpy(o.rpy[0], o.rpy[1], o.rpy[2]);
    let t_b = o.xyz.0;
    // Both inertials in l2's frame.
    let parent = robot.links[l2].inertial.clone();
    let child = robot.links[bracket].inertial.clone();
    let (m1, m2) = (parent.mass.value, child.mass.value);
    let c1 = parent.origin.xyz.0;
    let i1 = tensor(&parent.inertia); // l2's inertial has rpy 0
    let r_c = mat_mul(
        &r_b,
        &rpy(
            child.origin.rpy[0],
            child.origin.rpy[1],
            child.origin.rpy[2],
        ),
    );
    let c2 = {
        let p = mat_vec(&r_b, child.origin.xyz.0);
        [0, 1, 2].map(|k| p[k] + t_b[k])
    };
    let i2 = mat_mul(&mat_mul(&r_c, &tensor(&child.inertia)), &transpose(&r_c));
    let m = m1 + m2;
    let c = [0, 1, 2].map(|k| (m1 * c1[k] + m2 * c2[k]) / m);
    let a = shifted(&i1, m1, c1, c);
    let b = shifted(&i2, m2, c2, c);
    let total = [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[i][j] + b[i][j]));
    let merged = &mut robot.links[l2].inertial;
    merged.mass.value = m;
    merged.origin.xyz.0 = c;
    merged.inertia = urdf_rs::Inertia {
        ixx: total[0][0],
        ixy: total[0][1],
        ixz: total[0][2],
        iyy: total[1][1],
        iyz: total[1][2],
        izz: total[2][2],
    };
    // f3 now hangs from l2: its origin composed with the bracket's.
    let o3 = robot.joints[f3].origin.clone();
    let r3 = mat_mul(&r_b, &rpy(o3.rpy[0], o3.rpy[1], o3.rpy[2]));
    let t3 = {
        let p = mat_vec(&r_b, o3.xyz.0);
        [0, 1, 2].map(|k| p[k] + t_b[k])
    };
    let f3_joint = &mut robot.joints[f3];
    f3_joint.parent.link = "l2".into();
    f3_joint.origin.xyz.0 = t3;
    f3_joint.origin.rpy.0 = to_rpy(&r3);
    robot.joints.remove(fixed);
    robot.links.remove(bracket);
    urdf_rs::write_to_string(&robot).unwrap()
}

/// τ, M, g evaluated at a state.
fn evaluate(dynamics: &mut SymbolicDynamics, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    let mut ids = dynamics.inverse_dynamics();
    ids.extend(dynamics.mass_matrix().into_iter().flatten());
    ids.extend(dynamics.gravity_torques());
    dynamics.model.graph.eval::<f64>(&ids, |s| match s {
        Symbol::Position(k) => q[k as usize],
        Symbol::Velocity(k) => qd[k as usize],
        Symbol::Acceleration(k) => qdd[k as usize],
        _ => f64::NAN,
    })
}

#[test]
fn a_fixed_link_merged_by_hand_gives_the_same_dynamics() {
    let text = std::fs::read_to_string(fixture("fixed_link.urdf")).unwrap();
    let merged_text = merged_by_hand(&text);
    let options = LoadOptions::default();
    let fixed = read_robot(Description::urdf(&text, "fixed_link.urdf"), &options)
        .unwrap_or_else(|e| panic!("{e}"));
    let merged = read_robot(Description::urdf(&merged_text, "merged.urdf"), &options)
        .unwrap_or_else(|e| panic!("{e}"));
    // The root, l1, l2, the bracket and l3; without the bracket once merged by hand.
    assert_eq!(fixed.links.len(), 5);
    assert_eq!(merged.links.len(), 4);
    assert_eq!(fixed.joint_names(), merged.joint_names());
    let mut a = SymbolicDynamics::new(&fixed);
    let mut b = SymbolicDynamics::new(&merged);
    let states = [
        ([0.3, -0.7, 1.1], [0.5, -1.2, 0.8], [-0.4, 0.9, 1.5]),
        ([-1.9, 2.4, -0.2], [1.1, 0.3, -0.6], [0.2, -0.1, 0.7]),
        ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
    ];
    for (q, qd, qdd) in states {
        let x = evaluate(&mut a, &q, &qd, &qdd);
        let y = evaluate(&mut b, &q, &qd, &qdd);
        let scale = x.iter().fold(1.0, |m: f64, v| m.max(v.abs()));
        for (k, (u, v)) in x.iter().zip(&y).enumerate() {
            assert!(
                (u - v).abs() <= 1e-12 * scale,
                "output {k}: {u} != {v} at q = {q:?}"
            );
        }
    }
}

//! An independent reading of URDF semantics, for checking the importer: forward kinematics
//! straight from the URDF specification on urdf-rs's parse (no code shared with
//! `rne_symbolic::urdf` or the model), then
//!
//! ```text
//! V(q)      = −Σ_links m g·p_c                       (every link, the base's too)
//! T(q, q̇)   = ½ Σ_links (m |ṗ_c|² + ωᵀ I_world ω),   ṗ_c, ω = vee(Ṙ Rᵀ) by central differences
//! M_ij      = T(e_i + e_j) − T(e_i) − T(e_j),  M_ii = 2 T(e_i)   (T is quadratic in q̇)
//! g_i       = ∂V/∂q_i                                 (central differences)
//! ```
//!
//! M(q) and g(q) determine the whole of τ = M q̈ + C q̇ + g (C from M's Christoffel symbols), so
//! matching them checks every part of the import: frames, rpy, axes and their signs, prismatic
//! joints, inertial origins and rotations, fixed links, branches.

#![allow(dead_code)]

use std::collections::HashMap;

use urdf_rs::{JointType, Robot};

pub type V3 = [f64; 3];
pub type M3 = [[f64; 3]; 3];

const GRAVITY: V3 = [0.0, 0.0, -9.81];

fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn mat_vec(a: &M3, v: V3) -> V3 {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn transpose(a: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `Rz(y) Ry(p) Rx(r)`, written out.
pub fn rpy(r: f64, p: f64, y: f64) -> M3 {
    let (sr, cr) = r.sin_cos();
    let (sp, cp) = p.sin_cos();
    let (sy, cy) = y.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// Rotation by `angle` about the unit vector `u` (Rodrigues).
fn axis_angle(u: V3, angle: f64) -> M3 {
    let (s, c) = angle.sin_cos();
    let k = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let identity = if i == j { 1.0 } else { 0.0 };
            r[i][j] = c * identity + (1.0 - c) * u[i] * u[j] + s * k[i][j];
        }
    }
    r
}

/// A URDF robot with its joint variables in a given order.
pub struct Oracle {
    robot: Robot,
    /// Joint variable index of each joint (by index in `robot.joints`), `None` for fixed joints.
    variable: Vec<Option<usize>>,
    /// Joints in an order where a joint's parent link is placed before it.
    order: Vec<usize>,
    link_index: HashMap<String, usize>,
    root: usize,
    dof: usize,
}

/// Placement of every link in the root frame: rotation and origin.
type Poses = Vec<(M3, V3)>;

impl Oracle {
    /// Parses `urdf`; `joints` are the joint variable names in the model's order.
    pub fn new(urdf: &str, joints: &[String]) -> Oracle {
        let robot = urdf_rs::read_from_string(urdf).expect("valid URDF");
        let link_index: HashMap<String, usize> = robot
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| (l.name.clone(), i))
            .collect();
        let children: Vec<usize> = robot
            .joints
            .iter()
            .map(|j| link_index[&j.child.link])
            .collect();
        let root = (0..robot.links.len())
            .find(|l| !children.contains(l))
            .expect("a root");
        let variable = robot
            .joints
            .iter()
            .map(|j| match j.joint_type {
                JointType::Fixed => None,
                _ => Some(
                    joints
                        .iter()
                        .position(|n| *n == j.name)
                        .unwrap_or_else(|| panic!("joint {} not in the model", j.name)),
                ),
            })
            .collect();
        // From the root down: a joint comes after the joint that places its parent link.
        let mut order = Vec::new();
        let mut frontier = vec![root];
        while let Some(link) = frontier.pop() {
            for (j, joint) in robot.joints.iter().enumerate() {
                if link_index[&joint.parent.link] == link {
                    order.push(j);
                    frontier.push(link_index[&joint.child.link]);
                }
            }
        }
        Oracle {
            robot,
            variable,
            order,
            link_index,
            root,
            dof: joints.len(),
        }
    }

    fn poses(&self, q: &[f64]) -> Poses {
        let mut poses = vec![([[0.0; 3]; 3], [0.0; 3]); self.robot.links.len()];
        poses[self.root] = (
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [0.0; 3],
        );
        for &j in &self.order {
            let joint = &self.robot.joints[j];
            let (r_p, p_p) = poses[self.link_index[&joint.parent.link]];
            let o = &joint.origin;
            let r_o = rpy(o.rpy[0], o.rpy[1], o.rpy[2]);
            let mut r = mat_mul(&r_p, &r_o);
            let mut p = add(p_p, mat_vec(&r_p, o.xyz.0));
            if let Some(k) = self.variable[j] {
                let a = joint.axis.xyz.0;
                let length = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
                let u = a.map(|x| x / length);
                match joint.joint_type {
                    JointType::Prismatic => p = add(p, mat_vec(&r, u.map(|x| x * q[k]))),
                    _ => r = mat_mul(&r, &axis_angle(u, q[k])),
                }
            }
            poses[self.link_index[&joint.child.link]] = (r, p);
        }
        poses
    }

    /// COM in the root frame and inertia about it in root axes, of every link.
    fn inertials(&self, q: &[f64]) -> Vec<(f64, V3, M3)> {
        self.poses(q)
            .iter()
            .zip(&self.robot.links)
            .map(|((r, p), link)| {
                let inertial = &link.inertial;
                let o = &inertial.origin;
                let i = &inertial.inertia;
                let tensor = [
                    [i.ixx, i.ixy, i.ixz],
                    [i.ixy, i.iyy, i.iyz],
                    [i.ixz, i.iyz, i.izz],
                ];
                let r_in = mat_mul(r, &rpy(o.rpy[0], o.rpy[1], o.rpy[2]));
                let world = mat_mul(&mat_mul(&r_in, &tensor), &transpose(&r_in));
                (inertial.mass.value, add(*p, mat_vec(r, o.xyz.0)), world)
            })
            .collect()
    }

    /// V(q) = −Σ m g·p_c over every link.
    pub fn potential_energy(&self, q: &[f64]) -> f64 {
        self.inertials(q)
            .iter()
            .map(|(m, c, _)| -m * (0..3).map(|k| GRAVITY[k] * c[k]).sum::<f64>())
            .sum()
    }

    /// T(q, q̇) from central differences of the poses along q̇.
    pub fn kinetic_energy(&self, q: &[f64], qd: &[f64]) -> f64 {
        let h = 1e-5;
        let shifted = |s: f64| -> Vec<f64> { q.iter().zip(qd).map(|(q, v)| q + s * v).collect() };
        let (plus_poses, minus_poses) = (self.poses(&shifted(h)), self.poses(&shifted(-h)));
        let (plus, minus) = (self.inertials(&shifted(h)), self.inertials(&shifted(-h)));
        let now = self.inertials(q);
        let poses = self.poses(q);
        let mut energy = 0.0;
        for l in 0..self.robot.links.len() {
            let (m, _, inertia) = now[l];
            let v: V3 = [0, 1, 2].map(|k| (plus[l].1[k] - minus[l].1[k]) / (2.0 * h));
            let r = poses[l].0;
            let rdot: M3 = [0, 1, 2].map(|i| {
                [0, 1, 2].map(|j| (plus_poses[l].0[i][j] - minus_poses[l].0[i][j]) / (2.0 * h))
            });
            let w_hat = mat_mul(&rdot, &transpose(&r));
            let w = [w_hat[2][1], w_hat[0][2], w_hat[1][0]];
            let iw = mat_vec(&inertia, w);
            let vv: f64 = v.iter().map(|x| x * x).sum();
            energy += 0.5 * (m * vv + (0..3).map(|k| w[k] * iw[k]).sum::<f64>());
        }
        energy
    }

    /// M(q) by polarisation of the kinetic energy.
    pub fn mass_matrix(&self, q: &[f64]) -> Vec<Vec<f64>> {
        let n = self.dof;
        let unit = |i: usize, j: usize| -> Vec<f64> {
            (0..n)
                .map(|k| if k == i || k == j { 1.0 } else { 0.0 })
                .collect()
        };
        let t: Vec<f64> = (0..n)
            .map(|i| self.kinetic_energy(q, &unit(i, i)))
            .collect();
        let mut m = vec![vec![0.0; n]; n];
        for i in 0..n {
            m[i][i] = 2.0 * t[i];
            for j in 0..i {
                let both = self.kinetic_energy(q, &unit(i, j));
                m[i][j] = both - t[i] - t[j];
                m[j][i] = m[i][j];
            }
        }
        m
    }

    /// g(q) = ∂V/∂q by central differences.
    pub fn gravity_torques(&self, q: &[f64]) -> Vec<f64> {
        let h = 1e-6;
        (0..self.dof)
            .map(|i| {
                let mut plus = q.to_vec();
                let mut minus = q.to_vec();
                plus[i] += h;
                minus[i] -= h;
                (self.potential_energy(&plus) - self.potential_energy(&minus)) / (2.0 * h)
            })
            .collect()
    }
}

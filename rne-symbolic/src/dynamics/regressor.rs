//! The joint-torque regressor: τ = Y(q, q̇, q̈) π, linear in the standard inertial parameters
//! (Atkeson, An & Hollerbach, "Estimation of inertial parameters of manipulator loads and
//! links", IJRR 1986; Pinocchio's `computeJointTorqueRegressor` order, docs/design.md §4.4).
//!
//! Per moving body, in model order: `m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, with
//! c the centre of mass and I the inertia about the body frame's origin, in body axes; then
//! per joint, in link order, its friction coefficients `fv, fc, f0` when friction is included
//! and the joint has friction ([`super::friction`]), and its armature `Ia` when it has one.
//! A body's wrench at its origin
//! is linear in its parameters,
//!
//! ```text
//! f = m a + α × h + ω × (ω × h),      n = I α + ω × (I ω) + h × a      (h = m c),
//! ```
//!
//! with ω, α and the classical acceleration a of its origin (gravity included) from the
//! forward Newton–Euler recursion; column (body i, parameter p) is the wrench of a unit p
//! carried down to the base and projected on every joint it passes, as in the
//! composite-rigid-body algorithm.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::RobotModel;
use crate::motion::{JointMotion, LinkPlacement};
use crate::newton_euler::newton_euler;

use super::crba::columns;
use super::friction::{friction_joint, FRICTION_PARAMETER_NAMES};

/// Inertial parameters per body.
pub const PARAMETERS_PER_BODY: usize = 10;

/// The names of one body's parameters, in Pinocchio's order.
pub const BODY_PARAMETER_NAMES: [&str; PARAMETERS_PER_BODY] = [
    "m", "mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// The (row, column) pairs of the symmetric inertia entries `Ixx, Ixy, Iyy, Ixz, Iyz, Izz`.
const INERTIA_ENTRIES: [(usize, usize); 6] = [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)];

/// One column of the regressor: which body or joint it belongs to and which parameter.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RegressorColumn {
    /// Inertial parameter `parameter` (index into [`BODY_PARAMETER_NAMES`]) of a body (a link
    /// of the merged model).
    Body {
        /// The link index.
        link: usize,
        /// The parameter.
        parameter: usize,
    },
    /// Friction coefficient `parameter` (index into [`FRICTION_PARAMETER_NAMES`]) of a link's
    /// joint.
    Friction {
        /// The link index.
        link: usize,
        /// The coefficient.
        parameter: usize,
    },
    /// The armature of a link's joint.
    Armature {
        /// The link index.
        link: usize,
    },
}

impl RegressorColumn {
    /// The parameter's name: `link.m`, `link.mcx`, ..., `link.fv`, `link.Ia`.
    pub fn name(&self, model: &RobotModel) -> String {
        let (link, parameter) = match *self {
            RegressorColumn::Body { link, parameter } => (link, BODY_PARAMETER_NAMES[parameter]),
            RegressorColumn::Friction { link, parameter } => {
                (link, FRICTION_PARAMETER_NAMES[parameter])
            }
            RegressorColumn::Armature { link } => (link, "Ia"),
        };
        format!("{}.{parameter}", model.links[link].name)
    }
}

/// The columns of the regressor of `model` (merged: every link moves), in order; friction
/// columns only when `friction` is included in the dynamics.
pub fn regressor_columns(model: &RobotModel, friction: bool) -> Vec<RegressorColumn> {
    let mut out: Vec<RegressorColumn> = (0..model.links.len())
        .flat_map(|link| {
            (0..PARAMETERS_PER_BODY).map(move |parameter| RegressorColumn::Body { link, parameter })
        })
        .collect();
    for (link, l) in model.links.iter().enumerate() {
        if l.joint.is_none() {
            continue;
        }
        if friction && l.friction.is_some() {
            out.extend((0..3).map(|parameter| RegressorColumn::Friction { link, parameter }));
        }
        if l.armature.is_some() {
            out.push(RegressorColumn::Armature { link });
        }
    }
    out
}

/// The wrench [f; n] at the body origin of a unit value of parameter `p`.
fn unit_wrench(
    g: &mut ExprGraph,
    p: usize,
    (omega, alpha, accel): (Vec3, Vec3, Vec3),
) -> (Vec3, Vec3) {
    let zero = g.zero_vec();
    match p {
        0 => (accel, zero),
        1..=3 => {
            let mut e = [0.0; 3];
            e[p - 1] = 1.0;
            let e = g.const_vec(e);
            let tangential = g.cross(alpha, e);
            let spin = g.cross(omega, e);
            let centripetal = g.cross(omega, spin);
            (g.vadd(tangential, centripetal), g.cross(e, accel))
        }
        _ => {
            let (a, b) = INERTIA_ENTRIES[p - 4];
            let (z, o) = (g.zero(), g.one());
            let mut unit: Mat3 = [[z; 3]; 3];
            unit[a][b] = o;
            unit[b][a] = o;
            let e_alpha = g.mat_vec(&unit, alpha);
            let e_omega = g.mat_vec(&unit, omega);
            let gyroscopic = g.cross(omega, e_omega);
            (zero, g.vadd(e_alpha, gyroscopic))
        }
    }
}

/// Y(q, q̇, q̈), NV rows, the columns of [`regressor_columns`], at `motion` with `gravity`.
pub fn regressor(
    model: &mut RobotModel,
    motion: &JointMotion,
    gravity: Vec3,
    friction: bool,
) -> Vec<Vec<Id>> {
    let kinematics = newton_euler(model, motion, gravity).motion;
    let columns_of_link = columns(model);
    let layout = model.state_layout();
    let nv = layout.nv();
    let layout_columns = regressor_columns(model, friction);
    let g = &mut model.graph;
    let links = &model.links;
    let placements = LinkPlacement::all(g, links, motion);
    let mut terms: Vec<Vec<Vec<Id>>> = vec![vec![Vec::new(); layout_columns.len()]; nv];
    for (column, entry) in layout_columns.iter().enumerate() {
        match *entry {
            RegressorColumn::Body { link, parameter } => {
                let m = kinematics[link];
                let (mut force, mut moment) =
                    unit_wrench(g, parameter, (m.omega, m.alpha, m.accel));
                let mut j = link;
                loop {
                    for cb in &columns_of_link[j] {
                        let along = if cb.angular { moment } else { force };
                        let mut value = g.dot(cb.axis, along);
                        if let Some(multiplier) = cb.multiplier {
                            value = g.mul(multiplier, value);
                        }
                        terms[cb.index][column].push(value);
                    }
                    let Some(p) = links[j].parent else { break };
                    let f = placements[j].to_parent(g, force);
                    let n = placements[j].to_parent(g, moment);
                    let lever = g.cross(placements[j].attachment, f);
                    moment = g.vadd(n, lever);
                    force = f;
                    j = p;
                }
            }
            RegressorColumn::Friction { link, parameter } => {
                let Some(joint) = friction_joint(g, &links[link], &motion.qd, 0) else {
                    continue;
                };
                // f_v rate, f_c sign(rate) or f0, times the multiplier of a mimic follower.
                let mut value = match parameter {
                    0 => joint.rate,
                    1 => g.sign(joint.rate),
                    _ => g.one(),
                };
                if let Some(m) = joint.multiplier {
                    value = g.mul(m, value);
                }
                terms[layout.v_offset() + joint.index][column].push(value);
            }
            RegressorColumn::Armature { link } => {
                let (Some(joint), Some(cb)) = (links[link].joint, columns_of_link[link].first())
                else {
                    continue;
                };
                // I_a q̈ of the link's coordinate, projected: m² q̈_joint.
                let mut value = motion.qdd[joint];
                if let Some(multiplier) = cb.multiplier {
                    let squared = g.mul(multiplier, multiplier);
                    value = g.mul(squared, value);
                }
                terms[cb.index][column].push(value);
            }
        }
    }
    terms
        .into_iter()
        .map(|row| row.into_iter().map(|t| g.sum(t)).collect())
        .collect()
}

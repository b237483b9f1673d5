//! Kinetic and potential energy from link velocities and positions.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{axis_angle_rotation, JointKind, Link, RobotModel};

/// R_i^p(q) and the position of B_i's origin in B_p for every link.
fn placements(g: &mut ExprGraph, links: &[Link], q: &[Id]) -> Vec<(Mat3, Vec3)> {
    links
        .iter()
        .map(|link| match (link.kind, link.joint) {
            (JointKind::Revolute, Some(k)) => {
                let (c, s) = (g.cos(q[k]), g.sin(q[k]));
                let motion = axis_angle_rotation(g, link.axis, c, s);
                (g.mat_mul(&link.rotation, &motion), link.translation)
            }
            (JointKind::Prismatic, Some(k)) => {
                let slide = g.vscale(q[k], link.axis);
                let moved = g.mat_vec(&link.rotation, slide);
                (link.rotation, g.vadd(link.translation, moved))
            }
            _ => (link.rotation, link.translation),
        })
        .collect()
}

/// T = ½ Σ_i (m_i v_ci · v_ci + ω_iᵀ I_i ω_i), with ω_i from (3.26) and the COM velocity
/// v_ci = v_i + ω_i × r_{i−1,ci} (the velocity form of (3.31)), in body frames.
pub fn kinetic_energy(model: &mut RobotModel, q: &[Id], qd: &[Id]) -> Id {
    let g = &mut model.graph;
    let placements = placements(g, &model.links, q);
    let zero = g.zero_vec();
    let mut velocities: Vec<(Vec3, Vec3)> = Vec::with_capacity(model.links.len());
    let mut twice_energy = Vec::new();
    for (i, link) in model.links.iter().enumerate() {
        let (omega_p, v_p) = link.parent.map_or((zero, zero), |p| velocities[p]);
        let (r, s) = placements[i];
        // Velocity of the parent's material point at s, rotated into frame i.
        let transport = g.cross(omega_p, s);
        let v_point = g.vadd(v_p, transport);
        let mut v = g.mat_t_vec(&r, v_point);
        let mut omega = g.mat_t_vec(&r, omega_p);
        if let Some(k) = link.joint {
            let rate = g.vscale(qd[k], link.axis);
            match link.kind {
                JointKind::Revolute => omega = g.vadd(omega, rate),
                JointKind::Prismatic => v = g.vadd(v, rate),
                JointKind::Fixed | JointKind::FreeFlyer => {}
            }
        }
        let spin = g.cross(omega, link.com);
        let v_com = g.vadd(v, spin);
        let translational = g.dot(v_com, v_com);
        let translational = g.mul(link.mass, translational);
        let i_omega = g.mat_vec(&link.inertia, omega);
        let rotational = g.dot(omega, i_omega);
        twice_energy.push(g.add(translational, rotational));
        velocities.push((omega, v));
    }
    let total = g.sum(twice_energy);
    let half = g.constant(0.5);
    g.mul(half, total)
}

/// V = −Σ_i m_i g_0 · p_ci, with p_ci the COM of link i in the base frame.
pub fn potential_energy(model: &mut RobotModel, q: &[Id]) -> Id {
    let g = &mut model.graph;
    let placements = placements(g, &model.links, q);
    let mut poses: Vec<(Mat3, Vec3)> = Vec::with_capacity(model.links.len());
    let mut terms = Vec::new();
    for (i, link) in model.links.iter().enumerate() {
        let (r, s) = placements[i];
        let pose = match link.parent {
            Some(p) => {
                let (rp, pp) = poses[p];
                let rotation = g.mat_mul(&rp, &r);
                let moved = g.mat_vec(&rp, s);
                (rotation, g.vadd(pp, moved))
            }
            None => (r, s),
        };
        let com = {
            let rotated = g.mat_vec(&pose.0, link.com);
            g.vadd(pose.1, rotated)
        };
        let height = g.dot(model.gravity, com);
        terms.push(g.mul(link.mass, height));
        poses.push(pose);
    }
    let total = g.sum(terms);
    g.neg(total)
}

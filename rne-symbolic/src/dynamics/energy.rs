//! Link velocities and world poses, and the kinetic and potential energy built from them.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{JointKind, Link, RobotModel};
use crate::motion::{JointMotion, LinkCoordinate, LinkPlacement};

/// R_i^p(q) and the position of B_i's origin in B_p for every link.
fn placements(g: &mut ExprGraph, links: &[Link], motion: &JointMotion) -> Vec<(Mat3, Vec3)> {
    LinkPlacement::all(g, links, motion)
        .iter()
        .map(|p| (p.rotation(g), p.attachment))
        .collect()
}

/// Every link's angular velocity ω_i (3.26) and the velocity of its body origin v_i, in its
/// body frame: the parent's, carried to the attachment point and rotated, plus the joint's
/// rate along or about its axis; a free-flyer's are its coordinates.
pub(super) fn link_velocities(
    g: &mut ExprGraph,
    links: &[Link],
    motion: &JointMotion,
) -> Vec<(Vec3, Vec3)> {
    let placements = placements(g, links, motion);
    let zero = g.zero_vec();
    let mut velocities: Vec<(Vec3, Vec3)> = Vec::with_capacity(links.len());
    for (i, link) in links.iter().enumerate() {
        let (omega_p, v_p) = link.parent.map_or((zero, zero), |p| velocities[p]);
        let (r, s) = placements[i];
        // Velocity of the parent's material point at s, rotated into frame i.
        let transport = g.cross(omega_p, s);
        let v_point = g.vadd(v_p, transport);
        let mut v = g.mat_t_vec(&r, v_point);
        let mut omega = g.mat_t_vec(&r, omega_p);
        if let Some(c) = LinkCoordinate::of(g, link, motion) {
            let rate = g.vscale(c.qd, link.axis);
            match link.kind {
                JointKind::Prismatic => v = g.vadd(v, rate),
                _ => omega = g.vadd(omega, rate),
            }
        }
        if let (JointKind::FreeFlyer, Some(base)) = (link.kind, motion.base) {
            let [vx, vy, vz, wx, wy, wz] = base.velocity;
            v = [vx, vy, vz];
            omega = [wx, wy, wz];
        }
        velocities.push((omega, v));
    }
    velocities
}

/// Every link's orientation and origin in the world (base) frame.
pub(super) fn link_poses(
    g: &mut ExprGraph,
    links: &[Link],
    motion: &JointMotion,
) -> Vec<(Mat3, Vec3)> {
    let placements = placements(g, links, motion);
    let mut poses: Vec<(Mat3, Vec3)> = Vec::with_capacity(links.len());
    for (i, link) in links.iter().enumerate() {
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
        poses.push(pose);
    }
    poses
}

/// T = ½ Σ_i (m_i v_ci · v_ci + ω_iᵀ I_i ω_i + I_a,i q̇_i²), with ω_i from (3.26), the COM
/// velocity v_ci = v_i + ω_i × r_{i−1,ci} (the velocity form of (3.31)) in body frames, and
/// the rotor of a joint with armature spinning at its rate.
pub fn kinetic_energy(model: &mut RobotModel, motion: &JointMotion) -> Id {
    let g = &mut model.graph;
    let velocities = link_velocities(g, &model.links, motion);
    let mut twice_energy = Vec::new();
    for (link, &(omega, v)) in model.links.iter().zip(&velocities) {
        let spin = g.cross(omega, link.com);
        let v_com = g.vadd(v, spin);
        let translational = g.dot(v_com, v_com);
        let translational = g.mul(link.mass, translational);
        let i_omega = g.mat_vec(&link.inertia, omega);
        let rotational = g.dot(omega, i_omega);
        twice_energy.push(g.add(translational, rotational));
    }
    for link in &model.links {
        if let (Some(armature), Some(c)) = (link.armature, LinkCoordinate::of(g, link, motion)) {
            let rate_squared = g.square(c.qd);
            twice_energy.push(g.mul(armature, rate_squared));
        }
    }
    let total = g.sum(twice_energy);
    let half = g.constant(0.5);
    g.mul(half, total)
}

/// V = −Σ_i m_i g_0 · p_ci, with p_ci the COM of link i in the base frame.
pub fn potential_energy(model: &mut RobotModel, motion: &JointMotion) -> Id {
    let g = &mut model.graph;
    let poses = link_poses(g, &model.links, motion);
    let mut terms = Vec::new();
    for (link, (rotation, origin)) in model.links.iter().zip(&poses) {
        let com = {
            let rotated = g.mat_vec(rotation, link.com);
            g.vadd(*origin, rotated)
        };
        let height = g.dot(model.gravity, com);
        terms.push(g.mul(link.mass, height));
    }
    let total = g.sum(terms);
    g.neg(total)
}

//! The dynamics written in the standard inertial parameters themselves: per body its mass m,
//! first moment h = m c and inertia I about the body origin, each an expression of its own
//! (docs/design.md §4.4's π, Pinocchio's `computeJointTorqueRegressor` order).
//!
//! The chapter 3 recursion works with the centre of mass c and the inertia about it, so a body
//! whose parameters are free expressions would need c = h / m and a division by a parameter.
//! In h and the inertia about the origin every quantity is a polynomial, linear in π: the
//! wrench a body needs at its origin is (Atkeson, An and Hollerbach, IJRR 1986, eq. (9)–(10))
//!
//! ```text
//! f = m a + α × h + ω × (ω × h),      n = I α + ω × (I ω) + h × a,
//! ```
//!
//! with ω, α and the classical acceleration a of the origin (gravity included) from the
//! forward recursion (3.26), (3.30), (3.35); the backward recursion (3.21), (3.24) then carries
//! these wrenches to the joints unchanged. The energies follow from the same parameters:
//! `2T = m v·v + 2 v·(ω × h) + ωᵀ I ω` and `V = −g₀·(m p + R h)`. This is what lets a particular
//! solution π = P π_b of the base parameters, which gives some bodies zero mass but a first
//! moment, be substituted into the dynamics ([`super::SymbolicDynamics::with_standard_parameters`]).

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{Link, RobotModel};
use crate::motion::{JointMotion, LinkCoordinate, LinkPlacement};
use crate::newton_euler::{
    backward_recursion, generalised_forces, newton_euler, LinkMotion, NewtonEuler,
};

use super::crba::about_origin;
use super::energy::{link_poses, link_velocities};

/// One body's standard inertial parameters: mass, first moment h = m c and the symmetric
/// inertia about the body origin, in body-frame axes.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct BodyParameters {
    /// m.
    pub mass: Id,
    /// h = m c.
    pub first_moment: Vec3,
    /// I about the body origin (the same `Id` at (i, j) and (j, i)).
    pub inertia: Mat3,
}

impl BodyParameters {
    /// The parameters of a link as read: its mass, `m c` and its inertia moved from the COM to
    /// the origin by the parallel-axis theorem.
    pub fn of_link(g: &mut ExprGraph, link: &Link) -> BodyParameters {
        let (first_moment, inertia) = about_origin(g, link.mass, link.com, &link.inertia);
        BodyParameters {
            mass: link.mass,
            first_moment,
            inertia,
        }
    }

    /// The body from ten standard parameters in Pinocchio's order
    /// `m, mcx, mcy, mcz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`.
    pub fn from_standard(p: [Id; 10]) -> BodyParameters {
        let [m, hx, hy, hz, xx, xy, yy, xz, yz, zz] = p;
        BodyParameters {
            mass: m,
            first_moment: [hx, hy, hz],
            inertia: [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]],
        }
    }

    /// The wrench [f; n] at the body origin that moves the body with `motion`.
    fn wrench(&self, g: &mut ExprGraph, motion: &LinkMotion) -> (Vec3, Vec3) {
        let (omega, alpha, a) = (motion.omega, motion.alpha, motion.accel);
        let h = self.first_moment;
        let linear = g.vscale(self.mass, a);
        let tangential = g.cross(alpha, h);
        let spin = g.cross(omega, h);
        let centripetal = g.cross(omega, spin);
        let force = {
            let f = g.vadd(linear, tangential);
            g.vadd(f, centripetal)
        };
        let i_alpha = g.mat_vec(&self.inertia, alpha);
        let i_omega = g.mat_vec(&self.inertia, omega);
        let gyroscopic = g.cross(omega, i_omega);
        let lever = g.cross(h, a);
        let moment = {
            let n = g.vadd(i_alpha, gyroscopic);
            g.vadd(n, lever)
        };
        (force, moment)
    }
}

/// The recursion of [`newton_euler`] with the bodies' wrenches from `bodies` (one per link of
/// `model`): the same motion, reactions about the same origins and generalised forces
/// (armature and mimic projections included), as polynomials in the parameters.
pub(super) fn inverse_dynamics(
    model: &mut RobotModel,
    motion: &JointMotion,
    gravity: Vec3,
    bodies: &[BodyParameters],
) -> NewtonEuler {
    let kinematics = newton_euler(model, motion, gravity).motion;
    let layout = model.state_layout();
    let g = &mut model.graph;
    let links = &model.links;
    let placements = LinkPlacement::all(g, links, motion);
    // (3.21) and (3.24) about the body origin: each body's own wrench, then its children's.
    let reactions = backward_recursion(g, links, &placements, |g, i| {
        bodies[i].wrench(g, &kinematics[i])
    });
    let coordinates: Vec<Option<LinkCoordinate>> = links
        .iter()
        .map(|link| LinkCoordinate::of(g, link, motion))
        .collect();
    let torques = generalised_forces(g, links, &reactions, &coordinates, &layout);
    NewtonEuler {
        motion: kinematics,
        reactions,
        torques,
    }
}

/// T = ½ Σ_i (m_i v_i·v_i + 2 v_i·(ω_i × h_i) + ω_iᵀ I_i ω_i + I_a,i q̇_i²) with v_i the velocity
/// of body i's origin: the kinetic energy of [`super::energy::kinetic_energy`] in the standard
/// parameters.
pub(super) fn kinetic_energy(
    model: &mut RobotModel,
    motion: &JointMotion,
    bodies: &[BodyParameters],
) -> Id {
    let g = &mut model.graph;
    let velocities = link_velocities(g, &model.links, motion);
    let mut twice_energy = Vec::new();
    for (body, &(omega, v)) in bodies.iter().zip(&velocities) {
        let vv = g.dot(v, v);
        let translational = g.mul(body.mass, vv);
        let spin = g.cross(omega, body.first_moment);
        let coupling = g.dot(v, spin);
        let two = g.constant(2.0);
        let coupling = g.mul(two, coupling);
        let i_omega = g.mat_vec(&body.inertia, omega);
        let rotational = g.dot(omega, i_omega);
        twice_energy.push(g.sum([translational, coupling, rotational]));
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

/// V = −Σ_i g₀·(m_i p_i + R_i h_i), with p_i and R_i the origin and orientation of body i in the
/// base frame: m_i p_ci = m_i p_i + R_i h_i.
pub(super) fn potential_energy(
    model: &mut RobotModel,
    motion: &JointMotion,
    bodies: &[BodyParameters],
) -> Id {
    let g = &mut model.graph;
    let poses = link_poses(g, &model.links, motion);
    let mut terms = Vec::new();
    for (body, (rotation, origin)) in bodies.iter().zip(&poses) {
        let at_origin = g.vscale(body.mass, *origin);
        let moment = g.mat_vec(rotation, body.first_moment);
        let weighted = g.vadd(at_origin, moment);
        terms.push(g.dot(model.gravity, weighted));
    }
    let total = g.sum(terms);
    g.neg(total)
}

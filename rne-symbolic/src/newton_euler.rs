//! The symbolic Newton–Euler recursion of the thesis's chapter 3, on expression graphs.
//!
//! Every quantity of link i is expressed in its body frame B_i (the orientation of the
//! thesis's frame i, with its origin on joint i's axis; see [`crate::model`]). The forward
//! recursion runs from the base to the leaves, the backward recursion from the leaves to the
//! base; a link may have several children (a kinematic tree), whose forces and torques are
//! summed where the thesis's serial chain has one `R_{i+1}^i f_{i+1}`.
//!
//! Gravity enters as the acceleration of the base, `a_{e,0} = −g_0` (instead of the
//! `−m_i g_i` term of (3.21)): the two are the same equation, and this way gravity needs no
//! recursion of its own. The joint reactions f_i, τ_i therefore include the weight of the
//! links they carry, exactly as in (3.21) and (3.24).

use crate::expr::{ExprGraph, Id, Vec3};
use crate::model::{JointKind, Link, RobotModel, StateLayout};
pub use crate::motion::JointMotion;
use crate::motion::{LinkCoordinate, LinkPlacement};

/// Velocities and accelerations of one link, in its body frame.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct LinkMotion {
    /// Angular velocity ω_i, (3.26).
    pub omega: Vec3,
    /// Angular acceleration α_i, (3.30).
    pub alpha: Vec3,
    /// Acceleration of the body frame's origin (the joint), the thesis's `(R_i^{i−1})ᵀ a_{e,i−1}`
    /// of (3.34)–(3.35), plus the relative motion of a prismatic joint; gravity included as
    /// a base acceleration.
    pub accel: Vec3,
    /// Acceleration of the centre of mass a_{c,i}, (3.34).
    pub accel_com: Vec3,
}

/// The force and torque that the parent exerts on link i at the joint, in the link's body
/// frame: f_i of (3.21) and τ_i of (3.24). Their components off the joint axis are the loads
/// the joint must resist (the thesis, section 5.4).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct JointReaction {
    /// f_i.
    pub force: Vec3,
    /// τ_i.
    pub torque: Vec3,
}

/// Everything one pass of the recursion produces.
#[derive(Clone, Debug)]
pub struct NewtonEuler {
    /// Per link: velocities and accelerations.
    pub motion: Vec<LinkMotion>,
    /// Per link: the joint reaction.
    pub reactions: Vec<JointReaction>,
    /// The generalised forces, the left-hand side of (3.1): per joint variable `u_iᵀ τ_i`
    /// (revolute) or `u_iᵀ f_i` (prismatic), summed over the links it drives with their mimic
    /// multipliers, after the free-flyer's `[f; τ]` (base frame) on a floating base.
    pub torques: Vec<Id>,
}

/// The six products ω_a ω_b (a ≤ b) of an angular velocity, shared by every
/// `ω × (ω × v)` and by `ω × (I ω)` of one link.
#[derive(Copy, Clone, Debug)]
struct OmegaProducts {
    /// [ω0², ω1², ω2²].
    square: [Id; 3],
    /// [ω1 ω2, ω0 ω2, ω0 ω1]: `cross[k]` is the product of the two components other than k.
    cross: [Id; 3],
}

impl OmegaProducts {
    fn new(g: &mut ExprGraph, w: Vec3) -> OmegaProducts {
        OmegaProducts {
            square: [0, 1, 2].map(|k| g.square(w[k])),
            cross: [(1, 2), (0, 2), (0, 1)].map(|(a, b)| g.mul(w[a], w[b])),
        }
    }

    /// ω_a ω_b.
    fn product(&self, a: usize, b: usize) -> Id {
        if a == b {
            self.square[a]
        } else {
            self.cross[3 - a - b]
        }
    }

    /// `ω × (ω × v) = S(ω)² v = ω (ω·v) − |ω|² v` (from (2.6)), written with the shared
    /// products: component k is `Σ_{j≠k} ω_k ω_j v_j − (Σ_{j≠k} ω_j²) v_k`.
    fn centripetal(&self, g: &mut ExprGraph, v: Vec3) -> Vec3 {
        [0, 1, 2].map(|k| {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let pa = g.mul(self.product(k, a), v[a]);
            let pb = g.mul(self.product(k, b), v[b]);
            let squares = g.add(self.square[a], self.square[b]);
            let radial = g.mul(squares, v[k]);
            let along = g.add(pa, pb);
            g.sub(along, radial)
        })
    }

    /// The gyroscopic torque `ω × (I ω)` of a symmetric I, as a combination of the shared
    /// products: component k is `Σ_j (I_{k+2,j} ω_{k+1} ω_j − I_{k+1,j} ω_{k+2} ω_j)`.
    fn gyroscopic(&self, g: &mut ExprGraph, inertia: &crate::expr::Mat3) -> Vec3 {
        [0, 1, 2].map(|k| {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            // Collect the coefficient of each product ω_a ω_j (from ω_a (Iω)_b) minus
            // ω_b ω_j (from ω_b (Iω)_a), merging the product ω_a ω_b that both produce.
            let mut coefficient: Vec<((usize, usize), Id)> = Vec::new();
            let mut add = |g: &mut ExprGraph, pair: (usize, usize), c: Id, negate: bool| {
                let pair = (pair.0.min(pair.1), pair.0.max(pair.1));
                let c = if negate { g.neg(c) } else { c };
                match coefficient.iter_mut().find(|(p, _)| *p == pair) {
                    Some((_, existing)) => *existing = g.add(*existing, c),
                    None => coefficient.push((pair, c)),
                }
            };
            for j in 0..3 {
                add(g, (a, j), inertia[b][j], false);
                add(g, (b, j), inertia[a][j], true);
            }
            let terms: Vec<Id> = coefficient
                .into_iter()
                .map(|((x, y), c)| g.mul(c, self.product(x, y)))
                .collect();
            g.sum(terms)
        })
    }
}

/// Runs the recursion of section 3.4 on `model` for the given joint motion and gravity g_0
/// (base frame): forward (3.26), (3.30), (3.35), (3.34) from the base outwards, backward
/// (3.21), (3.24) from the leaves inwards, with the errata of docs/design.md §7 applied and
/// prismatic joints handled (no angular velocity; `u q̈ + 2 ω × u q̇` added to the linear
/// acceleration). A floating base's free-flyer moves with the motion's base velocity and
/// acceleration (its generalised force is its joint reaction); a mimic follower moves with its
/// coupled coordinate and passes its force to its leader times the multiplier; armature adds
/// `I_a q̈` to a joint's force.
pub fn newton_euler(model: &mut RobotModel, motion: &JointMotion, gravity: Vec3) -> NewtonEuler {
    let layout = model.state_layout();
    let g = &mut model.graph;
    let links = &model.links;

    let placements = LinkPlacement::all(g, links, motion);
    let coordinates: Vec<Option<LinkCoordinate>> = links
        .iter()
        .map(|link| LinkCoordinate::of(g, link, motion))
        .collect();
    let (out, products) = forward_recursion(g, links, &placements, &coordinates, motion, gravity);
    // Backward recursion, leaves first.
    let reactions = backward_recursion(g, links, &placements, |g, i| {
        own_load(g, &links[i], &out[i], &products[i])
    });
    let torques = generalised_forces(g, links, &reactions, &coordinates, &layout);
    NewtonEuler {
        motion: out,
        reactions,
        torques,
    }
}

/// The motion of a link's parent that the forward recursion carries to the link (the base's:
/// at rest, with acceleration −g_0).
#[derive(Copy, Clone)]
struct ParentMotion {
    omega: Vec3,
    alpha: Vec3,
    accel: Vec3,
    products: OmegaProducts,
}

/// A link's joint: its kind and its coordinate q, q̇, q̈ (`None`: fixed, or the coordinates
/// are the free-flyer's).
type JointState = Option<(JointKind, Id, Id, Id)>;

/// The forward recursion, from the base outwards: each link's [`LinkMotion`] and the
/// products of its angular velocity.
fn forward_recursion(
    g: &mut ExprGraph,
    links: &[Link],
    placements: &[LinkPlacement],
    coordinates: &[Option<LinkCoordinate>],
    motion: &JointMotion,
    gravity: Vec3,
) -> (Vec<LinkMotion>, Vec<OmegaProducts>) {
    let n = links.len();
    let zero = g.zero_vec();
    let base_accel = g.vneg(gravity);
    let mut out: Vec<LinkMotion> = Vec::with_capacity(n);
    let mut products: Vec<OmegaProducts> = Vec::with_capacity(n);
    let base = ParentMotion {
        omega: zero,
        alpha: zero,
        accel: base_accel,
        products: OmegaProducts::new(g, zero),
    };
    for (i, link) in links.iter().enumerate() {
        let parent = match link.parent {
            Some(p) => ParentMotion {
                omega: out[p].omega,
                alpha: out[p].alpha,
                accel: out[p].accel,
                products: products[p],
            },
            None => base,
        };
        let joint = coordinates[i].map(|c| (link.kind, c.q, c.qd, c.qdd));
        let (own, own_products) = forward_link(g, link, &placements[i], joint, &parent, motion);
        out.push(own);
        products.push(own_products);
    }
    (out, products)
}

/// One link's step of the forward recursion: (3.26) and (3.30), (3.35) at the attachment,
/// the free-flyer's or the prismatic joint's own motion, then (3.34).
fn forward_link(
    g: &mut ExprGraph,
    link: &Link,
    rot: &LinkPlacement,
    joint: JointState,
    parent: &ParentMotion,
    motion: &JointMotion,
) -> (LinkMotion, OmegaProducts) {
    let (mut omega, mut alpha) = angular_motion(g, link, rot, joint, parent);
    let mut accel = attachment_acceleration(g, link, rot, parent);
    if let (JointKind::FreeFlyer, Some(base)) = (link.kind, motion.base) {
        // The free-flyer's velocity and acceleration are its coordinates' (body frame):
        // ω, ω̇, and the classical acceleration of the origin v̇ + ω × v.
        let [vx, vy, vz, wx, wy, wz] = base.velocity;
        let [ax, ay, az, bx, by, bz] = base.acceleration;
        omega = [wx, wy, wz];
        alpha = [bx, by, bz];
        let transport = g.cross(omega, [vx, vy, vz]);
        accel = g.vadd(accel, [ax, ay, az]);
        accel = g.vadd(accel, transport);
    }
    if let Some((JointKind::Prismatic, q, qd, qdd)) = joint {
        accel = sliding_acceleration(g, link, (omega, alpha, accel), (q, qd, qdd));
    }

    // (3.34): a_{c,i} = a_i + α_i × r_{i−1,ci} + ω_i × (ω_i × r_{i−1,ci}).
    let own_products = OmegaProducts::new(g, omega);
    let c = link.com;
    let tangential = g.cross(alpha, c);
    let centripetal = own_products.centripetal(g, c);
    let accel_com = {
        let a = g.vadd(accel, tangential);
        g.vadd(a, centripetal)
    };
    let own = LinkMotion {
        omega,
        alpha,
        accel,
        accel_com,
    };
    (own, own_products)
}

/// ω_i of (3.26) and α_i of (3.30): the parent's, rotated into frame i, plus the revolute
/// joint's spin.
fn angular_motion(
    g: &mut ExprGraph,
    link: &Link,
    rot: &LinkPlacement,
    joint: JointState,
    parent: &ParentMotion,
) -> (Vec3, Vec3) {
    // (3.26): ω_i = (R_i^{i−1})ᵀ ω_{i−1} + b_i q̇_i.
    let mut omega = rot.to_child(g, parent.omega);
    let mut alpha = rot.to_child(g, parent.alpha);
    if let Some((JointKind::Revolute, _, qd, qdd)) = joint {
        let spin = g.vscale(qd, link.axis);
        omega = g.vadd(omega, spin);
        // (3.30): α_i = (R_i^{i−1})ᵀ α_{i−1} + b_i q̈_i + ω_i × b_i q̇_i.
        let spin_up = g.vscale(qdd, link.axis);
        let gyroscopic = g.cross(omega, spin);
        alpha = g.vadd(alpha, spin_up);
        alpha = g.vadd(alpha, gyroscopic);
    }
    (omega, alpha)
}

/// (3.35) evaluated in the parent for the point where link i is attached, then rotated into
/// frame i: the (R_i^{i−1})ᵀ a_{e,i−1} of (3.34).
fn attachment_acceleration(
    g: &mut ExprGraph,
    link: &Link,
    rot: &LinkPlacement,
    parent: &ParentMotion,
) -> Vec3 {
    let s = link.translation;
    let tangential = g.cross(parent.alpha, s);
    let centripetal = parent.products.centripetal(g, s);
    let attach_accel = {
        let a = g.vadd(parent.accel, tangential);
        g.vadd(a, centripetal)
    };
    rot.to_child(g, attach_accel)
}

/// The acceleration `accel` of a prismatic link's origin plus its slide: the joint moves the
/// body origin by u q along u, so the same rigid-motion terms for that offset, plus the
/// relative acceleration u q̈ and Coriolis 2 ω × u q̇.
fn sliding_acceleration(
    g: &mut ExprGraph,
    link: &Link,
    (omega, alpha, accel): (Vec3, Vec3, Vec3),
    (q, qd, qdd): (Id, Id, Id),
) -> Vec3 {
    let offset = g.vscale(q, link.axis);
    let rate = g.vscale(qd, link.axis);
    let tangential = g.cross(alpha, offset);
    let centripetal = OmegaProducts::new(g, omega).centripetal(g, offset);
    let omega_rate = g.cross(omega, rate);
    let two = g.constant(2.0);
    let coriolis = g.vscale(two, omega_rate);
    let relative = g.vscale(qdd, link.axis);
    let mut accel = accel;
    for term in [tangential, centripetal, coriolis, relative] {
        accel = g.vadd(accel, term);
    }
    accel
}

/// The force and the moment about its origin that link i's own motion needs, the terms of
/// (3.21) and (3.24) before its children's reactions are added.
fn own_load(
    g: &mut ExprGraph,
    link: &Link,
    own: &LinkMotion,
    products: &OmegaProducts,
) -> (Vec3, Vec3) {
    let LinkMotion {
        alpha, accel_com, ..
    } = *own;
    // (3.21): f_i = Σ_c R_c^i f_c + m_i a_{c,i}   (−m_i g_i is inside a_{c,i}).
    let inertial_force = g.vscale(link.mass, accel_com);
    // (3.24): τ_i = Σ_c [R_c^i τ_c + (R_c^i f_c) × r_{i,ci}] − f_i × r_{i−1,ci}
    //             + ω_i × (I_i ω_i) + I_i α_i.
    // With f_i substituted from (3.21) and the cross products regrouped as the thesis
    // does for the planar elbow in (4.36)–(4.41) (r_{i,ci} − r_{i−1,ci} = −r_{i−1,i}):
    //   τ_i = Σ_c [R_c^i τ_c + r_{i−1,c} × R_c^i f_c] + r_{i−1,ci} × m_i a_{c,i}
    //         + ω_i × (I_i ω_i) + I_i α_i,
    // where r_{i−1,c} is the point where child c is attached. Same torque, fewer
    // products: the attachment points are sparse where the COM is not.
    let gyroscopic = products.gyroscopic(g, &link.inertia);
    let i_alpha = g.mat_vec(&link.inertia, alpha);
    let own_moment = g.cross(link.com, inertial_force);
    let torque = g.vadd(gyroscopic, i_alpha);
    (inertial_force, g.vadd(torque, own_moment))
}

/// The backward recursion of (3.21) and (3.24), leaves first (children always come after their
/// parent): link i's reaction is `own(g, i)`, the force and the moment about its origin its
/// own motion needs, plus each child c's reaction carried into frame i, R_c^i f_c and
/// R_c^i τ_c, with the moment r_{i−1,c} × R_c^i f_c of the child's force about the origin
/// (r_{i−1,c} the point where c is attached). On a tree the children's terms are summed where
/// the thesis's serial chain has the single R_{i+1}^i f_{i+1}.
pub(crate) fn backward_recursion(
    g: &mut ExprGraph,
    links: &[Link],
    placements: &[LinkPlacement],
    mut own: impl FnMut(&mut ExprGraph, usize) -> (Vec3, Vec3),
) -> Vec<JointReaction> {
    let n = links.len();
    let mut reactions: Vec<Option<JointReaction>> = vec![None; n];
    for i in (0..n).rev() {
        let (mut force, mut torque) = own(g, i);
        for child in (i + 1..n).filter(|&c| links[c].parent == Some(i)) {
            let reaction = reactions[child].expect("children are processed before their parent");
            let f = placements[child].to_parent(g, reaction.force);
            let t = placements[child].to_parent(g, reaction.torque);
            let moment = g.cross(placements[child].attachment, f);
            force = g.vadd(force, f);
            torque = g.vadd(torque, t);
            torque = g.vadd(torque, moment);
        }
        reactions[i] = Some(JointReaction { force, torque });
    }
    reactions
        .into_iter()
        .map(|r| r.expect("every link was visited"))
        .collect()
}

/// The left-hand side of (3.1) from the joint reactions: per joint variable u_iᵀ τ_i
/// (revolute) or u_iᵀ f_i (prismatic) plus the rotor's reflected inertia I_a q̈ (armature),
/// carried onto the variable by the mimic multiplier and summed over the links it drives,
/// after the free-flyer's [f; τ] on a floating base.
pub(crate) fn generalised_forces(
    g: &mut ExprGraph,
    links: &[Link],
    reactions: &[JointReaction],
    coordinates: &[Option<LinkCoordinate>],
    layout: &StateLayout,
) -> Vec<Id> {
    let mut terms: Vec<Vec<Id>> = vec![Vec::new(); layout.nv()];
    for ((link, reaction), coordinate) in links.iter().zip(reactions).zip(coordinates) {
        if link.kind == JointKind::FreeFlyer {
            for a in 0..3 {
                terms[a].push(reaction.force[a]);
                terms[3 + a].push(reaction.torque[a]);
            }
        }
        if let Some(c) = coordinate {
            let mut along = match link.kind {
                JointKind::Prismatic => g.dot(link.axis, reaction.force),
                _ => g.dot(link.axis, reaction.torque),
            };
            if let Some(armature) = link.armature {
                let rotor = g.mul(armature, c.qdd);
                along = g.add(along, rotor);
            }
            terms[layout.v_offset() + c.variable].push(c.project(g, along));
        }
    }
    terms.into_iter().map(|t| g.sum(t)).collect()
}

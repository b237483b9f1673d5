//! Forward dynamics by the articulated-body algorithm, on expressions (Featherstone, Rigid
//! Body Dynamics Algorithms, table 7.1): linear in the number of links, where M + LᵀDL is
//! cubic, so it wins on long chains.
//!
//! Spatial vectors are `[angular; linear]` (RBDA's order) in each link's joint frame
//! ([`super::aba_frames`]: the body frame turned so that the joint axis is z), where a
//! joint's motion subspace is a unit column; articulated inertias are moved to the parent
//! in 3×3 blocks ([`ArticulatedInertia::to_parent`]). The algorithm applies to one-variable
//! joints on a fixed base; models with a free-flyer or mimic couplings use M + LᵀDL.

use crate::expr::{ExprGraph, Id, Vec3};
use crate::model::{Link, RobotModel};
use crate::motion::{JointMotion, LinkPlacement};

use super::aba_frames::{joint_frames, JointFrame};
use super::articulated_inertia::{ArticulatedInertia, Spatial};
use super::inertial_parameters::BodyParameters;

fn split(x: Spatial) -> (Vec3, Vec3) {
    ([x[0], x[1], x[2]], [x[3], x[4], x[5]])
}

fn join(a: Vec3, b: Vec3) -> Spatial {
    [a[0], a[1], a[2], b[0], b[1], b[2]]
}

/// A parent's motion vector in the child's coordinates: `ω_c = Rᵀ ω`, `v_c = Rᵀ (v + ω × s)`.
fn motion_to_child(g: &mut ExprGraph, p: &LinkPlacement, m: Spatial) -> Spatial {
    let (omega, v) = split(m);
    let transport = g.cross(omega, p.attachment);
    let v_point = g.vadd(v, transport);
    let w = p.to_child(g, omega);
    let v = p.to_child(g, v_point);
    join(w, v)
}

/// A child's force in the parent's coordinates: `f_p = R f`, `n_p = R n + s × f_p`.
fn force_to_parent(g: &mut ExprGraph, p: &LinkPlacement, f: Spatial) -> Spatial {
    let (n, f) = split(f);
    let fp = p.to_parent(g, f);
    let rotated = p.to_parent(g, n);
    let lever = g.cross(p.attachment, fp);
    join(g.vadd(rotated, lever), fp)
}

fn add(g: &mut ExprGraph, a: Spatial, b: Spatial) -> Spatial {
    std::array::from_fn(|i| g.add(a[i], b[i]))
}

fn dot(g: &mut ExprGraph, a: Spatial, b: Spatial) -> Id {
    let terms: Vec<Id> = (0..6).map(|r| g.mul(a[r], b[r])).collect();
    g.sum(terms)
}

/// `[ω; v] ×m [ω'; v'] = [ω × ω'; ω × v' + v × ω']`.
fn motion_cross(g: &mut ExprGraph, a: Spatial, b: Spatial) -> Spatial {
    let ((w, v), (w2, v2)) = (split(a), split(b));
    let angular = g.cross(w, w2);
    let (x, y) = (g.cross(w, v2), g.cross(v, w2));
    join(angular, g.vadd(x, y))
}

/// `[ω; v] ×* [n; f] = [ω × n + v × f; ω × f]`.
fn force_cross(g: &mut ExprGraph, a: Spatial, b: Spatial) -> Spatial {
    let ((w, v), (n, f)) = (split(a), split(b));
    let (x, y) = (g.cross(w, n), g.cross(v, f));
    let linear = g.cross(w, f);
    join(g.vadd(x, y), linear)
}

/// q̈ = FD(q, q̇, u) of `model` by the articulated-body algorithm, with u the generalised forces
/// `u`; `None` for a floating base or mimic couplings. The bodies' inertias are the links'
/// unless `bodies` gives them (one per link).
pub fn forward_dynamics(
    model: &mut RobotModel,
    motion: &JointMotion,
    u: &[Id],
    gravity: Vec3,
    bodies: Option<&[BodyParameters]>,
) -> Option<Vec<Id>> {
    if model.is_floating() || model.has_couplings() {
        return None;
    }
    let variables = model.joints.len();
    let g = &mut model.graph;
    let links = &model.links;
    let frames = joint_frames(g, links, motion, bodies);
    let zero = g.zero();
    let tree = Tree {
        links,
        frames: &frames,
        zero,
    };
    let outward = velocity_pass(g, &tree, motion);
    let inward = articulated_pass(g, &tree, u, outward);
    Some(acceleration_pass(g, &tree, &inward, gravity, variables))
}

/// The links in their joint frames, which every pass reads.
struct Tree<'a> {
    links: &'a [Link],
    frames: &'a [JointFrame],
    zero: Id,
}

/// What pass 1 leaves for pass 2, per link: the velocity-product accelerations c, the
/// rigid-body inertias (to become articulated ones) and the bias forces.
struct Outward {
    c: Vec<Spatial>,
    articulated: Vec<ArticulatedInertia>,
    bias: Vec<Spatial>,
}

/// Pass 1, outwards: velocities, velocity-product accelerations c, bias forces.
fn velocity_pass(g: &mut ExprGraph, tree: &Tree, motion: &JointMotion) -> Outward {
    let n = tree.links.len();
    let zero = tree.zero;
    let mut velocity: Vec<Spatial> = Vec::with_capacity(n);
    let mut c: Vec<Spatial> = Vec::with_capacity(n);
    let mut articulated: Vec<ArticulatedInertia> = Vec::with_capacity(n);
    let mut bias: Vec<Spatial> = Vec::with_capacity(n);
    for (i, link) in tree.links.iter().enumerate() {
        let frame = &tree.frames[i];
        let parent = match link.parent {
            Some(p) => motion_to_child(g, &frame.placement, velocity[p]),
            None => [zero; 6],
        };
        let (v, ci) = match frame.subspace {
            Some((s, k)) => {
                let rate: Spatial = s.map(|x| g.mul(x, motion.qd[k]));
                (add(g, parent, rate), motion_cross(g, parent, rate))
            }
            None => (parent, [zero; 6]),
        };
        let momentum = frame.inertia.apply(g, v);
        bias.push(force_cross(g, v, momentum));
        articulated.push(frame.inertia);
        velocity.push(v);
        c.push(ci);
    }
    Outward {
        c,
        articulated,
        bias,
    }
}

/// What pass 2 leaves for pass 3, per link: c, U = I^A S, D⁻¹ and u = τ − Sᵀ p^A (zero for a
/// link without a joint variable).
struct Inward {
    c: Vec<Spatial>,
    u_force: Vec<Spatial>,
    inverse_d: Vec<Id>,
    u_scalar: Vec<Id>,
}

/// Pass 2, inwards: articulated inertias and bias forces, each link's carried to its parent.
fn articulated_pass(g: &mut ExprGraph, tree: &Tree, u: &[Id], outward: Outward) -> Inward {
    let n = tree.links.len();
    let zero = tree.zero;
    let Outward {
        c,
        mut articulated,
        mut bias,
    } = outward;
    let mut inward = Inward {
        c,
        u_force: vec![[zero; 6]; n],
        inverse_d: vec![zero; n],
        u_scalar: vec![zero; n],
    };
    for i in (0..n).rev() {
        let (ia, pa) = (articulated[i], bias[i]);
        let (carried_inertia, carried_bias) = match tree.frames[i].subspace {
            Some((s, k)) => project(g, &mut inward, i, (ia, pa), (s, u[k])),
            None => {
                let ic = ia.apply(g, inward.c[i]);
                (ia, add(g, pa, ic))
            }
        };
        if let Some(p) = tree.links[i].parent {
            let placement = &tree.frames[i].placement;
            let moved_inertia = carried_inertia.to_parent(g, placement);
            let moved_bias = force_to_parent(g, placement, carried_bias);
            articulated[p] = articulated[p].plus(g, &moved_inertia);
            bias[p] = add(g, bias[p], moved_bias);
        }
    }
    inward
}

/// Link i's articulated inertia I^A and bias p^A with its joint's motion `s` and force `tau`
/// projected out, as its parent sees them: records U, D⁻¹ and u in `inward` and returns
/// I^a = I^A − U D⁻¹ Uᵀ and p^a = p^A + I^a c + U D⁻¹ u.
fn project(
    g: &mut ExprGraph,
    inward: &mut Inward,
    i: usize,
    (ia, pa): (ArticulatedInertia, Spatial),
    (s, tau): (Spatial, Id),
) -> (ArticulatedInertia, Spatial) {
    // U = I^A S, D = Sᵀ U, u = τ − Sᵀ p^A: a column and an entry for S = e_z.
    let ui = ia.apply(g, s);
    let di = dot(g, s, ui);
    let one = g.one();
    let dinv = g.div(one, di);
    let projected = dot(g, s, pa);
    let us = g.sub(tau, projected);
    inward.u_force[i] = ui;
    inward.inverse_d[i] = dinv;
    inward.u_scalar[i] = us;
    // I^a = I^A − U D⁻¹ Uᵀ, p^a = p^A + I^a c + U D⁻¹ u.
    let scaled: Spatial = ui.map(|x| g.mul(x, dinv));
    let reduced = ia.minus_outer(g, ui, scaled);
    let ic = reduced.apply(g, inward.c[i]);
    let pushed: Spatial = scaled.map(|x| g.mul(x, us));
    let pb = add(g, pa, ic);
    (reduced, add(g, pb, pushed))
}

/// Pass 3, outwards: accelerations, gravity as the base's acceleration −g; returns q̈ (one
/// entry per joint variable).
fn acceleration_pass(
    g: &mut ExprGraph,
    tree: &Tree,
    inward: &Inward,
    gravity: Vec3,
    variables: usize,
) -> Vec<Id> {
    let zero = tree.zero;
    let minus_g = g.vneg(gravity);
    let base = join([zero; 3], minus_g);
    let mut acceleration: Vec<Spatial> = Vec::with_capacity(tree.links.len());
    let mut qdd = vec![zero; variables];
    for (i, link) in tree.links.iter().enumerate() {
        let from_parent = match link.parent {
            Some(p) => acceleration[p],
            None => base,
        };
        let frame = &tree.frames[i];
        let moved = motion_to_child(g, &frame.placement, from_parent);
        let mut a = add(g, moved, inward.c[i]);
        if let Some((s, k)) = frame.subspace {
            let ua = dot(g, inward.u_force[i], a);
            let numerator = g.sub(inward.u_scalar[i], ua);
            let q = g.mul(inward.inverse_d[i], numerator);
            qdd[k] = q;
            let along: Spatial = s.map(|x| g.mul(x, q));
            a = add(g, a, along);
        }
        acceleration.push(a);
    }
    qdd
}

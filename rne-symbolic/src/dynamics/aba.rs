//! Forward dynamics by the articulated-body algorithm, on expressions (Featherstone, Rigid
//! Body Dynamics Algorithms, table 7.1): linear in the number of links, where M + LᵀDL is
//! cubic, so it wins on long chains.
//!
//! Spatial vectors are `[angular; linear]` in body coordinates at the body origin, as in
//! RBDA; a link's placement ([`LinkPlacement`]) maps them between a body and its parent. The
//! algorithm applies to one-variable joints on a fixed base; models with a free-flyer or mimic
//! couplings use M + LᵀDL.

use crate::expr::{ExprGraph, Id, Vec3};
use crate::model::{JointKind, RobotModel};
use crate::motion::{JointMotion, LinkPlacement};

use super::crba::about_origin;

type Spatial = [Id; 6];
type SpatialMatrix = [[Id; 6]; 6];

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

fn mat_vec(g: &mut ExprGraph, m: &SpatialMatrix, v: Spatial) -> Spatial {
    std::array::from_fn(|i| {
        let terms: Vec<Id> = (0..6).map(|j| g.mul(m[i][j], v[j])).collect();
        g.sum(terms)
    })
}

fn add(g: &mut ExprGraph, a: Spatial, b: Spatial) -> Spatial {
    std::array::from_fn(|i| g.add(a[i], b[i]))
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

/// The rigid-body inertia of a link about its origin: `[[Ī, [h]×], [−[h]×, m 1]]`, Ī about
/// the origin, h = m c (RBDA (2.63)).
fn rigid_inertia(g: &mut ExprGraph, mass: Id, com: Vec3, inertia: &[[Id; 3]; 3]) -> SpatialMatrix {
    let (h, about) = about_origin(g, mass, com, inertia);
    let z = g.zero();
    let nh = h.map(|x| g.neg(x));
    // [h]× = [[0, −h3, h2], [h3, 0, −h1], [−h2, h1, 0]].
    let hx = [[z, nh[2], h[1]], [h[2], z, nh[0]], [nh[1], h[0], z]];
    let mut out = [[z; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = about[i][j];
            out[i][3 + j] = hx[i][j];
            out[3 + i][j] = g.neg(hx[i][j]);
        }
        out[3 + i][3 + i] = mass;
    }
    out
}

/// A child's articulated inertia in its parent's coordinates, `X* I X`, column by column:
/// column k is the force of the inertia under the parent's unit motion e_k.
fn inertia_to_parent(
    g: &mut ExprGraph,
    p: &LinkPlacement,
    inertia: &SpatialMatrix,
) -> SpatialMatrix {
    let (z, o) = (g.zero(), g.one());
    let mut out = [[z; 6]; 6];
    for k in 0..6 {
        let mut unit = [z; 6];
        unit[k] = o;
        let motion = motion_to_child(g, p, unit);
        let force = mat_vec(g, inertia, motion);
        let column = force_to_parent(g, p, force);
        for i in 0..6 {
            out[i][k] = column[i];
        }
    }
    // Symmetric in exact arithmetic: keep one node per pair.
    for i in 0..6 {
        for j in 0..i {
            out[i][j] = out[j][i];
        }
    }
    out
}

/// q̈ = FD(q, q̇, u) of `model` by the articulated-body algorithm, with u the generalised forces
/// `u`; `None` for a floating base or mimic couplings.
pub fn forward_dynamics(
    model: &mut RobotModel,
    motion: &JointMotion,
    u: &[Id],
    gravity: Vec3,
) -> Option<Vec<Id>> {
    if model.is_floating() || model.has_couplings() {
        return None;
    }
    let n = model.links.len();
    let g = &mut model.graph;
    let links = &model.links;
    let placements = LinkPlacement::all(g, links, motion);
    let zero = g.zero();
    // The joint axis as a motion subspace S and the joint rate, per link.
    let subspace: Vec<Option<(Spatial, usize)>> = links
        .iter()
        .map(|link| {
            let k = link.joint?;
            let zeros = [zero; 3];
            let s = match link.kind {
                JointKind::Revolute => join(link.axis, zeros),
                JointKind::Prismatic => join(zeros, link.axis),
                _ => return None,
            };
            Some((s, k))
        })
        .collect();

    // Pass 1, outwards: velocities, velocity-product accelerations c, bias forces.
    let mut velocity: Vec<Spatial> = Vec::with_capacity(n);
    let mut c: Vec<Spatial> = Vec::with_capacity(n);
    let mut articulated: Vec<SpatialMatrix> = Vec::with_capacity(n);
    let mut bias: Vec<Spatial> = Vec::with_capacity(n);
    for (i, link) in links.iter().enumerate() {
        let parent = match link.parent {
            Some(p) => motion_to_child(g, &placements[i], velocity[p]),
            None => [zero; 6],
        };
        let (v, ci) = match subspace[i] {
            Some((s, k)) => {
                let rate: Spatial = s.map(|x| g.mul(x, motion.qd[k]));
                (add(g, parent, rate), motion_cross(g, parent, rate))
            }
            None => (parent, [zero; 6]),
        };
        let inertia = rigid_inertia(g, link.mass, link.com, &link.inertia);
        let momentum = mat_vec(g, &inertia, v);
        bias.push(force_cross(g, v, momentum));
        articulated.push(inertia);
        velocity.push(v);
        c.push(ci);
    }

    // Pass 2, inwards: articulated inertias and bias forces.
    let mut u_force: Vec<Spatial> = vec![[zero; 6]; n];
    let mut inverse_d: Vec<Id> = vec![zero; n];
    let mut u_scalar: Vec<Id> = vec![zero; n];
    for i in (0..n).rev() {
        let (ia, pa) = (articulated[i], bias[i]);
        let (carried_inertia, carried_bias) = match subspace[i] {
            Some((s, k)) => {
                let ui = mat_vec(g, &ia, s);
                let terms: Vec<Id> = (0..6).map(|r| g.mul(s[r], ui[r])).collect();
                let di = g.sum(terms);
                let one = g.one();
                let dinv = g.div(one, di);
                let terms: Vec<Id> = (0..6).map(|r| g.mul(s[r], pa[r])).collect();
                let projected = g.sum(terms);
                let us = g.sub(u[k], projected);
                u_force[i] = ui;
                inverse_d[i] = dinv;
                u_scalar[i] = us;
                // I^a = I^A − U D⁻¹ Uᵀ, p^a = p^A + I^a c + U D⁻¹ u.
                let mut reduced = ia;
                for r in 0..6 {
                    for col in r..6 {
                        let outer = g.mul(ui[r], ui[col]);
                        let scaled = g.mul(outer, dinv);
                        let entry = g.sub(ia[r][col], scaled);
                        reduced[r][col] = entry;
                        reduced[col][r] = entry;
                    }
                }
                let ic = mat_vec(g, &reduced, c[i]);
                let gain = g.mul(dinv, us);
                let pushed: Spatial = ui.map(|x| g.mul(x, gain));
                let pb = add(g, pa, ic);
                (reduced, add(g, pb, pushed))
            }
            None => {
                let ic = mat_vec(g, &ia, c[i]);
                (ia, add(g, pa, ic))
            }
        };
        if let Some(p) = links[i].parent {
            let moved_inertia = inertia_to_parent(g, &placements[i], &carried_inertia);
            let moved_bias = force_to_parent(g, &placements[i], carried_bias);
            for r in 0..6 {
                for col in r..6 {
                    let entry = g.add(articulated[p][r][col], moved_inertia[r][col]);
                    articulated[p][r][col] = entry;
                    articulated[p][col][r] = entry;
                }
            }
            bias[p] = add(g, bias[p], moved_bias);
        }
    }

    // Pass 3, outwards: accelerations, gravity as the base's acceleration −g.
    let minus_g = g.vneg(gravity);
    let base = join([zero; 3], minus_g);
    let mut acceleration: Vec<Spatial> = Vec::with_capacity(n);
    let mut qdd = vec![zero; model.joints.len()];
    for (i, link) in links.iter().enumerate() {
        let from_parent = match link.parent {
            Some(p) => acceleration[p],
            None => base,
        };
        let moved = motion_to_child(g, &placements[i], from_parent);
        let mut a = add(g, moved, c[i]);
        if let Some((s, k)) = subspace[i] {
            let terms: Vec<Id> = (0..6).map(|r| g.mul(u_force[i][r], a[r])).collect();
            let ua = g.sum(terms);
            let numerator = g.sub(u_scalar[i], ua);
            let q = g.mul(inverse_d[i], numerator);
            qdd[k] = q;
            let along: Spatial = s.map(|x| g.mul(x, q));
            a = add(g, a, along);
        }
        acceleration.push(a);
    }
    Some(qdd)
}

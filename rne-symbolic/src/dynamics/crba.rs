//! The mass matrix by the composite-rigid-body algorithm, on expressions.
//!
//! Each link's inertia is accumulated with that of everything it carries (its composite
//! body), once; column i of M is then the momentum of the composite body of link i moving
//! with a unit rate of joint i, carried down towards the base and projected on each
//! ancestor's joint axis (Featherstone, Rigid Body Dynamics Algorithms, §6.2, written here in
//! the body frames of [`crate::model`] with 3-vectors). This is the same M as the columns of
//! the Newton–Euler recursion with q̇ = 0, g = 0 and q̈ = e_j, at a fraction of the
//! operations: the recursion evaluates every link's inertial terms once per column.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{JointKind, Link, RobotModel};
use crate::motion::{JointMotion, LinkPlacement};

use super::inertial_parameters::BodyParameters;

/// Mass, first moment h = m c and inertia about the body origin, in body-frame axes.
#[derive(Copy, Clone, Debug)]
pub(super) struct Composite {
    pub(super) mass: Id,
    pub(super) first_moment: Vec3,
    pub(super) inertia: Mat3,
}

/// `R I Rᵀ` of a symmetric `I` through a placement's two factors, keeping the result
/// symmetric (one node per pair).
fn similarity(g: &mut ExprGraph, placement: &LinkPlacement, inertia: &Mat3) -> Mat3 {
    let rotated = match &placement.joint {
        Some(r) => symmetric_similarity(g, r, inertia),
        None => *inertia,
    };
    symmetric_similarity(g, &placement.fixed, &rotated)
}

/// `R S Rᵀ` for symmetric S, computing each of the six distinct entries once.
fn symmetric_similarity(g: &mut ExprGraph, r: &Mat3, s: &Mat3) -> Mat3 {
    let rs = g.mat_mul(r, s);
    let mut out = *s;
    for i in 0..3 {
        for j in i..3 {
            let entry = g.dot(rs[i], r[j]);
            out[i][j] = entry;
            out[j][i] = entry;
        }
    }
    out
}

/// Inertia about the body origin of a body with mass `m`, COM `c` and inertia `inertia`
/// about the COM: `I + m (|c|² 1 − c cᵀ)`.
pub(super) fn about_origin(g: &mut ExprGraph, m: Id, c: Vec3, inertia: &Mat3) -> (Vec3, Mat3) {
    let h = g.vscale(m, c);
    let mut out = *inertia;
    for i in 0..3 {
        for j in i..3 {
            // m (|c|² δ_ij − c_i c_j) = Σ_{k≠i} h_k c_k on the diagonal, −h_i c_j off it.
            let shift = if i == j {
                let (a, b) = ((i + 1) % 3, (i + 2) % 3);
                let ha = g.mul(h[a], c[a]);
                let hb = g.mul(h[b], c[b]);
                g.add(ha, hb)
            } else {
                let p = g.mul(h[i], c[j]);
                g.neg(p)
            };
            let entry = g.add(inertia[i][j], shift);
            out[i][j] = entry;
            out[j][i] = entry;
        }
    }
    (h, out)
}

/// The composite `child` (in its own frame) expressed in its parent's frame and origin:
/// `h' = R h + m s`, `I' = R I Rᵀ + m (|s|² 1 − s sᵀ) + 2 (s·h_r) 1 − s h_rᵀ − h_r sᵀ`
/// with `h_r = R h` (the parallel-axis theorem for a body whose COM is not at its origin).
pub(super) fn to_parent(
    g: &mut ExprGraph,
    child: &Composite,
    placement: &LinkPlacement,
) -> Composite {
    let s = placement.attachment;
    let h_r = placement.to_parent(g, child.first_moment);
    let ms = g.vscale(child.mass, s);
    let first_moment = g.vadd(h_r, ms);
    let rotated = similarity(g, placement, &child.inertia);
    // Cross terms with the moved first moment: for i, j
    //   δ_ij (m |s|² + 2 s·h_r) − m s_i s_j − s_i h_r,j − h_r,i s_j
    // = δ_ij (s · (m s + 2 h_r)) − s_i (m s_j + h_r,j) − h_r,i s_j.
    let two = g.constant(2.0);
    let twice_h = g.vscale(two, h_r);
    let weighted = g.vadd(ms, twice_h);
    let diagonal = g.dot(s, weighted);
    let moved = g.vadd(ms, h_r);
    let mut inertia = rotated;
    for i in 0..3 {
        for j in i..3 {
            let a = g.mul(s[i], moved[j]);
            let b = g.mul(h_r[i], s[j]);
            let off = g.add(a, b);
            let shift = if i == j {
                g.sub(diagonal, off)
            } else {
                g.neg(off)
            };
            let entry = g.add(rotated[i][j], shift);
            inertia[i][j] = entry;
            inertia[j][i] = entry;
        }
    }
    Composite {
        mass: child.mass,
        first_moment,
        inertia,
    }
}

/// One column of a link's motion subspace: a unit rate of one velocity coordinate turns the
/// body about (`angular`) or moves it along `axis`, through the body origin.
#[derive(Copy, Clone, Debug)]
pub(super) struct Column {
    /// The entry of v it belongs to.
    pub(super) index: usize,
    /// The mimic multiplier of the coordinate (`None`: the variable itself).
    pub(super) multiplier: Option<Id>,
    /// Rotation about `axis` (else translation along it).
    pub(super) angular: bool,
    /// The unit axis, in body axes.
    pub(super) axis: Vec3,
}

/// The motion-subspace columns of every link: one for a revolute or prismatic joint, six for
/// the free-flyer (linear then angular, along the body axes), none for a fixed joint.
pub(super) fn columns(model: &mut RobotModel) -> Vec<Vec<Column>> {
    let layout = model.state_layout();
    let g = &mut model.graph;
    let unit = |g: &mut ExprGraph, a: usize| {
        let mut e = [0.0; 3];
        e[a] = 1.0;
        g.const_vec(e)
    };
    model
        .links
        .iter()
        .map(|link| match (link.kind, link.joint) {
            (JointKind::FreeFlyer, _) => (0..6)
                .map(|a| Column {
                    index: a,
                    multiplier: None,
                    angular: a >= 3,
                    axis: unit(g, a % 3),
                })
                .collect(),
            (JointKind::Revolute | JointKind::Prismatic, Some(k)) => vec![Column {
                index: layout.v_offset() + k,
                multiplier: link.coupling.map(|c| c.multiplier),
                angular: link.kind == JointKind::Revolute,
                axis: link.axis,
            }],
            _ => Vec::new(),
        })
        .collect()
}

/// The composite body of every link (the link and everything it carries), in its body frame,
/// accumulated leaves first: children come after their parent (Featherstone, RBDA §6.2). The
/// bodies' inertias are the links' unless `bodies` gives them (one per link,
/// [`BodyParameters`]).
pub(super) fn composite_bodies(
    g: &mut ExprGraph,
    links: &[Link],
    placements: &[LinkPlacement],
    bodies: Option<&[BodyParameters]>,
) -> Vec<Composite> {
    let n = links.len();
    let mut composites: Vec<Composite> = links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let body = match bodies {
                Some(bodies) => bodies[i],
                None => BodyParameters::of_link(g, link),
            };
            Composite {
                mass: body.mass,
                first_moment: body.first_moment,
                inertia: body.inertia,
            }
        })
        .collect();
    for i in (0..n).rev() {
        if let Some(p) = links[i].parent {
            let moved = to_parent(g, &composites[i], &placements[i]);
            let parent = &composites[p];
            let mass = g.add(parent.mass, moved.mass);
            let first_moment = g.vadd(parent.first_moment, moved.first_moment);
            let mut inertia = parent.inertia;
            for a in 0..3 {
                for b in a..3 {
                    let entry = g.add(parent.inertia[a][b], moved.inertia[a][b]);
                    inertia[a][b] = entry;
                    inertia[b][a] = entry;
                }
            }
            composites[p] = Composite {
                mass,
                first_moment,
                inertia,
            };
        }
    }
    composites
}

/// M(q) of `model` at `motion`'s positions (row-major, symmetric: one `Id` per pair; NV × NV).
///
/// Entry (a, b) is `S_bᵀ I^c_i S_a` for column a of link i and column b of link i or of one of
/// its ancestors. With mimic joints several links share a variable, and the entries of their
/// coordinates are summed with the multipliers (M ← Jᵀ M J); armature adds `I_a m²` to the
/// variable's diagonal entry. The bodies' inertias are the links' unless `bodies` gives them
/// (one per link, [`BodyParameters`]).
pub fn mass_matrix(
    model: &mut RobotModel,
    motion: &JointMotion,
    bodies: Option<&[BodyParameters]>,
) -> Vec<Vec<Id>> {
    let n = model.links.len();
    let nv = model.state_layout().nv();
    let columns = columns(model);
    let g = &mut model.graph;
    let links = &model.links;
    let placements = LinkPlacement::all(g, links, motion);
    let composites = composite_bodies(g, links, &placements, bodies);

    // Columns: the momentum (n, f) of composite i for a unit rate of each of its columns,
    // carried down and projected on the columns of i and of every ancestor. `terms[a][b]`
    // (a ≤ b) collects the contributions to M_ab.
    let mut terms: Vec<Vec<Vec<Id>>> = vec![vec![Vec::new(); nv]; nv];
    for i in 0..n {
        let c = composites[i];
        for (ca_position, ca) in columns[i].iter().enumerate() {
            let u = ca.axis;
            let (mut angular, mut linear) = if ca.angular {
                // Unit angular velocity u about the origin: n = I u, f = u × h.
                (g.mat_vec(&c.inertia, u), g.cross(u, c.first_moment))
            } else {
                // Unit linear velocity u: n = h × u, f = m u.
                (g.cross(c.first_moment, u), g.vscale(c.mass, u))
            };
            let mut j = i;
            loop {
                for (cb_position, cb) in columns[j].iter().enumerate() {
                    // Within link i each unordered pair of columns once.
                    if j == i && cb_position > ca_position {
                        continue;
                    }
                    let along = if cb.angular { angular } else { linear };
                    let mut entry = g.dot(cb.axis, along);
                    for m in [ca.multiplier, cb.multiplier].into_iter().flatten() {
                        entry = g.mul(m, entry);
                    }
                    let (a, b) = (ca.index.min(cb.index), ca.index.max(cb.index));
                    // Two coordinates of one variable meet twice in Jᵀ M J: (a, b) and (b, a).
                    let twice = j != i && a == b;
                    terms[a][b].push(entry);
                    if twice {
                        terms[a][b].push(entry);
                    }
                }
                let Some(p) = links[j].parent else { break };
                let f = placements[j].to_parent(g, linear);
                let t = placements[j].to_parent(g, angular);
                let moment = g.cross(placements[j].attachment, f);
                angular = g.vadd(t, moment);
                linear = f;
                j = p;
            }
        }
    }
    for (i, link) in links.iter().enumerate() {
        if let (Some(armature), Some(column)) = (link.armature, columns[i].first()) {
            let mut entry = armature;
            if let Some(m) = column.multiplier {
                let m2 = g.mul(m, m);
                entry = g.mul(entry, m2);
            }
            terms[column.index][column.index].push(entry);
        }
    }
    let zero = g.zero();
    let mut m = vec![vec![zero; nv]; nv];
    for a in 0..nv {
        for b in a..nv {
            let entry = g.sum(std::mem::take(&mut terms[a][b]));
            m[a][b] = entry;
            m[b][a] = entry;
        }
    }
    m
}

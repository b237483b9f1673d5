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
use crate::model::{axis_angle_rotation, JointKind, RobotModel};

/// Mass, first moment h = m c and inertia about the body origin, in body-frame axes.
#[derive(Copy, Clone, Debug)]
struct Composite {
    mass: Id,
    first_moment: Vec3,
    inertia: Mat3,
}

/// R_i^p(q) = E Rot(u, q) applied as two factors, and the attachment point of each link.
struct Placement {
    fixed: Mat3,
    joint: Option<Mat3>,
    attachment: Vec3,
}

impl Placement {
    fn to_parent(&self, g: &mut ExprGraph, v: Vec3) -> Vec3 {
        let v = match &self.joint {
            Some(r) => g.mat_vec(r, v),
            None => v,
        };
        g.mat_vec(&self.fixed, v)
    }

    /// `R I Rᵀ` of a symmetric `I`, keeping the result symmetric (one node per pair).
    fn similarity(&self, g: &mut ExprGraph, inertia: &Mat3) -> Mat3 {
        let rotated = match &self.joint {
            Some(r) => symmetric_similarity(g, r, inertia),
            None => *inertia,
        };
        symmetric_similarity(g, &self.fixed, &rotated)
    }
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
fn about_origin(g: &mut ExprGraph, m: Id, c: Vec3, inertia: &Mat3) -> (Vec3, Mat3) {
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
fn to_parent(g: &mut ExprGraph, child: &Composite, placement: &Placement) -> Composite {
    let s = placement.attachment;
    let h_r = placement.to_parent(g, child.first_moment);
    let ms = g.vscale(child.mass, s);
    let first_moment = g.vadd(h_r, ms);
    let rotated = placement.similarity(g, &child.inertia);
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

/// M(q) of `model` at joint positions `q` (row-major, symmetric: one `Id` per pair).
pub fn mass_matrix(model: &mut RobotModel, q: &[Id]) -> Vec<Vec<Id>> {
    let n = model.links.len();
    let dof = model.joints.len();
    let g = &mut model.graph;
    let links = &model.links;
    let placements: Vec<Placement> = links
        .iter()
        .map(|link| {
            let (joint, attachment) = match (link.kind, link.joint) {
                (JointKind::Revolute, Some(k)) => {
                    let (c, s) = (g.cos(q[k]), g.sin(q[k]));
                    (
                        Some(axis_angle_rotation(g, link.axis, c, s)),
                        link.translation,
                    )
                }
                (JointKind::Prismatic, Some(k)) => {
                    let slide = g.vscale(q[k], link.axis);
                    let moved = g.mat_vec(&link.rotation, slide);
                    (None, g.vadd(link.translation, moved))
                }
                _ => (None, link.translation),
            };
            Placement {
                fixed: link.rotation,
                joint,
                attachment,
            }
        })
        .collect();

    // Composite bodies, leaves first (children come after their parent).
    let mut composites: Vec<Composite> = links
        .iter()
        .map(|link| {
            let (first_moment, inertia) = about_origin(g, link.mass, link.com, &link.inertia);
            Composite {
                mass: link.mass,
                first_moment,
                inertia,
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

    // Columns: the momentum (n, f) of composite i for a unit rate of joint i, carried down.
    let zero = g.zero();
    let mut m = vec![vec![zero; dof]; dof];
    for i in 0..n {
        let Some(ki) = links[i].joint else { continue };
        let u = links[i].axis;
        let c = composites[i];
        let (mut angular, mut linear) = match links[i].kind {
            // Unit angular velocity u about the origin: n = I u, f = u × h.
            JointKind::Revolute => (g.mat_vec(&c.inertia, u), g.cross(u, c.first_moment)),
            // Unit linear velocity u: n = h × u, f = m u.
            _ => (g.cross(c.first_moment, u), g.vscale(c.mass, u)),
        };
        let mut j = i;
        loop {
            if let Some(kj) = links[j].joint {
                let along = match links[j].kind {
                    JointKind::Revolute => angular,
                    _ => linear,
                };
                let entry = g.dot(links[j].axis, along);
                m[kj][ki] = entry;
                m[ki][kj] = entry;
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
    m
}

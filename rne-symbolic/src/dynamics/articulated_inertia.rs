//! The articulated-body inertia of the ABA in 3×3 blocks, and its change of coordinates from
//! a body to its parent by the rotation and translation blocks of the transform.
//!
//! A spatial inertia acting on `[ω; v]` (RBDA's order) is `I = [[A, B], [Bᵀ, C]]` with A and
//! C symmetric. Moving it to the parent, `Xᵀ I X` (RBDA (2.66)), is done as Pinocchio moves
//! inertias: a rotation `R I Rᵀ` block by block, then a shift of the reference point by the
//! attachment s, with `[s]×` products (derived in [`ArticulatedInertia::translated`]). Only
//! the upper triangles of A and C are computed, and rotations about coordinate axes (joint
//! frames, [`super::aba_frames`]) are sparse, their zeros folded away as the nodes are built.
//! The column-by-column product `X* I X` costs ≈ 645 multiplications per joint; this ≈ 200
//! with dense rotations and ≈ 130 with a joint about z.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::motion::LinkPlacement;

use super::crba::about_origin;

/// A spatial vector `[angular; linear]`.
pub(super) type Spatial = [Id; 6];

/// `[[A, B], [Bᵀ, C]]`, A and C symmetric (their entries below the diagonal are the nodes
/// above it).
#[derive(Copy, Clone, Debug)]
pub(super) struct ArticulatedInertia {
    a: Mat3,
    b: Mat3,
    c: Mat3,
}

/// The cross-product matrix `[s]×`.
fn skew(g: &mut ExprGraph, s: Vec3) -> Mat3 {
    let z = g.zero();
    let n = s.map(|x| g.neg(x));
    [[z, n[2], s[1]], [s[2], z, n[0]], [n[1], s[0], z]]
}

/// `r m rᵀ` of a symmetric `m`: `r m` in full, then the upper triangle of `(r m) rᵀ`.
fn rotate_symmetric(g: &mut ExprGraph, r: &Mat3, m: &Mat3) -> Mat3 {
    let rm = g.mat_mul(r, m);
    let mut out = *m;
    for i in 0..3 {
        for j in i..3 {
            let entry = g.dot(rm[i], r[j]);
            out[i][j] = entry;
            out[j][i] = entry;
        }
    }
    out
}

/// `m + n + nᵀ − k` of symmetric `m` and `k`, kept symmetric.
fn symmetric_update(g: &mut ExprGraph, m: &Mat3, n: &Mat3, k: &Mat3) -> Mat3 {
    let mut out = *m;
    for i in 0..3 {
        for j in i..3 {
            let pair = g.add(n[i][j], n[j][i]);
            let sum = g.add(m[i][j], pair);
            let entry = g.sub(sum, k[i][j]);
            out[i][j] = entry;
            out[j][i] = entry;
        }
    }
    out
}

impl ArticulatedInertia {
    /// The rigid-body inertia about the body origin: `A = Ī`, `B = [h]×`, `C = m 1` with h = m c
    /// (RBDA (2.63)), from the COM `com` and the inertia about the COM `inertia`.
    pub fn rigid(g: &mut ExprGraph, mass: Id, com: Vec3, inertia: &Mat3) -> ArticulatedInertia {
        let (h, about) = about_origin(g, mass, com, inertia);
        ArticulatedInertia::from_origin(g, mass, h, &about)
    }

    /// The rigid-body inertia of mass `mass`, first moment `h` and inertia `about` about the
    /// origin (RBDA (2.63)).
    pub fn from_origin(g: &mut ExprGraph, mass: Id, h: Vec3, about: &Mat3) -> ArticulatedInertia {
        let about = *about;
        let z = g.zero();
        ArticulatedInertia {
            a: about,
            b: skew(g, h),
            c: [[mass, z, z], [z, mass, z], [z, z, mass]],
        }
    }

    /// Entry `(r, k)` of the 6×6 matrix.
    pub fn entry(&self, r: usize, k: usize) -> Id {
        match (r < 3, k < 3) {
            (true, true) => self.a[r][k],
            (true, false) => self.b[r][k - 3],
            (false, true) => self.b[k][r - 3],
            (false, false) => self.c[r - 3][k - 3],
        }
    }

    /// `I x` (zeros of `x`, as in a joint's motion subspace, cost nothing).
    pub fn apply(&self, g: &mut ExprGraph, x: Spatial) -> Spatial {
        std::array::from_fn(|r| {
            let terms: Vec<Id> = (0..6).map(|k| g.mul(self.entry(r, k), x[k])).collect();
            g.sum(terms)
        })
    }

    /// The sum of two inertias in the same coordinates.
    pub fn plus(&self, g: &mut ExprGraph, other: &ArticulatedInertia) -> ArticulatedInertia {
        let mut out = *self;
        for i in 0..3 {
            for j in 0..3 {
                out.b[i][j] = g.add(self.b[i][j], other.b[i][j]);
                if j >= i {
                    out.a[i][j] = g.add(self.a[i][j], other.a[i][j]);
                    out.a[j][i] = out.a[i][j];
                    out.c[i][j] = g.add(self.c[i][j], other.c[i][j]);
                    out.c[j][i] = out.c[i][j];
                }
            }
        }
        out
    }

    /// `I − u wᵀ` for `w` a multiple of `u` (so the result is symmetric): the articulated
    /// inertia the parent sees, `I − U D⁻¹ Uᵀ` with `w = D⁻¹ U` (RBDA table 7.1).
    pub fn minus_outer(&self, g: &mut ExprGraph, u: Spatial, w: Spatial) -> ArticulatedInertia {
        let mut entry = |r: usize, k: usize| {
            let outer = g.mul(u[r], w[k]);
            g.sub(self.entry(r, k), outer)
        };
        let mut out = *self;
        for i in 0..3 {
            for j in 0..3 {
                out.b[i][j] = entry(i, 3 + j);
                if j >= i {
                    out.a[i][j] = entry(i, j);
                    out.a[j][i] = out.a[i][j];
                    out.c[i][j] = entry(3 + i, 3 + j);
                    out.c[j][i] = out.c[i][j];
                }
            }
        }
        out
    }

    /// `diag(r, r) I diag(rᵀ, rᵀ)`: the inertia in axes rotated by `r`, block by block.
    pub fn rotated(&self, g: &mut ExprGraph, r: &Mat3) -> ArticulatedInertia {
        ArticulatedInertia {
            a: rotate_symmetric(g, r, &self.a),
            b: g.similarity(r, &self.b),
            c: rotate_symmetric(g, r, &self.c),
        }
    }

    /// The inertia about a point `s` away: `X_sᵀ I X_s` with `X_s = [[1, 0], [−[s]×, 1]]`
    /// (a motion `[ω; v]` at the new reference point is `[ω; v + ω × s]` at the old one).
    /// Multiplied out, with `Q = [s]× C` and `P = [s]× Bᵀ`:
    /// `C' = C`, `B' = B + Q`, `A' = A + P + Pᵀ − Q [s]×` (A' symmetric, since
    /// `−B [s]× = Pᵀ` and `Q [s]× = [s]× C [s]×`).
    pub fn translated(&self, g: &mut ExprGraph, s: Vec3) -> ArticulatedInertia {
        let sx = skew(g, s);
        let q = g.mat_mul(&sx, &self.c);
        let bt = crate::expr::transpose(&self.b);
        let p = g.mat_mul(&sx, &bt);
        let b = std::array::from_fn(|i| std::array::from_fn(|j| g.add(self.b[i][j], q[i][j])));
        let mut qs = self.a;
        for i in 0..3 {
            for j in i..3 {
                let column = [sx[0][j], sx[1][j], sx[2][j]];
                qs[i][j] = g.dot(q[i], column);
            }
        }
        ArticulatedInertia {
            a: symmetric_update(g, &self.a, &p, &qs),
            b,
            c: self.c,
        }
    }

    /// The inertia in the parent's coordinates, `Xᵀ I X` for the placement `p`: rotated by
    /// the joint rotation, then by the fixed one, then moved to the parent's origin.
    pub fn to_parent(self, g: &mut ExprGraph, p: &LinkPlacement) -> ArticulatedInertia {
        let turned = match &p.joint {
            Some(joint) => self.rotated(g, joint),
            None => self,
        };
        turned.rotated(g, &p.fixed).translated(g, p.attachment)
    }
}

//! The composite-rigid-body algorithm (RBDA table 6.2): the joint-space inertia matrix M(q).
//!
//! ```text
//! I_i^c = I_i                                         for every body
//! i = N..1:  I_p^c += ᶦX_pᵀ I_i^c ᶦX_p                   (composite inertia of the subtree)
//!            F = I_i^c S_i,   M_ii = S_iᵀ F
//!            j = i; while j has a parent: F = ʲX_pᵀ F, j = p, M_ij = M_ji = S_jᵀ F
//! ```
//!
//! M is the matrix of the kinetic energy `T = ½ q̇ᵀ M q̇` (the thesis's section 6.1.1) and the
//! `q̈` part of (3.1). Fixed bodies add their inertia to the composite of their parent and are
//! passed through on the way to the root, contributing no row. Entries between joints of
//! different branches are never written and stay exactly zero.

use super::data::Data;
use super::model::Model;

/// Writes M(q) into `out` (`dof × dof`, row-major; M is symmetric, so column-major is the same).
/// Slices have the model's lengths (checked by the caller).
pub(crate) fn mass_matrix(model: &Model, data: &mut Data, q: &[f64], out: &mut [f64]) {
    let n = model.dof();
    out.fill(0.0);
    for (i, body) in model.bodies.iter().enumerate() {
        data.transforms[i] = body.transform(q);
        data.composite[i] = body.inertia;
    }
    for (i, body) in model.bodies.iter().enumerate().rev() {
        if let Some(p) = body.parent {
            let inertia = data.transforms[i].transpose_apply_inertia(&data.composite[i]);
            data.composite[p] += inertia;
        }
        let Some(k) = body.joint_index() else {
            continue;
        };
        let mut f = data.composite[i].apply(&body.motion_subspace);
        out[k * n + k] = body.motion_subspace.dot(&f);
        let mut j = i;
        while let Some(p) = model.bodies[j].parent {
            f = data.transforms[j].transpose_apply_force(&f);
            j = p;
            if let Some(l) = model.bodies[j].joint_index() {
                let entry = model.bodies[j].motion_subspace.dot(&f);
                out[k * n + l] = entry;
                out[l * n + k] = entry;
            }
        }
    }
}

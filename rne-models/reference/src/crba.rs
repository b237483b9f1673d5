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
//!
//! A free-flyer root (`S = 1`) contributes the 6×6 block of the whole robot's composite inertia
//! and, for every joint, the 6 entries `F` reaching the root (RBDA section 6.2 for floating
//! bases). Coupled (mimic) bodies are accumulated through the chain rule: M = Jᵀ M_bodies J with
//! `J` the multipliers, so an entry between two bodies of variables k and l adds
//! `m_i m_j S_iᵀ ᶦX_jᵀ … F` to M_kl and M_lk. Armature adds `m_i² I_a` to the diagonal.

use nalgebra::RealField;

use crate::data::Data;
use crate::model::{base_index, Model, Motion};

/// Writes M(q) into `out` (`nv × nv`, row-major; M is symmetric, so column-major is the same).
/// Slices have the model's lengths (checked by the caller).
pub(crate) fn mass_matrix<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    out: &mut [T],
) {
    let layout = &model.layout;
    let n = layout.nv();
    out.fill(T::zero());
    for (i, body) in model.bodies.iter().enumerate() {
        data.transforms[i] = body.transform(layout, q);
        data.composite[i] = body.inertia;
    }
    for (i, body) in model.bodies.iter().enumerate().rev() {
        if let Some(p) = body.parent {
            let inertia = data.transforms[i].transpose_apply_inertia(&data.composite[i]);
            data.composite[p] += inertia;
        }
        if body.motion == Motion::FreeFlyer {
            let composite = data.composite[i].to_matrix();
            for r in 0..6 {
                for c in r..6 {
                    let (row, column) = (base_index(r), base_index(c));
                    out[row * n + column] = composite[(r, c)];
                    out[column * n + row] = composite[(r, c)];
                }
            }
            continue;
        }
        let Some(drive) = body.drive else {
            continue;
        };
        let k = layout.v_joint(drive.variable);
        let mut f = data.composite[i].apply(&body.motion_subspace) * drive.multiplier;
        let armature = body.armature.unwrap_or_else(T::zero);
        out[k * n + k] +=
            drive.multiplier * (body.motion_subspace.dot(&f) + armature * drive.multiplier);
        let mut j = i;
        while let Some(p) = model.bodies[j].parent {
            f = data.transforms[j].transpose_apply_force(&f);
            j = p;
            let ancestor = &model.bodies[j];
            if ancestor.motion == Motion::FreeFlyer {
                for r in 0..6 {
                    out[base_index(r) * n + k] += f[r];
                    out[k * n + base_index(r)] += f[r];
                }
            } else if let Some(d) = ancestor.drive {
                let l = layout.v_joint(d.variable);
                let entry = d.multiplier * ancestor.motion_subspace.dot(&f);
                out[k * n + l] += entry;
                out[l * n + k] += entry;
            }
        }
    }
}

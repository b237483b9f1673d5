//! Forward kinematics of every link frame (RBDA section 4.1): placements in the world, geometric
//! Jacobians and the velocity-product acceleration `J̇ q̇`.
//!
//! Every link is a frame, links behind fixed joints included (the reference keeps them as
//! bodies). Jacobians have rows `[v; ω]`: the velocity of the frame origin and the angular
//! velocity, in world-aligned axes (Pinocchio's `LOCAL_WORLD_ALIGNED`). They are assembled
//! column by column from the joint axes in the world, not from the spatial recursion:
//!
//! ```text
//! revolute j (axis a_j, origin p_j):   ω_k += m a_j,   v_k += m a_j × (p − p_j)
//! prismatic j:                          v_k += m a_j
//! free-flyer (R, p_b):                  v_lin: v = R;   ω: ω = R, v = −(p − p_b)× R
//! ```
//!
//! (`m` the coupling multiplier of a mimic body, 1 otherwise). `J̇ q̇` is the classical
//! acceleration `[a_origin; α]` of the frame at q̈ = 0 without gravity, from the RNEA's forward
//! pass: with `[ω; v]` and `[α; a]` the body's spatial velocity and acceleration at its origin,
//! `a_origin = a + ω × v` (RBDA section 2.11), rotated into world axes. So the task
//! acceleration is `J q̈ + J̇ q̇`.

use nalgebra::{DMatrix, Matrix3, Vector3, Vector6};

use crate::error::ReferenceError;
use crate::model::{base_index, Motion};
use crate::spatial::{angular, linear, spatial};
use crate::{rnea, Reference};

/// A frame's placement in the world: its axes in world coordinates (rotation matrix) and its
/// origin.
pub type Placement = (Matrix3<f64>, Vector3<f64>);

impl Reference {
    /// The placement of every link frame in the world at q, in model order
    /// ([`Reference::link_names`]).
    pub fn frame_placements(&mut self, q: &[f64]) -> Result<Vec<Placement>, ReferenceError> {
        self.check(&[("q", q)], &[])?;
        self.place_frames(q);
        Ok(self
            .data
            .rotations
            .iter()
            .zip(&self.data.origins)
            .map(|(r, p)| (*r, *p))
            .collect())
    }

    /// The geometric Jacobian (6 × nv, rows `[v; ω]` of the frame origin in world-aligned axes)
    /// of every link frame at q, in model order.
    pub fn frame_jacobians(&mut self, q: &[f64]) -> Result<Vec<DMatrix<f64>>, ReferenceError> {
        self.check(&[("q", q)], &[])?;
        self.place_frames(q);
        let layout = self.model.layout;
        let (rotations, origins) = (&self.data.rotations, &self.data.origins);
        let jacobians = (0..self.model.bodies.len())
            .map(|frame| {
                let mut jacobian = DMatrix::zeros(6, layout.nv());
                let point = origins[frame];
                let mut next = Some(frame);
                while let Some(j) = next {
                    let body = &self.model.bodies[j];
                    let lever = point - origins[j];
                    match (body.motion, body.drive) {
                        (Motion::FreeFlyer, _) => {
                            let r = rotations[j];
                            let moment = -lever.cross_matrix() * r;
                            jacobian.view_mut((0, 0), (3, 3)).copy_from(&r);
                            jacobian.view_mut((3, 3), (3, 3)).copy_from(&r);
                            jacobian.view_mut((0, 3), (3, 3)).copy_from(&moment);
                        }
                        (Motion::Revolute, Some(d)) => {
                            let axis = rotations[j] * angular(&body.motion_subspace);
                            let k = layout.v_joint(d.variable);
                            let column = spatial(axis, axis.cross(&lever)) * d.multiplier;
                            add_column(&mut jacobian, k, &column);
                        }
                        (Motion::Prismatic, Some(d)) => {
                            let axis = rotations[j] * linear(&body.motion_subspace);
                            let k = layout.v_joint(d.variable);
                            let column = spatial(Vector3::zeros(), axis) * d.multiplier;
                            add_column(&mut jacobian, k, &column);
                        }
                        _ => {}
                    }
                    next = body.parent;
                }
                jacobian
            })
            .collect();
        Ok(jacobians)
    }

    /// `J̇ q̇` of every link frame at (q, q̇), in model order: `[a_origin; α]` in world axes at
    /// q̈ = 0, so that the frame's classical acceleration is `J q̈ + J̇ q̇`.
    pub fn frame_jacobian_dot_qd(
        &mut self,
        q: &[f64],
        qd: &[f64],
    ) -> Result<Vec<Vector6<f64>>, ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd)])?;
        rnea::motion_pass(
            &self.model,
            &mut self.data,
            q,
            Some(qd),
            None,
            Vector6::zeros(),
        );
        self.place_frames(q);
        let data = &self.data;
        Ok((0..self.model.bodies.len())
            .map(|i| {
                let (v, a) = (&data.velocities[i], &data.accelerations[i]);
                let origin = linear(a) + angular(v).cross(&linear(v));
                let r = &data.rotations[i];
                let world = spatial(r * angular(a), r * origin);
                Vector6::from_fn(|row, _| world[base_index(row)])
            })
            .collect())
    }

    /// Fills the world placements of every body into the workspace.
    fn place_frames(&mut self, q: &[f64]) {
        let layout = self.model.layout;
        for (i, body) in self.model.bodies.iter().enumerate() {
            let x = body.transform(&layout, q);
            let (rotation, origin) = match body.parent {
                Some(p) => (
                    self.data.rotations[p] * x.rotation.transpose(),
                    self.data.origins[p] + self.data.rotations[p] * x.translation,
                ),
                None => (x.rotation.transpose(), x.translation),
            };
            self.data.rotations[i] = rotation;
            self.data.origins[i] = origin;
        }
    }
}

/// Adds a spatial column `[ω; v]` to column `k` of a Jacobian with rows `[v; ω]`.
fn add_column(jacobian: &mut DMatrix<f64>, k: usize, column: &Vector6<f64>) {
    for r in 0..6 {
        jacobian[(base_index(r), k)] += column[r];
    }
}

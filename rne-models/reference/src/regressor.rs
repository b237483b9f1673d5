//! The joint-torque regressor `τ = Y(q, q̇, q̈) π` (docs/design.md §4.4), from the per-body spatial
//! regressor rather than from the RNEA's force recursion.
//!
//! The spatial force a rigid body needs, `f = I a + v ×* I v`, is linear in its ten standard
//! parameters `π = [m, m c_x, m c_y, m c_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]` (Pinocchio's
//! order; `I` about the body frame's origin, body axes). With `[ω; v]` and `[α; a]` the body's
//! spatial velocity and acceleration (gravity included as the world's upward acceleration) and
//! `b = a + ω × v` the classical acceleration of the origin (Atkeson, An and Hollerbach 1986;
//! RBDA section 2.13 for the spatial form):
//!
//! ```text
//! n = h × b + L(α) I⃗ + ω × L(ω) I⃗          L(x) I⃗ = I x,  I⃗ = [I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]
//! f = m b + α × h + ω × (ω × h)             h = m c
//! ```
//!
//! Each body's 6×10 block is carried to the root by the force transforms; every joint on the
//! way takes its row `m_j S_jᵀ F` (a free-flyer its six rows). Bodies behind fixed joints are
//! rigidly part of their nearest moving ancestor: their parameters are merged into it
//! ([`Reference::standard_parameters`]), and a body fixed to the world moves nothing.
//!
//! After the bodies' blocks come the joint parameters, per revolute or prismatic link in model
//! order: `f_v, f_c, offset` with columns `m q̇_i, m sign(q̇_i), m` when friction is included
//! ([`Reference::with_friction`]) and the link has it, then `I_a` with column `m q̈_i` when the
//! link has armature (`m` the coupling multiplier, `q_i` the link's own coordinate).

use nalgebra::{DMatrix, SMatrix, Vector3, Vector6};

use crate::error::ReferenceError;
use crate::friction::sign;
use crate::model::{base_index, Motion};
use crate::spatial::{angular, linear, spatial, RigidInertia};
use crate::{rnea, Reference};

/// The 6×10 spatial regressor of one body.
type BodyRegressor = SMatrix<f64, 6, 10>;

/// `L(x)`: the 3×6 matrix with `L(x) I⃗ = I x` for `I⃗ = [I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]`.
fn inertia_action(x: &Vector3<f64>) -> SMatrix<f64, 3, 6> {
    SMatrix::<f64, 3, 6>::from_row_slice(&[
        x.x, x.y, 0.0, x.z, 0.0, 0.0, //
        0.0, x.x, x.y, 0.0, x.z, 0.0, //
        0.0, 0.0, 0.0, x.x, x.y, x.z,
    ])
}

/// The body regressor for spatial velocity `velocity` and acceleration `acceleration`.
fn body_regressor(velocity: &Vector6<f64>, acceleration: &Vector6<f64>) -> BodyRegressor {
    let (w, v) = (angular(velocity), linear(velocity));
    let (alpha, a) = (angular(acceleration), linear(acceleration));
    let b = a + w.cross(&v);
    let wx = w.cross_matrix();
    let mut out = BodyRegressor::zeros();
    out.fixed_view_mut::<3, 3>(0, 1)
        .copy_from(&(-b.cross_matrix()));
    out.fixed_view_mut::<3, 6>(0, 4)
        .copy_from(&(inertia_action(&alpha) + wx * inertia_action(&w)));
    out.fixed_view_mut::<3, 1>(3, 0).copy_from(&b);
    out.fixed_view_mut::<3, 3>(3, 1)
        .copy_from(&(alpha.cross_matrix() + wx * wx));
    out
}

/// The ten standard parameters of a rigid-body inertia about its frame's origin.
fn parameters_of(inertia: &RigidInertia<f64>) -> [f64; 10] {
    let (h, i) = (inertia.first_moment, inertia.rotational);
    [
        inertia.mass,
        h.x,
        h.y,
        h.z,
        i[(0, 0)],
        i[(0, 1)],
        i[(1, 1)],
        i[(0, 2)],
        i[(1, 2)],
        i[(2, 2)],
    ]
}

impl Reference {
    /// The bodies that carry parameters: free-flyer, revolute and prismatic links, in model
    /// order.
    fn moving_bodies(&self) -> Vec<usize> {
        (0..self.model.bodies.len())
            .filter(|&i| self.model.bodies[i].motion != Motion::Fixed)
            .collect()
    }

    /// Number of regressor columns: 10 per moving body, then the joint parameters.
    pub fn parameter_count(&self) -> usize {
        self.standard_parameters().len()
    }

    /// Names of the standard parameters, in the regressor's column order: `link.m`, `link.mcx`,
    /// `link.mcy`, `link.mcz`, `link.Ixx`, `link.Ixy`, `link.Iyy`, `link.Ixz`, `link.Iyz`,
    /// `link.Izz` per moving body, then `link.fv`, `link.fc`, `link.f0`, `link.Ia` as present.
    pub fn parameter_names(&self) -> Vec<String> {
        const BODY: [&str; 10] = [
            "m", "mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
        ];
        let mut names: Vec<String> = self
            .moving_bodies()
            .into_iter()
            .flat_map(|i| BODY.iter().map(move |p| (i, *p)))
            .map(|(i, p)| format!("{}.{p}", self.link_names[i]))
            .collect();
        for (i, body) in self.model.bodies.iter().enumerate() {
            if body.drive.is_none() {
                continue;
            }
            if self.friction && body.friction.is_some() {
                names.extend(["fv", "fc", "f0"].map(|p| format!("{}.{p}", self.link_names[i])));
            }
            if body.armature.is_some() {
                names.push(format!("{}.Ia", self.link_names[i]));
            }
        }
        names
    }

    /// The standard parameters π of the model, in the regressor's column order: per moving
    /// body its inertia about its frame's origin with every body fixed behind it merged in, then
    /// the joint parameters (see [`Reference::parameter_names`]).
    pub fn standard_parameters(&self) -> Vec<f64> {
        let bodies = &self.model.bodies;
        // A fixed body's transform reads no coordinate.
        let layout = &self.model.layout;
        let mut merged: Vec<RigidInertia<f64>> = bodies.iter().map(|b| b.inertia).collect();
        for i in (0..bodies.len()).rev() {
            if let (Motion::Fixed, Some(p)) = (bodies[i].motion, bodies[i].parent) {
                let carried = bodies[i]
                    .transform(layout, &[])
                    .transpose_apply_inertia(&merged[i]);
                merged[p] += carried;
            }
        }
        let mut parameters: Vec<f64> = self
            .moving_bodies()
            .into_iter()
            .flat_map(|i| parameters_of(&merged[i]))
            .collect();
        for body in bodies.iter().filter(|b| b.drive.is_some()) {
            if let (true, Some(friction)) = (self.friction, body.friction) {
                parameters.extend(friction);
            }
            parameters.extend(body.armature);
        }
        parameters
    }

    /// The regressor `Y(q, q̇, q̈)` (`nv × parameter_count`) with
    /// `Y π = τ = inverse_dynamics(q, q̇, q̈)` for `π = standard_parameters()`.
    pub fn regressor(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DMatrix<f64>, ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("qdd", qdd)])?;
        let layout = self.model.layout;
        let world_acceleration = spatial(Vector3::zeros(), -self.model.gravity);
        rnea::motion_pass(
            &self.model,
            &mut self.data,
            q,
            Some(qd),
            Some(qdd),
            world_acceleration,
        );
        let moving = self.moving_bodies();
        let mut y = DMatrix::zeros(layout.nv(), self.parameter_count());
        for (block, &k) in moving.iter().enumerate() {
            let mut force = body_regressor(&self.data.velocities[k], &self.data.accelerations[k]);
            let mut next = Some(k);
            while let Some(j) = next {
                let body = &self.model.bodies[j];
                if body.motion == Motion::FreeFlyer {
                    for r in 0..6 {
                        let mut row = y.fixed_view_mut::<1, 10>(base_index(r), 10 * block);
                        row += force.row(r);
                    }
                } else if let Some(d) = body.drive {
                    let row_sum = body.motion_subspace.transpose() * force * d.multiplier;
                    let mut row = y.fixed_view_mut::<1, 10>(layout.v_joint(d.variable), 10 * block);
                    row += row_sum;
                }
                if body.parent.is_some() {
                    let x = &self.data.transforms[j];
                    for mut column in force.column_iter_mut() {
                        let moved = x.transpose_apply_force(&column.clone_owned());
                        column.copy_from(&moved);
                    }
                }
                next = body.parent;
            }
        }
        let mut column = 10 * moving.len();
        for body in &self.model.bodies {
            let Some(d) = body.drive else {
                continue;
            };
            let row = layout.v_joint(d.variable);
            let rate = d.multiplier * qd[row];
            if self.friction && body.friction.is_some() {
                for value in [rate, sign(rate), 1.0] {
                    y[(row, column)] += d.multiplier * value;
                    column += 1;
                }
            }
            if body.armature.is_some() {
                y[(row, column)] += d.multiplier * d.multiplier * qdd[row];
                column += 1;
            }
        }
        Ok(y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    #[test]
    fn inertia_action_applies_the_symmetric_inertia() {
        let i = Matrix3::new(0.5, 0.02, -0.01, 0.02, 0.4, 0.03, -0.01, 0.03, 0.3);
        let x = Vector3::new(0.3, -1.2, 0.7);
        let vector = nalgebra::Vector6::new(
            i[(0, 0)],
            i[(0, 1)],
            i[(1, 1)],
            i[(0, 2)],
            i[(1, 2)],
            i[(2, 2)],
        );
        assert!((inertia_action(&x) * vector - i * x).norm() < 1e-15);
    }
}

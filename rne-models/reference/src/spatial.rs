//! Spatial vector algebra (Featherstone, *Rigid Body Dynamics Algorithms* (RBDA), chapter 2):
//! six-dimensional motion and force vectors, Plücker transforms, the spatial cross products and
//! rigid-body inertias.
//!
//! Spatial vectors are [`Vector6`]s with the angular part first: a motion vector is
//! `[ω; v_O]` (angular velocity, velocity of the frame's origin O), a force vector is
//! `[n_O; f]` (moment about O, force). Everything is expressed in the coordinates of one body
//! frame; the link algorithms never need a world frame.

use nalgebra::{Matrix3, Matrix6, RealField, Vector3, Vector6};

/// The angular (upper) half of a spatial vector.
pub(crate) fn angular<T: RealField + Copy>(v: &Vector6<T>) -> Vector3<T> {
    v.fixed_rows::<3>(0).into_owned()
}

/// The linear (lower) half of a spatial vector.
pub(crate) fn linear<T: RealField + Copy>(v: &Vector6<T>) -> Vector3<T> {
    v.fixed_rows::<3>(3).into_owned()
}

/// Stacks an angular and a linear part into a spatial vector.
pub(crate) fn spatial<T: RealField + Copy>(angular: Vector3<T>, linear: Vector3<T>) -> Vector6<T> {
    Vector6::new(
        angular.x, angular.y, angular.z, linear.x, linear.y, linear.z,
    )
}

/// Motion cross product `v ×m m` (RBDA (2.31)):
/// `[ω; v] ×m [ω_m; v_m] = [ω × ω_m; ω × v_m + v × ω_m]`.
pub(crate) fn motion_cross<T: RealField + Copy>(v: &Vector6<T>, m: &Vector6<T>) -> Vector6<T> {
    let (w, vl) = (angular(v), linear(v));
    let (mw, ml) = (angular(m), linear(m));
    spatial(w.cross(&mw), w.cross(&ml) + vl.cross(&mw))
}

/// Force cross product `v ×* f = −(v ×m)ᵀ f` (RBDA (2.32)):
/// `[ω; v] ×* [n; f] = [ω × n + v × f; ω × f]`.
pub(crate) fn force_cross<T: RealField + Copy>(v: &Vector6<T>, f: &Vector6<T>) -> Vector6<T> {
    let (w, vl) = (angular(v), linear(v));
    let (n, fl) = (angular(f), linear(f));
    spatial(w.cross(&n) + vl.cross(&fl), w.cross(&fl))
}

/// The Plücker transform `ᴮX_A` from frame A to frame B (RBDA (2.24)):
///
/// ```text
/// ᴮX_A = [ E      0 ]      E: rotates A coordinates into B coordinates,
///        [ −E r×  E ]      r: the origin of B in A coordinates.
/// ```
///
/// For a link, A is the parent's body frame and B the link's, so `E = (R_i^p)ᵀ` and `r` is the
/// link's origin in the parent frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Transform<T: RealField + Copy> {
    /// `E`.
    pub rotation: Matrix3<T>,
    /// `r`.
    pub translation: Vector3<T>,
}

impl<T: RealField + Copy> Transform<T> {
    /// The transform to a frame B with orientation `r_ba` (B's axes in A coordinates, the
    /// thesis's `R_B^A`) and origin `origin` (in A coordinates).
    pub fn from_placement(r_ba: &Matrix3<T>, origin: Vector3<T>) -> Transform<T> {
        Transform {
            rotation: r_ba.transpose(),
            translation: origin,
        }
    }

    /// `ᴮX_A m` for a motion vector given in A: `[E ω; E (v − r × ω)]`.
    pub fn apply_motion(&self, m: &Vector6<T>) -> Vector6<T> {
        let w = angular(m);
        let v = linear(m) - self.translation.cross(&w);
        spatial(self.rotation * w, self.rotation * v)
    }

    /// `(ᴮX_A)ᵀ f` for a force vector given in B, which is the same force expressed in A
    /// (`ᴬX_B^* = (ᴮX_A)ᵀ`): `[Eᵀ n + r × Eᵀ f; Eᵀ f]`.
    pub fn transpose_apply_force(&self, f: &Vector6<T>) -> Vector6<T> {
        let fl = self.rotation.tr_mul(&linear(f));
        let n = self.rotation.tr_mul(&angular(f)) + self.translation.cross(&fl);
        spatial(n, fl)
    }

    /// `(ᴮX_A)ᵀ I ᴮX_A` for a rigid-body inertia given in B: the same inertia expressed in A
    /// (RBDA (2.66), with `h = m c`):
    ///
    /// ```text
    /// m' = m,   h' = Eᵀ h + m r,   Ī' = Eᵀ Ī E − r× (Eᵀh)× − h'× r×
    /// ```
    pub fn transpose_apply_inertia(&self, inertia: &RigidInertia<T>) -> RigidInertia<T> {
        let h = self.rotation.tr_mul(&inertia.first_moment);
        let moment = h + self.translation * inertia.mass;
        let rx = self.translation.cross_matrix();
        RigidInertia {
            mass: inertia.mass,
            first_moment: moment,
            rotational: self.rotation.tr_mul(&inertia.rotational) * self.rotation
                - rx * h.cross_matrix()
                - moment.cross_matrix() * rx,
        }
    }

    /// `(ᴮX_A)ᵀ I ᴮX_A` for a general symmetric 6×6 inertia given in B (an articulated-body
    /// inertia). With `I = [A B; Bᵀ C]` rotated into A axes (`A' = Eᵀ A E`, …):
    ///
    /// ```text
    /// [ A' − B' r× + r× B'ᵀ − r× C' r×    B' + r× C' ]
    /// [ (B' + r× C')ᵀ                      C'         ]
    /// ```
    pub fn transpose_apply_matrix(&self, inertia: &Matrix6<T>) -> Matrix6<T> {
        let e = &self.rotation;
        let a = e.tr_mul(&inertia.fixed_view::<3, 3>(0, 0)) * e;
        let b = e.tr_mul(&inertia.fixed_view::<3, 3>(0, 3)) * e;
        let c = e.tr_mul(&inertia.fixed_view::<3, 3>(3, 3)) * e;
        let rx = self.translation.cross_matrix();
        let rc = rx * c;
        let top_left = a - b * rx + rx * b.transpose() - rc * rx;
        let top_right = b + rc;
        let mut out = Matrix6::zeros();
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&top_left);
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&top_right);
        out.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&top_right.transpose());
        out.fixed_view_mut::<3, 3>(3, 3).copy_from(&c);
        out
    }
}

/// A rigid-body inertia about the origin of its frame (RBDA (2.62)–(2.63)):
///
/// ```text
/// I = [ Ī    h× ]      h = m c (first moment of mass),
///     [ h×ᵀ  m 1 ]     Ī = I_c − m c× c× (rotational inertia about the origin)
/// ```
///
/// Ten numbers instead of 36, closed under addition and under [`Transform`]s, which is what the
/// composite-rigid-body algorithm needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RigidInertia<T: RealField + Copy> {
    /// m.
    pub mass: T,
    /// h = m c.
    pub first_moment: Vector3<T>,
    /// Ī, the rotational inertia about the frame origin.
    pub rotational: Matrix3<T>,
}

impl<T: RealField + Copy> RigidInertia<T> {
    /// The inertia of a body of mass `mass` whose centre of mass lies at `com` with rotational
    /// inertia `inertia_com` about it (parallel-axis theorem: `Ī = I_c − m c× c×`).
    pub fn from_com(mass: T, com: Vector3<T>, inertia_com: &Matrix3<T>) -> RigidInertia<T> {
        let cx = com.cross_matrix();
        RigidInertia {
            mass,
            first_moment: com * mass,
            rotational: inertia_com - cx * cx * mass,
        }
    }

    /// The force `I v` of a motion `v = [ω; v_O]`: `[Ī ω + h × v_O; m v_O − h × ω]`
    /// (momentum when `v` is a velocity).
    pub fn apply(&self, v: &Vector6<T>) -> Vector6<T> {
        let (w, vl) = (angular(v), linear(v));
        spatial(
            self.rotational * w + self.first_moment.cross(&vl),
            vl * self.mass - self.first_moment.cross(&w),
        )
    }

    /// The 6×6 matrix of this inertia.
    pub fn to_matrix(self) -> Matrix6<T> {
        let hx = self.first_moment.cross_matrix();
        let mut out = Matrix6::zeros();
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotational);
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&hx);
        out.fixed_view_mut::<3, 3>(3, 0).copy_from(&hx.transpose());
        out.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Matrix3::identity() * self.mass));
        out
    }
}

impl<T: RealField + Copy> std::ops::AddAssign for RigidInertia<T> {
    fn add_assign(&mut self, other: RigidInertia<T>) {
        self.mass += other.mass;
        self.first_moment += other.first_moment;
        self.rotational += other.rotational;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Unit};

    fn sample_transform() -> Transform<f64> {
        let axis = Unit::new_normalize(Vector3::new(0.3, -0.8, 0.5));
        let r = Rotation3::from_axis_angle(&axis, 0.9).into_inner();
        Transform::from_placement(&r, Vector3::new(0.4, -1.2, 0.7))
    }

    /// The full 6×6 matrix `ᴮX_A` of RBDA (2.24), written out independently.
    fn plucker_matrix(x: &Transform<f64>) -> Matrix6<f64> {
        let mut out = Matrix6::zeros();
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&x.rotation);
        out.fixed_view_mut::<3, 3>(3, 3).copy_from(&x.rotation);
        out.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(-x.rotation * x.translation.cross_matrix()));
        out
    }

    fn sample_inertia() -> RigidInertia<f64> {
        let inertia = Matrix3::new(0.5, 0.02, -0.01, 0.02, 0.4, 0.03, -0.01, 0.03, 0.3);
        RigidInertia::from_com(2.5, Vector3::new(0.1, -0.2, 0.35), &inertia)
    }

    fn close(a: &Matrix6<f64>, b: &Matrix6<f64>) -> bool {
        (a - b).abs().max() <= 1e-13 * (1.0 + b.abs().max())
    }

    #[test]
    fn transform_methods_equal_the_plucker_matrix_products() {
        let x = sample_transform();
        let xm = plucker_matrix(&x);
        let v = Vector6::new(0.3, -1.1, 0.7, 2.0, -0.4, 0.9);
        assert!((x.apply_motion(&v) - xm * v).abs().max() < 1e-14);
        assert!(
            (x.transpose_apply_force(&v) - xm.transpose() * v)
                .abs()
                .max()
                < 1e-14
        );
        let inertia = sample_inertia();
        let expected = xm.transpose() * inertia.to_matrix() * xm;
        assert!(close(
            &x.transpose_apply_inertia(&inertia).to_matrix(),
            &expected
        ));
        let mut general = inertia.to_matrix();
        general[(0, 5)] += 0.1;
        general[(5, 0)] += 0.1;
        general[(3, 4)] += 0.05;
        general[(4, 3)] += 0.05;
        let expected = xm.transpose() * general * xm;
        assert!(close(&x.transpose_apply_matrix(&general), &expected));
    }

    #[test]
    fn cross_products_equal_their_matrices_and_are_dual() {
        let v = Vector6::new(0.3, -1.1, 0.7, 2.0, -0.4, 0.9);
        let m = Vector6::new(-0.5, 0.2, 1.3, 0.1, 0.8, -0.6);
        let mut crm = Matrix6::zeros();
        crm.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&angular(&v).cross_matrix());
        crm.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&angular(&v).cross_matrix());
        crm.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&linear(&v).cross_matrix());
        assert!((motion_cross(&v, &m) - crm * m).abs().max() < 1e-14);
        assert!((force_cross(&v, &m) + crm.transpose() * m).abs().max() < 1e-14);
    }

    #[test]
    fn rigid_inertia_matrix_is_symmetric_and_applies_as_a_matrix() {
        let inertia = sample_inertia();
        let matrix = inertia.to_matrix();
        assert_eq!(matrix, matrix.transpose());
        let v = Vector6::new(0.3, -1.1, 0.7, 2.0, -0.4, 0.9);
        assert!((inertia.apply(&v) - matrix * v).abs().max() < 1e-14);
    }
}

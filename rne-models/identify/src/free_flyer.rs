//! Trajectories of a floating base: six base coordinates moved like joints, turned into the
//! free-flyer's configuration, velocity and acceleration (docs/design.md §4.5, Pinocchio's layout).
//!
//! The base coordinates are its origin p = (x, y, z) in the world and three angles a₁, a₂,
//! a₃ of the orientation `R = Rx(a₁) Ry(a₂) Rz(a₃)` (rotations about the body's x, then the
//! new y, then the new z axis). The free-flyer's state is
//!
//! ```text
//! q = [p, quaternion(R), joints],  v = [Rᵀ ṗ, ω, joint rates],  a = [Rᵀ p̈ − ω × Rᵀ ṗ, ω̇, joint accelerations],
//! ```
//!
//! with ω and ω̇ in the body frame from the three elementary rotations taken as a chain of
//! revolute joints ((3.26) and (3.30): ω ← Rₖᵀ ω + eₖ ȧₖ, ω̇ ← Rₖᵀ ω̇ + eₖ äₖ + ω × eₖ ȧₖ), and
//! the linear acceleration the rate of the body-frame velocity (the classical acceleration
//! less ω × v), as the free-flyer's acceleration is defined.

use crate::base::State;

/// Number of base coordinates before the joints.
pub const BASE_COORDINATES: usize = 6;

/// `Rot(e_axis, angle)` as rows.
fn elementary(axis: usize, angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut r = [[0.0; 3]; 3];
    r[axis][axis] = 1.0;
    r[i][i] = c;
    r[j][j] = c;
    r[i][j] = -s;
    r[j][i] = s;
    r
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose_apply(r: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| r[k][i] * v[k]).sum())
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The unit quaternion [x, y, z, w] of a rotation matrix (Shepperd's method: the largest of
/// the four squared components is taken first, so that nothing divides by a small number).
fn quaternion(r: &[[f64; 3]; 3]) -> [f64; 4] {
    let trace = r[0][0] + r[1][1] + r[2][2];
    let q = if trace > r[0][0].max(r[1][1]).max(r[2][2]) {
        let w = 0.5 * (1.0 + trace).sqrt();
        let f = 0.25 / w;
        [
            (r[2][1] - r[1][2]) * f,
            (r[0][2] - r[2][0]) * f,
            (r[1][0] - r[0][1]) * f,
            w,
        ]
    } else {
        let i = (0..3)
            .max_by(|&a, &b| r[a][a].total_cmp(&r[b][b]))
            .unwrap_or(0);
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let x = 0.5 * (1.0 + r[i][i] - r[j][j] - r[k][k]).sqrt();
        let f = 0.25 / x;
        let mut q = [0.0; 4];
        q[i] = x;
        q[j] = (r[j][i] + r[i][j]) * f;
        q[k] = (r[k][i] + r[i][k]) * f;
        q[3] = (r[k][j] - r[j][k]) * f;
        q
    };
    if q[3] < 0.0 {
        q.map(|x| -x)
    } else {
        q
    }
}

/// The free-flyer state of coordinates `(c, ċ, c̈)`: six base coordinates (module docs), then
/// the joints'.
pub fn free_flyer_state((c, cd, cdd): &State) -> State {
    let mut rotation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (mut omega, mut alpha) = ([0.0; 3], [0.0; 3]);
    for axis in 0..3 {
        let k = 3 + axis;
        let r = elementary(axis, c[k]);
        rotation = mat_mul(&rotation, &r);
        let mut e = [0.0; 3];
        e[axis] = 1.0;
        omega = transpose_apply(&r, omega);
        omega[axis] += cd[k];
        alpha = transpose_apply(&r, alpha);
        alpha[axis] += cdd[k];
        let gyroscopic = cross(omega, e.map(|x| x * cd[k]));
        alpha = std::array::from_fn(|i| alpha[i] + gyroscopic[i]);
    }
    let v = transpose_apply(&rotation, [cd[0], cd[1], cd[2]]);
    let classical = transpose_apply(&rotation, [cdd[0], cdd[1], cdd[2]]);
    let transport = cross(omega, v);
    let a: [f64; 3] = std::array::from_fn(|i| classical[i] - transport[i]);
    let joints = BASE_COORDINATES..c.len();
    let q = [c[0], c[1], c[2]]
        .into_iter()
        .chain(quaternion(&rotation))
        .chain(c[joints.clone()].iter().copied())
        .collect();
    let qd = v
        .into_iter()
        .chain(omega)
        .chain(cd[joints.clone()].iter().copied())
        .collect();
    let qdd = a
        .into_iter()
        .chain(alpha)
        .chain(cdd[joints].iter().copied())
        .collect();
    (q, qd, qdd)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth coordinate trajectory and its exact derivatives.
    fn coordinates(t: f64) -> State {
        let f = |k: f64| ((0.7 + 0.3 * k) * t + k).sin();
        let fd = |k: f64| (0.7 + 0.3 * k) * ((0.7 + 0.3 * k) * t + k).cos();
        let fdd = |k: f64| -(0.7 + 0.3 * k).powi(2) * ((0.7 + 0.3 * k) * t + k).sin();
        let n = 8;
        (
            (0..n).map(|k| f(k as f64)).collect(),
            (0..n).map(|k| fd(k as f64)).collect(),
            (0..n).map(|k| fdd(k as f64)).collect(),
        )
    }

    /// The base's rotation from the quaternion (xyzw) of q, by nalgebra.
    fn rotation_of(q: &[f64]) -> [[f64; 3]; 3] {
        let quaternion = nalgebra::Quaternion::new(q[6], q[3], q[4], q[5]);
        let r = nalgebra::UnitQuaternion::from_quaternion(quaternion).to_rotation_matrix();
        std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]))
    }

    /// Against central differences: the quaternion is a unit quaternion of R, the body
    /// angular velocity is the axial vector of Rᵀ Ṙ, the body linear velocity is Rᵀ ṗ, and
    /// the accelerations are the rates of the body-frame velocities.
    #[test]
    fn velocities_and_accelerations_are_the_rates_of_the_configuration() {
        let h = 1e-5;
        for k in 0..20 {
            let t = 0.37 * k as f64;
            let (q, v, a) = free_flyer_state(&coordinates(t));
            let (before, after) = (
                free_flyer_state(&coordinates(t - h)),
                free_flyer_state(&coordinates(t + h)),
            );
            let norm: f64 = q[3..7].iter().map(|x| x * x).sum();
            assert!((norm - 1.0).abs() < 1e-14);
            let r = rotation_of(&q);
            let (r0, r1) = (rotation_of(&before.0), rotation_of(&after.0));
            let rdot: [[f64; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| (r1[i][j] - r0[i][j]) / (2.0 * h)));
            // Rᵀ Ṙ = [ω]×.
            let skew: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|m| r[m][i] * rdot[m][j]).sum())
            });
            let omega = [skew[2][1], skew[0][2], skew[1][0]];
            let pdot: Vec<f64> = (0..3)
                .map(|i| (after.0[i] - before.0[i]) / (2.0 * h))
                .collect();
            let body = transpose_apply(&r, [pdot[0], pdot[1], pdot[2]]);
            for i in 0..3 {
                assert!((omega[i] - v[3 + i]).abs() < 1e-8, "ω at t = {t}");
                assert!((body[i] - v[i]).abs() < 1e-8, "v at t = {t}");
            }
            for (i, &ai) in a.iter().enumerate() {
                let rate = (after.1[i] - before.1[i]) / (2.0 * h);
                assert!(
                    (rate - ai).abs() < 1e-7,
                    "a[{i}] at t = {t}: {rate} vs {ai}"
                );
            }
        }
    }
}

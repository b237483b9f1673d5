//! Hand-written models for the simulation tests: a simple pendulum, a linear oscillator, the
//! thesis's planar elbow from its closed forms (4.45)–(4.47) with the Christoffel C, and a free
//! rigid body on a floating base.

use rne_runtime::{Dynamics, Kernel};

use super::linalg::{dot, mat_vec, solve_spd};

/// A point mass `m` on a massless rod of length `l`; q = 0 hangs straight down.
#[derive(Clone, Copy, Debug)]
pub struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

impl Pendulum {
    pub fn new(m: f64, l: f64, g: f64) -> Self {
        Self { m, l, g }
    }

    /// The exact period for amplitude `theta0`: T = 4 K(sin(θ₀/2)) / ω₀ with ω₀ = √(g/l) and
    /// the complete elliptic integral K(k) = π / (2 AGM(1, √(1 − k²))).
    pub fn period(&self, theta0: f64) -> f64 {
        let k = (0.5 * theta0).sin();
        let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
        // Quadratic convergence: far fewer than 30 rounds reach the rounding level.
        for _ in 0..30 {
            (a, b) = (0.5 * (a + b), (a * b).sqrt());
        }
        let big_k = std::f64::consts::PI / (2.0 * a);
        4.0 * big_k / (self.g / self.l).sqrt()
    }
}

impl Pendulum {
    pub fn forward_dynamics(&self, q: &[f64; 1], _qd: &[f64; 1], tau: &[f64; 1]) -> [f64; 1] {
        [(tau[0] - self.gravity_torques(q)[0]) / (self.m * self.l * self.l)]
    }
    pub fn mass_matrix(&self, _q: &[f64; 1]) -> [[f64; 1]; 1] {
        [[self.m * self.l * self.l]]
    }
    pub fn coriolis_matrix(&self, _q: &[f64; 1], _qd: &[f64; 1]) -> [[f64; 1]; 1] {
        [[0.0]]
    }
    pub fn gravity_torques(&self, q: &[f64; 1]) -> [f64; 1] {
        [self.m * self.g * self.l * q[0].sin()]
    }
    pub fn kinetic_energy(&self, _q: &[f64; 1], qd: &[f64; 1]) -> f64 {
        0.5 * self.m * self.l * self.l * qd[0] * qd[0]
    }
    pub fn potential_energy(&self, q: &[f64; 1]) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }
}

/// q̈ = −ω² q: exact solution q(t) = cos(ωt) from (1, 0).
#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    pub omega: f64,
}

impl Oscillator {
    pub fn forward_dynamics(&self, q: &[f64; 1], _qd: &[f64; 1], tau: &[f64; 1]) -> [f64; 1] {
        [tau[0] - self.omega * self.omega * q[0]]
    }
    pub fn mass_matrix(&self, _q: &[f64; 1]) -> [[f64; 1]; 1] {
        [[1.0]]
    }
    pub fn coriolis_matrix(&self, _q: &[f64; 1], _qd: &[f64; 1]) -> [[f64; 1]; 1] {
        [[0.0]]
    }
    pub fn gravity_torques(&self, q: &[f64; 1]) -> [f64; 1] {
        [self.omega * self.omega * q[0]]
    }
    pub fn kinetic_energy(&self, _q: &[f64; 1], qd: &[f64; 1]) -> f64 {
        0.5 * qd[0] * qd[0]
    }
    pub fn potential_energy(&self, q: &[f64; 1]) -> f64 {
        0.5 * self.omega * self.omega * q[0] * q[0]
    }
}

/// The planar elbow manipulator of chapter 4: M from (4.45), g from (4.47) with gravity along
/// −y (q = 0 is horizontal), the Christoffel C (not (4.46)) and the energies T = ½ q̇ᵀ M q̇,
/// V = (m₁ l_c1 + m₂ l₁) g sin q₁ + m₂ l_c2 g sin(q₁ + q₂).
#[derive(Clone, Copy, Debug)]
pub struct PlanarElbow {
    m1: f64,
    m2: f64,
    l1: f64,
    lc1: f64,
    lc2: f64,
    i1: f64,
    i2: f64,
    g: f64,
}

impl PlanarElbow {
    /// Table 6.1: two identical steel links, m = 15 kg, l = 0.3 m, COM at the middle,
    /// w = √(m / (7850 · 0.3)) (6.18), I = m (l² + w²) / 12 (6.21), g = 9.81.
    pub fn thesis() -> Self {
        let (m, l): (f64, f64) = (15.0, 0.3);
        let w = (m / (7850.0 * l)).sqrt();
        let i = m * (l * l + w * w) / 12.0;
        Self {
            m1: m,
            m2: m,
            l1: l,
            lc1: 0.5 * l,
            lc2: 0.5 * l,
            i1: i,
            i2: i,
            g: 9.81,
        }
    }
}

impl PlanarElbow {
    pub fn forward_dynamics(&self, q: &[f64; 2], qd: &[f64; 2], tau: &[f64; 2]) -> [f64; 2] {
        let cqd = mat_vec(&self.coriolis_matrix(q, qd), qd);
        let g = self.gravity_torques(q);
        let rhs = [tau[0] - cqd[0] - g[0], tau[1] - cqd[1] - g[1]];
        solve_spd(&self.mass_matrix(q), &rhs).expect("M is positive definite")
    }
    pub fn mass_matrix(&self, q: &[f64; 2]) -> [[f64; 2]; 2] {
        let c2 = q[1].cos();
        let (m1, m2, l1, lc1, lc2) = (self.m1, self.m2, self.l1, self.lc1, self.lc2);
        let m11 = 2.0 * m2 * l1 * lc2 * c2
            + m2 * lc2 * lc2
            + m2 * l1 * l1
            + m1 * lc1 * lc1
            + self.i1
            + self.i2;
        let m12 = m2 * l1 * lc2 * c2 + m2 * lc2 * lc2 + self.i2;
        let m22 = self.i2 + m2 * lc2 * lc2;
        [[m11, m12], [m12, m22]]
    }
    pub fn coriolis_matrix(&self, q: &[f64; 2], qd: &[f64; 2]) -> [[f64; 2]; 2] {
        let h = self.m2 * self.l1 * self.lc2 * q[1].sin();
        [[-h * qd[1], -h * (qd[0] + qd[1])], [h * qd[0], 0.0]]
    }
    pub fn gravity_torques(&self, q: &[f64; 2]) -> [f64; 2] {
        let (c1, c12) = (q[0].cos(), (q[0] + q[1]).cos());
        let g = self.g;
        [
            self.m2 * self.l1 * g * c1 + self.m1 * self.lc1 * g * c1 + self.m2 * self.lc2 * g * c12,
            self.m2 * self.lc2 * g * c12,
        ]
    }
    pub fn kinetic_energy(&self, q: &[f64; 2], qd: &[f64; 2]) -> f64 {
        0.5 * dot(qd, &mat_vec(&self.mass_matrix(q), qd))
    }
    pub fn potential_energy(&self, q: &[f64; 2]) -> f64 {
        (self.m1 * self.lc1 + self.m2 * self.l1) * self.g * q[0].sin()
            + self.m2 * self.lc2 * self.g * (q[0] + q[1]).sin()
    }
}

/// Implements the runtime's `Dynamics<N, N>` for a hand-written model by wrapping its
/// closed-form methods (which keep their array results for the tests) in `Some`.
macro_rules! closed_form_dynamics {
    ($model:ident, $n:literal, $name:literal, $joints:expr) => {
        impl Dynamics<$n, $n> for $model {
            type Scalar = f64;
            const NAME: &'static str = $name;
            const JOINTS: &'static [&'static str] = &$joints;
            const FLOATING_BASE: bool = false;
            const KERNELS: &'static [Kernel] = &crate::SIMULATED;
            fn forward_dynamics(
                &self,
                q: &[f64; $n],
                qd: &[f64; $n],
                tau: &[f64; $n],
            ) -> Option<[f64; $n]> {
                Some($model::forward_dynamics(self, q, qd, tau))
            }
            fn mass_matrix(&self, q: &[f64; $n]) -> Option<[[f64; $n]; $n]> {
                Some($model::mass_matrix(self, q))
            }
            fn coriolis_matrix(&self, q: &[f64; $n], qd: &[f64; $n]) -> Option<[[f64; $n]; $n]> {
                Some($model::coriolis_matrix(self, q, qd))
            }
            fn gravity_torques(&self, q: &[f64; $n]) -> Option<[f64; $n]> {
                Some($model::gravity_torques(self, q))
            }
            fn kinetic_energy(&self, q: &[f64; $n], qd: &[f64; $n]) -> Option<f64> {
                Some($model::kinetic_energy(self, q, qd))
            }
            fn potential_energy(&self, q: &[f64; $n]) -> Option<f64> {
                Some($model::potential_energy(self, q))
            }
        }
    };
}

closed_form_dynamics!(Pendulum, 1, "pendulum", ["q"]);
closed_form_dynamics!(Oscillator, 1, "oscillator", ["q"]);
closed_form_dynamics!(PlanarElbow, 2, "planar elbow", ["q1", "q2"]);

/// A free rigid body on a floating base (NQ = 7, NV = 6), its centre of mass at the base origin
/// and its principal axes along the base axes: M = diag(m, m, m, I₁, I₂, I₃), and the skew
/// Christoffel-type C = [[m ω×, 0], [0, −(I ω)×]] (Ṁ = 0 = C + Cᵀ) with C v = [ω × m v; ω × I ω],
/// the Newton–Euler bias in body coordinates. Gravity `gravity` (world frame) gives
/// g(q) = [−m Rᵀ g; 0] and V = −m gᵀ p.
#[derive(Clone, Copy, Debug)]
pub struct FreeBody {
    pub m: f64,
    pub inertia: [f64; 3],
    pub gravity: [f64; 3],
}

impl FreeBody {
    fn mass_diagonal(&self) -> [f64; 6] {
        let [a, b, c] = self.inertia;
        [self.m, self.m, self.m, a, b, c]
    }
}

impl Dynamics<7, 6> for FreeBody {
    type Scalar = f64;
    const NAME: &'static str = "free body";
    const JOINTS: &'static [&'static str] = &[];
    const FLOATING_BASE: bool = true;
    const KERNELS: &'static [Kernel] = &crate::SIMULATED;
    fn forward_dynamics(&self, q: &[f64; 7], v: &[f64; 6], tau: &[f64; 6]) -> Option<[f64; 6]> {
        let cv = mat_vec(&self.coriolis_matrix(q, v)?, v);
        let g = self.gravity_torques(q)?;
        let d = self.mass_diagonal();
        Some(std::array::from_fn(|i| (tau[i] - cv[i] - g[i]) / d[i]))
    }
    fn mass_matrix(&self, _q: &[f64; 7]) -> Option<[[f64; 6]; 6]> {
        let d = self.mass_diagonal();
        Some(std::array::from_fn(|i| {
            std::array::from_fn(|j| if i == j { d[i] } else { 0.0 })
        }))
    }
    fn coriolis_matrix(&self, _q: &[f64; 7], v: &[f64; 6]) -> Option<[[f64; 6]; 6]> {
        let hat = |w: [f64; 3]| [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
        let w = [v[3], v[4], v[5]];
        let iw = [
            self.inertia[0] * w[0],
            self.inertia[1] * w[1],
            self.inertia[2] * w[2],
        ];
        let (mw, iw) = (hat(w), hat(iw));
        let mut c = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = self.m * mw[i][j];
                c[3 + i][3 + j] = -iw[i][j];
            }
        }
        Some(c)
    }
    fn gravity_torques(&self, q: &[f64; 7]) -> Option<[f64; 6]> {
        let r = crate::se3::rotation(&[q[3], q[4], q[5], q[6]]);
        let f = crate::se3::rotate_back(&r, &self.gravity);
        Some([
            -self.m * f[0],
            -self.m * f[1],
            -self.m * f[2],
            0.0,
            0.0,
            0.0,
        ])
    }
    fn kinetic_energy(&self, q: &[f64; 7], v: &[f64; 6]) -> Option<f64> {
        Some(0.5 * dot(v, &mat_vec(&self.mass_matrix(q)?, v)))
    }
    fn potential_energy(&self, q: &[f64; 7]) -> Option<f64> {
        Some(-self.m * (0..3).map(|i| self.gravity[i] * q[i]).sum::<f64>())
    }
}

/// Observed convergence orders log₂(eₖ / eₖ₊₁) of errors at successively halved steps.
pub fn observed_order(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hand-written elbow is self-consistent: Ṁ = C + Cᵀ (Christoffel C), g = ∂V/∂q,
    /// checked by central differences at an arbitrary state.
    #[test]
    fn planar_elbow_model_is_consistent() {
        let arm = PlanarElbow::thesis();
        let q = [0.4, -1.1];
        let qd = [0.7, 1.9];
        let e = 1e-6;
        let mp = arm.mass_matrix(&[q[0] + e * qd[0], q[1] + e * qd[1]]);
        let mm = arm.mass_matrix(&[q[0] - e * qd[0], q[1] - e * qd[1]]);
        let c = arm.coriolis_matrix(&q, &qd);
        for i in 0..2 {
            for j in 0..2 {
                let mdot = (mp[i][j] - mm[i][j]) / (2.0 * e);
                assert!((mdot - c[i][j] - c[j][i]).abs() < 1e-8);
            }
        }
        let g = arm.gravity_torques(&q);
        for (k, gk) in g.iter().enumerate() {
            let mut a = q;
            let mut b = q;
            a[k] += e;
            b[k] -= e;
            let dv = (arm.potential_energy(&a) - arm.potential_energy(&b)) / (2.0 * e);
            assert!((dv - gk).abs() < 1e-7, "{dv} vs {gk}");
        }
        let w = (15.0_f64 / (7850.0 * 0.3)).sqrt();
        assert!((w - 0.0798).abs() < 1e-4, "(6.18): w = {w}");
    }

    /// The elliptic-integral period reduces to 2π √(l/g) for small amplitudes.
    #[test]
    fn pendulum_period_limits() {
        let p = Pendulum::new(2.0, 0.5, 9.81);
        let t0 = 2.0 * std::f64::consts::PI * (0.5_f64 / 9.81).sqrt();
        assert!((p.period(1e-8) / t0 - 1.0).abs() < 1e-14);
        // Series T = T0 (1 + θ²/16 + 11 θ⁴/3072 + ...).
        let th = 0.2_f64;
        let series = t0 * (1.0 + th * th / 16.0 + 11.0 * th.powi(4) / 3072.0);
        assert!((p.period(th) / series - 1.0).abs() < 1e-7);
    }
}

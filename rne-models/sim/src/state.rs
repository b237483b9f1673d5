//! The state x = (q, q̇) of the first-order form (6.1), (6.3)–(6.5).

/// The state (q, q̇) of an N-joint model: the thesis's x = (x₁, …, x₂ₙ) of (6.3)–(6.5), kept as
/// two arrays instead of interleaved.
///
/// The integrators also use this type for the time derivative ẋ = (q̇, q̈), in which case `q`
/// holds q̇ and `qd` holds q̈.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<const N: usize> {
    /// Joint positions q (rad for revolute joints, m for prismatic ones).
    pub q: [f64; N],
    /// Joint velocities q̇.
    pub qd: [f64; N],
}

impl<const N: usize> State<N> {
    /// The state (q, q̇).
    pub fn new(q: [f64; N], qd: [f64; N]) -> Self {
        Self { q, qd }
    }

    /// The state (q, 0): released from rest.
    pub fn at_rest(q: [f64; N]) -> Self {
        Self { q, qd: [0.0; N] }
    }

    /// `self + h · d`, componentwise.
    pub(crate) fn add_scaled(&self, h: f64, d: &Self) -> Self {
        Self {
            q: std::array::from_fn(|i| self.q[i] + h * d.q[i]),
            qd: std::array::from_fn(|i| self.qd[i] + h * d.qd[i]),
        }
    }

    /// `self + h · Σ cⱼ dⱼ`, componentwise: one Runge–Kutta stage or update.
    pub(crate) fn add_combination(&self, h: f64, terms: &[(f64, &Self)]) -> Self {
        let mut out = *self;
        for i in 0..N {
            let mut dq = 0.0;
            let mut dqd = 0.0;
            for (c, d) in terms {
                dq += c * d.q[i];
                dqd += c * d.qd[i];
            }
            out.q[i] += h * dq;
            out.qd[i] += h * dqd;
        }
        out
    }

    /// The 2N components, positions first.
    pub(crate) fn components(&self) -> impl Iterator<Item = f64> + '_ {
        self.q.iter().chain(&self.qd).copied()
    }

    /// Whether every component is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.components().all(f64::is_finite)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The linear combinations used by the Runge–Kutta stages agree with each other.
    #[test]
    fn combinations_are_componentwise() {
        let x = State::new([1.0, 2.0], [3.0, 4.0]);
        let d1 = State::new([1.0, 0.0], [0.0, 1.0]);
        let d2 = State::new([0.5, 0.5], [2.0, -1.0]);
        let a = x.add_combination(0.1, &[(2.0, &d1), (-1.0, &d2)]);
        let b = x.add_scaled(0.2, &d1).add_scaled(-0.1, &d2);
        for (u, v) in a.components().zip(b.components()) {
            assert!((u - v).abs() < 1e-15);
        }
        assert_eq!(State::at_rest([1.0]), State::new([1.0], [0.0]));
        assert!(!State::new([f64::NAN], [0.0]).is_finite());
        assert!(x.is_finite());
    }
}

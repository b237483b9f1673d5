//! Seeded input states, shared by the timing and the error measurement.
//!
//! A [`Sample`] holds `len` states of a robot with `dof` joints, drawn from a ChaCha8
//! generator: |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10 (the ranges of `rne verify` and of the accuracy
//! tests), and torques uniform in ±max(10, ‖g(q)‖∞), of the size of the gravity torques, for
//! forward dynamics (torques made as τ(q̈) would cancel most of their digits against the bias
//! when q̈ is small, and measure that cancellation instead of the kernel). The other inputs of
//! the benchmark derive from it: the same states at rest, rounded to `f32`, or without a locked
//! joint.

use std::f64::consts::PI;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::Real;

use rne_codegen::Input as Array;
use rne_interpreted::{Error, StateRef};

use crate::calls::Input;

/// Bound on |q|.
pub const Q_BOUND: f64 = PI;
/// Bound on |q̇|.
pub const QD_BOUND: f64 = 10.0;
/// Bound on |q̈|.
pub const QDD_BOUND: f64 = 10.0;
/// Smallest bound on |τ|.
pub const TAU_FLOOR: f64 = 10.0;

/// `len` states, stored flat: state k's positions are `q[k·dof .. (k+1)·dof]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Number of joints.
    pub dof: usize,
    /// Joint positions.
    pub q: Vec<f64>,
    /// Joint velocities.
    pub qd: Vec<f64>,
    /// Joint accelerations.
    pub qdd: Vec<f64>,
    /// Joint torques.
    pub tau: Vec<f64>,
}

impl Sample {
    /// Draws `len` states (see the module documentation); `gravity(q)` gives g(q), which sets
    /// the size of the torques.
    pub fn draw(
        dof: usize,
        len: usize,
        seed: u64,
        mut gravity: impl FnMut(&[f64]) -> Vec<f64>,
    ) -> Sample {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut sample = Sample {
            dof,
            q: Vec::with_capacity(dof * len),
            qd: Vec::with_capacity(dof * len),
            qdd: Vec::with_capacity(dof * len),
            tau: Vec::with_capacity(dof * len),
        };
        for _ in 0..len {
            let mut uniform = |bound: f64| -> Vec<f64> {
                (0..dof).map(|_| rng.gen_range(-bound..=bound)).collect()
            };
            let (q, qd, qdd) = (uniform(Q_BOUND), uniform(QD_BOUND), uniform(QDD_BOUND));
            let scale = gravity(&q)
                .iter()
                .fold(TAU_FLOOR, |m, g| if g.abs() > m { g.abs() } else { m });
            let tau = uniform(scale);
            sample.q.extend(q);
            sample.qd.extend(qd);
            sample.qdd.extend(qdd);
            sample.tau.extend(tau);
        }
        sample
    }

    /// Number of states.
    pub fn len(&self) -> usize {
        self.q.len().checked_div(self.dof).unwrap_or(0)
    }

    /// Whether there is no state.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// State `k`.
    pub fn state(&self, k: usize) -> StateRef<'_> {
        let range = k * self.dof..(k + 1) * self.dof;
        StateRef {
            q: &self.q[range.clone()],
            qd: &self.qd[range.clone()],
            qdd: &self.qdd[range.clone()],
            tau: &self.tau[range],
        }
    }

    /// The first `len` states.
    pub fn truncated(&self, len: usize) -> Sample {
        let end = len.min(self.len()) * self.dof;
        Sample {
            dof: self.dof,
            q: self.q[..end].to_vec(),
            qd: self.qd[..end].to_vec(),
            qdd: self.qdd[..end].to_vec(),
            tau: self.tau[..end].to_vec(),
        }
    }

    /// The same states with q̇ = 0: the inputs of a static scene.
    pub fn at_rest(&self) -> Sample {
        Sample {
            qd: vec![0.0; self.qd.len()],
            ..self.clone()
        }
    }

    /// Every value rounded to the nearest `f32` (and held exactly as `f64`): the inputs of the
    /// single-precision kernels, whose error is then measured against the exact value at these
    /// inputs.
    pub fn rounded_to_f32(&self) -> Sample {
        let round = |v: &[f64]| v.iter().map(|&x| f64::from(x as f32)).collect();
        Sample {
            dof: self.dof,
            q: round(&self.q),
            qd: round(&self.qd),
            qdd: round(&self.qdd),
            tau: round(&self.tau),
        }
    }

    /// The same states without joint `joint`: the inputs of a model with that joint locked.
    pub fn without_joint(&self, joint: usize) -> Sample {
        let dof = self.dof;
        let keep = |v: &[f64]| -> Vec<f64> {
            v.iter()
                .enumerate()
                .filter(|(i, _)| i % dof != joint)
                .map(|(_, &x)| x)
                .collect()
        };
        Sample {
            dof: if joint < dof { dof - 1 } else { dof },
            q: keep(&self.q),
            qd: keep(&self.qd),
            qdd: keep(&self.qdd),
            tau: keep(&self.tau),
        }
    }

    /// The states as a generated function with scalar `T` and N joints takes them (each value
    /// converted by [`Real::from_f64`]), or an error if the sample has another number of
    /// joints.
    pub fn inputs<T: Real, const N: usize>(&self) -> Result<Vec<Input<T, N>>, Error> {
        if self.dof != N {
            return Err(Error::Dimension {
                input: Array::Q,
                got: self.dof,
                expected: N,
            });
        }
        let array = |v: &[f64]| -> [T; N] { std::array::from_fn(|i| T::from_f64(v[i])) };
        Ok((0..self.len())
            .map(|k| {
                let s = self.state(k);
                Input {
                    q: array(s.q),
                    qd: array(s.qd),
                    qdd: array(s.qdd),
                    tau: array(s.tau),
                }
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Draws are reproducible and in range; derived samples keep the states.
    #[test]
    fn draws_and_derived_samples() {
        let gravity = |q: &[f64]| q.iter().map(|x| 100.0 * x).collect();
        let a = Sample::draw(3, 50, 7, gravity);
        assert_eq!(a, Sample::draw(3, 50, 7, gravity));
        assert_eq!(a.len(), 50);
        assert!(a.q.iter().all(|x| x.abs() <= Q_BOUND));
        assert!(a.qd.iter().chain(&a.qdd).all(|x| x.abs() <= 10.0));
        assert!(a.tau.iter().any(|x| x.abs() > TAU_FLOOR));
        let s = a.state(4);
        let locked = a.without_joint(0);
        assert_eq!(locked.dof, 2);
        assert_eq!(locked.state(4).q, &s.q[1..]);
        assert!(a.at_rest().qd.iter().all(|&x| x == 0.0));
        let single = a.rounded_to_f32();
        assert_eq!(single.q[5], f64::from(a.q[5] as f32));
        let inputs = a.inputs::<f32, 3>().unwrap();
        assert_eq!(f64::from(inputs[4].q[2]), single.state(4).q[2]);
        assert!(a.inputs::<f64, 2>().is_err());
        assert_eq!(a.truncated(10).len(), 10);
    }
}

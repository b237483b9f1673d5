//! [`Dynamics`] over the slice-based [`Kernels`] interface: how a user scenario simulates a
//! robot whose N is only known at run time — a built-in robot through its generated kernels'
//! slice adapter, or any spec file through the expression graph
//! ([`Interpreted`](crate::interpreted::Interpreted)).
//!
//! The adapter is const-generic over N and the caller dispatches on the model's number of
//! joints, instantiating the simulation for every N up to [`MAX_DOF`]. Each call goes through
//! `Vec`s, so unlike the generated kernels of [`models`](super::models) this path allocates per
//! evaluation; it serves scenario files, not the thesis's timed runs.

use crate::kernels::{DimensionError, Kernels};
use crate::sim::Dynamics;

/// The largest number of joints a scenario file may simulate.
pub const MAX_DOF: usize = 8;

/// A [`Kernels`] implementation with exactly N joints, seen as a [`Dynamics<N>`].
#[derive(Clone, Copy)]
pub struct KernelDynamics<'a, const N: usize> {
    kernels: &'a dyn Kernels,
}

impl<'a, const N: usize> KernelDynamics<'a, N> {
    /// The adapter, or `None` if the kernels do not have N joints.
    pub fn new(kernels: &'a dyn Kernels) -> Option<Self> {
        (kernels.dof() == N).then_some(Self { kernels })
    }
}

/// The array of a kernel's result. The dimensions were checked when the adapter was built, so
/// an error cannot occur; were it to, NaNs make the integrator stop with a non-finite state
/// instead of panicking.
fn vector<const N: usize>(result: Result<Vec<f64>, DimensionError>) -> [f64; N] {
    result
        .ok()
        .and_then(|v| v.try_into().ok())
        .unwrap_or([f64::NAN; N])
}

/// The matrix of a kernel's result; see [`vector`].
fn matrix<const N: usize>(result: Result<Vec<Vec<f64>>, DimensionError>) -> [[f64; N]; N] {
    let rows = result.unwrap_or_default();
    let mut m = [[f64::NAN; N]; N];
    if rows.len() == N {
        for (row, values) in m.iter_mut().zip(rows) {
            *row = vector(Ok(values));
        }
    }
    m
}

impl<const N: usize> Dynamics<N> for KernelDynamics<'_, N> {
    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> [f64; N] {
        vector(self.kernels.forward_dynamics(q, qd, tau))
    }
    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N] {
        matrix(self.kernels.mass_matrix(q))
    }
    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; N] {
        matrix(self.kernels.coriolis_matrix(q, qd))
    }
    fn gravity_torques(&self, q: &[f64; N]) -> [f64; N] {
        vector(self.kernels.gravity_torques(q))
    }
    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> f64 {
        self.kernels.kinetic_energy(q, qd).unwrap_or(f64::NAN)
    }
    fn potential_energy(&self, q: &[f64; N]) -> f64 {
        self.kernels.potential_energy(q).unwrap_or(f64::NAN)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin::builtin;
    use crate::interpreted::Interpreted;
    use crate::sim::scenarios::models::PlanarElbow;
    use rne_symbolic::spec::LoadOptions;

    /// The adapter gives the generated kernels' values, through the built-in slice adapter
    /// (bit for bit) and through the expression graph (to rounding); it refuses a wrong N.
    #[test]
    fn adapter_matches_the_generated_kernels() {
        let robot = builtin("planar-elbow").unwrap();
        let generated = KernelDynamics::<2>::new(robot.kernels).unwrap();
        assert!(KernelDynamics::<3>::new(robot.kernels).is_none());
        let model = crate::builtin::RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let graph = Interpreted::new(&model);
        let interpreted = KernelDynamics::<2>::new(&graph).unwrap();
        let (q, qd, tau) = ([0.3, -1.2], [0.5, 2.0], [1.0, -3.0]);
        let direct = PlanarElbow.forward_dynamics(&q, &qd, &tau);
        assert_eq!(generated.forward_dynamics(&q, &qd, &tau), direct);
        assert_eq!(generated.mass_matrix(&q), PlanarElbow.mass_matrix(&q));
        let via_graph = interpreted.forward_dynamics(&q, &qd, &tau);
        for i in 0..2 {
            assert!((via_graph[i] - direct[i]).abs() <= 1e-12 * direct[i].abs().max(1.0));
        }
        let c = interpreted.coriolis_matrix(&q, &qd);
        let c_gen = PlanarElbow.coriolis_matrix(&q, &qd);
        for i in 0..2 {
            for j in 0..2 {
                assert!((c[i][j] - c_gen[i][j]).abs() < 1e-12);
            }
        }
        assert!(
            (interpreted.potential_energy(&q) - PlanarElbow.potential_energy(&q)).abs() < 1e-12
        );
        assert!(
            (interpreted.kinetic_energy(&q, &qd) - PlanarElbow.kinetic_energy(&q, &qd)).abs()
                < 1e-12
        );
        assert!(matrix::<2>(Ok(vec![vec![1.0]]))[0][0].is_nan());
    }
}

//! Generated kernels behind a dynamically sized interface, so that the command line and the
//! benchmarks can treat every built-in robot alike.

/// A state array had the wrong length.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{argument}` has {got} values; the robot needs {expected}")]
pub struct DimensionError {
    /// The argument.
    pub argument: &'static str,
    /// Its length.
    pub got: usize,
    /// The length the robot needs (NQ for `q`, NV for the others).
    pub expected: usize,
}

/// The generated functions of one robot, over slices (DESIGN.md §4).
pub trait Kernels {
    /// Number of joint variables.
    fn dof(&self) -> usize;
    /// Joint names.
    fn joints(&self) -> Vec<String>;
    /// τ(q, q̇, q̈).
    fn inverse_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, DimensionError>;
    /// M(q), row-major.
    fn mass_matrix(&self, q: &[f64]) -> Result<Vec<Vec<f64>>, DimensionError>;
    /// The Christoffel C(q, q̇).
    fn coriolis_matrix(&self, q: &[f64], qd: &[f64]) -> Result<Vec<Vec<f64>>, DimensionError>;
    /// g(q).
    fn gravity_torques(&self, q: &[f64]) -> Result<Vec<f64>, DimensionError>;
    /// C(q, q̇) q̇ + g(q).
    fn bias_torques(&self, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, DimensionError>;
    /// q̈(q, q̇, τ).
    fn forward_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
    ) -> Result<Vec<f64>, DimensionError>;
    /// Kinetic energy.
    fn kinetic_energy(&self, q: &[f64], qd: &[f64]) -> Result<f64, DimensionError>;
    /// Potential energy.
    fn potential_energy(&self, q: &[f64]) -> Result<f64, DimensionError>;
}

/// Converts a slice argument to the generated functions' array type.
pub fn array<'a, const N: usize>(
    argument: &'static str,
    values: &'a [f64],
) -> Result<&'a [f64; N], DimensionError> {
    values.try_into().map_err(|_| DimensionError {
        argument,
        got: values.len(),
        expected: N,
    })
}

/// Implements [`Kernels`] for a generated module with every output.
#[macro_export]
macro_rules! impl_kernels {
    ($name:ident, $module:path) => {
        /// Slice adapter of the generated module.
        pub struct $name;

        impl $crate::kernels::Kernels for $name {
            fn dof(&self) -> usize {
                use $module as m;
                m::NDOF
            }
            fn joints(&self) -> Vec<String> {
                use $module as m;
                m::JOINTS.iter().map(|j| j.to_string()).collect()
            }
            fn inverse_dynamics(
                &self,
                q: &[f64],
                qd: &[f64],
                qdd: &[f64],
            ) -> Result<Vec<f64>, $crate::kernels::DimensionError> {
                use $crate::kernels::array;
                use $module as m;
                Ok(
                    m::inverse_dynamics(array("q", q)?, array("qd", qd)?, array("qdd", qdd)?)
                        .to_vec(),
                )
            }
            fn mass_matrix(
                &self,
                q: &[f64],
            ) -> Result<Vec<Vec<f64>>, $crate::kernels::DimensionError> {
                use $module as m;
                Ok(m::mass_matrix($crate::kernels::array("q", q)?)
                    .iter()
                    .map(|r| r.to_vec())
                    .collect())
            }
            fn coriolis_matrix(
                &self,
                q: &[f64],
                qd: &[f64],
            ) -> Result<Vec<Vec<f64>>, $crate::kernels::DimensionError> {
                use $crate::kernels::array;
                use $module as m;
                Ok(m::coriolis_matrix(array("q", q)?, array("qd", qd)?)
                    .iter()
                    .map(|r| r.to_vec())
                    .collect())
            }
            fn gravity_torques(
                &self,
                q: &[f64],
            ) -> Result<Vec<f64>, $crate::kernels::DimensionError> {
                use $module as m;
                Ok(m::gravity_torques($crate::kernels::array("q", q)?).to_vec())
            }
            fn bias_torques(
                &self,
                q: &[f64],
                qd: &[f64],
            ) -> Result<Vec<f64>, $crate::kernels::DimensionError> {
                use $crate::kernels::array;
                use $module as m;
                Ok(m::bias_torques(array("q", q)?, array("qd", qd)?).to_vec())
            }
            fn forward_dynamics(
                &self,
                q: &[f64],
                qd: &[f64],
                tau: &[f64],
            ) -> Result<Vec<f64>, $crate::kernels::DimensionError> {
                use $crate::kernels::array;
                use $module as m;
                Ok(
                    m::forward_dynamics(array("q", q)?, array("qd", qd)?, array("tau", tau)?)
                        .to_vec(),
                )
            }
            fn kinetic_energy(
                &self,
                q: &[f64],
                qd: &[f64],
            ) -> Result<f64, $crate::kernels::DimensionError> {
                use $crate::kernels::array;
                use $module as m;
                Ok(m::kinetic_energy(array("q", q)?, array("qd", qd)?))
            }
            fn potential_energy(&self, q: &[f64]) -> Result<f64, $crate::kernels::DimensionError> {
                use $module as m;
                Ok(m::potential_energy($crate::kernels::array("q", q)?))
            }
        }
    };
}

//! `rne.Model`: a robot's kernels compiled in memory, called under Pinocchio's names (and
//! snake_case aliases) on numpy arrays, one state or a batch.

use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rne_codegen_core::Kernel;
use rne_jit::JitModel;
use rne_symbolic::RobotModel;

use crate::arrays::Array;
use crate::call::{call, Plan};
use crate::errors;
use crate::load::{read_and_compile, robot_path, settings, Options};

/// A robot's kernels compiled in memory for this processor (rne's JIT, Cranelift).
///
/// Made by `rne.load`. Every kernel takes numpy arrays (lists too): a 1-D `q` of `nq` values
/// (and `v`, `a`, `tau` of `nv`) is one state and gives one result; 2-D `(N, nq)` arrays are N
/// states and give results with N first, computed with the GIL released, on `threads` threads
/// (1 by default, 0 for every core; at most one per 256 states). The kernels perform the generated programs' operations in
/// their order: the values are those of rne's Rust kernels, bit for bit (with `fma=False`).
#[pyclass(module = "rne._rne", name = "Model")]
pub struct Model {
    jit: JitModel,
    plans: Vec<Plan>,
    numeric: RobotModel,
    origin: String,
}

impl Model {
    /// The compiled kernels.
    pub(crate) fn jit(&self) -> &JitModel {
        &self.jit
    }

    /// The model as the options made it, parameters as numbers (identification's).
    pub(crate) fn numeric(&self) -> &RobotModel {
        &self.numeric
    }

    fn run<'py>(
        &self,
        py: Python<'py>,
        kernel: Kernel,
        args: &[&Bound<'py, PyAny>],
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        call(
            py,
            &self.jit,
            Plan::find(&self.plans, kernel)?,
            args,
            threads,
        )
    }
}

/// Reads a robot and compiles its kernels: `robot` is a built-in name (`rne.BUILTIN_ROBOTS`)
/// or the path of a URDF or rne TOML file.
///
/// - `floating_base`: a free-flyer root, q = [x, y, z, qx, qy, qz, qw, joints], v = [v, ω]
///   of the base in its own axes, then the joints (Pinocchio's `JointModelFreeFlyer`).
/// - `mimic`: `"constrained"` (URDF semantics: a follower has no variable) or `"free"` (every
///   follower a joint of its own, Pinocchio's default).
/// - `friction`: joint friction (viscous, Coulomb, offset) in the dynamics and the regressor.
/// - `gravity`: three numbers overriding the file's gravity.
/// - `lock`: {joint: value} of joints locked at positions (they leave the state).
/// - `frames`: the link names of the kinematics kernels, in output order (default: every link).
/// - `parameters`: `"constant"` (folded, the fastest), `"runtime"` (the file's named
///   parameters, set by `Model.set_parameters`) or `"base"` (the base parameters).
/// - `kernels`: rne's names of the kernels to compile (default: every one the robot has).
/// - `fma`: fused multiply-adds where the processor has them (faster, not bit for bit with the
///   portable kernels).
/// - `strict`: every warning about the robot file is an error.
#[pyfunction]
#[pyo3(signature = (robot, floating_base=false, mimic="constrained", friction=false, gravity=None, lock=None, frames=None, parameters="constant", *, kernels=None, fma=false, strict=false))]
#[allow(clippy::too_many_arguments)]
pub fn load<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyAny>,
    floating_base: bool,
    mimic: &'py str,
    friction: bool,
    gravity: Option<Vec<f64>>,
    lock: Option<Bound<'py, PyDict>>,
    frames: Option<Vec<String>>,
    parameters: &'py str,
    kernels: Option<Vec<String>>,
    fma: bool,
    strict: bool,
) -> PyResult<Model> {
    let path = robot_path(robot)?;
    let options = Options {
        floating_base,
        mimic,
        friction,
        gravity,
        lock,
        frames,
        parameters,
        fma,
        strict,
    };
    let settings = settings(&options)?;
    let loaded = py.detach(|| read_and_compile(&path, settings, kernels.as_deref()))?;
    Ok(Model {
        plans: Plan::all(&loaded.jit),
        jit: loaded.jit,
        numeric: loaded.numeric,
        origin: loaded.origin,
    })
}

#[pymethods]
impl Model {
    /// The robot's name.
    #[getter]
    fn name(&self) -> &str {
        self.jit.robot()
    }

    /// The robot file (a built-in robot's relative to rne-models/).
    #[getter]
    fn file(&self) -> &str {
        &self.origin
    }

    /// Size of the configuration q (nv + 1 on a floating base).
    #[getter]
    fn nq(&self) -> usize {
        self.jit.nq()
    }

    /// Size of the velocity v, of a and of tau.
    #[getter]
    fn nv(&self) -> usize {
        self.jit.nv()
    }

    /// Whether the root is a free flyer.
    #[getter]
    fn floating_base(&self) -> bool {
        self.jit.programs().floating_base
    }

    /// The joint variables' names, in state order (a floating base's six first are not joints).
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.jit.joints().to_vec()
    }

    /// The frames (link names) of the kinematics kernels, in output order.
    #[getter]
    fn frame_names(&self) -> Vec<String> {
        self.jit.frames().to_vec()
    }

    /// The standard parameters' names: the regressor's columns.
    #[getter]
    fn parameter_names(&self) -> Vec<String> {
        self.jit.parameter_names().to_vec()
    }

    /// The base parameters' names: the base regressor's columns.
    #[getter]
    fn base_parameter_names(&self) -> Vec<String> {
        self.jit.base_parameter_names().to_vec()
    }

    /// The kernels compiled (rne's names).
    #[getter]
    fn kernels(&self) -> Vec<&'static str> {
        self.jit.kernels().iter().map(|k| k.name()).collect()
    }

    /// The names of the parameters read at run time (`parameters="runtime"` or `"base"`).
    #[getter]
    fn runtime_parameter_names(&self) -> Vec<String> {
        self.jit.parameter_symbols().to_vec()
    }

    /// Their values (the robot file's until `set_parameters`).
    #[getter]
    fn runtime_parameters<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.jit.parameters())
    }

    /// Sets the run-time parameters' values, in `runtime_parameter_names`' order.
    fn set_parameters(&mut self, values: &Bound<'_, PyAny>) -> PyResult<()> {
        let width = self.jit.parameters().len();
        let array = Array::read(values, "values", width)?;
        if array.states.is_some() {
            return Err(PyValueError::new_err(format!(
                "`values` must be 1-D ({width},)"
            )));
        }
        self.jit.set_parameters(array.values()).map_err(errors::jit)
    }

    /// Whether multiply-adds are fused (`fma=True` on a processor with FMA).
    #[getter]
    fn fused(&self) -> bool {
        self.jit.fused()
    }

    /// Seconds spent generating the kernels' programs and compiling them: (generation,
    /// compilation).
    #[getter]
    fn load_times(&self) -> (f64, f64) {
        let t = self.jit.timings();
        (t.generation.as_secs_f64(), t.compilation.as_secs_f64())
    }

    /// The index of frame `name` in `frame_names` (the first axis of the kinematics kernels).
    fn frame_index(&self, name: &str) -> PyResult<usize> {
        self.jit
            .frames()
            .iter()
            .position(|f| f == name)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "no frame `{name}`; the frames are {}",
                    self.jit.frames().join(", ")
                ))
            })
    }

    fn __repr__(&self) -> String {
        format!(
            "<rne.Model {} ({}): nq={}, nv={}, {} kernels>",
            self.jit.robot(),
            self.origin,
            self.jit.nq(),
            self.jit.nv(),
            self.jit.kernels().len()
        )
    }

    /// Joint torques τ = M(q) a + C(q, v) v + g(q): Pinocchio's `rnea(model, data, q, v, a)`.
    #[pyo3(signature = (q, v, a, threads=None))]
    fn rnea<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::InverseDynamics, &[q, v, a], threads)
    }

    /// Alias of `rnea`.
    #[pyo3(signature = (q, v, a, threads=None))]
    fn inverse_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.rnea(py, q, v, a, threads)
    }

    /// The mass matrix M(q), full and symmetric: Pinocchio's `crba` with both triangles.
    #[pyo3(signature = (q, threads=None))]
    fn crba<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::MassMatrix, &[q], threads)
    }

    /// Alias of `crba`.
    #[pyo3(signature = (q, threads=None))]
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.crba(py, q, threads)
    }

    /// Bias torques C(q, v) v + g(q): Pinocchio's `nonLinearEffects(model, data, q, v)`.
    #[pyo3(signature = (q, v, threads=None))]
    #[allow(non_snake_case)]
    fn nonLinearEffects<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::BiasTorques, &[q, v], threads)
    }

    /// Alias of `nonLinearEffects`.
    #[pyo3(signature = (q, v, threads=None))]
    fn bias_torques<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.nonLinearEffects(py, q, v, threads)
    }

    /// Gravity torques g(q): Pinocchio's `computeGeneralizedGravity(model, data, q)`.
    #[pyo3(signature = (q, threads=None))]
    #[allow(non_snake_case)]
    fn computeGeneralizedGravity<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::GravityTorques, &[q], threads)
    }

    /// Alias of `computeGeneralizedGravity`.
    #[pyo3(signature = (q, threads=None))]
    fn gravity_torques<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeGeneralizedGravity(py, q, threads)
    }

    /// The Christoffel Coriolis matrix C(q, v) (Ṁ − 2C skew-symmetric; Pinocchio's
    /// `computeCoriolisMatrix` is another factorisation with the same C v).
    #[pyo3(signature = (q, v, threads=None))]
    fn coriolis_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::CoriolisMatrix, &[q, v], threads)
    }

    /// Forward dynamics a = M(q)⁻¹ (τ − C(q, v) v − g(q)): Pinocchio's `aba(model, data, q, v, tau)`.
    #[pyo3(signature = (q, v, tau, threads=None))]
    fn aba<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::ForwardDynamics, &[q, v, tau], threads)
    }

    /// Alias of `aba`.
    #[pyo3(signature = (q, v, tau, threads=None))]
    fn forward_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.aba(py, q, v, tau, threads)
    }

    /// M(q)⁻¹, full and symmetric: Pinocchio's `computeMinverse` with both triangles.
    #[pyo3(signature = (q, threads=None))]
    #[allow(non_snake_case)]
    fn computeMinverse<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::MassMatrixInverse, &[q], threads)
    }

    /// Alias of `computeMinverse`.
    #[pyo3(signature = (q, threads=None))]
    fn mass_matrix_inverse<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeMinverse(py, q, threads)
    }

    /// (∂τ/∂q, ∂τ/∂v) at (q, v, a), ∂/∂q in the tangent space: Pinocchio's
    /// `computeRNEADerivatives` (its ∂τ/∂a is M, `crba`).
    #[pyo3(signature = (q, v, a, threads=None))]
    #[allow(non_snake_case)]
    fn computeRNEADerivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::InverseDynamicsDerivatives, &[q, v, a], threads)
    }

    /// Alias of `computeRNEADerivatives`.
    #[pyo3(signature = (q, v, a, threads=None))]
    fn inverse_dynamics_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeRNEADerivatives(py, q, v, a, threads)
    }

    /// (∂a/∂q, ∂a/∂v, M⁻¹) at (q, v, tau): Pinocchio's `computeABADerivatives`.
    #[pyo3(signature = (q, v, tau, threads=None))]
    #[allow(non_snake_case)]
    fn computeABADerivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(
            py,
            Kernel::ForwardDynamicsDerivatives,
            &[q, v, tau],
            threads,
        )
    }

    /// Alias of `computeABADerivatives`.
    #[pyo3(signature = (q, v, tau, threads=None))]
    fn forward_dynamics_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeABADerivatives(py, q, v, tau, threads)
    }

    /// Every frame's placement in the world, as (rotations (nf, 3, 3), origins (nf, 3)):
    /// Pinocchio's `data.oMf[frame].rotation` and `.translation` after
    /// `framesForwardKinematics`.
    #[pyo3(signature = (q, threads=None))]
    #[allow(non_snake_case)]
    fn framePlacements<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::FramePlacements, &[q], threads)
    }

    /// Alias of `framePlacements`.
    #[pyo3(signature = (q, threads=None))]
    fn frame_placements<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.framePlacements(py, q, threads)
    }

    /// Every frame's geometric Jacobian (nf, 6, nv), rows [v; ω] of the frame origin in world
    /// axes: Pinocchio's `getFrameJacobian(model, data, frame, LOCAL_WORLD_ALIGNED)`.
    #[pyo3(signature = (q, threads=None))]
    #[allow(non_snake_case)]
    fn frameJacobians<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::FrameJacobians, &[q], threads)
    }

    /// Alias of `frameJacobians`.
    #[pyo3(signature = (q, threads=None))]
    fn frame_jacobians<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.frameJacobians(py, q, threads)
    }

    /// Every frame's J̇ v (nf, 6), world axes at the frame origin: the frame's classical
    /// acceleration is J a + J̇ v (Pinocchio's `getFrameClassicalAcceleration(model, data,
    /// frame, LOCAL_WORLD_ALIGNED)` after `forwardKinematics(q, v, 0)`).
    #[pyo3(signature = (q, v, threads=None))]
    #[allow(non_snake_case)]
    fn frameJacobianTimeVariationDotV<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::FrameJacobianDotQd, &[q, v], threads)
    }

    /// Alias of `frameJacobianTimeVariationDotV`.
    #[pyo3(signature = (q, v, threads=None))]
    fn frame_jacobian_dot_v<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.frameJacobianTimeVariationDotV(py, q, v, threads)
    }

    /// Joint friction f_v v + f_c sign(v) + offset (nv,), sign(0) = 0.
    #[pyo3(signature = (v, threads=None))]
    fn friction_torques<'py>(
        &self,
        py: Python<'py>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::FrictionTorques, &[v], threads)
    }

    /// The joint-torque regressor Y (nv, len(parameter_names)) of τ = Y π: Pinocchio's
    /// `computeJointTorqueRegressor`, its columns first (per body m, m cx, m cy, m cz, Ixx,
    /// Ixy, Iyy, Ixz, Iyz, Izz about the body origin), then friction and armature columns.
    #[pyo3(signature = (q, v, a, threads=None))]
    #[allow(non_snake_case)]
    fn computeJointTorqueRegressor<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::Regressor, &[q, v, a], threads)
    }

    /// Alias of `computeJointTorqueRegressor`.
    #[pyo3(signature = (q, v, a, threads=None))]
    fn regressor<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeJointTorqueRegressor(py, q, v, a, threads)
    }

    /// The base regressor Y_b (nv, len(base_parameter_names)) of τ = Y_b π_b, full column rank.
    #[pyo3(signature = (q, v, a, threads=None))]
    fn base_regressor<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::BaseRegressor, &[q, v, a], threads)
    }

    /// The base parameters π_b of standard parameters π (in `parameter_names`' order).
    fn base_parameters<'py>(
        &self,
        py: Python<'py>,
        standard: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let width = self.jit.parameter_names().len();
        let array = Array::read(standard, "standard", width)?;
        if array.states.is_some() {
            return Err(PyValueError::new_err(format!(
                "`standard` must be 1-D ({width},)"
            )));
        }
        let values = self
            .jit
            .base_parameters(array.values())
            .map_err(errors::jit)?;
        Ok(PyArray1::from_vec(py, values))
    }

    /// Kinetic energy ½ vᵀ M(q) v: Pinocchio's `computeKineticEnergy(model, data, q, v)`.
    #[pyo3(signature = (q, v, threads=None))]
    #[allow(non_snake_case)]
    fn computeKineticEnergy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::KineticEnergy, &[q, v], threads)
    }

    /// Alias of `computeKineticEnergy`.
    #[pyo3(signature = (q, v, threads=None))]
    fn kinetic_energy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computeKineticEnergy(py, q, v, threads)
    }

    /// Potential energy −Σ m gᵀ c (zero with every centre of mass at the world origin):
    /// Pinocchio's `computePotentialEnergy(model, data, q)`.
    #[pyo3(signature = (q, threads=None))]
    #[allow(non_snake_case)]
    fn computePotentialEnergy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.run(py, Kernel::PotentialEnergy, &[q], threads)
    }

    /// Alias of `computePotentialEnergy`.
    #[pyo3(signature = (q, threads=None))]
    fn potential_energy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        threads: Option<isize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.computePotentialEnergy(py, q, threads)
    }
}

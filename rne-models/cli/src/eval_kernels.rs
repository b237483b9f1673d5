//! The control and identification quantities of `rne eval` (`--what derivatives|kinematics|
//! regressor`), under the JSON keys of docs/design.md §5: from the generator's optimised programs
//! (exactly what `derive_dynamics!` emits, evaluated operation by operation) or from the
//! independent numeric reference.

use nalgebra::DMatrix;
use rne_codegen::Kernel;
use rne_codegen_core::{build_kernel_with, KernelSetup, Scene};
use rne_reference::Reference;
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};
use serde_json::{json, Value};

use super::CliError;

/// A state: q (NQ) and the velocity-sized q̇, q̈, τ.
pub struct State<'a> {
    /// Configuration.
    pub q: &'a [f64],
    /// Velocities.
    pub qd: &'a [f64],
    /// Accelerations.
    pub qdd: &'a [f64],
    /// Generalised forces.
    pub tau: &'a [f64],
}

/// Which group of quantities.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Group {
    /// `dtau_dq`, `dtau_dqd`, `dqdd_dq`, `dqdd_dqd`, `Minv`.
    Derivatives,
    /// `frames`, `placements`, `jacobians`, `jacobian_dot_qd`.
    Kinematics,
    /// `parameters`, `regressor`, `base_parameters`, `base_regressor`.
    Regressor,
}

impl Group {
    /// The kernels behind the group's entries.
    pub fn kernels(self) -> &'static [Kernel] {
        match self {
            Group::Derivatives => &[
                Kernel::InverseDynamicsDerivatives,
                Kernel::ForwardDynamicsDerivatives,
            ],
            Group::Kinematics => &[
                Kernel::FramePlacements,
                Kernel::FrameJacobians,
                Kernel::FrameJacobianDotQd,
            ],
            Group::Regressor => &[Kernel::Regressor, Kernel::BaseRegressor],
        }
    }
}

fn rows(flat: &[f64], columns: usize) -> Value {
    json!(flat
        .chunks(columns.max(1))
        .map(<[f64]>::to_vec)
        .collect::<Vec<_>>())
}

fn matrix_rows(m: &DMatrix<f64>) -> Value {
    json!(m
        .row_iter()
        .map(|r| r.iter().copied().collect::<Vec<f64>>())
        .collect::<Vec<_>>())
}

/// What the entries of a group are named and sized by: the kinematics kernels' frames, the
/// standard and base parameters' names, NV.
pub struct Names<'a> {
    /// The frames of the kinematics kernels, in output order.
    pub frames: &'a [String],
    /// The standard parameters (the regressor's columns).
    pub parameters: &'a [String],
    /// The base parameters (the base regressor's columns).
    pub base_parameters: &'a [String],
    /// Size of the velocity.
    pub nv: usize,
}

/// The entries of `group` from its kernels' values, `eval(kernel)` (matrices row-major,
/// tuples concatenated): the same keys whatever engine computed them.
pub fn entries(
    group: Group,
    names: &Names<'_>,
    eval: &mut dyn FnMut(Kernel) -> Result<Vec<f64>, CliError>,
) -> Result<Vec<(&'static str, Value)>, CliError> {
    let nv = names.nv;
    let nn = nv * nv;
    Ok(match group {
        Group::Derivatives => {
            let id = eval(Kernel::InverseDynamicsDerivatives)?;
            let fd = eval(Kernel::ForwardDynamicsDerivatives)?;
            vec![
                ("dtau_dq", rows(&id[..nn], nv)),
                ("dtau_dqd", rows(&id[nn..], nv)),
                ("dqdd_dq", rows(&fd[..nn], nv)),
                ("dqdd_dqd", rows(&fd[nn..2 * nn], nv)),
                ("Minv", rows(&fd[2 * nn..], nv)),
            ]
        }
        Group::Kinematics => {
            let placements: Vec<Value> = eval(Kernel::FramePlacements)?
                .chunks(12)
                .map(|p| json!([rows(&p[..9], 3), p[9..].to_vec()]))
                .collect();
            let jacobians: Vec<Value> = eval(Kernel::FrameJacobians)?
                .chunks(6 * nv.max(1))
                .map(|j| rows(j, nv))
                .collect();
            vec![
                ("frames", json!(names.frames)),
                ("placements", json!(placements)),
                ("jacobians", json!(jacobians)),
                (
                    "jacobian_dot_qd",
                    rows(&eval(Kernel::FrameJacobianDotQd)?, 6),
                ),
            ]
        }
        Group::Regressor => vec![
            ("parameters", json!(names.parameters)),
            (
                "regressor",
                rows(&eval(Kernel::Regressor)?, names.parameters.len()),
            ),
            ("base_parameters", json!(names.base_parameters)),
            (
                "base_regressor",
                rows(&eval(Kernel::BaseRegressor)?, names.base_parameters.len()),
            ),
        ],
    })
}

/// The entries of `group` at `state` from the generator's programs for `model` as `scene` sees
/// it (the model options' scene: the base and mimic mode already applied are kept), evaluated
/// operation by operation.
pub fn symbolic(
    model: &RobotModel,
    scene: &Scene,
    group: Group,
    state: &State,
) -> Result<Vec<(&'static str, Value)>, CliError> {
    let model = scene.apply(model)?;
    let dynamics = SymbolicDynamics::new(&model);
    let setup = KernelSetup::new(&dynamics, group.kernels());
    let nv = dynamics.layout().nv();
    let mut eval = |kernel: Kernel| -> Result<Vec<f64>, CliError> {
        let program = build_kernel_with(&dynamics, kernel, &setup).program;
        Ok(program.eval(|s| match s {
            Symbol::Position(k) => state.q[k as usize],
            Symbol::Velocity(k) => state.qd[k as usize],
            Symbol::Acceleration(k) => state.qdd[k as usize],
            Symbol::Force(k) => state.tau[k as usize],
            Symbol::Parameter(_) => model.parameter_value(s).unwrap_or(f64::NAN),
            // Given its lane's value by `Program::eval`.
            Symbol::Lane(_) => f64::NAN,
        }))
    };
    let frames: Vec<String> = setup
        .frames
        .iter()
        .map(|&f| dynamics.frames()[f].name.clone())
        .collect();
    let parameters = dynamics.parameter_names();
    let base_parameters = setup
        .base_parameters
        .as_ref()
        .map(|base| base.names(&parameters))
        .unwrap_or_default();
    let names = Names {
        frames: &frames,
        parameters: &parameters,
        base_parameters: &base_parameters,
        nv,
    };
    entries(group, &names, &mut eval)
}

/// The entries of `group` at `state` from the independent numeric reference (the base
/// parameters chosen as the generator chooses them).
pub fn numeric(
    model: &RobotModel,
    scene: &Scene,
    group: Group,
    state: &State,
) -> Result<Vec<(&'static str, Value)>, CliError> {
    let model = scene.apply(model)?;
    let mut reference = Reference::try_new(&model.to_numeric())?;
    let (q, qd, qdd, tau) = (state.q, state.qd, state.qdd, state.tau);
    Ok(match group {
        Group::Derivatives => {
            let (dq, dv) = reference.inverse_dynamics_derivatives(q, qd, qdd)?;
            let fd = reference.forward_dynamics_derivatives(q, qd, tau)?;
            vec![
                ("dtau_dq", matrix_rows(&dq)),
                ("dtau_dqd", matrix_rows(&dv)),
                ("dqdd_dq", matrix_rows(&fd.dqdd_dq)),
                ("dqdd_dqd", matrix_rows(&fd.dqdd_dqd)),
                ("Minv", matrix_rows(&fd.mass_matrix_inverse)),
            ]
        }
        Group::Kinematics => {
            let placements: Vec<Value> = reference
                .frame_placements(q)?
                .iter()
                .map(|(r, p)| {
                    json!([
                        matrix_rows(&DMatrix::from_iterator(3, 3, r.iter().copied())),
                        p.as_slice()
                    ])
                })
                .collect();
            let jacobians: Vec<Value> = reference
                .frame_jacobians(q)?
                .iter()
                .map(matrix_rows)
                .collect();
            let jdot: Vec<Vec<f64>> = reference
                .frame_jacobian_dot_qd(q, qd)?
                .iter()
                .map(|v| v.as_slice().to_vec())
                .collect();
            vec![
                ("frames", json!(reference.link_names())),
                ("placements", json!(placements)),
                ("jacobians", json!(jacobians)),
                ("jacobian_dot_qd", json!(jdot)),
            ]
        }
        Group::Regressor => {
            let y = reference.regressor(q, qd, qdd)?;
            let base = SymbolicDynamics::new(&model).base_parameters();
            let names = reference.parameter_names();
            let base_y =
                DMatrix::from_fn(y.nrows(), base.len(), |i, j| y[(i, base.independent[j])]);
            vec![
                ("parameters", json!(names)),
                ("regressor", matrix_rows(&y)),
                ("base_parameters", json!(base.names(&names))),
                ("base_regressor", matrix_rows(&base_y)),
            ]
        }
    })
}

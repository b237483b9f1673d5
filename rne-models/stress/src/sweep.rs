//! A robot's kernels measured at a set of states: each evaluated twice — in `f64` exactly as
//! the generated code computes it ([`Probe::eval_f64`]: the programs interpreted or compiled
//! in memory, bit for bit the compiled kernel, checked on every built-in robot by
//! [`crate::cases::compiled`]) and in double-double through the graph before optimisation
//! ([`Interpreted::exact`](rne_interpreted::Interpreted::exact), the value of the `f64` model
//! to about 10⁻³¹ relative). Their difference is the error of the generated kernel alone: the
//! rounding of its operations and of the constants the optimiser folds anew, not an error of
//! the model or of the inputs.

use rne_codegen::{DoubleDouble, Kernel};
use rne_figures::{Deviation, Format};
use rne_interpreted::JointState;

use crate::probe::Probe;

use crate::measure::{condition, scaled_condition, ErrorsByKernel, KernelErrors, Spread, EPSILON};

/// The errors of several kernels over a set of states, and how well conditioned M was there.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sweep {
    /// The errors of each kernel.
    pub errors: ErrorsByKernel,
    /// cond(M) over the states.
    pub condition: Spread,
    /// The condition number of M scaled to a unit diagonal over the states.
    pub scaled_condition: Spread,
    /// The cancellation κ in forward dynamics' right-hand side over the states (see
    /// [`cancellation`]).
    pub cancellation: Spread,
    /// Forward dynamics' error over ε·max(κ, 1)·(scaled cond), state by state: the error of
    /// forming τ − b (ε κ relative) amplified by the conditioning of M.
    pub fd_over_estimate: Spread,
}

/// What the generated `f64` kernel returns at `state` (matrices row-major). `None` if the
/// programs were not built with this kernel.
pub fn eval_f64(programs: &Probe, kernel: Kernel, state: &JointState) -> Option<Vec<f64>> {
    programs.eval(kernel, state.as_ref())
}

/// The rounding error of the `f64` kernel at `state`, against double-double.
pub fn deviation(programs: &Probe, kernel: Kernel, state: &JointState) -> Option<Deviation> {
    let computed = eval_f64(programs, kernel, state)?;
    let exact = programs.exact(kernel, state.as_ref())?;
    Some(Deviation::between(&computed, &exact, Format::F64))
}

/// The errors of each of `kernels` that the programs were built with, over `states`.
pub fn errors(programs: &Probe, kernels: &[Kernel], states: &[JointState]) -> ErrorsByKernel {
    ErrorsByKernel(
        kernels
            .iter()
            .filter_map(|&kernel| {
                let deviations: Option<Vec<Deviation>> = states
                    .iter()
                    .map(|state| deviation(programs, kernel, state))
                    .collect();
                Some((kernel, KernelErrors::of(&deviations?)))
            })
            .collect(),
    )
}

/// The torque τ(q, q̇, q̈) of `state` as the `f64` inverse-dynamics kernel computes it: the
/// input that makes forward dynamics reproduce `state.qdd`. `None` without inverse dynamics.
pub fn torque_for(programs: &Probe, state: &JointState) -> Option<Vec<f64>> {
    eval_f64(programs, Kernel::InverseDynamics, state)
}

/// cond(M(q)) and the condition number of M scaled to a unit diagonal (see
/// [`scaled_condition`]), from M in double-double rounded once to `f64`. `None` without the
/// mass matrix.
pub fn conditions(programs: &Probe, q: &[f64]) -> Option<(f64, f64)> {
    let state = JointState::at(q);
    let m: Vec<f64> = programs
        .exact(Kernel::MassMatrix, state.as_ref())?
        .into_iter()
        .map(DoubleDouble::to_f64)
        .collect();
    let n = programs.dof();
    Some((condition(&m, n), scaled_condition(&m, n)))
}

/// The cancellation κ = ‖b‖∞ / ‖τ − b‖∞ in forward dynamics' right-hand side τ − b, with
/// b = C(q, q̇) q̇ + g(q) from the `f64` bias kernel: the subtraction leaves an absolute error
/// of about ε‖b‖, which is ε κ relative to τ − b. `None` without the bias or without τ.
pub fn cancellation(programs: &Probe, state: &JointState) -> Option<f64> {
    let bias = eval_f64(programs, Kernel::BiasTorques, state)?;
    if state.tau.len() != bias.len() {
        return None;
    }
    let norm = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, x| m.max(x.abs()));
    let net = norm(&mut state.tau.iter().zip(&bias).map(|(t, b)| t - b));
    Some(norm(&mut bias.iter().copied()) / net)
}

/// The errors of `kernels` over `states`, with the spread of cond(M), of the scaled condition
/// number and of the cancellation κ over the same states, and forward dynamics' error against
/// the estimate ε·max(κ, 1)·(scaled cond) where all three are available.
pub fn sweep(programs: &Probe, kernels: &[Kernel], states: &[JointState]) -> Sweep {
    let conditions: Vec<Option<(f64, f64)>> =
        states.iter().map(|s| conditions(programs, &s.q)).collect();
    let cancellations: Vec<Option<f64>> =
        states.iter().map(|s| cancellation(programs, s)).collect();
    let fd_estimate = states
        .iter()
        .zip(conditions.iter().zip(&cancellations))
        .filter_map(|(s, (c, k))| {
            let error = deviation(programs, Kernel::ForwardDynamics, s)?.relative;
            Some(error / (EPSILON * k.as_ref()?.max(1.0) * c.as_ref()?.1))
        });
    Sweep {
        fd_over_estimate: Spread::of(fd_estimate),
        errors: errors(programs, kernels, states),
        condition: Spread::of(conditions.iter().flatten().map(|c| c.0)),
        scaled_condition: Spread::of(conditions.iter().flatten().map(|c| c.1)),
        cancellation: Spread::of(cancellations.into_iter().flatten()),
    }
}

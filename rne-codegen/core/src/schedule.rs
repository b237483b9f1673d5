//! The third stage of generation: build every kernel of a [`Plan`] on two threads, each
//! finished (emitted, or handed to another backend) by the caller's function on the thread
//! that built it.
//!
//! This thread builds the derivative kernels, the costliest. The other builds forward
//! dynamics (both ways, to choose) and finds the base parameters when a kernel reads them,
//! then builds those kernels. When both derivative kernels are built, forward dynamics' takes
//! the sweep inverse dynamics' chose in scalars (the same torques). Built in scalars, the
//! graph of ∂ID is built both ways at once, by forward sweeps on this thread and by reverse
//! sweeps on the other, which sends its cost; this thread chooses ([`Sweep::cheaper`], as one
//! thread trying both would; its forward sweeps stop as soon as they cost more than the
//! reverse ones, once that cost has arrived), hands over its graph if the forward sweeps won,
//! and builds ∂FD by the chosen sweep while the other finishes ∂ID from the graph it was
//! handed or its own.
//! Built in lanes (`derivatives: lanes`), this thread builds ∂ID and then ∂FD: only a ∂ID too
//! long for lanes falls back to scalars and chooses a sweep, known once it is built. Every
//! other kernel is shared: each thread, once done with its own, takes the next, costliest
//! first, until none is left. Each kernel is built from the same dynamics and setup on either
//! thread, so the module does not depend on which.
//!
//! A kernel whose expression graph reaches the graph's node limit is an error naming it
//! ([`CodegenError::TooLarge`]); the threads stop at the first error.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::time::{Duration, Instant};

use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::dynamics::derivatives::Sweep;
use rne_symbolic::SymbolicDynamics;

use crate::built::{build_in_scalars, build_kernel_with, choose_forward_dynamics, BuiltKernel};
use crate::error::CodegenError;
use crate::generation_options::ForwardDynamicsMethod;
use crate::kernel::{articulated_applies, Dims, Kernel};
use crate::module::ForwardDynamicsChoice;
use crate::plan::{reads_base, Plan};

/// How a built kernel is finished, on the thread that built it: its kernel, the array sizes
/// and when its building started are given with it.
pub(crate) type Finish<'f, T> =
    dyn Fn(BuiltKernel, Kernel, Dims, Instant) -> Result<T, CodegenError> + Sync + 'f;

/// Every kernel of a plan, finished.
pub(crate) struct Built<T> {
    /// One per kernel of [`Plan::kernels`], in its order.
    pub kernels: Vec<T>,
    /// Both ways forward dynamics could be built, when it was and both apply.
    pub forward_dynamics_choice: Option<ForwardDynamicsChoice>,
    /// The base parameters, when a kernel reads them.
    pub base_parameters: Option<BaseParameters>,
}

/// A kernel and its place in [`Plan::kernels`].
type Numbered = (usize, Kernel);

/// Which thread builds which kernels.
struct Assignment {
    /// This thread's own: the derivative kernels.
    this: Vec<Numbered>,
    /// The other thread's own: forward dynamics, the kernels of the base parameters.
    other: Vec<Numbered>,
    /// Taken by either, costliest first.
    shared: Vec<Numbered>,
    /// Whether ∂ID is built by forward sweeps here and reverse sweeps there, to choose.
    id_sweeps_on_both_threads: bool,
}

impl Assignment {
    fn new(plan: &Plan) -> Assignment {
        let kernels = &plan.kernels;
        let id_sweeps_on_both_threads = kernels.contains(&Kernel::InverseDynamicsDerivatives)
            && kernels.contains(&Kernel::ForwardDynamicsDerivatives)
            && !plan.setup.derivative_lanes;
        let here = |kernel: Kernel| match kernel {
            Kernel::ForwardDynamicsDerivatives => true,
            Kernel::InverseDynamicsDerivatives => !id_sweeps_on_both_threads,
            _ => false,
        };
        let there = |kernel: Kernel| match kernel {
            Kernel::ForwardDynamics => true,
            Kernel::InverseDynamicsDerivatives => id_sweeps_on_both_threads,
            kernel => plan.finds_base_parameters && reads_base(kernel),
        };
        let numbered = |keep: &dyn Fn(Kernel) -> bool| -> Vec<Numbered> {
            kernels
                .iter()
                .copied()
                .enumerate()
                .filter(|&(_, k)| keep(k))
                .collect()
        };
        let mut this = numbered(&here);
        // ∂ID before ∂FD, which takes the sweep ∂ID chose if it fell back to scalars.
        this.sort_by_key(|&(_, k)| k == Kernel::ForwardDynamicsDerivatives);
        let mut other = numbered(&there);
        // The handed-over graph after the others, when it is most likely ready.
        other.sort_by_key(|&(_, k)| k == Kernel::InverseDynamicsDerivatives);
        let mut shared = numbered(&|k| !here(k) && !there(k));
        shared.sort_by_key(|&(_, k)| costliest_first(k));
        Assignment {
            this,
            other,
            shared,
            id_sweeps_on_both_threads,
        }
    }
}

/// The shared kernels, each taken once by whichever thread asks first.
struct Shared {
    kernels: Vec<Numbered>,
    next: AtomicUsize,
}

impl Shared {
    fn take(&self) -> Option<Numbered> {
        self.kernels
            .get(self.next.fetch_add(1, Ordering::Relaxed))
            .copied()
    }
}

/// What the other thread returns: the forward-dynamics choice, the base parameters it found
/// and its finished kernels.
type OtherResult<T> = (
    Option<ForwardDynamicsChoice>,
    Option<BaseParameters>,
    Vec<(usize, T)>,
);

/// Builds and finishes every kernel of `plan` (module docs).
pub(crate) fn build<T: Send>(
    plan: &Plan,
    finish: &Finish<'_, T>,
) -> Result<Built<T>, CodegenError> {
    let assignment = Assignment::new(plan);
    let shared = Shared {
        kernels: assignment.shared,
        next: AtomicUsize::new(0),
    };
    let both = assignment.id_sweeps_on_both_threads;
    let mut finished: Vec<Option<T>> = (0..plan.kernels.len()).map(|_| None).collect();
    let (choice, base_parameters) = std::thread::scope(|scope| {
        // Made inside the scope: an early return drops the senders before the scope joins
        // the other thread, which then stops waiting.
        let (handover, handed) = channel::<Option<(SymbolicDynamics, Duration)>>();
        let (cost_sender, cost) = channel::<usize>();
        let other = {
            let (shared, kernels) = (&shared, assignment.other);
            scope.spawn(move || {
                other_thread(plan, kernels, shared, both, handed, cost_sender, finish)
            })
        };
        let mut dynamics = plan.dynamics.clone();
        if both {
            dynamics = choose_sweep(dynamics, &cost, handover);
        }
        let mine = this_thread(plan, dynamics, assignment.this, &shared, finish);
        let theirs = other
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        let (choice, base_parameters, theirs) = theirs?;
        for (k, t) in mine?.into_iter().chain(theirs) {
            finished[k] = Some(t);
        }
        Ok::<_, CodegenError>((choice, base_parameters))
    })?;
    Ok(Built {
        kernels: finished
            .into_iter()
            .map(|t| t.expect("every kernel is finished"))
            .collect(),
        forward_dynamics_choice: choice,
        base_parameters: if plan.finds_base_parameters {
            base_parameters
        } else {
            plan.setup.base_parameters.clone()
        },
    })
}

/// Builds ∂ID by forward sweeps, keeps the cheaper of them and the other thread's reverse
/// sweeps, and hands its graph over if it won: the dynamics with the sweep chosen. Once the
/// reverse sweeps' cost has arrived, the forward sweeps stop as soon as what they have built
/// costs more ([`SymbolicDynamics::forward_derivatives_cost_within`]): the choice is the one
/// the whole would give, and on robots where the reverse sweeps win by far (the humanoids) the
/// derivative kernels start sooner.
fn choose_sweep(
    dynamics: SymbolicDynamics,
    reverse_cost: &Receiver<usize>,
    handover: Sender<Option<(SymbolicDynamics, Duration)>>,
) -> SymbolicDynamics {
    let start = Instant::now();
    let mut forward = dynamics.clone().with_derivative_sweep(Sweep::Forward);
    let mut reverse: Option<usize> = None;
    let mut bound = || {
        if reverse.is_none() {
            reverse = reverse_cost.try_recv().ok();
        }
        reverse
    };
    let sweep = match forward.forward_derivatives_cost_within(&mut bound) {
        // Fails only when the other thread has ended early, which its join reports; until
        // then this thread goes on as if the reverse sweeps had lost.
        Some(forward_cost) => {
            let reverse = reverse.or_else(|| reverse_cost.recv().ok());
            Sweep::cheaper(forward_cost, reverse.unwrap_or(usize::MAX))
        }
        None => Sweep::Reverse,
    };
    let _ = handover.send((sweep == Sweep::Forward).then(|| (forward, start.elapsed())));
    dynamics.with_derivative_sweep(sweep)
}

/// This thread's kernels, then shared ones until none is left.
fn this_thread<T>(
    plan: &Plan,
    mut dynamics: SymbolicDynamics,
    own: Vec<Numbered>,
    shared: &Shared,
    finish: &Finish<'_, T>,
) -> Result<Vec<(usize, T)>, CodegenError> {
    let mut done = Vec::new();
    for (k, kernel) in own.into_iter().chain(std::iter::from_fn(|| shared.take())) {
        let start = Instant::now();
        let built = checked(build_kernel_with(&dynamics, kernel, &plan.setup), kernel)?;
        if kernel == Kernel::InverseDynamicsDerivatives {
            if let Some(sweep) = built.dynamics.derivative_sweep() {
                dynamics = dynamics.with_derivative_sweep(sweep);
            }
        }
        done.push((k, finish(built, kernel, plan.dims, start)?));
    }
    Ok(done)
}

/// The other thread: ∂ID's reverse sweeps (when both threads build it), forward dynamics
/// both ways (when it applies), the base parameters (when a kernel reads them), its own
/// kernels, then shared ones.
fn other_thread<T>(
    plan: &Plan,
    kernels: Vec<Numbered>,
    shared: &Shared,
    id_sweeps_on_both_threads: bool,
    handed: Receiver<Option<(SymbolicDynamics, Duration)>>,
    reverse_cost: Sender<usize>,
    finish: &Finish<'_, T>,
) -> Result<OtherResult<T>, CodegenError> {
    let dynamics = &plan.dynamics;
    let (mut setup, mut dims) = (plan.setup.clone(), plan.dims);
    let mut by_reverse_sweeps = id_sweeps_on_both_threads.then(|| {
        let start = Instant::now();
        let mut reverse = dynamics.clone().with_derivative_sweep(Sweep::Reverse);
        let _ = reverse_cost.send(reverse.inverse_dynamics_derivatives_cost());
        (reverse, start.elapsed())
    });
    let builds_forward_dynamics = kernels.iter().any(|&(_, k)| k == Kernel::ForwardDynamics);
    let choosing = Instant::now();
    let (choice, mut chosen) = if builds_forward_dynamics && articulated_applies(dynamics) {
        let (choice, built) =
            choose_forward_dynamics(dynamics, &setup, plan.options.forward_dynamics);
        (Some(choice), Some((built, choosing.elapsed())))
    } else {
        (None, None)
    };
    setup.articulated = choice
        .as_ref()
        .is_some_and(|c| c.chosen == ForwardDynamicsMethod::Aba);
    if plan.finds_base_parameters {
        let base = dynamics.base_parameters();
        dims.nb = base.len();
        setup.base_parameters = Some(base);
    }
    let mut done = Vec::new();
    for (k, kernel) in kernels
        .into_iter()
        .chain(std::iter::from_fn(|| shared.take()))
    {
        let (built, start) = match kernel {
            Kernel::ForwardDynamics if chosen.is_some() => {
                let (built, time) = chosen.take().expect("forward dynamics is built once");
                (built, started(time))
            }
            Kernel::InverseDynamicsDerivatives if id_sweeps_on_both_threads => {
                // This thread's own graph when the other ended before handing one over.
                let (graph, time) = handed
                    .recv()
                    .ok()
                    .flatten()
                    .or_else(|| by_reverse_sweeps.take())
                    .expect("∂ID is built once");
                (build_in_scalars(graph, kernel, &setup), started(time))
            }
            _ => (build_kernel_with(dynamics, kernel, &setup), Instant::now()),
        };
        done.push((k, finish(checked(built, kernel)?, kernel, dims, start)?));
    }
    Ok((choice, setup.base_parameters, done))
}

/// `built`, or the error naming `kernel` when its graph reached the node limit.
fn checked(built: BuiltKernel, kernel: Kernel) -> Result<BuiltKernel, CodegenError> {
    let graph = &built.dynamics.model.graph;
    if graph.limit_reached() {
        return Err(CodegenError::TooLarge {
            kernel,
            limit: graph.node_limit(),
        });
    }
    Ok(built)
}

/// The instant `time` ago: when a kernel whose building took `time` so far started.
fn started(time: Duration) -> Instant {
    let now = Instant::now();
    now.checked_sub(time).unwrap_or(now)
}

/// Where `kernel` comes in the order the two threads take the shared kernels in: costliest
/// first, so that the last kernel taken is a cheap one and the threads end close together
/// (Graham's "longest processing time first", SIAM J. Appl. Math. 17(2), 1969). The order is
/// that of the kernels' generation times on a 48-joint chain (`rne stats`), where the
/// regressor, taken last in the module's order, had kept one thread busy long after the other
/// had run out of work.
fn costliest_first(kernel: Kernel) -> usize {
    const ORDER: [Kernel; 18] = [
        Kernel::ForwardDynamicsDerivatives,
        Kernel::InverseDynamicsDerivatives,
        Kernel::Regressor,
        Kernel::BaseRegressor,
        Kernel::MassMatrixInverse,
        Kernel::CoriolisMatrix,
        Kernel::FrameJacobians,
        Kernel::ForwardDynamics,
        Kernel::MassMatrix,
        Kernel::BaseParameters,
        Kernel::InverseDynamics,
        Kernel::BiasTorques,
        Kernel::FrameJacobianDotQd,
        Kernel::GravityTorques,
        Kernel::KineticEnergy,
        Kernel::FramePlacements,
        Kernel::PotentialEnergy,
        Kernel::FrictionTorques,
    ];
    ORDER
        .iter()
        .position(|&k| k == kernel)
        .unwrap_or(ORDER.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kernel has a place of its own in the threads' order: none falls to the end as
    /// unknown, and no two tie (a tie would leave their order to the sort).
    #[test]
    fn the_shared_order_places_every_kernel() {
        let mut places: Vec<usize> = Kernel::ALL.iter().map(|&k| costliest_first(k)).collect();
        places.sort_unstable();
        assert_eq!(places, (0..Kernel::ALL.len()).collect::<Vec<_>>());
    }
}

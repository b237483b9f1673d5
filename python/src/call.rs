//! One kernel called from Python: the arrays read and checked, one state computed in place, or
//! a batch of N states computed with the GIL released on one or more threads, and the values
//! returned as numpy arrays (`layout`).

use std::cell::RefCell;

use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyTuple};
use rne_codegen_core::{Input, Kernel, Shape};
use rne_jit::{Batch, JitModel, State};

use crate::arrays::Array;
use crate::batch::Job;
use crate::errors;
use crate::layout::{self, Part, Sizes};
use crate::pool;

/// The most a base quaternion's norm may differ from 1 (as `rne eval` checks it).
const QUATERNION_TOLERANCE: f64 = 1e-9;

/// The Python name of a kernel's input (Pinocchio's: q, v, a, tau).
pub(crate) fn input_name(input: Input) -> &'static str {
    match input {
        Input::Q => "q",
        Input::Qd => "v",
        Input::Qdd => "a",
        Input::Tau => "tau",
        Input::Standard => "standard",
    }
}

/// How a compiled kernel is called and its values returned: prepared for every kernel when the
/// model is loaded, so that a call allocates nothing but its arrays.
pub(crate) struct Plan {
    /// The kernel.
    kernel: Kernel,
    /// Values per state.
    per: usize,
    /// The arrays of the result (`layout`).
    parts: Vec<Part>,
    /// Whether the one part is the whole output in order (written in place).
    whole: bool,
    /// Whether the parts are the kernel's matrices (each written in place into its array).
    matrices: bool,
    /// Operations per state (the program's), for the threads a batch is worth.
    ops: usize,
}

impl Plan {
    /// The plans of every kernel `model` compiled.
    pub fn all(model: &JitModel) -> Vec<Plan> {
        model
            .programs()
            .kernels
            .iter()
            .filter_map(|k| {
                let per = model.output_len(k.kernel)?;
                let parts = layout::parts(k.kernel, sizes(model), per);
                Some(Plan {
                    kernel: k.kernel,
                    per,
                    whole: layout::is_whole(&parts, per),
                    matrices: matches!(k.kernel.shape(), Shape::Matrices(_)),
                    parts,
                    ops: k.report.ops.total(),
                })
            })
            .collect()
    }

    /// The plan of `kernel` among `plans`; an error when the model was loaded without it.
    pub fn find(plans: &[Plan], kernel: Kernel) -> PyResult<&Plan> {
        plans.iter().find(|p| p.kernel == kernel).ok_or_else(|| {
            PyValueError::new_err(format!(
                "the model has no `{kernel}` kernel: it was loaded without it (see `kernels=` of rne.load)"
            ))
        })
    }
}

/// Operations a thread of a batch must have at least (about 50 µs of work): below that,
/// starting a thread costs more than it saves. Results do not depend on the thread count.
const OPS_PER_THREAD: usize = 100_000;

/// The kernel of `plan` at the state(s) `args` (the kernel's inputs in order), on up to
/// `threads` threads for a batch.
pub(crate) fn call<'py>(
    py: Python<'py>,
    model: &JitModel,
    plan: &Plan,
    args: &[&Bound<'py, PyAny>],
    threads: Option<isize>,
) -> PyResult<Bound<'py, PyAny>> {
    let inputs = read_inputs(model, plan.kernel, args)?;
    let states = batch_states(&inputs)?;
    check_quaternions(model, &inputs)?;
    match states {
        None => single(py, model, plan, &inputs),
        Some(n) => {
            let worth = (n.saturating_mul(plan.ops) / OPS_PER_THREAD).max(1);
            let threads = thread_count(threads)?.min(worth);
            batch(py, model, plan, &inputs, n, threads)
        }
    }
}

/// The sizes of `model`'s outputs.
fn sizes(model: &JitModel) -> Sizes {
    Sizes {
        nv: model.nv(),
        nf: model.frames().len(),
        np: model.parameter_names().len(),
        nb: model.base_parameter_names().len(),
    }
}

/// A kernel's inputs as read, one slot per kind of input (no allocation per call).
pub(crate) struct Inputs<'py> {
    /// The kernel's inputs in order.
    order: &'static [Input],
    /// The arrays, at `slot(input)`.
    arrays: [Option<Array<'py>>; 5],
}

/// The slot of `input` in `Inputs::arrays`.
fn slot(input: Input) -> usize {
    match input {
        Input::Q => 0,
        Input::Qd => 1,
        Input::Qdd => 2,
        Input::Tau => 3,
        Input::Standard => 4,
    }
}

impl<'py> Inputs<'py> {
    /// The array of `input`, when the kernel takes it.
    fn get(&self, input: Input) -> Option<&Array<'py>> {
        self.arrays[slot(input)].as_ref()
    }

    /// The values of `input` (empty when the kernel does not take it).
    fn values(&self, input: Input) -> &[f64] {
        self.get(input).map_or(&[], Array::values)
    }
}

/// The kernel's inputs read from `args`.
fn read_inputs<'py>(
    model: &JitModel,
    kernel: Kernel,
    args: &[&Bound<'py, PyAny>],
) -> PyResult<Inputs<'py>> {
    let mut inputs = Inputs {
        order: kernel.inputs(),
        arrays: Default::default(),
    };
    for (&input, arg) in kernel.inputs().iter().zip(args) {
        let width = match input {
            Input::Q => model.nq(),
            Input::Standard => model.parameter_names().len(),
            _ => model.nv(),
        };
        inputs.arrays[slot(input)] = Some(Array::read(arg, input_name(input), width)?);
    }
    Ok(inputs)
}

/// `None` when every input is one state, `Some(N)` when every input holds N states.
fn batch_states(inputs: &Inputs<'_>) -> PyResult<Option<usize>> {
    let mut read = inputs
        .order
        .iter()
        .filter_map(|&i| Some((i, inputs.get(i)?)));
    let Some((first_input, first)) = read.next() else {
        return Ok(None);
    };
    for (input, array) in read {
        if array.states != first.states {
            let describe = |s: Option<usize>| match s {
                None => "one state (1-D)".to_owned(),
                Some(n) => format!("{n} states (2-D)"),
            };
            return Err(PyValueError::new_err(format!(
                "`{}` holds {} but `{}` holds {}: give every argument as one state or every one as N states",
                input_name(first_input),
                describe(first.states),
                input_name(input),
                describe(array.states)
            )));
        }
    }
    Ok(first.states)
}

/// On a floating base, every configuration's quaternion [qx, qy, qz, qw] (q[3..7]) must have
/// unit norm: the kernels assume it.
fn check_quaternions(model: &JitModel, inputs: &Inputs<'_>) -> PyResult<()> {
    if !model.programs().floating_base {
        return Ok(());
    }
    let Some(q) = inputs.get(Input::Q) else {
        return Ok(());
    };
    for (k, state) in q.values().chunks_exact(model.nq()).enumerate() {
        let norm = state[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        if (norm - 1.0).abs() > QUATERNION_TOLERANCE {
            let at = match q.states {
                Some(_) => format!("q[{k}, 3:7]"),
                None => "q[3:7]".to_owned(),
            };
            return Err(PyValueError::new_err(format!(
                "the base quaternion [qx, qy, qz, qw] = {at} = {:?} has norm {norm}; it must be a unit quaternion (divide it by its norm)",
                &state[3..7]
            )));
        }
    }
    Ok(())
}

/// The thread count asked for: one by default, every core for 0.
fn thread_count(threads: Option<isize>) -> PyResult<usize> {
    match threads {
        None | Some(1) => Ok(1),
        Some(0) => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
        Some(n) if n > 0 => Ok(n.unsigned_abs()),
        Some(n) => Err(PyValueError::new_err(format!(
            "threads must be positive (or 0 for every core), got {n}"
        ))),
    }
}

/// A new C-contiguous array of `shape` (one state's result); its values are not initialised.
///
/// # Safety
/// Every value must be written before the array is handed to Python.
unsafe fn new_array<'py>(py: Python<'py>, shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    // SAFETY: as the function's contract says. (`IxDyn` keeps a kernel's at most three axes
    // without allocating.)
    unsafe { PyArrayDyn::<f64>::new(py, IxDyn(shape), false) }
}

/// New C-contiguous arrays, one per part (one state's result).
///
/// # Safety
/// As `new_array`'s: `layout::gather` writes every value of every part (tested in `layout`).
unsafe fn new_arrays<'py>(py: Python<'py>, parts: &[Part]) -> Vec<Bound<'py, PyArrayDyn<f64>>> {
    parts
        .iter()
        // SAFETY: as the function's contract says.
        .map(|p| unsafe { new_array(py, &p.shape) })
        .collect()
}

/// The writable values of `arrays`.
///
/// # Safety
/// The arrays must have been created by `new_arrays` in this call and not handed to Python
/// yet: nothing else reads or writes them while the slices live.
// A numpy array is shared memory behind a shared reference (as a `Cell`'s contents are): the
// contract above, not the borrow, makes the slices exclusive.
#[allow(clippy::mut_from_ref)]
unsafe fn slices<'a>(arrays: &'a [Bound<'_, PyArrayDyn<f64>>]) -> PyResult<Vec<&'a mut [f64]>> {
    arrays
        .iter()
        // SAFETY: as the function's contract says, nothing else accesses the array.
        .map(|a| unsafe { slice(a) })
        .collect()
}

/// The arrays as the Python result: one array (a float for one state's scalar), or a tuple.
fn result<'py>(
    py: Python<'py>,
    arrays: Vec<Bound<'py, PyArrayDyn<f64>>>,
    single_scalar: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    if let Some(x) = single_scalar {
        return Ok(PyFloat::new(py, x).into_any());
    }
    match <[_; 1]>::try_from(arrays) {
        Ok([array]) => Ok(array.into_any()),
        Err(arrays) => Ok(PyTuple::new(py, arrays)?.into_any()),
    }
}

/// The writable values of `array`.
///
/// # Safety
/// As `slices`'.
#[allow(clippy::mut_from_ref)]
unsafe fn slice<'a>(array: &'a Bound<'_, PyArrayDyn<f64>>) -> PyResult<&'a mut [f64]> {
    // SAFETY: as the function's contract says, nothing else accesses the array.
    unsafe { array.as_slice_mut() }
        .map_err(|e| PyRuntimeError::new_err(format!("internal error in rne: {e}")))
}

/// One state, computed with the GIL held (a call of a few microseconds at most).
fn single<'py>(
    py: Python<'py>,
    model: &JitModel,
    plan: &Plan,
    inputs: &Inputs<'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let state = State {
        q: inputs.values(Input::Q),
        qd: inputs.values(Input::Qd),
        qdd: inputs.values(Input::Qdd),
        tau: inputs.values(Input::Tau),
    };
    let (kernel, parts) = (plan.kernel, &plan.parts);
    if parts.len() == 1 && parts[0].shape.is_empty() {
        let mut value = [0.0];
        model
            .evaluate(kernel, state, &mut value)
            .map_err(errors::jit)?;
        return result(py, Vec::new(), Some(value[0]));
    }
    if plan.whole {
        // SAFETY: the kernel writes every value (its output is the whole array) before the
        // array is returned; on an error it is dropped unseen.
        let array = unsafe { new_array(py, &parts[0].shape) };
        // SAFETY: the array was just created and is returned after the slice's last use.
        let out = unsafe { slice(&array)? };
        model.evaluate(kernel, state, out).map_err(errors::jit)?;
        return Ok(array.into_any());
    }
    // SAFETY: `gather` writes every value before the arrays are returned.
    let arrays = unsafe { new_arrays(py, parts) };
    // SAFETY: the arrays were just created and are returned only after the slices' last use.
    let mut outs = unsafe { slices(&arrays)? };
    evaluate_gathered(model, plan, state, &mut outs)?;
    drop(outs);
    result(py, arrays, None)
}

thread_local! {
    /// The values of the last single call on this thread, before they were gathered into
    /// their arrays: kept, so that a call neither allocates nor zeroes a buffer of its own
    /// (docs/python.md, the single call's overhead).
    static VALUES: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

/// `plan`'s kernel at `state`, its values gathered into `outs` (one slice per part) through
/// this thread's `VALUES` (a new buffer when that is in use).
fn evaluate_gathered(
    model: &JitModel,
    plan: &Plan,
    state: State<'_>,
    outs: &mut [&mut [f64]],
) -> PyResult<()> {
    let mut run = |values: &mut Vec<f64>| {
        values.resize(plan.per, 0.0);
        model.evaluate(plan.kernel, state, values)?;
        layout::gather(values, plan.per, &plan.parts, outs, 0);
        Ok(())
    };
    let kept = VALUES.try_with(|cell| cell.try_borrow_mut().ok().map(|mut v| run(&mut v)));
    kept.ok()
        .flatten()
        .unwrap_or_else(|| run(&mut Vec::new()))
        .map_err(errors::jit)
}

/// N states (their arrays copied by `Array::read`), computed with the GIL released, on
/// `threads` threads.
fn batch<'py>(
    py: Python<'py>,
    model: &JitModel,
    plan: &Plan,
    inputs: &Inputs<'py>,
    n: usize,
    threads: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let states = Batch {
        q: inputs.values(Input::Q),
        qd: inputs.values(Input::Qd),
        qdd: inputs.values(Input::Qdd),
        tau: inputs.values(Input::Tau),
    };
    // The values computed into buffers kept between batches (`pool`), which then become the
    // arrays' own: the kernel (a whole part) or `gather` writes every value.
    let mut buffers = plan
        .parts
        .iter()
        .map(|p| pool::take(n.saturating_mul(p.len())))
        .collect::<PyResult<Vec<Vec<f64>>>>()?;
    let outs: Vec<&mut [f64]> = buffers.iter_mut().map(Vec::as_mut_slice).collect();
    let job = Job {
        model,
        kernel: plan.kernel,
        states,
        per: plan.per,
        parts: &plan.parts,
        whole: plan.whole,
        matrices: plan.matrices,
    };
    if let Err(e) = py.detach(|| job.run(n, outs, threads)) {
        buffers.into_iter().for_each(pool::give_back);
        return Err(errors::jit(e));
    }
    let arrays = buffers
        .into_iter()
        .zip(&plan.parts)
        .map(|(values, part)| {
            let shape: Vec<usize> = std::iter::once(n)
                .chain(part.shape.iter().copied())
                .collect();
            pool::into_array(py, values, &shape)
        })
        .collect::<PyResult<Vec<_>>>()?;
    result(py, arrays, None)
}

//! rne for Python: the extension module `rne._rne` behind the `rne` package (python/rne).
//!
//! A robot read from a built-in name or a URDF / TOML file has every kernel compiled in memory
//! by rne's JIT ([`rne_jit::JitModel`]: the optimised straight-line programs of the
//! Newton–Euler recursion, after Høifødt, *Dynamics of robot manipulators by the Newton–Euler
//! formulation*, NTNU 2010, lowered to machine code by Cranelift). The `Model` class (`model.rs`) calls them
//! under Pinocchio's names on numpy arrays: one state, or a batch of N states computed with the
//! GIL released on one or more threads. Identification (`excitation`, `identify`, `validate`)
//! is the `rne identify` command's, on arrays.
//!
//! Nothing here panics on user input: every argument is checked (`arrays`, `load`) and rne's
//! errors become Python exceptions (`errors`).

mod arrays;
mod batch;
mod builtin;
mod call;
mod errors;
mod identify;
mod layout;
mod load;
mod model;
mod pool;

use pyo3::prelude::*;

/// The built-in robots' names.
#[pyfunction]
fn builtin_robots() -> Vec<&'static str> {
    builtin::BUILTINS.iter().map(|b| b.name).collect()
}

/// The kernels rne can compile (rne's names, in the order of rne's design document §4).
#[pyfunction]
fn kernel_names() -> Vec<&'static str> {
    rne_codegen_core::Kernel::ALL
        .iter()
        .map(|k| k.name())
        .collect()
}

/// The extension module.
#[pymodule]
fn _rne(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<model::Model>()?;
    m.add_function(wrap_pyfunction!(model::load, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_robots, m)?)?;
    m.add_function(wrap_pyfunction!(kernel_names, m)?)?;
    m.add_function(wrap_pyfunction!(identify::excitation, m)?)?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_function(wrap_pyfunction!(identify::validate, m)?)?;
    Ok(())
}

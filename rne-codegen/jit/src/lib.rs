//! Any robot at run time, at compiled speed: the optimised straight-line programs that
//! `derive_dynamics!` emits as Rust, compiled in memory to machine code for the running
//! processor by Cranelift (the Wasmtime project's code generator), with no Rust build.
//!
//! ```no_run
//! use rne_codegen_core::{GenerationOptions, Kernel, Scene};
//! use rne_jit::{JitModel, State};
//!
//! let outputs = vec![Kernel::InverseDynamics, Kernel::MassMatrix];
//! let options = GenerationOptions { outputs, ..GenerationOptions::default() };
//! let model = JitModel::load("robots/ur5.urdf".as_ref(), &Scene::default(), &options)?;
//! let (q, qd, qdd) = (vec![0.1; 6], vec![0.0; 6], vec![0.0; 6]);
//! let tau = model.evaluate_vec(Kernel::InverseDynamics, State { q: &q, qd: &qd, qdd: &qdd, ..State::default() })?;
//! # Ok::<(), rne_jit::JitError>(())
//! ```
//!
//! Pipeline: the robot is read and its kernels generated as for the macro
//! ([`rne_codegen_core::generate_programs`]: the same validation, plan, symbolic recursion and
//! optimisations, the same two-thread build); each kernel's [`Program`] is lowered to
//! Cranelift IR (`lower.rs`), compiled for the processor's features detected at run time
//! (AVX2 and FMA on x86-64; AArch64), and called through one audited `unsafe` place
//! (`code.rs`).
//!
//! # Bit for bit
//! The compiled code performs the program's operations in the program's order, with the
//! runtime's own sines and cosines: with `fma` off it returns the macro's portable kernel's
//! bits. With `fma` on, products and sums are fused where this processor has FMA, as the
//! macro's kernel compiled for it (`-C target-cpu=native`) fuses them; the sines and cosines
//! are those of the runtime as this program was compiled (fused only in a build with FMA).
//!
//! # Threads
//! Each kernel is lowered and compiled as soon as the generator has built it, while it builds
//! the costliest ones (`pipeline.rs`); the functions of all kernels are compiled together on
//! one thread per core (`RNE_JIT_THREADS=n` sets the number; each thread keeps one Cranelift
//! context for all its functions, as Cranelift advises) and defined in the options'
//! order of the kernels: the code does not depend on the number of threads or on which
//! kernel was built first. At the fast tier, programs of
//! more than 2000 instructions (the derivative kernels of arms, most kernels of large robots)
//! are compiled as parts of at most 1000, so that one long kernel does not keep one thread
//! busy while the others wait, and the register allocator, whose time grows faster than the
//! length of a function, sees short ones; the optimized tier cuts programs as the Rust
//! emitter does (above 15 000 instructions), for the faster code. The results are the same
//! bits.
//! `RNE_JIT_SPLIT_ABOVE=n` and `RNE_JIT_PART_LEN=n` set the cut, `RNE_JIT_TIMINGS=1` prints
//! each function's compile time to stderr (for measuring).
//!
//! # Batches
//! [`JitModel::evaluate_batch`] computes two states a call: at a kernel's first batch of two
//! or more states it is compiled again in two lanes (`f64x2`, one lane a state; `lanes.rs`),
//! kept until the model is dropped. Each lane performs the scalar kernel's operations, so a
//! batch gives the single calls' bits. `RNE_JIT_LANES=1`, set when a model is compiled, makes
//! its batches one state a call (for measuring what the lanes gain).
//! [`JitModel::evaluate_batch_threaded`] shares a batch between threads that each take the
//! next 64 states when they are done with the last (`share.rs`), so that a core the machine
//! slows down holds the batch up by a chunk, not by its share.
//! [`JitModel::evaluate_batch_matrices`] (and `_threaded`) batches a kernel that returns
//! several matrices (∂ID, ∂FD) into one array per matrix, each lane storing straight into its
//! matrix's array (`matrices.rs`).
//!
//! # Limits
//! - `f64` only; the derivative kernels are built in scalars (the Rust emitter's lanes of
//!   directions are not used), batches in lanes of two states.
//! - Processors Cranelift has no backend for (other than x86-64, AArch64, RISC-V 64, s390x)
//!   get [`JitError::UnsupportedHost`]; rne's interpreter is the fallback there.
//!
//! [`Program`]: rne_codegen_core::Program
#![deny(missing_docs)]

mod admit;
mod batch;
mod code;
mod compile;
mod constants;
mod error;
mod lanes;
mod lower;
mod matrices;
mod model;
mod pipeline;
mod registers;
#[cfg(feature = "threads")]
pub mod share;
mod windows;

pub use batch::Batch;
pub use error::JitError;
pub use model::{host_support, JitModel, State, Tier, Timings};

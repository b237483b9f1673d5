//! The code generator behind `rne-codegen`: from a robot model and a scene to a module of
//! flat Rust functions.
//!
//! Pipeline: the scene is applied to the model (gravity, locked joints); the symbolic
//! dynamics build each requested kernel into one shared expression graph (so common
//! subexpressions are shared and constants folded as they are created); each kernel is
//! lowered to a straight-line [`Program`] (dead code removed, negations absorbed); the
//! program is emitted with `quote`.
#![deny(missing_docs)]

mod builder;
mod emit;
mod error;
mod kernel;
mod load;
mod module;
mod program;
mod scene;

pub use builder::{Builder, KEEP_GENERATED_ENV};
pub use emit::{emit_kernel, EmitContext};
pub use error::CodegenError;
pub use kernel::{Input, Kernel, Shape, UnknownKernel};
pub use load::{generate_from_path, read_robot};
pub use module::{generate, GeneratedModule, KernelReport};
pub use program::{Instr, Operand, Program};
pub use scene::{ParameterMode, ScalarType, Scene};

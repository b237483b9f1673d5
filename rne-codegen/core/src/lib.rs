//! The code generator behind `rne-codegen`: from a robot model, its [`Scene`] (the physical
//! world: gravity, locked joints, rest, base, mimic, friction) and the [`GenerationOptions`]
//! (which functions, scalar, parameters, arithmetic) to a module of flat Rust functions.
//!
//! Pipeline: the scene is applied to the model (gravity, locked joints); each requested
//! kernel is built by the symbolic dynamics into an expression graph of its own
//! ([`build_kernel`]: a kernel is the same code whichever other kernels the module has), in
//! which common subexpressions are shared and constants folded as nodes are created; its
//! linear combinations are rewritten ([`distribute_constants`]); it is lowered to a
//! straight-line [`Program`] (dead code removed, negations absorbed); the program is emitted
//! with `quote` as a function, next to the module's constants and its `Model` type.
//! [`generate_c`] writes the same programs ([`generate_programs`]) as a C99 header and source
//! for C and C++ programs, bit for bit the Rust kernels (`emit_c.rs`).
//!
//! # Optimisations and their limits
//! Every rewrite keeps or lowers the operation count ([`rne_symbolic::OpCount`]). Only the
//! linear-combination pass re-associates: it rebuilds the sums it opens as balanced trees
//! (changing rounding in the last bits); graph construction, lowering and emission never
//! re-associate floating-point sums or products.
//! - **Common subexpressions** are shared within a kernel by hash-consing: syntactically
//!   equal subtrees (commutative operands ordered) are one node. Limit: no associativity or
//!   distributivity, so `a·b·c` built as `(a·b)·c` and `a·(b·c)` are two nodes; nothing is
//!   shared between the kernels of a module.
//! - **Constant folding and identities** as nodes are built: `x·0 = 0`, `x·1 = x`, `x + 0 = x`,
//!   `x + (−x) = 0`, `−(−x) = x`, constant chains `c₁·(c₂·x)`, division by powers of two as
//!   multiplication, and exact `sin`/`cos` at multiples of π/2 — which is how structural
//!   zeros (sparse rotations, zero products of inertia, zero COM components) cost nothing.
//!   Limit: `x·0 = 0` holds in real arithmetic only, so an output that does not depend on an
//!   input structurally stays finite when that input is NaN (every output that does depend on
//!   it is NaN).
//! - **Trigonometry**: the graph only holds `sin` and `cos` of joint variables (angle sums
//!   such as `cos(q₁ + q₂)` never arise: the recursion multiplies the rotations out), and
//!   each joint's pair is computed once with `sin_cos`.
//! - **Dead code**: only the nodes an output needs are lowered ([`Program::lower`]).
//! - **Linear combinations**: constant factors are distributed over sums used once, equal
//!   terms merged, equal coefficients factored out again, and the sums rebuilt adding the
//!   two earliest-ready terms first: balanced trees (log₂ n deep instead of n − 1) whose
//!   late terms — the recursion's values from the previous link — come in last
//!   ([`distribute_constants`]).
//! - **Negations** are absorbed into subtractions and computed only when something other
//!   than an addition uses them.
//! - **Large kernels** (over 15 000 instructions, `split.rs`) are emitted as a chain of
//!   `#[inline(never)]` parts of about 1 000 instructions in modules of their own, passing
//!   values through a slot array: rustc and LLVM compile them several times faster than one
//!   huge function, and in parallel; the arithmetic is unchanged.
//! - **Cost model**: [`rne_symbolic::OpCount::cost`] weighs the operations; `rne stats`
//!   reports counts and cost per kernel.
#![deny(missing_docs)]

mod assemble;
mod builder;
mod built;
mod dispatch;
mod emit;
mod emit_c;
mod error;
mod generation_options;
mod kernel;
mod latency;
mod linear;
mod load;
mod model_type;
mod module;
mod params;
mod plan;
mod program;
mod programs;
mod register_order;
mod scene;
mod schedule;
mod scratch_slots;
mod shape;
mod split;

pub use builder::{Builder, KEEP_GENERATED_ENV};
pub use built::{build_kernel, build_kernel_with, kernel_program, BuiltKernel};
pub use dispatch::DISPATCH_FROM;
pub use emit_c::{c_identifier, emit_c, generate_c, CModule};
pub use error::CodegenError;
pub use generation_options::{ForwardDynamicsMethod, GenerationOptions, ParameterMode, ScalarType};
pub use kernel::{Dims, Input, Kernel, KernelSetup, Shape, UnknownKernel};
pub use linear::distribute_constants;
pub use load::{generate_from_path, read_robot};
pub use module::{generate, ForwardDynamicsChoice, GeneratedModule, KernelReport};
pub use program::{Instr, Operand, Program};
pub use programs::{generate_programs, generate_programs_each, GeneratedPrograms, KernelProgram};
pub use scene::{MimicMode, Scene};
pub use scratch_slots::ScratchSlots;
pub use split::{PART_LEN, SPLIT_ABOVE};

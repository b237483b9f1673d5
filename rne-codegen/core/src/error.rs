//! Errors of code generation.

use std::path::PathBuf;

use crate::kernel::Kernel;

/// Why a module could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum CodegenError {
    /// The robot description could not be read.
    #[error(transparent)]
    Spec(#[from] rne_symbolic::spec::SpecError),
    /// The robot file could not be read.
    #[error("cannot read robot file `{file}`: {cause}")]
    Read {
        /// The file, as the user named it.
        file: String,
        /// The cause.
        cause: std::io::Error,
    },
    /// A `lock` names no joint.
    #[error(transparent)]
    Lock(#[from] rne_symbolic::model::LockError),
    /// Mimic joints that cannot be constrained (a loop, a missing leader).
    #[error(transparent)]
    Mimic(#[from] rne_symbolic::model::MimicError),
    /// A fixed-base robot without a moving joint.
    #[error(transparent)]
    NothingMoves(#[from] rne_symbolic::model::NothingMoves),
    /// A joint is locked twice.
    #[error("joint `{0}` is locked twice")]
    LockedTwice(String),
    /// `parameters: base` for a model read with symbolic parameters: the base parameters are
    /// found at numeric geometry.
    #[error("{robot}: `parameters: base` needs the robot read with numeric parameters (its base parameters are found at its geometry)")]
    SymbolicBaseParameters {
        /// The robot file.
        robot: String,
    },
    /// The gravity vector has a NaN or infinite component.
    #[error("gravity must be finite, got {0:?}")]
    Gravity([f64; 3]),
    /// Kernels that solve with M(q) were asked for a model whose M(q) is singular at every q.
    #[error("{robot}: {} cannot be generated: {joint}", kernel_list(kernels))]
    Massless {
        /// The robot file.
        robot: String,
        /// The kernels asked for that solve with M ([`Kernel::inverts_mass_matrix`]).
        kernels: Vec<Kernel>,
        /// The joint that moves no mass.
        joint: rne_symbolic::model::MasslessJoint,
    },
    /// A kernel's expression graph reached its node limit while being built.
    #[error(
        "`{kernel}` is too large to generate for this robot: its expression graph reached the \
         limit of {limit} nodes (about {} MB); generate fewer kernels, lock joints or split the \
         robot",
        limit * 30 / 1_000_000
    )]
    TooLarge {
        /// The kernel.
        kernel: Kernel,
        /// The limit ([`rne_symbolic::ExprGraph::node_limit`]).
        limit: usize,
    },
    /// An `outputs` entry is not a kernel.
    #[error("unknown output `{name}`; {cause}")]
    UnknownKernel {
        /// The name given.
        name: String,
        /// The names there are.
        cause: crate::kernel::UnknownKernel,
    },
    /// A `frames` entry names no link of the robot.
    #[error("unknown frame `{frame}`; the robot's frames are: {}", known.join(", "))]
    UnknownFrame {
        /// The name given.
        frame: String,
        /// The robot's frames (link names).
        known: Vec<String>,
    },
    /// A frame is listed twice in `frames`.
    #[error("frame `{0}` is listed twice")]
    FrameTwice(String),
    /// The `crate` setting is not a path.
    #[error("`{0}` is not a path to the rne-codegen crate (e.g. `::my_reexport::rne_codegen`)")]
    CratePath(String),
    /// A parameter name cannot be a Rust field name.
    #[error("parameter `{0}` cannot be a Rust field name of `Params`")]
    ParameterName(String),
    /// A kernel cannot be written as C.
    #[error("cannot write `{kernel}` as C: {reason}")]
    CKernel {
        /// The kernel.
        kernel: crate::kernel::Kernel,
        /// Why not.
        reason: String,
    },
    /// A parameter name cannot be a field of the C parameters' struct.
    #[error("parameter `{0}` cannot be a field of the C parameters' struct (a C identifier that is no C or C++ keyword)")]
    CParameterName(String),
    /// The scene asks for something the C emitter does not write.
    #[error("cannot write C: {0}")]
    CEmission(String),
    /// Writing generated files failed.
    #[error("cannot write {path}: {cause}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// A required environment variable of a build script is missing.
    #[error("environment variable {0} is not set (is this running inside a build script?)")]
    MissingEnv(&'static str),
}

/// `a`, `a and b`, `a, b and c`: the kernels' names in a sentence.
fn kernel_list(kernels: &[Kernel]) -> String {
    let names: Vec<&str> = kernels.iter().map(|k| k.name()).collect();
    match names.split_last() {
        Some((last, [])) => (*last).to_owned(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

//! Argument parsing shared by the subcommands, and the command's error type.

use rne_codegen::Kernel;
use rne_codegen_core::{GenerationOptions, Scene};

/// Why a command failed; printed as `error: ...` with a non-zero exit code. Every library
/// error is kept whole in a variant of its own, so that the message says what failed (a bad
/// argument, a model, a simulation, a file that could not be written) and why. As everywhere
/// in rne (docs/design.md §2.3), the message carries the cause and `source()` does not
/// return it again.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The robot file could not be read.
    #[error(transparent)]
    Spec(#[from] rne_symbolic::spec::SpecError),
    /// Code generation failed.
    #[error(transparent)]
    Codegen(#[from] rne_codegen_core::CodegenError),
    /// A model could not be evaluated at the given state (a state of the wrong length, a
    /// kernel the engine does not have).
    #[error(transparent)]
    Evaluation(#[from] rne_interpreted::Error),
    /// The JIT could not compile the model or call a kernel.
    #[error(transparent)]
    Jit(#[from] rne_jit::JitError),
    /// The numeric reference rejected the model or the state.
    #[error("numeric reference: {0}")]
    Reference(rne_reference::ReferenceError),
    /// A scenario could not be run or written.
    #[error(transparent)]
    Scenario(Box<rne_scenarios::ScenarioError>),
    /// A stress case could not be run or its report written.
    #[error(transparent)]
    Stress(Box<rne_stress::StressError>),
    /// A benchmark could not be run or its report written.
    #[error(transparent)]
    Bench(Box<rne_bench::BenchError>),
    /// A built-in robot's kernels disagree with the numeric reference.
    #[error(
        "kernels disagree with the numeric reference beyond their tolerance: {}",
        failures.join(", ")
    )]
    Disagreement {
        /// The robot, kernel, errors and tolerance of each kernel above its tolerance.
        failures: Vec<String>,
    },
    /// The model's mimic joints cannot be constrained (a loop, a missing leader).
    #[error("{model}: {cause}")]
    Mimic {
        /// The model as the command names it.
        model: String,
        /// Why.
        cause: rne_symbolic::model::MimicError,
    },
    /// The model cannot be read or built with its mimic joints constrained, and it can with
    /// them free: the error, and that suggestion.
    #[error("{cause} (load it with `--mimic free` to treat mimic joints as independent)")]
    MimicFreeLoads {
        /// The error with the mimic joints constrained.
        cause: Box<CliError>,
    },
    /// Nothing in the model moves on the base the options give it.
    #[error("{model}: {cause}")]
    NothingMoves {
        /// The model as the command names it.
        model: String,
        /// The robot's own error.
        cause: rne_symbolic::model::NothingMoves,
    },
    /// A kernel name that is not a kernel's.
    #[error("unknown {what} `{name}`; {cause}")]
    UnknownKernel {
        /// What the name was given as: "output", "kernel (--kernels)".
        what: &'static str,
        /// The name.
        name: String,
        /// The runtime's error, which lists the names.
        cause: rne_codegen::UnknownKernel,
    },
    /// Forward dynamics asked of a model whose mass matrix is singular.
    #[error("{model}: {cause}")]
    Massless {
        /// The model as the command names it.
        model: String,
        /// The joint that moves no mass.
        cause: rne_symbolic::model::MasslessJoint,
    },
    /// Identification, its data or its excitation failed.
    #[error(transparent)]
    Identify(#[from] rne_identify::IdentifyError),
    /// The file of Pinocchio's values for `rne corpus` is not what its script writes.
    #[error("{}: not Pinocchio's values: {cause}", path.display())]
    PinocchioValues {
        /// The file.
        path: std::path::PathBuf,
        /// The JSON reader's error.
        cause: serde_json::Error,
    },
    /// Robots of the corpus disagree with Pinocchio or are refused.
    #[error(
        "{} case(s) disagree with Pinocchio above {tolerance:e} or are refused: {}",
        failures.len(),
        failures.join(", ")
    )]
    CorpusDisagreement {
        /// The largest relative error accepted.
        tolerance: f64,
        /// The robot file and base of each case, with the kernel where one is to blame.
        failures: Vec<String>,
    },
    /// An input file could not be read.
    #[error("cannot read {}: {cause}", path.display())]
    Read {
        /// The file.
        path: std::path::PathBuf,
        /// The system's error.
        cause: std::io::Error,
    },
    /// An output file could not be written.
    #[error("cannot write {}: {cause}", path.display())]
    Write {
        /// The file.
        path: std::path::PathBuf,
        /// The system's error.
        cause: std::io::Error,
    },
    /// A malformed argument.
    #[error("{0}")]
    Argument(String),
    /// Writing the output failed.
    #[error("cannot write output: {0}")]
    Io(std::io::Error),
    /// rne failed internally (a panic: a bug, whatever the input).
    #[error(
        "internal error in rne: {message}{}; this is a bug: please report it with the command \
         and the robot file",
        if location.is_empty() { String::new() } else { format!(" (at {location})") }
    )]
    Internal {
        /// What failed.
        message: String,
        /// Where in rne's source, when known.
        location: String,
    },
}

// By hand rather than `#[from]`, which would also return the cause from `source()`.
impl From<rne_reference::ReferenceError> for CliError {
    fn from(error: rne_reference::ReferenceError) -> CliError {
        CliError::Reference(error)
    }
}

// Boxed: the errors of the benchmarks, the scenarios and the stress cases are the largest, and
// every command's result would carry their size.
impl From<rne_bench::BenchError> for CliError {
    fn from(error: rne_bench::BenchError) -> CliError {
        CliError::Bench(Box::new(error))
    }
}

impl From<rne_scenarios::ScenarioError> for CliError {
    fn from(error: rne_scenarios::ScenarioError) -> CliError {
        CliError::Scenario(Box::new(error))
    }
}

impl From<rne_stress::StressError> for CliError {
    fn from(error: rne_stress::StressError) -> CliError {
        CliError::Stress(Box::new(error))
    }
}

impl From<std::io::Error> for CliError {
    fn from(error: std::io::Error) -> CliError {
        CliError::Io(error)
    }
}

impl CliError {
    /// Whether the output was a pipe its reader closed (`rne show panda | head`): an
    /// [`std::io::ErrorKind::BrokenPipe`] here or among the error's causes. The command then
    /// ends quietly with status 0, as `cat` or `grep` would (Rust ignores SIGPIPE, so the
    /// write returns the error instead of ending the process).
    pub fn is_broken_pipe(&self) -> bool {
        // `Io` prints its cause in its message, so it does not return it from `source()`.
        if let CliError::Io(io) = self {
            return io.kind() == std::io::ErrorKind::BrokenPipe;
        }
        let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(self);
        while let Some(error) = cause {
            if let Some(io) = error.downcast_ref::<std::io::Error>() {
                if io.kind() == std::io::ErrorKind::BrokenPipe {
                    return true;
                }
            }
            cause = error.source();
        }
        false
    }
}

/// Parses `1.5,-2,0` into numbers.
pub fn parse_list(name: &str, text: &str) -> Result<Vec<f64>, CliError> {
    text.split(',')
        .map(|item| {
            let item = item.trim();
            item.parse::<f64>()
                .map_err(|_| CliError::Argument(format!("--{name}: `{item}` is not a number")))
        })
        .collect()
}

/// Parses `q1=0,q2=1.5` into locked joints.
pub fn parse_locks(text: &str) -> Result<Vec<(String, f64)>, CliError> {
    text.split(',')
        .map(|item| {
            let (name, value) = item.split_once('=').ok_or_else(|| {
                CliError::Argument(format!("--lock: `{item}` is not `joint=value`"))
            })?;
            let value = value
                .trim()
                .parse::<f64>()
                .map_err(|_| CliError::Argument(format!("--lock: `{value}` is not a number")))?;
            Ok((name.trim().to_owned(), value))
        })
        .collect()
}

/// The scene described by the `--gravity` and `--lock` options, and the generation options
/// described by `--outputs`.
pub fn scene_and_options(
    outputs: Option<&str>,
    gravity: Option<&str>,
    lock: Option<&str>,
) -> Result<(Scene, GenerationOptions), CliError> {
    let (mut scene, mut options) = (Scene::default(), GenerationOptions::default());
    if let Some(outputs) = outputs {
        options.outputs = outputs
            .split(',')
            .map(|name| {
                let name = name.trim();
                name.parse::<Kernel>()
                    .map_err(|cause| CliError::UnknownKernel {
                        what: "output",
                        name: name.to_owned(),
                        cause,
                    })
            })
            .collect::<Result<_, _>>()?;
    }
    if let Some(gravity) = gravity {
        let g = parse_list("gravity", gravity)?;
        scene.gravity = Some(g.try_into().map_err(|g: Vec<f64>| {
            CliError::Argument(format!("--gravity needs 3 values, got {}", g.len()))
        })?);
    }
    if let Some(lock) = lock {
        scene.lock = parse_locks(lock)?;
    }
    Ok((scene, options))
}

//! Generation and compilation overlapped: each kernel's program is lowered and its functions
//! handed to the compiling threads as soon as the generator has built it, while the
//! costliest kernels (the derivatives, built last) are still being built.
//!
//! Generation builds the kernels on two threads, one of them busy with the derivative kernels
//! long after the other has run out of work (`rne_codegen_core`'s `schedule`; on Talos, ∂FD
//! alone takes most of the time). Compiling every kernel only once the last one is built
//! left that time unused. Here this thread lowers the programs in the order they are finished
//! ([`generate_programs_each`]), one compiling thread fewer than [`compile::threads`] starts
//! at once, and this thread joins them when generation has ended. The functions are still
//! defined in the module in the options' order of the kernels, so the code, and where it lands
//! in memory, do not depend on which kernel was finished first.

use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::Instant;

use cranelift_jit::JITModule;
use rne_codegen_core::{
    generate_programs_each, GeneratedPrograms, GenerationOptions, Kernel, KernelProgram, Scene,
};
use rne_symbolic::RobotModel;

use crate::compile::{self, Job, Pool};
use crate::error::JitError;
use crate::lower::{Lowered, Lowering};
use crate::model::{
    define_kernels, host_module, lower_kernel, Compiled, CompiledParts, Tier, Timings,
};

/// What [`generate_and_compile`] gives: the programs, the module owning the code, whether
/// multiply-adds are fused, each kernel's entries (in the programs' order) and the timings.
pub(crate) struct Pipelined {
    pub programs: GeneratedPrograms,
    pub module: JITModule,
    pub fused: bool,
    pub kernels: Vec<Compiled>,
    pub timings: Timings,
}

/// One kernel lowered: the kernel, its number of outputs and its functions, each with its
/// index among all functions in the order they were lowered.
type LoweredKernel = (Kernel, usize, Vec<(usize, Arc<Lowered>)>);

/// Generates the kernels `options` ask for, for `model` in `scene` (`source` names the robot
/// file in errors), and compiles each at `tier` as soon as it is built (module docs).
/// Timings: generation is the generator's own time; compilation what is left after it.
pub(crate) fn generate_and_compile(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
    tier: Tier,
) -> Result<Pipelined, JitError> {
    let start = Instant::now();
    let (mut module, isa, fused) = host_module(options.fma, tier)?;
    let mut lowering =
        Lowering::new(&mut module, fused, 1, tier).map_err(|message| JitError::Compile {
            kernel: options
                .kernels()
                .first()
                .copied()
                .unwrap_or(Kernel::InverseDynamics),
            message,
        })?;
    let (job_sender, jobs) = channel::<Job>();
    let pool = Pool::new(&*isa, jobs);
    let (program_sender, finished) = channel::<KernelProgram>();
    let (generated, lowered) = std::thread::scope(|scope| {
        let generation = scope.spawn(move || {
            let sender = program_sender;
            // The receiver stops listening only when lowering failed, whose error is returned.
            generate_programs_each(model, scene, options, source, &|program| {
                let _ = sender.send(program.clone());
            })
        });
        for thread in 1..compile::threads() {
            let pool = &pool;
            scope.spawn(move || pool.work(thread));
        }
        let lowered = lower_as_finished(&mut module, &mut lowering, finished, job_sender);
        let generated = generation
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        pool.work(0);
        (generated, lowered)
    });
    let programs = generated?;
    let compiled = with_outcomes(&programs, lowered?, pool);
    let kernels = define_kernels(&mut module, compiled)?;
    let generation = programs.generation_time;
    let timings = Timings {
        generation,
        compilation: start.elapsed().saturating_sub(generation),
    };
    Ok(Pipelined {
        programs,
        module,
        fused,
        kernels,
        timings,
    })
}

/// Lowers each program `finished` receives, until the generator is done, and sends its
/// functions to the compiling threads; the first program that cannot be lowered stops it.
fn lower_as_finished(
    module: &mut JITModule,
    lowering: &mut Lowering,
    finished: Receiver<KernelProgram>,
    jobs: Sender<Job>,
) -> Result<Vec<LoweredKernel>, JitError> {
    let mut lowered = Vec::new();
    let mut next = 0;
    for k in finished {
        let parts = lower_kernel(module, lowering, &k)?;
        let mut numbered = Vec::with_capacity(parts.len());
        for part in parts {
            // The pool's receiver outlives this function: sending cannot fail.
            let _ = jobs.send((next, Arc::clone(&part)));
            numbered.push((next, part));
            next += 1;
        }
        lowered.push((k.kernel, k.program.outputs.len(), numbered));
    }
    Ok(lowered)
}

/// The lowered kernels in the order of `programs` (the options' order), each function with its
/// outcome in `pool`.
fn with_outcomes(
    programs: &GeneratedPrograms,
    mut lowered: Vec<LoweredKernel>,
    pool: Pool<'_>,
) -> Vec<CompiledParts> {
    let place = |kernel: Kernel| {
        programs
            .kernels
            .iter()
            .position(|p| p.kernel == kernel)
            .unwrap_or(usize::MAX)
    };
    lowered.sort_by_key(|(kernel, _, _)| place(*kernel));
    let count = lowered.iter().map(|(_, _, parts)| parts.len()).sum();
    let mut outcomes: Vec<Option<compile::Outcome>> =
        pool.into_outcomes(count).into_iter().map(Some).collect();
    lowered
        .into_iter()
        .map(|(kernel, outputs, parts)| {
            let parts = parts
                .into_iter()
                .map(|(k, part)| {
                    let outcome = outcomes[k].take().expect("each function has one outcome");
                    (part, outcome)
                })
                .collect();
            (kernel, outputs, parts)
        })
        .collect()
}

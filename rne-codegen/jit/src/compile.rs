//! Lowered functions compiled to machine code on every core, and defined in the module in
//! their order.
//!
//! Cranelift compiles one function without looking at any other, so the functions of all
//! kernels are compiled together in parallel (as Wasmtime compiles a module's functions) and
//! their bytes and relocations handed to the module one by one, in the order the caller
//! gives: the code, and where it lands in memory, are those of compiling them one after
//! another. A [`Pool`] compiles functions as they are sent to it (`pipeline.rs` sends each
//! kernel's as soon as it is built); given all at once ([`compile_all`]), threads take
//! the longest function not yet taken first, so that no long function is left to compile
//! alone at the end.
//!
//! `RNE_JIT_THREADS=n` sets the number of threads (default: one per core);
//! `RNE_JIT_TIMINGS=1` prints each function's compile time to stderr;
//! `RNE_JIT_DUMP=DIR` writes each function's machine code (`NAME.bin`, for
//! `objdump -D -b binary -m i386:x86-64`), its code after register allocation (`NAME.vcode`)
//! and its IR (`NAME.clif`) to the existing directory DIR (`NAME_x2.*` in two lanes).

use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::isa::TargetIsa;
use cranelift_codegen::{CompiledCode, Context};
use cranelift_jit::JITModule;
use cranelift_module::{Module, ModuleReloc};

use crate::lower::Lowered;

/// One function's machine code: its bytes, alignment and relocations.
struct Machine {
    bytes: Vec<u8>,
    alignment: u64,
    relocs: Vec<ModuleReloc>,
}

/// One function's outcome: its machine code or the error, the thread that compiled it and
/// how long it took.
pub(crate) struct Outcome {
    machine: Result<Machine, String>,
    thread: usize,
    time: Duration,
}

/// A function that failed to compile or be defined: its index in `functions`, the message.
pub(crate) type Failure = (usize, String);

/// A function to compile and its index among the functions to define.
pub(crate) type Job = (usize, Arc<Lowered>);

/// Threads compiling the functions sent to them, each taking the next function as it finishes
/// one, until the sender is dropped and none is left.
pub(crate) struct Pool<'i> {
    isa: &'i dyn TargetIsa,
    jobs: Mutex<Receiver<Job>>,
    outcomes: Mutex<Vec<Option<Outcome>>>,
}

impl<'i> Pool<'i> {
    /// A pool compiling for `isa` the functions `jobs` receives.
    pub(crate) fn new(isa: &'i dyn TargetIsa, jobs: Receiver<Job>) -> Pool<'i> {
        Pool {
            isa,
            jobs: Mutex::new(jobs),
            outcomes: Mutex::new(Vec::new()),
        }
    }

    /// Compiles functions on this thread, numbered `thread` in reports, until there are none.
    pub(crate) fn work(&self, thread: usize) {
        // One context a thread, reused: Cranelift keeps its register allocator's memory there.
        let mut context = Context::new();
        loop {
            let job = match self.jobs.lock() {
                Ok(jobs) => jobs.recv(),
                Err(_) => return,
            };
            let Ok((k, lowered)) = job else { return };
            let start = Instant::now();
            let machine = compile(self.isa, &lowered, &mut context);
            let outcome = Outcome {
                machine,
                thread,
                time: start.elapsed(),
            };
            if let Ok(mut outcomes) = self.outcomes.lock() {
                if outcomes.len() <= k {
                    outcomes.resize_with(k + 1, || None);
                }
                outcomes[k] = Some(outcome);
            }
        }
    }

    /// The outcome of each of the `n` functions, by index: an error for one no thread compiled.
    pub(crate) fn into_outcomes(self, n: usize) -> Vec<Outcome> {
        let mut outcomes = self
            .outcomes
            .into_inner()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        outcomes.resize_with(n, || None);
        outcomes
            .into_iter()
            .map(|o| {
                o.unwrap_or_else(|| Outcome {
                    machine: Err("a compiling thread stopped".to_owned()),
                    thread: 0,
                    time: Duration::ZERO,
                })
            })
            .collect()
    }
}

/// Compiles `functions` for `isa` on up to [`threads`] threads, longest first: each one's
/// outcome, by index.
pub(crate) fn compile_all(isa: &dyn TargetIsa, functions: &[Arc<Lowered>]) -> Vec<Outcome> {
    let threads = threads().min(functions.len()).max(1);
    let (sender, jobs) = channel();
    for k in longest_first(functions) {
        // The receiver lives in `pool` below: sending cannot fail.
        let _ = sender.send((k, Arc::clone(&functions[k])));
    }
    drop(sender);
    let pool = Pool::new(isa, jobs);
    std::thread::scope(|scope| {
        for thread in 1..threads {
            let pool = &pool;
            scope.spawn(move || pool.work(thread));
        }
        pool.work(0);
    });
    pool.into_outcomes(functions.len())
}

/// Defines `functions` in `module` in their order, each from its outcome (same index).
pub(crate) fn define(
    module: &mut JITModule,
    functions: &[Arc<Lowered>],
    outcomes: Vec<Outcome>,
) -> Result<(), Failure> {
    if std::env::var_os("RNE_JIT_TIMINGS").is_some() {
        report(functions, &outcomes);
    }
    for (k, (lowered, outcome)) in functions.iter().zip(outcomes).enumerate() {
        let machine = outcome.machine.map_err(|e| (k, e))?;
        module
            .define_function_bytes(
                lowered.id,
                machine.alignment,
                &machine.bytes,
                &machine.relocs,
            )
            .map_err(|e| (k, format!("{e:?}")))?;
    }
    Ok(())
}

/// How many threads compile: `RNE_JIT_THREADS` if set to a positive number, else the number
/// of cores.
pub(crate) fn threads() -> usize {
    std::env::var("RNE_JIT_THREADS")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// The indices of `functions`, longest (most IR instructions) first, in order among equals.
fn longest_first(functions: &[Arc<Lowered>]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..functions.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(functions[k].function.dfg.num_insts()));
    order
}

/// One function to machine code.
fn compile(
    isa: &dyn TargetIsa,
    lowered: &Lowered,
    context: &mut Context,
) -> Result<Machine, String> {
    context.clear();
    context.func = lowered.function.clone();
    let dump_dir = std::env::var_os("RNE_JIT_DUMP").map(PathBuf::from);
    context.set_disasm(dump_dir.is_some());
    let code = context
        .compile(isa, &mut ControlPlane::default())
        .map_err(|e| format!("{:?}", e.inner))?;
    if let Some(dir) = dump_dir {
        dump(&dir, lowered, code);
    }
    let alignment = u64::from(code.buffer.alignment);
    let bytes = code.code_buffer().to_vec();
    let relocs = code
        .buffer
        .relocs()
        .iter()
        .map(|r| ModuleReloc::from_mach_reloc(r, &lowered.function, lowered.id))
        .collect();
    Ok(Machine {
        bytes,
        alignment,
        relocs,
    })
}

/// `RNE_JIT_DUMP`: the function's machine code, its code after register allocation and its IR
/// into `dir`, named after the function and, in two lanes, `_x2`; a file that cannot be
/// written is said on stderr (a diagnostic: compiling goes on).
fn dump(dir: &Path, lowered: &Lowered, code: &CompiledCode) {
    let lanes = if lowered.lanes > 1 { "_x2" } else { "" };
    let files = [
        ("bin", code.code_buffer().to_vec()),
        ("vcode", code.vcode.clone().unwrap_or_default().into_bytes()),
        ("clif", lowered.function.display().to_string().into_bytes()),
    ];
    for (extension, bytes) in files {
        let path = dir.join(format!("{}{lanes}.{extension}", lowered.name));
        if let Err(e) = std::fs::write(&path, bytes) {
            eprintln!(
                "rne-jit: RNE_JIT_DUMP: cannot write {}: {e}",
                path.display()
            );
        }
    }
}

/// `RNE_JIT_TIMINGS`: one line per function (name, IR instructions, thread, milliseconds),
/// longest compile first, then each thread's busy time.
fn report(functions: &[Arc<Lowered>], outcomes: &[Outcome]) {
    let mut order: Vec<usize> = (0..functions.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(outcomes[k].time));
    let mut busy: Vec<Duration> = Vec::new();
    for &k in &order {
        let (lowered, outcome) = (&functions[k], &outcomes[k]);
        eprintln!(
            "rne-jit: {:<40} {:>7} IR instructions, thread {}, {:9.3} ms",
            lowered.name,
            lowered.function.dfg.num_insts(),
            outcome.thread,
            outcome.time.as_secs_f64() * 1e3
        );
        if busy.len() <= outcome.thread {
            busy.resize(outcome.thread + 1, Duration::ZERO);
        }
        busy[outcome.thread] += outcome.time;
    }
    for (thread, time) in busy.iter().enumerate() {
        eprintln!(
            "rne-jit: thread {thread} busy {:9.3} ms",
            time.as_secs_f64() * 1e3
        );
    }
}

//! Lowered functions compiled to machine code on every core, and defined in the module in
//! their order.
//!
//! Cranelift compiles one function without looking at any other, so the functions of all
//! kernels are compiled in parallel (as Wasmtime compiles a module's functions) and their
//! bytes and relocations handed to the module one by one, in the order they were lowered: the
//! code, and where it lands in memory, are those of compiling them one after another.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::isa::TargetIsa;
use cranelift_codegen::Context;
use cranelift_jit::JITModule;
use cranelift_module::{Module, ModuleReloc};

use crate::lower::Lowered;

/// One function's machine code: its bytes, alignment and relocations.
struct Machine {
    bytes: Vec<u8>,
    alignment: u64,
    relocs: Vec<ModuleReloc>,
}

/// Compiles `functions` on up to [`threads`] threads and defines them in `module`,
/// in order. An error names the function that failed.
pub(crate) fn define(module: &mut JITModule, functions: &[Lowered]) -> Result<(), String> {
    let compiled = compile_all(module.isa(), functions);
    for (lowered, machine) in functions.iter().zip(compiled) {
        let machine = machine?;
        module
            .define_function_bytes(
                lowered.id,
                machine.alignment,
                &machine.bytes,
                &machine.relocs,
            )
            .map_err(|e| format!("{e:?}"))?;
    }
    Ok(())
}

/// How many threads compile: `RNE_JIT_THREADS` if set to a positive number, else the number
/// of cores.
fn threads() -> usize {
    std::env::var("RNE_JIT_THREADS")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// Every function compiled, in order; threads take the next function as they finish one.
fn compile_all(isa: &dyn TargetIsa, functions: &[Lowered]) -> Vec<Result<Machine, String>> {
    let threads = threads().min(functions.len()).max(1);
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<Machine, String>>>> =
        Mutex::new((0..functions.len()).map(|_| None).collect());
    let work = || loop {
        let k = next.fetch_add(1, Ordering::Relaxed);
        let Some(lowered) = functions.get(k) else {
            return;
        };
        let machine = compile(isa, lowered);
        if let Ok(mut results) = results.lock() {
            results[k] = Some(machine);
        }
    };
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
    results
        .into_inner()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err("a compiling thread stopped".to_owned())))
        .collect()
}

/// One function to machine code.
fn compile(isa: &dyn TargetIsa, lowered: &Lowered) -> Result<Machine, String> {
    let mut context = Context::for_function(lowered.function.clone());
    let code = context
        .compile(isa, &mut ControlPlane::default())
        .map_err(|e| format!("{:?}", e.inner))?;
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

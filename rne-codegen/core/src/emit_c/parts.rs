//! A large kernel as a chain of parts: `static` functions of about `PART_LEN` instructions
//! each, never inlined (GCC inlines a static function called once, which would make the
//! kernel one function again), passing the values a later part reads through a slot array
//! that the kernel owns, as the Rust emitter's parts do (module `split`, whose plan this
//! follows). The kernel computes its joints' sines and cosines, calls the parts in turn and
//! copies its results from their slots: the results are written after every input has been
//! read, so an output array may still be an input.

use std::collections::BTreeSet;
use std::fmt::Write;

use rne_symbolic::Symbol;

use super::body::Body;
use super::TEXT;
use crate::program::Operand;
use crate::split::{SplitPlan, Statement};

/// `RNE_NOINLINE`, defined before the first split kernel.
pub(super) const NOINLINE: &str = "\
/* The parts of a large kernel stay functions of their own (a compiler takes time that grows
 * faster than linearly with a function's length to compile it). */
#if defined(__GNUC__)
#define RNE_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define RNE_NOINLINE __declspec(noinline)
#else
#define RNE_NOINLINE
#endif
";

/// What the parts of a kernel are declared with.
pub(super) struct Head {
    /// The kernel's C name, which the parts' names extend: `ur5_mass_matrix_part3`.
    pub name: String,
    /// The kernel's parameters before its results (`const double q[6]`), which every part
    /// takes too.
    pub parameters: Vec<String>,
    /// Their names, as the kernel passes them on.
    pub arguments: Vec<&'static str>,
}

/// The parts of the kernel `body` and the kernel calling them (`prototype`), storing output
/// k to `places[k]` (returned when there is none), by `plan`.
pub(super) fn write(
    body: &Body,
    plan: &SplitPlan,
    head: &Head,
    places: &[(&str, usize)],
    prototype: &str,
    out: &mut String,
) {
    for (p, statements) in plan.parts.iter().enumerate() {
        write_part(body, plan, head, p, statements, out);
        out.push('\n');
    }
    let outputs = &body.program.outputs;
    out.push_str(prototype);
    out.push_str(" {\n");
    let reads: BTreeSet<Symbol> = body
        .trig_angles()
        .chain(outputs.iter().filter_map(|o| match *o {
            Operand::Input(symbol) => Some(symbol),
            _ => None,
        }))
        .collect();
    body.write_locals(reads.into_iter(), out);
    writeln!(out, "    double slots[{}];", plan.len).expect(TEXT);
    body.write_trig(out);
    let prologue = body.prologue_flags();
    for (&value, &slot) in plan.slots.iter().filter(|(&value, _)| prologue[value]) {
        writeln!(out, "    slots[{slot}] = {};", body.value_name(value)).expect(TEXT);
    }
    let arguments: String = head.arguments.iter().map(|a| format!("{a}, ")).collect();
    for p in 0..plan.parts.len() {
        writeln!(out, "    {}_part{p}({arguments}slots);", head.name).expect(TEXT);
    }
    for (k, &output) in outputs.iter().enumerate() {
        match places.get(k) {
            Some((name, index)) => write!(out, "    {name}[{index}] = ").expect(TEXT),
            None => out.push_str("    return "),
        }
        match output {
            Operand::Temp(_) => write!(out, "slots[{k}]").expect(TEXT),
            other => body.write_operand(other, out),
        }
        out.push_str(";\n");
    }
    out.push_str("}\n");
}

/// Part `p`: its inputs read into locals, the values of earlier parts and of the prologue
/// read from their slots, then its statements, each value a later part reads stored to its
/// slot and each output to the output's.
fn write_part(
    body: &Body,
    plan: &SplitPlan,
    head: &Head,
    p: usize,
    statements: &[Statement],
    out: &mut String,
) {
    writeln!(
        out,
        "static RNE_NOINLINE void {}_part{p}({}, double slots[{}]) {{",
        head.name,
        head.parameters.join(", "),
        plan.len
    )
    .expect(TEXT);
    let reads: BTreeSet<Symbol> = statements
        .iter()
        .filter_map(|s| match *s {
            Statement::Let(i) => Some(i),
            Statement::Output { .. } => None,
        })
        .flat_map(|i| body.inputs_of(i))
        .collect();
    body.write_unused(&reads, out);
    body.write_locals(reads.into_iter(), out);
    for &value in &plan.imports[p] {
        let name = body.value_name(value);
        writeln!(
            out,
            "    const double {name} = slots[{}];",
            plan.slots[&value]
        )
        .expect(TEXT);
    }
    for &statement in statements {
        match statement {
            Statement::Let(i) => {
                body.write_statement(i, out);
                if let Some(&slot) = plan.slots.get(&i) {
                    writeln!(out, "    slots[{slot}] = {};", body.value_name(i)).expect(TEXT);
                }
            }
            Statement::Output { output, instr } => {
                writeln!(out, "    slots[{output}] = {};", body.value_name(instr)).expect(TEXT)
            }
        }
    }
    out.push_str("}\n");
}

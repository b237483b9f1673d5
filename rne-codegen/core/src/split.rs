//! How a large kernel is cut into parts.
//!
//! rustc and LLVM take time that grows faster than linearly with the length of one
//! straight-line function (scheduling, register allocation and the scalar passes over one huge
//! basic block), and they compile one function on one core. A program of more than
//! [`SPLIT_ABOVE`] instructions is therefore emitted as a sequence of `#[inline(never)]`
//! functions of about [`PART_LEN`] instructions each, each in a module of its own so that
//! rustc can place them in different codegen units and compile them in parallel
//! (`emit.rs`). A value one part computes and a later part reads travels through a slot of
//! an array the kernel owns; outputs are written to their own slots; slots are reused once
//! the value in them has been read for the last time. Smaller programs are emitted as one
//! function, so the kernels of arms and small robots are written as one straight-line body.
//!
//! The plan is a function of the program alone, so the emitted text is the same on every
//! build.

use std::collections::BTreeMap;

use crate::program::{Operand, Program};
use crate::scratch_slots::ScratchSlots;

/// Programs with more instructions than this are split.
pub const SPLIT_ABOVE: usize = 15000;

/// Instructions per part (a statement belongs to the part of its instruction's index).
pub const PART_LEN: usize = 1000;

/// A statement of the emitted kernel.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Statement {
    /// `let t = …;` of instruction `i`, a result used more than once.
    Let(usize),
    /// `slots[output] = …;`: output `output` is the value of instruction `instr`.
    Output {
        /// The index of the output.
        output: usize,
        /// The instruction whose value it is.
        instr: usize,
    },
}

/// The parts of a split kernel and the slots between them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitPlan {
    /// The statements of each part, in program order.
    pub parts: Vec<Vec<Statement>>,
    /// The values (instruction indices) each part reads from a slot, ascending.
    pub imports: Vec<Vec<usize>>,
    /// The slot of every value that a part other than its own reads.
    pub slots: BTreeMap<usize, usize>,
    /// Slots in all: the outputs' (one per output, at the output's index) and the values'.
    pub len: usize,
}

/// One line per part (the values it reads from slots, then its statements), then the slot of
/// each value that travels and the number of slots:
///
/// ```text
/// part 0: let t1, out[1] = t3
/// part 1: reads t1; let t4, out[0] = t6
/// slots: t1 in 2
/// slots in all: 3
/// ```
impl std::fmt::Display for SplitPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (p, statements) in self.parts.iter().enumerate() {
            write!(f, "part {p}: ")?;
            if !self.imports[p].is_empty() {
                let imports: Vec<String> =
                    self.imports[p].iter().map(|v| format!("t{v}")).collect();
                write!(f, "reads {}; ", imports.join(" "))?;
            }
            let statements: Vec<String> = statements
                .iter()
                .map(|s| match *s {
                    Statement::Let(i) => format!("let t{i}"),
                    Statement::Output { output, instr } => format!("out[{output}] = t{instr}"),
                })
                .collect();
            writeln!(f, "{}", statements.join(", "))?;
        }
        let slots: Vec<String> = self
            .slots
            .iter()
            .map(|(v, s)| format!("t{v} in {s}"))
            .collect();
        writeln!(f, "slots: {}", slots.join(", "))?;
        writeln!(f, "slots in all: {}", self.len)
    }
}

/// Plans the parts of `program`, or `None` when it is small enough to stay one function.
///
/// `named[i]`: instruction `i` is bound by a `let` (used more than once); `prologue[i]`: its
/// value is bound before the parts run (the joint sines and cosines). Any other instruction
/// is written inline where it is used, so a statement reads the named and prologue values
/// found by walking its expression through the unnamed ones.
pub fn plan(program: &Program, named: &[bool], prologue: &[bool]) -> Option<SplitPlan> {
    (program.instrs.len() > SPLIT_ABOVE).then(|| plan_parts(program, named, prologue, PART_LEN))
}

/// [`plan`] with parts of `part_len` instructions, whatever the program's length (the C
/// emitter's, `emit_c`, whose compilers call for other lengths than rustc; the golden files'
/// small split cases).
pub fn plan_parts(
    program: &Program,
    named: &[bool],
    prologue: &[bool],
    part_len: usize,
) -> SplitPlan {
    let parts = statements(program, named, part_len);
    let (defined, readers) = readers(program, named, prologue, &parts);
    let mut imports: Vec<Vec<usize>> = vec![Vec::new(); parts.len()];
    // (part defining it, +1 so that the prologue is 0; last part reading it; value)
    let mut travelling: Vec<(usize, usize, usize)> = Vec::new();
    for (value, reading) in readers.iter().enumerate() {
        let home = defined[value];
        let mut foreign = reading
            .iter()
            .copied()
            .filter(|&p| Some(p) != home)
            .peekable();
        if foreign.peek().is_none() {
            continue;
        }
        for p in foreign {
            imports[p].push(value);
        }
        let last = *reading.last().expect("read by a part");
        travelling.push((home.map_or(0, |p| p + 1), last, value));
    }
    travelling.sort_unstable();
    let (slots, len) = slots(&travelling, program.outputs.len());
    SplitPlan {
        parts,
        imports,
        slots,
        len,
    }
}

/// The statements of each part that has any, in program order: a statement belongs to the
/// part of its instruction's index.
fn statements(program: &Program, named: &[bool], part_len: usize) -> Vec<Vec<Statement>> {
    let mut outputs_at: Vec<Vec<usize>> = vec![Vec::new(); program.instrs.len()];
    for (k, output) in program.outputs.iter().enumerate() {
        if let Operand::Temp(t) = *output {
            outputs_at[t as usize].push(k);
        }
    }
    let part_of = |i: usize| i / part_len;
    let mut parts: BTreeMap<usize, Vec<Statement>> = BTreeMap::new();
    for i in 0..program.instrs.len() {
        if named[i] {
            parts.entry(part_of(i)).or_default().push(Statement::Let(i));
        }
        for &output in &outputs_at[i] {
            let statement = Statement::Output { output, instr: i };
            parts.entry(part_of(i)).or_default().push(statement);
        }
    }
    parts.into_values().collect()
}

/// Where each named value is defined (`None`: the prologue) and every part reading it,
/// ascending (parts are visited in order).
fn readers(
    program: &Program,
    named: &[bool],
    prologue: &[bool],
    parts: &[Vec<Statement>],
) -> (Vec<Option<usize>>, Vec<Vec<usize>>) {
    let mut defined: Vec<Option<usize>> = vec![None; program.instrs.len()];
    let mut readers: Vec<Vec<usize>> = vec![Vec::new(); program.instrs.len()];
    for (p, statements) in parts.iter().enumerate() {
        for &statement in statements {
            let mut reads = Vec::new();
            match statement {
                Statement::Let(i) => {
                    defined[i] = Some(p);
                    for operand in program.instrs[i].operands() {
                        values_read(program, named, prologue, operand, &mut reads);
                    }
                }
                Statement::Output { instr, .. } => {
                    let temp = Operand::Temp(instr as u32);
                    values_read(program, named, prologue, temp, &mut reads);
                }
            }
            for value in reads {
                if readers[value].last() != Some(&p) {
                    readers[value].push(p);
                }
            }
        }
    }
    (defined, readers)
}

/// The slot of each travelling value (sorted (home part + 1, last part reading it, value)),
/// after the `outputs` slots of the outputs, each reused once every part reading its value has
/// run; and the number of slots.
fn slots(travelling: &[(usize, usize, usize)], outputs: usize) -> (BTreeMap<usize, usize>, usize) {
    let mut slots = BTreeMap::new();
    let mut scratch = ScratchSlots::starting_at(outputs);
    for &(home, last, value) in travelling {
        // Written in part `home − 1` (a prologue value, `home` 0, before part 0).
        slots.insert(value, scratch.place(home.saturating_sub(1), last));
    }
    (slots, scratch.count())
}

/// The named and prologue values `operand` reads, through the unnamed instructions written
/// inline.
fn values_read(
    program: &Program,
    named: &[bool],
    prologue: &[bool],
    operand: Operand,
    reads: &mut Vec<usize>,
) {
    let Operand::Temp(t) = operand else { return };
    let t = t as usize;
    if named[t] || prologue[t] {
        reads.push(t);
        return;
    }
    for child in program.instrs[t].operands() {
        values_read(program, named, prologue, child, reads);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::Instr;
    use rne_symbolic::Symbol;

    /// A long program whose values are read far from where they are computed: instruction i
    /// adds instruction i − 1 and i − 2500 (or an input), every output reads a value from
    /// another part, and two joint sines come from the prologue.
    fn long_program() -> (Program, Vec<bool>, Vec<bool>) {
        let n = SPLIT_ABOVE + 3000;
        let mut instrs = vec![
            Instr::Sin(Operand::Input(Symbol::Position(0))),
            Instr::Sin(Operand::Input(Symbol::Position(1))),
        ];
        for i in 2..n {
            let far = if i >= 2500 {
                Operand::Temp((i - 2500) as u32)
            } else {
                Operand::Input(Symbol::Velocity(0))
            };
            let near = Operand::Temp((i - 1) as u32);
            instrs.push(if i % 3 == 0 {
                Instr::Mul(near, far)
            } else {
                Instr::Add(near, far)
            });
        }
        instrs.push(Instr::Mul(Operand::Temp(0), Operand::Temp(1)));
        let outputs = vec![
            Operand::Temp(100),
            Operand::Const(2.0),
            Operand::Temp(n as u32),
            Operand::Temp(n as u32 - 1),
            Operand::Temp(1),
        ];
        let program = Program { instrs, outputs };
        let uses = program.use_counts();
        let prologue: Vec<bool> = (0..program.instrs.len()).map(|i| i < 2).collect();
        let named = (0..program.instrs.len())
            .map(|i| !prologue[i] && uses[i] >= 2)
            .collect();
        (program, named, prologue)
    }

    #[test]
    fn small_programs_stay_one_function() {
        let program = Program {
            instrs: vec![Instr::Add(Operand::Const(1.0), Operand::Const(2.0)); SPLIT_ABOVE],
            outputs: vec![Operand::Temp(0)],
        };
        let flags = vec![false; SPLIT_ABOVE];
        assert_eq!(plan(&program, &flags, &flags), None);
    }

    /// Running the parts in order over the slot array, every value a part imports is in its
    /// slot when the part starts (no later value has overwritten it), and every output ends
    /// in its own slot.
    #[test]
    fn every_imported_value_is_in_its_slot_when_read_and_slots_are_reused() {
        let (program, named, prologue) = long_program();
        let plan = plan(&program, &named, &prologue).expect("long enough to split");
        assert!(
            plan.parts.len() > SPLIT_ABOVE / PART_LEN,
            "{} parts",
            plan.parts.len()
        );
        #[derive(Copy, Clone, Debug, PartialEq)]
        enum Held {
            Value(usize),
            Output(usize),
        }
        let mut slots: Vec<Option<Held>> = vec![None; plan.len];
        for (&value, &slot) in &plan.slots {
            if prologue[value] {
                slots[slot] = Some(Held::Value(value));
            }
        }
        for (p, statements) in plan.parts.iter().enumerate() {
            for &value in &plan.imports[p] {
                assert_eq!(
                    slots[plan.slots[&value]],
                    Some(Held::Value(value)),
                    "part {p} reads {value}"
                );
            }
            for &statement in statements {
                match statement {
                    Statement::Let(i) => {
                        if let Some(&slot) = plan.slots.get(&i) {
                            assert!(slot >= program.outputs.len(), "{i} in an output's slot");
                            slots[slot] = Some(Held::Value(i));
                        }
                    }
                    Statement::Output { output, .. } => slots[output] = Some(Held::Output(output)),
                }
            }
        }
        for (k, output) in program.outputs.iter().enumerate() {
            if matches!(output, Operand::Temp(_)) {
                assert_eq!(slots[k], Some(Held::Output(k)));
            }
        }
        // 2500-instruction reach: each value travels at most two parts, so slots are reused.
        assert!(plan.len < program.outputs.len() + plan.slots.len());
    }
}

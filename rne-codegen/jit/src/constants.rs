//! The constants of a function in lanes, in a read-only table of the module, so that each is
//! read by the operation that uses it.
//!
//! x86-64 reads an operation's second operand from memory, and Cranelift folds a `load` with
//! one reader into it when that reader's own value is read once; a constant pair (`vconst`)
//! it always loads into a register by an instruction of its own. At the optimized tier a constant is made anew at each use (`lower.rs`): in
//! lanes, from this table, each constant twice (one per lane) at its own 16 bytes. Scalar
//! constants need no table: Cranelift reads `f64const` from its constant pool as the operand.

use cranelift_codegen::ir::{Function, GlobalValue};
use cranelift_jit::JITModule;
use cranelift_module::{DataDescription, Module};
use rne_codegen_core::{Operand, Program};
use rustc_hash::FxHashMap;

/// One function's constants: the table's symbol in the function and each constant's offset,
/// by its bits.
pub(crate) struct ConstantTable {
    pub global: GlobalValue,
    offsets: FxHashMap<u64, i32>,
}

/// Bytes per entry: one `f64` per lane, two lanes.
const ENTRY: usize = 16;

/// Constant `c` in both lanes of an `f64x2`, as its bytes in memory (little-endian).
pub(crate) fn lane_pair(c: f64) -> [u8; ENTRY] {
    let mut pair = [0; ENTRY];
    pair[..8].copy_from_slice(&c.to_le_bytes());
    pair[8..].copy_from_slice(&c.to_le_bytes());
    pair
}

impl ConstantTable {
    /// Defines in `module` the table of the constants that instructions `range` of `program`
    /// read (and its outputs, when `range` reaches its end), in the order they are first
    /// read, and declares it in `function`; `None` when there are none.
    pub(crate) fn define(
        module: &mut JITModule,
        function: &mut Function,
        program: &Program,
        range: std::ops::Range<usize>,
    ) -> Result<Option<ConstantTable>, String> {
        let outputs = match range.end == program.instrs.len() {
            true => &program.outputs[..],
            false => &[],
        };
        let read = program.instrs[range]
            .iter()
            .flat_map(|instr| instr.operands())
            .chain(outputs.iter().copied());
        let mut offsets = FxHashMap::default();
        let mut bytes = Vec::new();
        for o in read {
            if let Operand::Const(c) = o {
                offsets.entry(c.to_bits()).or_insert_with(|| {
                    let at = bytes.len() as i32;
                    bytes.extend_from_slice(&lane_pair(c));
                    at
                });
            }
        }
        if bytes.is_empty() {
            return Ok(None);
        }
        let id = module
            .declare_anonymous_data(false, false)
            .map_err(|e| e.to_string())?;
        let mut table = DataDescription::new();
        table.define(bytes.into_boxed_slice());
        table.set_align(ENTRY as u64);
        module.define_data(id, &table).map_err(|e| e.to_string())?;
        Ok(Some(ConstantTable {
            global: module.declare_data_in_func(id, function),
            offsets,
        }))
    }

    /// Constant `c`'s offset in the table, if the table has it.
    pub(crate) fn offset(&self, c: f64) -> Option<i32> {
        self.offsets.get(&c.to_bits()).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{host_module, Tier};
    use cranelift_codegen::ir::{Signature, UserFuncName};
    use cranelift_codegen::isa::CallConv;
    use rne_codegen_core::Instr;
    use rne_symbolic::Symbol;

    fn table(program: &Program, range: std::ops::Range<usize>) -> Option<ConstantTable> {
        let (mut module, _, _) = host_module(false, Tier::Optimized).expect("a host backend");
        let signature = Signature::new(CallConv::SystemV);
        let mut function = Function::with_name_signature(UserFuncName::user(0, 0), signature);
        ConstantTable::define(&mut module, &mut function, program, range).expect("defined")
    }

    /// Each distinct constant once, 16 bytes apart in the order first read; a part's table
    /// holds its own instructions' constants, and the outputs' only in the last part.
    #[test]
    fn each_constant_has_one_entry_in_the_order_first_read() {
        let x = Operand::Input(Symbol::Position(0));
        let program = Program {
            instrs: vec![
                Instr::Mul(x, Operand::Const(3.0)),
                Instr::Add(Operand::Temp(0), Operand::Const(-0.5)),
                Instr::Mul(Operand::Temp(1), Operand::Const(3.0)),
                Instr::Sub(Operand::Temp(2), x),
            ],
            outputs: vec![Operand::Temp(3), Operand::Const(7.0)],
        };
        let whole = table(&program, 0..4).expect("constants");
        assert_eq!(whole.offset(3.0), Some(0));
        assert_eq!(whole.offset(-0.5), Some(16));
        assert_eq!(whole.offset(7.0), Some(32));
        assert_eq!(whole.offset(0.5), None);
        let first = table(&program, 0..2).expect("constants");
        assert_eq!(first.offset(7.0), None);
        let third = table(&program, 2..3).expect("constants");
        assert_eq!((third.offset(3.0), third.offset(-0.5)), (Some(0), None));
        let last = table(&program, 3..4).expect("the outputs' constant in the last part");
        assert_eq!(last.offset(7.0), Some(0));
    }
}

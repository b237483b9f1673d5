//! A straight-line [`Program`] lowered to Cranelift IR: one function, or for a program longer
//! than the JIT's split threshold ([`Split`]) one function per part of about equal length,
//! called in turn, values read by a later part passing through a scratch array.
//!
//! The optimized tier splits as the Rust emitter does ([`SPLIT_ABOVE`]); the fast tier at a
//! lower threshold of its own: Cranelift compiles one function on one thread, and its register
//! allocator takes time that grows faster than linearly with a function's length, so there
//! the longest kernels (the derivatives) are cut into parts that the threads of `compile.rs`
//! share. The parts run the program's instructions in its order; a value crossing parts is
//! stored as the `f64` it is and loaded back, so splitting changes no bit of the results.
//!
//! Each instruction becomes the one IEEE operation it names, in program order — `fadd`,
//! `fsub`, `fmul`, `fdiv`, `fneg`, `sqrt`; `sign` as the runtime's (`1`, `−1`, or the value
//! itself for ±0 and NaN) by two comparisons and selects; a multiply-add one `fma` where the
//! processor fuses (else a product and a sum, as the runtime's `mul_add` without FMA). The
//! sines and cosines of the joint angles a part needs are computed at its start, as the
//! emitted Rust computes them at the top of the function: at the optimized tier by the
//! runtime's fast path written out in IR (`lower/trig.rs`: the same operations, so the same
//! bits), the runtime's `sin_cos_array` ([`crate::code::sin_cos_array`]) called only for
//! angles outside its range; at the fast tier by one call of `sin_cos_array`. Cranelift
//! neither reassociates nor contracts floating-point operations, so the compiled code
//! computes the program's values bit for bit.
//!
//! A program is lowered in scalars (`f64`, one state per call) or in two lanes (`f64x2`, two
//! states per call, for batches): the same instructions on vectors, each lane one state's IEEE
//! operation, so each lane gets the scalar function's bits. In two lanes the inputs and the
//! scratch array hold their values interleaved, state 0's and state 1's side by side
//! (`q[2k + l]` is state l's q_k); the outputs are each state's in turn (`out[l·M + k]` is
//! state l's output k of M), each lane stored by itself, so that a batch's results need no
//! de-interleaving; the parameters, shared by the states, are loaded once and splat. A
//! function lowered with output blocks (a kernel returning several matrices, batched into
//! one array per matrix: `matrices.rs`) takes as `out` a table of the blocks' addresses, and
//! each lane stores output k of block b at `block_b[l·L + k]`, L the block's length.

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    types, AbiParam, Endianness, FuncRef, Function, InstBuilder, MemFlagsData, Signature,
    StackSlotData, StackSlotKind, Type, UserFuncName, Value,
};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Linkage, Module};
use rne_codegen_core::{Instr, Operand, Program, ScratchSlots, PART_LEN, SPLIT_ABOVE};
use rne_symbolic::Symbol;
use rustc_hash::FxHashMap;

use crate::code::{Extents, MAX_BLOCKS};
use crate::constants::{lane_pair, ConstantTable};
use crate::model::Tier;
use crate::registers::{distinct_temps, held_limit, Registers};
use crate::windows::{window_of, windows_limit, Windows};

mod trig;

/// The name compiled code calls the runtime's sines and cosines by.
pub(crate) const SIN_COS: &str = "rne_jit_sin_cos_array";

/// What lowering needs of the module: the pointer type, the kernels' and `sin_cos_array`'s
/// signatures and the function it calls.
pub(crate) struct Lowering {
    pointer: Type,
    /// States per call: 1 (scalars) or 2 (`f64x2` lanes).
    lanes: usize,
    kernel_signature: Signature,
    sin_cos: FuncId,
    /// Whether multiply-adds are fused (`fma` on and the processor has FMA).
    pub fused: bool,
    /// Where long programs are cut.
    split: Split,
    /// The most values held in registers ([`Registers`]): at the optimized tier only, where
    /// the code's speed is what counts; the fast tier's compile time grows with the loads and
    /// stores this adds.
    held: Option<usize>,
    /// The output blocks (0: none): with B blocks, the outputs are cut into B blocks of
    /// equal length, and `out` is the address of a table of B addresses, one per block, each
    /// block holding its outputs of each lane in turn (`code.rs`, `Out::Blocks`).
    pub blocks: usize,
    builder: FunctionBuilderContext,
}

/// The instructions `[start, end)` of a program as one function.
#[derive(Copy, Clone, Debug)]
struct Part {
    start: usize,
    end: usize,
}

/// Where the values that cross parts live: instruction index → scratch slot.
type Slots = FxHashMap<usize, usize>;

/// Where the JIT cuts long programs: a program of more than `above` instructions becomes
/// parts of at most `part_len` instructions, of about equal length.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Split {
    /// Programs with more instructions than this are split.
    pub above: usize,
    /// The most instructions in one part.
    pub part_len: usize,
}

impl Split {
    /// The fast tier's cut: programs of more than two parts' worth of instructions, in parts
    /// of at most the Rust emitter's part length ([`PART_LEN`]). The derivative kernels of
    /// arms are split, their dynamics kernels (shorter) stay one function each: the compile
    /// time is what this tier is for, and the threads of `compile.rs` share the parts.
    pub(crate) const FAST: Split = Split {
        above: 2 * PART_LEN,
        part_len: PART_LEN,
    };

    /// The optimized tier's cut: the Rust emitter's ([`SPLIT_ABOVE`], [`PART_LEN`]), so that
    /// the kernels the macro emits as one function are one function here too. A value that
    /// crosses parts is stored and loaded back, and each part's registers start empty: the
    /// arms' derivative kernels run faster whole than in the fast tier's parts, for a longer
    /// compile (docs/performance.md, "Robots chosen at run time").
    pub(crate) const OPTIMIZED: Split = Split {
        above: SPLIT_ABOVE,
        part_len: PART_LEN,
    };

    /// The cut of `tier`, or as `RNE_JIT_SPLIT_ABOVE` and `RNE_JIT_PART_LEN` say (positive
    /// numbers; for measuring the compile time and speed of other cuts).
    pub(crate) fn for_tier(tier: Tier) -> Split {
        let default = match tier {
            Tier::Fast => Split::FAST,
            Tier::Optimized => Split::OPTIMIZED,
        };
        let read = |name: &str, default: usize| {
            std::env::var(name)
                .ok()
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|&n| n > 0)
                .unwrap_or(default)
        };
        Split {
            above: read("RNE_JIT_SPLIT_ABOVE", default.above),
            part_len: read("RNE_JIT_PART_LEN", default.part_len),
        }
    }
}

impl Lowering {
    /// Declares `sin_cos_array` in `module`; `fused` as [`Lowering::fused`]; `lanes` states
    /// per call (1 or 2); long programs cut as `tier`'s [`Split`].
    pub(crate) fn new(
        module: &mut JITModule,
        fused: bool,
        lanes: usize,
        tier: Tier,
    ) -> Result<Lowering, String> {
        if !matches!(lanes, 1 | 2) {
            return Err(format!("{lanes} lanes (1 or 2 are lowered)"));
        }
        let pointer = module.target_config().pointer_type();
        let mut kernel_signature = module.make_signature();
        for _ in 0..7 {
            kernel_signature.params.push(AbiParam::new(pointer));
        }
        let mut trig = module.make_signature();
        for _ in 0..4 {
            trig.params.push(AbiParam::new(pointer));
        }
        let sin_cos = module
            .declare_function(SIN_COS, Linkage::Import, &trig)
            .map_err(|e| e.to_string())?;
        Ok(Lowering {
            pointer,
            lanes,
            kernel_signature,
            sin_cos,
            fused,
            split: Split::for_tier(tier),
            held: (tier == Tier::Optimized).then(held_limit),
            blocks: 0,
            builder: FunctionBuilderContext::new(),
        })
    }

    /// Lowers `program` to Cranelift IR as functions declared in `module` and named after
    /// `name`, to be called in order with one scratch array: their ids, IR and extents, for
    /// [`crate::compile::define`] to compile.
    pub(crate) fn lower(
        &mut self,
        module: &mut JITModule,
        name: &str,
        program: &Program,
    ) -> Result<Vec<Lowered>, String> {
        let blocks = self.blocks;
        if blocks > MAX_BLOCKS || (blocks > 0 && !program.outputs.len().is_multiple_of(blocks)) {
            return Err(format!(
                "{} outputs cannot be cut into {blocks} output blocks",
                program.outputs.len()
            ));
        }
        let parts = parts(program, self.split);
        let (slots, scratch) = crossing_slots(program, &parts);
        let outputs = temp_outputs(program)?;
        let mut functions = Vec::with_capacity(parts.len());
        for (k, &part) in parts.iter().enumerate() {
            let name = format!("{name}_{k}");
            let id = module
                .declare_function(&name, Linkage::Local, &self.kernel_signature)
                .map_err(|e| e.to_string())?;
            let mut function = Function::with_name_signature(
                UserFuncName::user(0, id.as_u32()),
                self.kernel_signature.clone(),
            );
            let sin_cos = module.declare_func_in_func(self.sin_cos, &mut function);
            let mut extents = Extents {
                scratch: scratch * self.lanes,
                ..Extents::default()
            };
            let table = match (self.held.is_some(), self.lanes) {
                (true, 2) => {
                    ConstantTable::define(module, &mut function, program, part.start..part.end)?
                }
                _ => None,
            };
            let config = module.target_config();
            {
                let builder = FunctionBuilder::new(&mut function, &mut self.builder);
                let mut body = Body::new(builder, self.pointer, sin_cos, self.fused, self.lanes);
                body.outputs = program.outputs.len();
                body.blocks = blocks;
                body.temps.start = part.start;
                body.temps.own = vec![None; part.end - part.start];
                body.registers = self
                    .held
                    .map(|limit| Registers::new(program, part.start, part.end, limit));
                body.spill_area.1 = body.registers.as_ref().map_or(0, Registers::most_alive);
                if body.registers.is_some() {
                    body.windows = Windows::new(windows_limit());
                    body.inline_trig = true;
                }
                body.constant_table = table.map(|table| (None, table));
                body.run(program, part, &slots, &outputs, &mut extents)?;
                body.builder.finalize(config);
            }
            functions.push(Lowered {
                id,
                name,
                function,
                extents,
                lanes: self.lanes,
            });
        }
        Ok(functions)
    }
}

/// One function in Cranelift IR, declared and not yet compiled.
pub(crate) struct Lowered {
    /// Its id in the module.
    pub id: FuncId,
    /// Its name in the module: the kernel's, then the part's number.
    pub name: String,
    /// Its IR.
    pub function: Function,
    /// The array lengths it reads and writes.
    pub extents: Extents,
    /// States per call.
    pub lanes: usize,
}

/// The outputs that are instructions' values, as (instruction, output) pairs in the order of
/// the instructions; an error for a program in lanes.
fn temp_outputs(program: &Program) -> Result<Vec<(usize, usize)>, String> {
    let mut outputs = Vec::with_capacity(program.outputs.len());
    for (k, &o) in program.outputs.iter().enumerate() {
        match o {
            Operand::Temp(t) => outputs.push((t as usize, k)),
            Operand::Lane { .. } => return Err("a program in lanes".to_owned()),
            _ => {}
        }
    }
    outputs.sort_unstable();
    Ok(outputs)
}

/// The values of a function's instructions: those of its own part by index, those of earlier
/// parts (loaded from scratch) by instruction.
#[derive(Default)]
struct Temps {
    start: usize,
    own: Vec<Option<Value>>,
    earlier: FxHashMap<usize, Value>,
}

impl Temps {
    fn get(&self, t: usize) -> Option<Value> {
        match t.checked_sub(self.start) {
            Some(k) if k < self.own.len() => self.own[k],
            _ => self.earlier.get(&t).copied(),
        }
    }

    fn remove(&mut self, t: usize) -> Option<Value> {
        match t.checked_sub(self.start) {
            Some(k) if k < self.own.len() => self.own[k].take(),
            _ => self.earlier.remove(&t),
        }
    }

    fn insert(&mut self, t: usize, value: Value) {
        match t.checked_sub(self.start) {
            Some(k) if k < self.own.len() => self.own[k] = Some(value),
            _ => {
                self.earlier.insert(t, value);
            }
        }
    }
}

/// The parts of `program` as `split` cuts it: one, or the fewest of at most `part_len`
/// instructions, their lengths differing by at most one.
fn parts(program: &Program, split: Split) -> Vec<Part> {
    let n = program.instrs.len();
    if n <= split.above {
        return vec![Part { start: 0, end: n }];
    }
    let count = n.div_ceil(split.part_len.max(1));
    (0..count)
        .map(|k| Part {
            start: k * n / count,
            end: (k + 1) * n / count,
        })
        .collect()
}

/// A scratch slot for every value a later part reads, and the number of slots. A slot is
/// reused by a value of a part after the last part reading the value it held.
fn crossing_slots(program: &Program, parts: &[Part]) -> (Slots, usize) {
    let part_of = |t: usize| parts.partition_point(|p| p.end <= t);
    let mut last_reader: Vec<Option<usize>> = vec![None; program.instrs.len()];
    for (k, instr) in program.instrs.iter().enumerate() {
        for t in instr.operands().filter_map(Operand::temp) {
            let (home, reader) = (part_of(t as usize), part_of(k));
            if home != reader {
                let last = &mut last_reader[t as usize];
                *last = Some(last.map_or(reader, |r| r.max(reader)));
            }
        }
    }
    let mut slots = Slots::default();
    let mut scratch = ScratchSlots::starting_at(0);
    for (t, last) in last_reader.iter().enumerate() {
        let Some(last) = *last else { continue };
        slots.insert(t, scratch.place(part_of(t), last));
    }
    (slots, scratch.count())
}

/// The pointer parameters of a compiled function, in order.
#[derive(Copy, Clone)]
enum Array {
    Q = 0,
    Qd = 1,
    Qdd = 2,
    Tau = 3,
    Parameters = 4,
    Out = 5,
    Scratch = 6,
}

/// The body of one function being built.
struct Body<'f> {
    builder: FunctionBuilder<'f>,
    pointer: Type,
    sin_cos: FuncRef,
    /// Whether the runtime's sines and cosines are computed inline (`lower/trig.rs`): at the
    /// optimized tier.
    inline_trig: bool,
    fused: bool,
    /// States per call (1 or 2) and the type of a value: `f64` or `f64x2`.
    lanes: usize,
    ty: Type,
    arrays: [Value; 7],
    /// The program's number of outputs (where the second lane's outputs start).
    outputs: usize,
    /// The output blocks ([`Lowering::blocks`]).
    blocks: usize,
    /// Values of this function: instructions' held in registers, inputs' and constants'.
    temps: Temps,
    /// Which instruction values are held in registers ([`Registers`]), at the optimized tier;
    /// at the fast tier every value is Cranelift's to place.
    registers: Option<Registers>,
    /// Where each instruction value that is not held lives besides scratch, as an address
    /// and an offset: its spill slot or its place in the sines' and cosines' array.
    homes: FxHashMap<usize, (Value, i32)>,
    /// The spill area: its address once a value is spilled, and its size in slots (the most
    /// values alive at once: no more can be spilled at once).
    spill_area: (Option<Value>, usize),
    /// Spill slots whose values are read no more, and the next slot never used.
    free_slots: Vec<i32>,
    next_slot: usize,
    inputs: FxHashMap<Symbol, Value>,
    constants: FxHashMap<u64, Value>,
    /// In lanes at the optimized tier, the function's constants' table, with its address once
    /// a constant has been read.
    constant_table: Option<(Option<Value>, ConstantTable)>,
    /// The registers through which the stack, the constants' table and the inputs are
    /// reached by one-byte displacements, at the optimized tier on x86-64.
    windows: Windows,
}

impl<'f> Body<'f> {
    fn new(
        mut builder: FunctionBuilder<'f>,
        pointer: Type,
        sin_cos: FuncRef,
        fused: bool,
        lanes: usize,
    ) -> Self {
        let block = builder.create_block();
        builder.append_block_params_for_function_params(block);
        builder.switch_to_block(block);
        builder.seal_block(block);
        let params = builder.block_params(block);
        let arrays = std::array::from_fn(|k| params[k]);
        Body {
            builder,
            pointer,
            sin_cos,
            inline_trig: false,
            fused,
            lanes,
            ty: if lanes == 1 { types::F64 } else { types::F64X2 },
            arrays,
            outputs: 0,
            blocks: 0,
            temps: Temps::default(),
            registers: None,
            homes: FxHashMap::default(),
            spill_area: (None, 0),
            free_slots: Vec::new(),
            next_slot: 0,
            inputs: FxHashMap::default(),
            constants: FxHashMap::default(),
            constant_table: None,
            windows: Windows::new(0),
        }
    }

    /// Lowers `part` of `program`: its joints' sines and cosines, its instructions (each
    /// stored to scratch when a later part reads it, to the outputs it is), and in the last
    /// part the outputs that are constants or inputs.
    fn run(
        &mut self,
        program: &Program,
        part: Part,
        slots: &Slots,
        outputs: &[(usize, usize)],
        extents: &mut Extents,
    ) -> Result<(), String> {
        self.joint_trig(program, part, extents);
        let mut next_output = outputs.partition_point(|&(t, _)| t < part.start);
        for t in part.start..part.end {
            let value = if self.homes.contains_key(&t) {
                let crosses = slots.contains_key(&t)
                    || outputs.get(next_output).is_some_and(|&(o, _)| o == t);
                if !crosses {
                    continue;
                }
                self.home_value(t, slots)?
            } else if self.registers.is_some() {
                self.held_instruction(program, t, slots, extents)?
            } else {
                let value = self.instruction(program.instrs[t], slots, extents)?;
                self.temps.insert(t, value);
                value
            };
            if let Some(&slot) = slots.get(&t) {
                self.store(Array::Scratch, slot, value);
            }
            while let Some(&(_, k)) = outputs.get(next_output).filter(|&&(o, _)| o == t) {
                self.store(Array::Out, k, value);
                next_output += 1;
            }
        }
        if part.end == program.instrs.len() {
            for (k, &o) in program.outputs.iter().enumerate() {
                if o.temp().is_none() {
                    let value = self.operand(o, slots, extents)?;
                    self.store(Array::Out, k, value);
                }
            }
        }
        extents.out = self.lanes * program.outputs.len() / self.blocks.max(1);
        extents.blocks = self.blocks;
        self.builder.ins().return_(&[]);
        Ok(())
    }

    /// The sines and cosines of the joint angles the part's instructions take, by one call:
    /// each instruction's value recorded before the instructions are lowered.
    fn joint_trig(&mut self, program: &Program, part: Part, extents: &mut Extents) {
        let mut joints: Vec<u16> = Vec::new();
        for instr in &program.instrs[part.start..part.end] {
            if let Instr::Sin(Operand::Input(Symbol::Position(k)))
            | Instr::Cos(Operand::Input(Symbol::Position(k))) = *instr
            {
                if !joints.contains(&k) {
                    joints.push(k);
                }
            }
        }
        if joints.is_empty() {
            return;
        }
        let angles: Vec<Value> = joints
            .iter()
            .map(|&k| self.input(Symbol::Position(k), extents))
            .collect();
        let array = self.sin_cos_array(&angles);
        let base = self.builder.ins().stack_addr(self.pointer, array.slot, 0);
        for t in part.start..part.end {
            let (k, kind) = match program.instrs[t] {
                Instr::Sin(Operand::Input(Symbol::Position(k))) => (k, 1),
                Instr::Cos(Operand::Input(Symbol::Position(k))) => (k, 2),
                _ => continue,
            };
            let j = joints
                .iter()
                .position(|&j| j == k)
                .expect("collected above");
            self.homes.insert(t, (base, array.at(j, kind)));
        }
    }

    /// `(sin xᵢ, cos xᵢ)` of `angles`, loaded from [`Body::sin_cos_array`]'s array.
    fn sin_cos(&mut self, angles: &[Value]) -> (Vec<Value>, Vec<Value>) {
        let array = self.sin_cos_array(angles);
        let (pointer, ty) = (self.pointer, self.ty);
        let mut load = |kind: usize, k: usize| {
            self.builder
                .ins()
                .stack_load(pointer, ty, array.slot, array.at(k, kind))
        };
        let s = (0..angles.len()).map(|k| load(1, k)).collect();
        let c = (0..angles.len()).map(|k| load(2, k)).collect();
        (s, c)
    }

    /// Instruction `t`'s value, its operands brought into registers first and those it read
    /// for the last time released after; held if it is read again ([`Registers`]).
    fn held_instruction(
        &mut self,
        program: &Program,
        t: usize,
        slots: &Slots,
        extents: &mut Extents,
    ) -> Result<Value, String> {
        let reads = distinct_temps(program, t);
        let reads = reads.as_slice();
        self.bring_in(reads, slots)?;
        let value = self.instruction(program.instrs[t], slots, extents)?;
        for &r in reads {
            if self.held().read(r) {
                self.release(r);
            }
        }
        let evicted = if self.held().is_read_again(t) {
            self.held().hold(t);
            self.temps.insert(t, value);
            self.held().make_room(0, &[])
        } else {
            Vec::new()
        };
        for e in evicted {
            self.evict(e, slots);
        }
        Ok(value)
    }

    /// The held values' bookkeeping (the optimized tier's).
    fn held(&mut self) -> &mut Registers {
        self.registers.as_mut().expect("held values are tracked")
    }

    /// Loads the values instruction reads `reads` that are not held, after evicting what
    /// must make room for them ([`Registers::make_room`]): the loads come last, right before
    /// their reader.
    fn bring_in(&mut self, reads: &[usize], slots: &Slots) -> Result<(), String> {
        let missing: Vec<usize> = reads
            .iter()
            .copied()
            .filter(|&t| self.temps.get(t).is_none())
            .collect();
        let evicted = self.held().make_room(missing.len(), reads);
        for &t in &missing {
            self.held().hold(t);
        }
        for e in evicted {
            self.evict(e, slots);
        }
        for t in missing {
            let value = self.home_value(t, slots)?;
            self.temps.insert(t, value);
        }
        Ok(())
    }

    /// Value `t`, no longer held, kept in memory: stored to a spill slot unless it has a
    /// place already (scratch, the sines' and cosines' array, an earlier spill).
    fn evict(&mut self, t: usize, slots: &Slots) {
        let value = self.temps.remove(t).expect("an evicted value is held");
        if self.homes.contains_key(&t) || slots.contains_key(&t) {
            return;
        }
        let base = self.spill_base();
        let offset = match self.free_slot(base) {
            Some(offset) => offset,
            None => {
                let width = 8 * self.lanes;
                let offset = (width * self.next_slot) as i32;
                self.next_slot += 1;
                offset
            }
        };
        let flags = self.flags_aligned();
        let (window, at) = self.reach(base, offset, true);
        self.builder.ins().store(flags, value, window, at);
        self.homes.insert(t, (base, offset));
    }

    /// A free spill slot, one in a held window ([`Windows`]) if there is one, the most
    /// recently used window's first.
    fn free_slot(&mut self, base: Value) -> Option<i32> {
        for number in self.windows.held_of(base) {
            let found = self
                .free_slots
                .iter()
                .rposition(|&offset| window_of(offset).0 == number);
            if let Some(k) = found {
                return Some(self.free_slots.swap_remove(k));
            }
        }
        self.free_slots.pop()
    }

    /// The place `offset` bytes from `area` as an address and a displacement: through a
    /// window ([`Windows`]) when windows are in use and `area` is on the stack (whose
    /// displacement from `rsp` is the slot's own plus `offset`) or `offset` needs four bytes.
    fn reach(&mut self, area: Value, offset: i32, stack: bool) -> (Value, i32) {
        if !self.windows.enabled() || (!stack && (-128..=127).contains(&offset)) {
            return (area, offset);
        }
        let builder = &mut self.builder;
        self.windows.reach(area, offset, |middle| {
            let address = builder.ins().iadd_imm_s(area, i64::from(middle));
            builder.ins().band_imm_s(address, -1)
        })
    }

    /// The spill area's address, the area made at the first spill.
    fn spill_base(&mut self) -> Value {
        if let Some(base) = self.spill_area.0 {
            return base;
        }
        let bytes = u32::try_from(8 * self.lanes * self.spill_area.1.max(1)).expect("a frame");
        let slot = self.builder.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            bytes,
            4,
        ));
        let base = self.builder.ins().stack_addr(self.pointer, slot, 0);
        self.spill_area.0 = Some(base);
        base
    }

    /// Value `t` is read no more in this function: its register and spill slot are free.
    fn release(&mut self, t: usize) {
        self.temps.remove(t);
        if let Some((base, offset)) = self.homes.remove(&t) {
            if Some(base) == self.spill_area.0 {
                self.free_slots.push(offset);
            }
        }
    }

    /// Value `t` loaded from where it is kept: its spill slot or place in the sines' and
    /// cosines' array, else its scratch slot.
    fn home_value(&mut self, t: usize, slots: &Slots) -> Result<Value, String> {
        if let Some(&(base, offset)) = self.homes.get(&t) {
            let (ty, flags) = (self.ty, self.flags_aligned());
            let (window, at) = self.reach(base, offset, true);
            return Ok(self.builder.ins().load(ty, flags, window, at));
        }
        let slot = *slots.get(&t).ok_or("a value read before it is computed")?;
        Ok(self.load(Array::Scratch, slot))
    }

    /// One instruction's value.
    fn instruction(
        &mut self,
        instr: Instr,
        slots: &Slots,
        extents: &mut Extents,
    ) -> Result<Value, String> {
        let mut v = |o: Operand, body: &mut Self| body.operand(o, slots, extents);
        fn ins<'b, 'f>(body: &'b mut Body<'f>) -> cranelift_frontend::FuncInstBuilder<'b, 'f> {
            body.builder.ins()
        }
        Ok(match instr {
            Instr::Add(a, b) => {
                let (a, b) = leaf_second(a, b);
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fadd(a, b)
            }
            Instr::Sub(a, b) => {
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fsub(a, b)
            }
            Instr::Mul(a, b) => {
                let (a, b) = leaf_second(a, b);
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fmul(a, b)
            }
            Instr::Div(a, b) => {
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fdiv(a, b)
            }
            Instr::Neg(a) => {
                let a = v(a, self)?;
                ins(self).fneg(a)
            }
            Instr::Sqrt(a) => {
                let a = v(a, self)?;
                ins(self).sqrt(a)
            }
            Instr::Sign(a) => {
                let a = v(a, self)?;
                self.sign(a)
            }
            Instr::Sin(a) | Instr::Cos(a) => {
                let a = v(a, self)?;
                let (s, c) = self.sin_cos(&[a]);
                if matches!(instr, Instr::Sin(_)) {
                    s[0]
                } else {
                    c[0]
                }
            }
            Instr::MulAdd(a, b, c) => {
                let (a, b, c) = (v(a, self)?, v(b, self)?, v(c, self)?);
                self.mul_add(a, b, c)
            }
            Instr::MulSub(a, b, c) => {
                let (a, b, c) = (v(a, self)?, v(b, self)?, v(c, self)?);
                let c = ins(self).fneg(c);
                self.mul_add(a, b, c)
            }
            Instr::NegMulAdd(a, b, c) => {
                let (a, b, c) = (v(a, self)?, v(b, self)?, v(c, self)?);
                let a = ins(self).fneg(a);
                self.mul_add(a, b, c)
            }
        })
    }

    /// `a·b + c`: one rounding where fused, two otherwise (the runtime's `mul_add`).
    fn mul_add(&mut self, a: Value, b: Value, c: Value) -> Value {
        if self.fused {
            self.builder.ins().fma(a, b, c)
        } else {
            let product = self.builder.ins().fmul(a, b);
            self.builder.ins().fadd(product, c)
        }
    }

    /// The runtime's sign: 1 above zero, −1 below, the value itself for ±0 and NaN (in lanes,
    /// lane by lane).
    fn sign(&mut self, x: Value) -> Value {
        let zero = self.constant(0.0);
        let one = self.constant(1.0);
        let minus_one = self.constant(-1.0);
        let below = self.builder.ins().fcmp(FloatCC::LessThan, x, zero);
        let not_above = self.choose(below, minus_one, x);
        let above = self.builder.ins().fcmp(FloatCC::GreaterThan, x, zero);
        self.choose(above, one, not_above)
    }

    /// `condition ? a : b` for a comparison's result: a select on scalars, a bit select by the
    /// comparison's lane masks on vectors.
    fn choose(&mut self, condition: Value, a: Value, b: Value) -> Value {
        if self.lanes == 1 {
            return self.builder.ins().select(condition, a, b);
        }
        let little = MemFlagsData::new().with_endianness(Endianness::Little);
        let mask = self.builder.ins().bitcast(self.ty, little, condition);
        self.builder.ins().bitselect(mask, a, b)
    }

    /// An operand's value: an instruction of this part, one of an earlier part (from its
    /// scratch slot), a constant or an input.
    fn operand(
        &mut self,
        o: Operand,
        slots: &Slots,
        extents: &mut Extents,
    ) -> Result<Value, String> {
        Ok(match o {
            Operand::Const(c) => self.constant(c),
            Operand::Input(Symbol::Lane(_)) | Operand::Lane { .. } => {
                return Err("a program in lanes".to_owned())
            }
            Operand::Input(s) => self.input(s, extents),
            Operand::Temp(t) => {
                let t = t as usize;
                match self.temps.get(t) {
                    Some(v) => v,
                    None => {
                        let v = self.home_value(t, slots)?;
                        self.temps.insert(t, v);
                        v
                    }
                }
            }
        })
    }

    /// Constant `c`'s value. At the optimized tier a new one at each use, next to its reader
    /// ([`Body::rematerialised`]): a scalar is read from Cranelift's constant pool by the
    /// operation itself, a pair in lanes from the function's [`ConstantTable`] (or, for a
    /// constant the table lacks, loaded from the pool by an instruction of its own). At the
    /// fast tier, one value per function.
    fn constant(&mut self, c: f64) -> Value {
        if self.rematerialised() {
            if self.lanes == 1 {
                return self.builder.ins().f64const(c);
            }
            if let Some(v) = self.table_constant(c) {
                return v;
            }
            return self.pool_pair(c);
        }
        if let Some(&v) = self.constants.get(&c.to_bits()) {
            return v;
        }
        let mut v = self.builder.ins().f64const(c);
        if self.lanes > 1 {
            v = self.builder.ins().splat(self.ty, v);
        }
        self.constants.insert(c.to_bits(), v);
        v
    }

    /// Constant `c` in both lanes of an `f64x2`, loaded from Cranelift's constant pool by an
    /// instruction of its own.
    fn pool_pair(&mut self, c: f64) -> Value {
        let constants = &mut self.builder.func.dfg.constants;
        let handle = constants.insert(lane_pair(c).to_vec().into());
        self.builder.ins().vconst(types::F64X2, handle)
    }

    /// An input's value, loaded at each use at the optimized tier ([`Body::rematerialised`]:
    /// the load becomes its reader's memory operand when that reader's value is read once),
    /// once per function at the fast tier; the extents grow to cover it.
    fn input(&mut self, s: Symbol, extents: &mut Extents) -> Value {
        if let Some(&v) = self.inputs.get(&s).filter(|_| !self.rematerialised()) {
            return v;
        }
        let (array, index, extent) = match s {
            Symbol::Position(k) => (Array::Q, k, &mut extents.q),
            Symbol::Velocity(k) => (Array::Qd, k, &mut extents.qd),
            Symbol::Acceleration(k) => (Array::Qdd, k, &mut extents.qdd),
            Symbol::Force(k) => (Array::Tau, k, &mut extents.tau),
            Symbol::Parameter(k) => (Array::Parameters, k, &mut extents.parameters),
            Symbol::Lane(_) => unreachable!("lanes are refused by `operand`"),
        };
        let lanes = match array {
            Array::Parameters => 1,
            _ => self.lanes,
        };
        *extent = (*extent).max(lanes * (usize::from(index) + 1));
        let v = self.load(array, usize::from(index));
        if !self.rematerialised() {
            self.inputs.insert(s, v);
        }
        v
    }

    /// Constant pair `c` loaded from the function's table, if it has one with `c`: a load
    /// with one reader, which Cranelift folds into that reader when the reader's own value is
    /// read once (it never folds into an operation whose value has several readers).
    fn table_constant(&mut self, c: f64) -> Option<Value> {
        let (base, table) = self.constant_table.as_mut()?;
        let offset = table.offset(c)?;
        let base = *base
            .get_or_insert_with(|| self.builder.ins().symbol_value(self.pointer, table.global));
        let flags = MemFlagsData::trusted().with_readonly();
        let (window, at) = self.reach(base, offset, false);
        Some(self.builder.ins().load(self.ty, flags, window, at))
    }

    /// Whether constants and inputs are made anew at each use: at the optimized tier, where
    /// the lowering chooses which values stay in registers ([`Registers`]). Kept one per
    /// function, they would live in registers from their first use to their last, beside the
    /// values held, and Cranelift would spill and reload them (docs/performance.md,
    /// "Constants and inputs at each use").
    fn rematerialised(&self) -> bool {
        self.registers.is_some()
    }

    /// Value `index` of `array`: in lanes, the pair at `2·index` (the parameters, shared by
    /// the states, one value splat).
    fn load(&mut self, array: Array, index: usize) -> Value {
        let base = self.arrays[array as usize];
        if self.lanes > 1 && matches!(array, Array::Parameters) {
            let flags = MemFlagsData::trusted();
            let (window, at) = self.reach(base, (8 * index) as i32, false);
            let scalar = self.builder.ins().load(types::F64, flags, window, at);
            return self.builder.ins().splat(self.ty, scalar);
        }
        let (offset, flags, ty) = ((8 * self.lanes * index) as i32, self.flags(), self.ty);
        let (window, at) = self.reach(base, offset, false);
        self.builder.ins().load(ty, flags, window, at)
    }

    fn store(&mut self, array: Array, index: usize, value: Value) {
        let base = self.arrays[array as usize];
        let flags = self.flags();
        if matches!(array, Array::Out) && (self.lanes > 1 || self.blocks > 0) {
            // Each lane into its own state's outputs (module docs).
            let (base, per_lane, index) = self.output_place(index);
            for lane in 0..self.lanes {
                let x = match self.lanes {
                    1 => value,
                    _ => self.builder.ins().extractlane(value, lane as u8),
                };
                let offset = (8 * (lane * per_lane + index)) as i32;
                self.builder.ins().store(flags, x, base, offset);
            }
            return;
        }
        let offset = (8 * self.lanes * index) as i32;
        let (window, at) = match array {
            // Each output is stored once, in the order computed: a window would rarely serve
            // a second output before it made room for another.
            Array::Out => (base, offset),
            _ => self.reach(base, offset, false),
        };
        self.builder.ins().store(flags, value, window, at);
    }

    /// Where output `index` goes: the address its lanes are stored from, the values between
    /// one lane's and the next, and its index there. Without blocks, the outputs' array, all
    /// outputs, `index`; with blocks, its block's address (read from the table `out` points
    /// to), the block's length, its index in the block.
    fn output_place(&mut self, index: usize) -> (Value, usize, usize) {
        let out = self.arrays[Array::Out as usize];
        if self.blocks == 0 {
            return (out, self.outputs, index);
        }
        let len = self.outputs / self.blocks;
        let flags = MemFlagsData::trusted().with_readonly();
        let block = (index / len) as i32;
        let address = self.builder.ins().load(self.pointer, flags, out, 8 * block);
        (address, len, index % len)
    }

    /// The stack's accesses: in bounds and aligned (the spill area and the sines' and cosines'
    /// array are aligned to 16 bytes, a pair of lanes).
    fn flags_aligned(&self) -> MemFlagsData {
        MemFlagsData::trusted()
    }

    /// The arrays' accesses: in bounds (`Entry::call` checks the extents) and aligned to the
    /// scalar; vectors are aligned to 8 bytes only, so they are not marked aligned.
    fn flags(&self) -> MemFlagsData {
        match self.lanes {
            1 => MemFlagsData::trusted(),
            _ => MemFlagsData::new().with_notrap(),
        }
    }
}

/// A sum's or product's operands with a constant or an input second when the other is
/// neither. x86-64 takes an operation's second operand from memory but its first only from
/// a register: the program writes products constant first (`c·x`), and Cranelift
/// materialises such a constant in a register (`movabs` and `movq`) that then lives from its
/// first use to its last, spilled and reloaded, while second it is read from the constant
/// pool by the operation itself. Swapping the operands of an addition or a multiplication
/// changes no bit of its result.
fn leaf_second(a: Operand, b: Operand) -> (Operand, Operand) {
    let leaf = |o: Operand| matches!(o, Operand::Const(_) | Operand::Input(_));
    if leaf(a) && !leaf(b) {
        (b, a)
    } else {
        (a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A program of `n` instructions where instruction i adds instruction i − 1 and
    /// i − `reach` (or an input), so values are read up to `reach` instructions away.
    fn chain(n: usize, reach: usize) -> Program {
        let instrs = (0..n)
            .map(|i| {
                let near = match i {
                    0 => Operand::Input(Symbol::Position(0)),
                    _ => Operand::Temp((i - 1) as u32),
                };
                let far = match i.checked_sub(reach) {
                    Some(j) => Operand::Temp(j as u32),
                    None => Operand::Input(Symbol::Velocity(0)),
                };
                Instr::Add(near, far)
            })
            .collect();
        Program {
            instrs,
            outputs: vec![Operand::Temp(n as u32 - 1)],
        }
    }

    #[test]
    fn programs_up_to_the_threshold_stay_one_function() {
        let split = Split::FAST;
        let parts = parts(&chain(split.above, 3), split);
        assert_eq!(parts.len(), 1);
        assert_eq!((parts[0].start, parts[0].end), (0, split.above));
    }

    /// The optimized tier keeps whole what the Rust emitter keeps whole (an arm's derivative
    /// kernel, a few thousand instructions), which the fast tier cuts; both cut what the
    /// emitter cuts.
    #[test]
    fn the_optimized_tier_cuts_only_what_the_rust_emitter_cuts() {
        let arm_derivative = chain(5 * PART_LEN, 3);
        assert_eq!(parts(&arm_derivative, Split::OPTIMIZED).len(), 1);
        assert_eq!(parts(&arm_derivative, Split::FAST).len(), 5);
        let humanoid = chain(SPLIT_ABOVE + 1, 3);
        let cut = (SPLIT_ABOVE + 1).div_ceil(PART_LEN);
        assert_eq!(parts(&humanoid, Split::OPTIMIZED).len(), cut);
        assert_eq!(parts(&humanoid, Split::FAST).len(), cut);
    }

    /// Longer programs: the fewest parts of at most `part_len`, in order, covering every
    /// instruction once, their lengths within one of each other.
    #[test]
    fn longer_programs_are_cut_into_consecutive_parts_of_about_equal_length() {
        let split = Split::FAST;
        for n in [split.above + 1, 3 * split.part_len, 7 * split.part_len + 13] {
            let parts = parts(&chain(n, 3), split);
            assert_eq!(parts.len(), n.div_ceil(split.part_len), "{n} instructions");
            assert_eq!(parts[0].start, 0);
            assert_eq!(parts.last().map(|p| p.end), Some(n));
            for pair in parts.windows(2) {
                assert_eq!(pair[0].end, pair[1].start);
            }
            let lengths: Vec<usize> = parts.iter().map(|p| p.end - p.start).collect();
            let (shortest, longest) = (lengths.iter().min(), lengths.iter().max());
            assert!(longest.is_some_and(|&l| l <= split.part_len), "{lengths:?}");
            assert!(longest.zip(shortest).is_some_and(|(l, s)| l - s <= 1));
        }
    }

    /// Running the instructions in order over the scratch array, each storing its value to
    /// its slot, every value a part reads from an earlier part is in its slot when read (no
    /// value stored since has overwritten it), and
    /// slots are reused once the values in them are read for the last time.
    #[test]
    fn every_crossing_value_is_in_its_slot_when_read_and_slots_are_reused() {
        let program = chain(9000, 1500);
        let parts = parts(&program, Split::FAST);
        let (slots, len) = crossing_slots(&program, &parts);
        let mut scratch: Vec<Option<usize>> = vec![None; len];
        for part in &parts {
            for t in part.start..part.end {
                for u in program.instrs[t].operands().filter_map(Operand::temp) {
                    let u = u as usize;
                    if u < part.start {
                        assert_eq!(scratch[slots[&u]], Some(u), "instruction {t} reads {u}");
                    }
                }
                if let Some(&slot) = slots.get(&t) {
                    scratch[slot] = Some(t);
                }
            }
        }
        assert!(len < slots.len(), "{len} slots for {} values", slots.len());
    }
}

//! A straight-line [`Program`] lowered to Cranelift IR: one function, or for a program longer
//! than the Rust emitter's split threshold ([`SPLIT_ABOVE`]) one function per part of
//! [`PART_LEN`] instructions, called in turn, values read by a later part passing through a
//! scratch array.
//!
//! Each instruction becomes the one IEEE operation it names, in program order — `fadd`,
//! `fsub`, `fmul`, `fdiv`, `fneg`, `sqrt`; `sign` as the runtime's (`1`, `−1`, or the value
//! itself for ±0 and NaN) by two comparisons and selects; a multiply-add one `fma` where the
//! processor fuses (else a product and a sum, as the runtime's `mul_add` without FMA). The
//! sines and cosines of the joint angles a part needs are computed at its start by one call
//! of the runtime's `sin_cos_array` ([`crate::code::sin_cos_array`]), as the emitted Rust
//! computes them at the top of the function. Cranelift neither reassociates nor contracts
//! floating-point operations, so the compiled code computes the program's values bit for bit.

use std::collections::HashMap;

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    types, AbiParam, FuncRef, Function, InstBuilder, MemFlagsData, Signature, StackSlotData,
    StackSlotKind, Type, UserFuncName, Value,
};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Linkage, Module};
use rne_codegen_core::{Instr, Operand, Program, PART_LEN, SPLIT_ABOVE};
use rne_symbolic::Symbol;

use crate::code::Extents;

/// The name compiled code calls the runtime's sines and cosines by.
pub(crate) const SIN_COS: &str = "rne_jit_sin_cos_array";

/// What lowering needs of the module: the pointer type, the kernels' and `sin_cos_array`'s
/// signatures and the function it calls.
pub(crate) struct Lowering {
    pointer: Type,
    kernel_signature: Signature,
    sin_cos: FuncId,
    /// Whether multiply-adds are fused (`fma` on and the processor has FMA).
    pub fused: bool,
    builder: FunctionBuilderContext,
}

/// The instructions `[start, end)` of a program as one function.
#[derive(Copy, Clone, Debug)]
struct Part {
    start: usize,
    end: usize,
}

/// Where the values that cross parts live: instruction index → scratch slot.
type Slots = HashMap<usize, usize>;

impl Lowering {
    /// Declares `sin_cos_array` in `module`; `fused` as [`Lowering::fused`].
    pub(crate) fn new(module: &mut JITModule, fused: bool) -> Result<Lowering, String> {
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
            kernel_signature,
            sin_cos,
            fused,
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
        let parts = parts(program);
        let slots = crossing_slots(program, &parts);
        let mut functions = Vec::with_capacity(parts.len());
        for (k, &part) in parts.iter().enumerate() {
            let id = module
                .declare_function(
                    &format!("{name}_{k}"),
                    Linkage::Local,
                    &self.kernel_signature,
                )
                .map_err(|e| e.to_string())?;
            let mut function = Function::with_name_signature(
                UserFuncName::user(0, id.as_u32()),
                self.kernel_signature.clone(),
            );
            let sin_cos = module.declare_func_in_func(self.sin_cos, &mut function);
            let mut extents = Extents {
                scratch: slots.len(),
                ..Extents::default()
            };
            let config = module.target_config();
            {
                let builder = FunctionBuilder::new(&mut function, &mut self.builder);
                let mut body = Body::new(builder, self.pointer, sin_cos, self.fused);
                body.run(program, part, &slots, &mut extents)?;
                body.builder.finalize(config);
            }
            functions.push(Lowered {
                id,
                function,
                extents,
            });
        }
        Ok(functions)
    }
}

/// One function in Cranelift IR, declared and not yet compiled.
pub(crate) struct Lowered {
    /// Its id in the module.
    pub id: FuncId,
    /// Its IR.
    pub function: Function,
    /// The array lengths it reads and writes.
    pub extents: Extents,
}

/// One function's part of a program, [`SPLIT_ABOVE`] and [`PART_LEN`] as the Rust emitter's.
fn parts(program: &Program) -> Vec<Part> {
    let n = program.instrs.len();
    if n <= SPLIT_ABOVE {
        return vec![Part { start: 0, end: n }];
    }
    (0..n)
        .step_by(PART_LEN)
        .map(|start| Part {
            start,
            end: (start + PART_LEN).min(n),
        })
        .collect()
}

/// A scratch slot for every value a later part reads, numbered in program order.
fn crossing_slots(program: &Program, parts: &[Part]) -> Slots {
    let part_of = |t: usize| parts.partition_point(|p| p.end <= t);
    let mut crossing = vec![false; program.instrs.len()];
    for (k, instr) in program.instrs.iter().enumerate() {
        for t in instr.operands().filter_map(Operand::temp) {
            if part_of(t as usize) != part_of(k) {
                crossing[t as usize] = true;
            }
        }
    }
    crossing
        .iter()
        .enumerate()
        .filter(|(_, &c)| c)
        .enumerate()
        .map(|(slot, (t, _))| (t, slot))
        .collect()
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
    fused: bool,
    arrays: [Value; 7],
    /// Values of this function: instructions', inputs' and constants'.
    temps: HashMap<usize, Value>,
    inputs: HashMap<Symbol, Value>,
    constants: HashMap<u64, Value>,
}

impl<'f> Body<'f> {
    fn new(mut builder: FunctionBuilder<'f>, pointer: Type, sin_cos: FuncRef, fused: bool) -> Self {
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
            fused,
            arrays,
            temps: HashMap::new(),
            inputs: HashMap::new(),
            constants: HashMap::new(),
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
        extents: &mut Extents,
    ) -> Result<(), String> {
        let mut outputs_of: HashMap<usize, Vec<usize>> = HashMap::new();
        for (k, &o) in program.outputs.iter().enumerate() {
            match o {
                Operand::Temp(t) => outputs_of.entry(t as usize).or_default().push(k),
                Operand::Lane { .. } => return Err("a program in lanes".to_owned()),
                _ => {}
            }
        }
        self.joint_trig(program, part, extents);
        for t in part.start..part.end {
            let value = match self.temps.get(&t) {
                Some(&v) => v,
                None => self.instruction(program.instrs[t], slots, extents)?,
            };
            self.temps.insert(t, value);
            if let Some(&slot) = slots.get(&t) {
                self.store(Array::Scratch, slot, value);
            }
            for &k in outputs_of.get(&t).into_iter().flatten() {
                self.store(Array::Out, k, value);
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
        extents.out = program.outputs.len();
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
        let (sines, cosines) = self.sin_cos(&angles);
        for t in part.start..part.end {
            let (k, values) = match program.instrs[t] {
                Instr::Sin(Operand::Input(Symbol::Position(k))) => (k, &sines),
                Instr::Cos(Operand::Input(Symbol::Position(k))) => (k, &cosines),
                _ => continue,
            };
            let j = joints
                .iter()
                .position(|&j| j == k)
                .expect("collected above");
            self.temps.insert(t, values[j]);
        }
    }

    /// `(sin xᵢ, cos xᵢ)` of `angles` through the runtime, by a stack array of the angles and
    /// their sines and cosines.
    fn sin_cos(&mut self, angles: &[Value]) -> (Vec<Value>, Vec<Value>) {
        let n = angles.len();
        let bytes = u32::try_from(24 * n).expect("a few joints");
        let slot = self.builder.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            bytes,
            3,
        ));
        let address = |b: &mut FunctionBuilder, offset: usize| {
            b.ins().stack_addr(self.pointer, slot, (8 * offset) as i32)
        };
        for (k, &angle) in angles.iter().enumerate() {
            self.builder
                .ins()
                .stack_store(self.pointer, angle, slot, (8 * k) as i32);
        }
        let start = address(&mut self.builder, 0);
        let sines = address(&mut self.builder, n);
        let cosines = address(&mut self.builder, 2 * n);
        let count = self.builder.ins().iconst(self.pointer, n as i64);
        self.builder
            .ins()
            .call(self.sin_cos, &[start, count, sines, cosines]);
        let pointer = self.pointer;
        let load = |b: &mut FunctionBuilder, offset: usize| {
            b.ins()
                .stack_load(pointer, types::F64, slot, (8 * offset) as i32)
        };
        let s = (0..n).map(|k| load(&mut self.builder, n + k)).collect();
        let c = (0..n).map(|k| load(&mut self.builder, 2 * n + k)).collect();
        (s, c)
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
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fadd(a, b)
            }
            Instr::Sub(a, b) => {
                let (a, b) = (v(a, self)?, v(b, self)?);
                ins(self).fsub(a, b)
            }
            Instr::Mul(a, b) => {
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

    /// The runtime's sign: 1 above zero, −1 below, the value itself for ±0 and NaN.
    fn sign(&mut self, x: Value) -> Value {
        let zero = self.constant(0.0);
        let one = self.constant(1.0);
        let minus_one = self.constant(-1.0);
        let ins = self.builder.ins();
        let below = ins.fcmp(FloatCC::LessThan, x, zero);
        let not_above = self.builder.ins().select(below, minus_one, x);
        let above = self.builder.ins().fcmp(FloatCC::GreaterThan, x, zero);
        self.builder.ins().select(above, one, not_above)
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
                match self.temps.get(&t) {
                    Some(&v) => v,
                    None => {
                        let slot = *slots.get(&t).ok_or("a value read before it is computed")?;
                        let v = self.load(Array::Scratch, slot);
                        self.temps.insert(t, v);
                        v
                    }
                }
            }
        })
    }

    fn constant(&mut self, c: f64) -> Value {
        if let Some(&v) = self.constants.get(&c.to_bits()) {
            return v;
        }
        let v = self.builder.ins().f64const(c);
        self.constants.insert(c.to_bits(), v);
        v
    }

    /// An input's value, loaded once per function; the extents grow to cover it.
    fn input(&mut self, s: Symbol, extents: &mut Extents) -> Value {
        if let Some(&v) = self.inputs.get(&s) {
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
        *extent = (*extent).max(usize::from(index) + 1);
        let v = self.load(array, usize::from(index));
        self.inputs.insert(s, v);
        v
    }

    fn load(&mut self, array: Array, index: usize) -> Value {
        let base = self.arrays[array as usize];
        self.builder.ins().load(
            types::F64,
            MemFlagsData::trusted(),
            base,
            (8 * index) as i32,
        )
    }

    fn store(&mut self, array: Array, index: usize, value: Value) {
        let base = self.arrays[array as usize];
        self.builder
            .ins()
            .store(MemFlagsData::trusted(), value, base, (8 * index) as i32);
    }
}

//! The runtime's sines and cosines computed in the compiled function itself: the fast path of
//! `rne_runtime::sin_cos` (Cody and Waite's reduction, fdlibm's polynomials by Estrin's
//! scheme, the quadrant's swap and signs) as Cranelift IR, operation for operation, so that
//! its results are the runtime's bits; only an argument outside the fast path's range (or
//! not finite) sends all of the array's angles to the runtime's `sin_cos_array`, by a call in
//! a cold block.
//!
//! A call for every part's angles, as before, cost the kernels its latency and registers:
//! the angles went to memory, the call clobbered every vector register, and the kernel's
//! first link waited for the results (docs/performance.md, "The sines and cosines inline").
//! The multiply–adds here are fused exactly where the runtime's are
//! (`rne_runtime::trig::FUSED`, a property of the build, not of the model's `fma`). Angles
//! are evaluated two at a time in `f64x2` (in scalars, pairs of angles as the runtime's SSE2
//! pairs; in lanes, one angle of the two states); the results go to the sines' and cosines'
//! array, where the kernel's instructions find them.

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    types, Endianness, InstBuilder, MemFlagsData, StackSlot, StackSlotData, StackSlotKind, Value,
};
use rne_runtime::trig::{C, FRAC_2_PI, FUSED, PIO2_1, PIO2_2, PIO2_2T, QUADRANTS, ROUND, S};

use super::Body;

/// Where the sines and cosines of a call's angles are: the stack array of the angles, their
/// sines and their cosines, each of `stride` values, and the bytes between two angles' values.
#[derive(Copy, Clone)]
pub(super) struct TrigArray {
    pub slot: StackSlot,
    stride: usize,
    width: usize,
}

impl TrigArray {
    /// The offset of angle k's sine (`array` 1) or cosine (`array` 2), or the angle (0).
    pub fn at(&self, k: usize, array: usize) -> i32 {
        (8 * array * self.stride + self.width * k) as i32
    }
}

impl Body<'_> {
    /// The sines and cosines of `angles` in a new stack array: at the optimized tier the fast
    /// path inline, and the runtime's `sin_cos_array` in a cold block when an angle is
    /// outside its range; at the fast tier, whose compile time counts more than its code's,
    /// a call of `sin_cos_array` (the fast path is about 80 more machine instructions per
    /// pair of angles in every function to compile).
    pub(super) fn sin_cos_array(&mut self, angles: &[Value]) -> TrigArray {
        // In scalars, pairs of angles (the last repeated when their number is odd) in a
        // stride rounded up to pairs, so that each pair's results are one aligned store.
        let per_vector = 2 / self.lanes;
        let stride = angles.len().div_ceil(per_vector) * 2;
        let bytes = u32::try_from(24 * stride).expect("a few joints");
        let slot = self.builder.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            bytes,
            4,
        ));
        let array = TrigArray {
            slot,
            stride,
            width: 8 * self.lanes,
        };
        if !self.inline_trig {
            self.call_runtime(angles, array);
            return array;
        }
        let mut all_in_range = None;
        for (pair, first) in (0..angles.len()).step_by(per_vector).enumerate() {
            let x = self.pair_of(angles, first);
            let (sin, cos, in_range) = self.fast_path(x);
            for (values, kind) in [(sin, 1), (cos, 2)] {
                let offset = array.at(0, kind) + 16 * pair as i32;
                let pointer = self.pointer;
                self.builder
                    .ins()
                    .stack_store(pointer, values, slot, offset);
            }
            all_in_range = Some(match all_in_range {
                None => in_range,
                Some(all) => self.builder.ins().band(all, in_range),
            });
        }
        if let Some(all) = all_in_range {
            self.out_of_range(angles, array, all);
        }
        array
    }

    /// Angles `first` and `first + 1` (or `first` twice, the last of an odd number) as an
    /// `f64x2` in scalars; angle `first` itself in lanes.
    fn pair_of(&mut self, angles: &[Value], first: usize) -> Value {
        if self.lanes == 2 {
            return angles[first];
        }
        let second = angles.get(first + 1).unwrap_or(&angles[first]);
        let x = self
            .builder
            .ins()
            .scalar_to_vector(types::F64X2, angles[first]);
        self.builder.ins().insertlane(x, *second, 1)
    }

    /// Unless every lane of `all_in_range` is set, the runtime's `sin_cos_array` overwrites
    /// the array's sines and cosines: a block apart, marked cold, that the code rejoins.
    fn out_of_range(&mut self, angles: &[Value], array: TrigArray, all_in_range: Value) {
        let all = self.builder.ins().vall_true(all_in_range);
        let (cold, join) = (self.builder.create_block(), self.builder.create_block());
        self.builder.set_cold_block(cold);
        self.builder.ins().brif(all, join, &[], cold, &[]);
        self.builder.seal_block(cold);
        self.builder.switch_to_block(cold);
        self.call_runtime(angles, array);
        self.builder.ins().jump(join, &[]);
        self.builder.seal_block(join);
        self.builder.switch_to_block(join);
    }

    /// The runtime's `sin_cos_array` of `angles` (stored into the array's first part) into
    /// the array's sines and cosines.
    fn call_runtime(&mut self, angles: &[Value], array: TrigArray) {
        let pointer = self.pointer;
        for (k, &angle) in angles.iter().enumerate() {
            let offset = array.at(k, 0);
            self.builder
                .ins()
                .stack_store(pointer, angle, array.slot, offset);
        }
        let mut address = |kind: usize| {
            self.builder
                .ins()
                .stack_addr(pointer, array.slot, array.at(0, kind))
        };
        let (start, sines, cosines) = (address(0), address(1), address(2));
        let count = (angles.len() * self.lanes) as i64;
        let count = self.builder.ins().iconst(pointer, count);
        let sin_cos = self.sin_cos;
        self.builder
            .ins()
            .call(sin_cos, &[start, count, sines, cosines]);
    }

    /// `rne_runtime::trig::fast_path` and `reduced` of the two lanes of `x`: their sines,
    /// cosines, and a mask of the lanes in the fast path's range.
    fn fast_path(&mut self, x: Value) -> (Value, Value, Value) {
        let shifted = self.runtime_mul_add(x, FRAC_2_PI, ROUND);
        let round = self.splat(ROUND);
        let k = self.builder.ins().fsub(shifted, round);
        let mut r = x;
        for part in [PIO2_1, PIO2_2, PIO2_2T] {
            let part = self.splat(part);
            r = self.runtime_neg_mul_add(k, part, r);
        }
        let z = self.builder.ins().fmul(r, r);
        let z2 = self.builder.ins().fmul(z, z);
        let r_z = self.builder.ins().fmul(r, z);
        let sin_polynomial = self.polynomial(z, z2, S);
        let sin = self.runtime_mul_add_values(r_z, sin_polynomial, r);
        let cos_polynomial = self.polynomial(z, z2, C);
        let half = self.splat(0.5);
        let half_z = self.builder.ins().fmul(half, z);
        let tail = self.runtime_neg_mul_add(z2, cos_polynomial, half_z);
        let one = self.splat(1.0);
        let cos = self.builder.ins().fsub(one, tail);
        let magnitude = self.builder.ins().fabs(k);
        let limit = self.splat(QUADRANTS);
        let in_range = self.builder.ins().fcmp(FloatCC::LessThan, magnitude, limit);
        let (sin, cos) = self.quadrant(shifted, sin, cos);
        (sin, cos, in_range)
    }

    /// `trig::polynomial`: `c₀ + ((c₁ z + z² (c₂ + c₃ z)) + z⁴ (c₄ + c₅ z))`.
    fn polynomial(&mut self, z: Value, z2: Value, c: [f64; 6]) -> Value {
        let pair_23 = self.runtime_mul_add(z, c[3], c[2]);
        let c1 = self.splat(c[1]);
        let z_c1 = self.builder.ins().fmul(z, c1);
        let inner = self.runtime_mul_add_values(z2, pair_23, z_c1);
        let pair_45 = self.runtime_mul_add(z, c[5], c[4]);
        let z4 = self.builder.ins().fmul(z2, z2);
        let sum = self.runtime_mul_add_values(z4, pair_45, inner);
        let c0 = self.splat(c[0]);
        self.builder.ins().fadd(c0, sum)
    }

    /// `trig::reduced`'s quadrant: k mod 4 from the low bits of `shifted`; odd quadrants swap
    /// sine and cosine, quadrants 2 and 3 negate the sine, 1 and 2 the cosine.
    fn quadrant(&mut self, shifted: Value, sin: Value, cos: Value) -> (Value, Value) {
        let little = MemFlagsData::new().with_endianness(Endianness::Little);
        let bits = |b: &mut Self, v: Value| b.builder.ins().bitcast(types::I64X2, little, v);
        let (shifted, sin, cos) = (bits(self, shifted), bits(self, sin), bits(self, cos));
        let three = self.integers(3);
        let quadrant = self.builder.ins().band(shifted, three);
        let one = self.integers(1);
        let odd = self.builder.ins().band(quadrant, one);
        let swap = self.builder.ins().ineg(odd);
        let s = self.builder.ins().bitselect(swap, cos, sin);
        let c = self.builder.ins().bitselect(swap, sin, cos);
        let two = self.integers(2);
        let high = self.builder.ins().band(quadrant, two);
        let flip_sin = self.builder.ins().ishl_imm_u(high, 62);
        let next = self.builder.ins().iadd(quadrant, one);
        let high = self.builder.ins().band(next, two);
        let flip_cos = self.builder.ins().ishl_imm_u(high, 62);
        let s = self.builder.ins().bxor(s, flip_sin);
        let c = self.builder.ins().bxor(c, flip_cos);
        let float = |b: &mut Self, v: Value| b.builder.ins().bitcast(types::F64X2, little, v);
        (float(self, s), float(self, c))
    }

    /// `x·a + b` for constants `a` and `b`, rounded as the runtime's.
    fn runtime_mul_add(&mut self, x: Value, a: f64, b: f64) -> Value {
        let (a, b) = (self.splat(a), self.splat(b));
        self.runtime_mul_add_values(x, a, b)
    }

    /// The runtime's `mul_add` in its build: one `fma` if fused, else a product and a sum.
    fn runtime_mul_add_values(&mut self, x: Value, y: Value, z: Value) -> Value {
        if FUSED {
            return self.builder.ins().fma(x, y, z);
        }
        let product = self.builder.ins().fmul(x, y);
        self.builder.ins().fadd(product, z)
    }

    /// The runtime's `neg_mul_add`, `z − x·y`, in its build: one `fma` of `−x` if fused.
    fn runtime_neg_mul_add(&mut self, x: Value, y: Value, z: Value) -> Value {
        if FUSED {
            let minus_x = self.builder.ins().fneg(x);
            return self.builder.ins().fma(minus_x, y, z);
        }
        let product = self.builder.ins().fmul(x, y);
        self.builder.ins().fsub(z, product)
    }

    /// `c` in both lanes of an `f64x2`.
    fn splat(&mut self, c: f64) -> Value {
        match self.lanes {
            2 => self.constant(c),
            _ => self.pool_pair(c),
        }
    }

    /// `n` in both lanes of an `i64x2`.
    fn integers(&mut self, n: u64) -> Value {
        let bytes: Vec<u8> = [n, n].iter().flat_map(|v| v.to_le_bytes()).collect();
        let handle = self.builder.func.dfg.constants.insert(bytes.into());
        self.builder.ins().vconst(types::I64X2, handle)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use rne_codegen_core::{Instr, KernelProgram, KernelReport, Operand, Program};
    use rne_runtime::Kernel;
    use rne_symbolic::Symbol;

    use crate::code::{Arrays, Code, Out};
    use crate::model::{compile_programs, Tier};

    /// The sines and cosines of `n` joint angles, as a kernel's program.
    fn sines_and_cosines(n: u16) -> KernelProgram {
        let angle = |k| Operand::Input(Symbol::Position(k));
        let instrs: Vec<Instr> = (0..n)
            .flat_map(|k| [Instr::Sin(angle(k)), Instr::Cos(angle(k))])
            .collect();
        let outputs = (0..instrs.len() as u32).map(Operand::Temp).collect();
        KernelProgram {
            kernel: Kernel::InverseDynamics,
            program: Arc::new(Program { instrs, outputs }),
            report: KernelReport {
                kernel: Kernel::InverseDynamics,
                ops: Default::default(),
                critical_path: 0,
                generation_time: Default::default(),
            },
        }
    }

    /// Angles where the fast path's steps are at their edges: zeros, the quadrants' borders
    /// (multiples of π/4) and an ulp either side, the reduction's limit 2²⁰·π/2 either side,
    /// tiny, huge and seeded random angles.
    fn hard_angles() -> Vec<f64> {
        use rand::{Rng, SeedableRng};
        let mut angles = vec![0.0, -0.0, 1e-300, -5e-324, 1e300, -f64::MAX, 1e-8];
        for k in -12..=12 {
            let x = f64::from(k) * std::f64::consts::FRAC_PI_4;
            angles.extend([x, x.next_up(), x.next_down()]);
        }
        let limit = 1_048_576.0 * std::f64::consts::FRAC_PI_2;
        angles.extend([limit, limit.next_down(), -limit, 1.6e6, -1.7e6]);
        let mut random = rand_chacha::ChaCha8Rng::seed_from_u64(0x7219);
        angles.extend((0..400).map(|_| random.gen_range(-100.0..100.0)));
        angles
    }

    /// Compiled at both tiers (inline at the optimized, a call at the fast), in scalars and in
    /// two lanes, for 1 to 9 angles (odd counts leave a pair half used): every sine and cosine
    /// is `rne_runtime::sin_cos`'s, bit for bit, including where one angle of a call is out
    /// of the fast path's range and its neighbours are not.
    #[test]
    fn sines_and_cosines_are_the_runtime_s_bit_for_bit() {
        let angles = hard_angles();
        for n in 1..=9u16 {
            let program = sines_and_cosines(n);
            for tier in [Tier::Optimized, Tier::Fast] {
                for lanes in [1, 2] {
                    let (module, _, kernels) =
                        compile_programs(&[&program], false, tier, (lanes, 0)).unwrap();
                    let _code = Code::new(module);
                    let kernel = &kernels[0];
                    let per_call = usize::from(n) * lanes;
                    for q in angles.chunks_exact(per_call) {
                        let mut out = vec![f64::NAN; 2 * per_call];
                        let arrays = Arrays { q, ..Arrays::NONE };
                        kernel
                            .run(arrays, Out::Whole(&mut out), &mut kernel.scratch())
                            .unwrap();
                        check(q, &out, n, lanes, tier);
                    }
                }
            }
        }
    }

    /// `out` holds each lane's sines and cosines of its angles of `q` (interleaved in lanes).
    fn check(q: &[f64], out: &[f64], n: u16, lanes: usize, tier: Tier) {
        let n = usize::from(n);
        for lane in 0..lanes {
            for k in 0..n {
                let x = q[lanes * k + lane];
                let (s, c) = rne_runtime::sin_cos(x);
                let at = lane * 2 * n + 2 * k;
                assert_eq!(
                    (out[at].to_bits(), out[at + 1].to_bits()),
                    (s.to_bits(), c.to_bits()),
                    "sin_cos({x:e}), angle {k} of {n}, lane {lane} of {lanes}, {tier:?}"
                );
            }
        }
    }
}

//! Emission of a [`Program`] as a straight-line Rust function, written as source text.
//!
//! A result used more than once becomes a `let` binding; a result used once is written
//! inline where it is used, so the text follows the expression's shape. Operator precedence
//! is respected without ever re-associating: `a + (b + c)` keeps its parentheses, because
//! floating-point addition is not associative and the emitted code must compute exactly
//! what the program says. The sine and cosine of each joint angle are computed once, with
//! the runtime's `Real::sin_cos` (or `Real::sin_cos_array` for several), at the top of the
//! function. Each output is stored into the result as soon as the bindings it reads are
//! computed, not returned as one expression at the end, so that it need not stay live
//! until the return.
//!
//! The body is appended to one `String` rather than built as a token stream: a kernel of a
//! million operations is tens of megabytes of text, where a `proc_macro2::TokenStream` of it
//! (one heap object per token) took gigabytes; the macro lexes the text once
//! ([`GeneratedModule::items`](crate::GeneratedModule::items)). The signatures are text too:
//! emission uses no `proc_macro2`, which inside the macro reaches the compiler from the
//! macro's thread only, so kernels can be emitted on any thread.
//!
//! Emitted code names nothing but `core` and the runtime, which it reaches through the path
//! in [`EmitContext::runtime`] (`::rne_codegen::__private` unless the `crate:` setting says
//! otherwise).

use std::collections::BTreeMap;
use std::fmt::Write;

use proc_macro2::{Ident, Span, TokenStream};
use rne_symbolic::dynamics::LANES;
use rne_symbolic::{Symbol, SymbolTable};

use crate::dispatch::{dispatching_body, DISPATCH_FROM};
use crate::generation_options::{ParameterMode, ScalarType};
use crate::kernel::{Dims, Input, Kernel};
use crate::program::{Instr, Operand, Program};
use crate::shape::Layout;
use crate::split::{self, SplitPlan, Statement};

/// What the emitter needs besides the program.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EmitContext<'a> {
    /// The `Params` field of each parameter symbol, by index (`parameter_fields`).
    pub fields: &'a [String],
    /// The scalar type.
    pub scalar: ScalarType,
    /// Constant or runtime parameters.
    pub parameters: ParameterMode,
    /// The path of the runtime crate (`rne-runtime`) from the generated code, as source text
    /// ([`GenerationOptions::runtime_path`](crate::GenerationOptions::runtime_path)).
    pub runtime: &'a str,
}

/// Binding strength of an emitted expression; a child is parenthesised when it binds less
/// tightly than its position requires.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Precedence {
    Sum = 1,
    Product = 2,
    Unary = 3,
    Atom = 4,
}

/// The name of a joint's sine or cosine in the emitted code: `s3` is the sine of joint 3.
#[derive(Copy, Clone, Debug)]
struct TrigName {
    /// `'s'` or `'c'`.
    function: char,
    /// The joint's number, from 1.
    joint: u32,
}

impl std::fmt::Display for TrigName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{}", self.function, self.joint)
    }
}

struct Emitter<'a> {
    program: &'a Program,
    ctx: EmitContext<'a>,
    /// Number `n` of each materialised temporary `tn`.
    names: Vec<Option<u32>>,
    /// `sin`/`cos` of joint k: which of the two are used.
    trig: BTreeMap<u16, (bool, bool)>,
    /// Whether the kernel reads standard parameters (`base_parameters`), which its program
    /// holds as `Symbol::Parameter(i)` = `standard[i]`.
    reads_standard: bool,
    /// `<path to the runtime>::Real`.
    real: String,
    /// Whether each instruction's result is a vector ([`Program::vector_results`]), written
    /// as the runtime's `F64x4`.
    vector: Vec<bool>,
}

impl Emitter<'_> {
    fn constant(&self, c: f64, out: &mut String) {
        if c.is_sign_negative() && !c.is_nan() {
            out.push('-');
        }
        let generic = self.ctx.scalar == ScalarType::Generic;
        if generic {
            write!(out, "<T as {}>::from_f64(", self.real).expect("writing to a String");
        }
        if c.is_finite() {
            // As `proc_macro2::Literal::f64_unsuffixed` writes it: shortest round trip, never
            // an exponent, always a point.
            let start = out.len();
            write!(out, "{}", c.abs()).expect("writing to a String");
            if !out[start..].contains('.') {
                out.push_str(".0");
            }
        } else {
            let special = if c.is_nan() { "NAN" } else { "INFINITY" };
            let float = if self.ctx.scalar == ScalarType::F32 {
                "f32"
            } else {
                "f64"
            };
            write!(out, "{float}::{special}").expect("writing to a String");
        }
        if generic {
            out.push(')');
        }
    }

    fn input(&self, s: Symbol, out: &mut String) {
        let mut element = |array: &str, index: u16| {
            out.push_str(array);
            out.push('[');
            push_number(out, u32::from(index));
            out.push(']');
        };
        match s {
            Symbol::Position(k) => element("q", k),
            Symbol::Velocity(k) => element("qd", k),
            Symbol::Acceleration(k) => element("qdd", k),
            Symbol::Force(k) => element("tau", k),
            Symbol::Lane(l) => {
                let unit: Vec<&str> = (0..LANES)
                    .map(|k| if k == usize::from(l) { "1.0" } else { "0.0" })
                    .collect();
                write!(
                    out,
                    "{}::F64x4::new([{}])",
                    self.ctx.runtime,
                    unit.join(", ")
                )
                .expect("writing to a String");
            }
            Symbol::Parameter(i) if self.reads_standard => element("standard", i),
            Symbol::Parameter(i) => {
                let field = &self.ctx.fields[usize::from(i)];
                match self.ctx.scalar {
                    ScalarType::F64 => write!(out, "p.{field}"),
                    ScalarType::F32 => write!(out, "(p.{field} as f32)"),
                    ScalarType::Generic => write!(out, "<T as {}>::from_f64(p.{field})", self.real),
                }
                .expect("writing to a String");
            }
        }
    }

    fn joint_trig(&self, instr: Instr) -> Option<TrigName> {
        let (function, k) = match instr {
            Instr::Sin(Operand::Input(Symbol::Position(k))) => ('s', k),
            Instr::Cos(Operand::Input(Symbol::Position(k))) => ('c', k),
            _ => return None,
        };
        Some(TrigName {
            function,
            joint: u32::from(k) + 1,
        })
    }

    /// How tightly operand `o` binds as written.
    fn precedence(&self, o: Operand) -> Precedence {
        match o {
            Operand::Const(c) if c.is_sign_negative() && !c.is_nan() => Precedence::Unary,
            Operand::Const(_) | Operand::Input(_) | Operand::Lane { .. } => Precedence::Atom,
            Operand::Temp(t) if self.names[t as usize].is_some() => Precedence::Atom,
            Operand::Temp(t) => {
                let instr = self.program.instrs[t as usize];
                if self.joint_trig(instr).is_some() {
                    return Precedence::Atom;
                }
                match instr {
                    Instr::Add(..) | Instr::Sub(..) => Precedence::Sum,
                    Instr::Mul(..) | Instr::Div(..) => Precedence::Product,
                    Instr::Neg(_) => Precedence::Unary,
                    _ => Precedence::Atom,
                }
            }
        }
    }

    /// Operand `o` (a name, a constant, an input, or an unnamed instruction written out),
    /// appended to `out`: every character is written once, so writing a kernel takes time
    /// linear in its text.
    fn write(&self, o: Operand, out: &mut String) {
        match o {
            Operand::Const(c) => self.constant(c, out),
            Operand::Input(s) => self.input(s, out),
            Operand::Temp(t) => match self.names[t as usize] {
                Some(n) => {
                    out.push('t');
                    push_number(out, n);
                }
                None => self.write_instr(t as usize, out),
            },
            Operand::Lane { temp, lane } => {
                self.write_at_least(Operand::Temp(temp), Precedence::Atom, out);
                write!(out, ".to_array()[{lane}]").expect("writing to a String");
            }
        }
    }

    /// Whether `o` is a vector ([`Program::vector_results`]).
    fn is_vector(&self, o: Operand) -> bool {
        match o {
            Operand::Temp(t) => self.vector[t as usize],
            Operand::Input(Symbol::Lane(_)) => true,
            Operand::Const(_) | Operand::Input(_) | Operand::Lane { .. } => false,
        }
    }

    /// `o` as an operand of an instruction whose result is a vector when `vector` is set (a
    /// scalar then broadcast to every lane with `F64x4::splat`), else as [`write_at_least`].
    ///
    /// [`write_at_least`]: Self::write_at_least
    fn write_in(&self, o: Operand, vector: bool, min: Precedence, out: &mut String) {
        if vector && !self.is_vector(o) {
            write!(out, "{}::F64x4::splat(", self.ctx.runtime).expect("writing to a String");
            self.write(o, out);
            out.push(')');
        } else {
            self.write_at_least(o, min, out);
        }
    }

    /// Operand `o` as a `String` of its own.
    fn operand(&self, o: Operand) -> String {
        let mut text = String::new();
        self.write(o, &mut text);
        text
    }

    /// `o`, parenthesised when it binds less tightly than `min`.
    fn write_at_least(&self, o: Operand, min: Precedence, out: &mut String) {
        if self.precedence(o) >= min {
            self.write(o, out);
        } else {
            out.push('(');
            self.write(o, out);
            out.push(')');
        }
    }

    /// `Real::method(args)`, each argument negated where its flag says so. `sin`, `cos`,
    /// `sqrt` and `sign` go through the runtime's `Real` for every scalar type, so that `f64`
    /// kernels get the fast, accurate runtime `sin_cos` and no kernel needs `std`; so does
    /// `mul_add` (`fma: true`), whose variants fold a negated product or addend.
    ///
    /// With `vector` set, the call's value is a vector and so is every argument.
    fn write_call(&self, method: &str, args: &[(Operand, bool)], vector: bool, out: &mut String) {
        write!(out, "{}::{method}(", self.real).expect("writing to a String");
        for (k, &(a, negated)) in args.iter().enumerate() {
            if k > 0 {
                out.push_str(", ");
            }
            if negated {
                out.push('-');
                self.write_in(a, vector, Precedence::Unary, out);
            } else {
                self.write_in(a, vector, Precedence::Sum, out);
            }
        }
        out.push(')');
    }

    /// Instruction `t` written out.
    fn write_instr(&self, t: usize, out: &mut String) {
        let (instr, vector) = (self.program.instrs[t], self.vector[t]);
        if let Some(name) = self.joint_trig(instr) {
            write!(out, "{name}").expect("writing to a String");
            return;
        }
        use Precedence::*;
        // A space on both sides of the operator: `a - -b` must not lex as anything else.
        let mut binary = |a: Operand, op: &str, b: Operand, left: Precedence, right: Precedence| {
            self.write_in(a, vector, left, out);
            out.push_str(op);
            self.write_in(b, vector, right, out);
        };
        match instr {
            Instr::Add(a, b) => binary(a, " + ", b, Sum, Product),
            Instr::Sub(a, b) => binary(a, " - ", b, Sum, Product),
            Instr::Mul(a, b) => binary(a, " * ", b, Product, Unary),
            Instr::Div(a, b) => binary(a, " / ", b, Product, Unary),
            Instr::Neg(a) => {
                out.push('-');
                self.write_in(a, vector, Unary, out);
            }
            Instr::Sin(a) => self.write_call("sin", &[(a, false)], vector, out),
            Instr::Cos(a) => self.write_call("cos", &[(a, false)], vector, out),
            Instr::Sqrt(a) => self.write_call("sqrt", &[(a, false)], vector, out),
            Instr::Sign(a) => self.write_call("sign", &[(a, false)], vector, out),
            Instr::MulAdd(a, b, c) => self.write_call(
                "mul_add",
                &[(a, false), (b, false), (c, false)],
                vector,
                out,
            ),
            Instr::MulSub(a, b, c) => {
                self.write_call("mul_add", &[(a, false), (b, false), (c, true)], vector, out)
            }
            Instr::NegMulAdd(a, b, c) => {
                self.write_call("mul_add", &[(a, true), (b, false), (c, false)], vector, out)
            }
        }
    }

    /// The sines and cosines of the joint angles the kernel uses (a mass matrix never needs
    /// the first joint's), all at once with `Real::sin_cos_array` when two or more are needed,
    /// else one. `f64` and `f32` evaluate the array in `f64`, two lanes per vector
    /// instruction, so an odd count is padded with a repeat of the last angle: a lane of its
    /// own costs more than a pair. Generic kernels, mostly evaluated in double-double, are not.
    fn write_trig_bindings(&self, out: &mut String) {
        let angle = |k: u16| self.operand(Operand::Input(Symbol::Position(k)));
        if self.trig.len() >= 2 {
            let mut angles: Vec<String> = self.trig.keys().map(|&k| angle(k)).collect();
            if self.ctx.scalar != ScalarType::Generic && angles.len() % 2 == 1 {
                angles.push(angles[angles.len() - 1].clone());
            }
            writeln!(
                out,
                "let (sin_q, cos_q) = {}::sin_cos_array(&[{}]);",
                self.real,
                angles.join(", ")
            )
            .expect("writing to a String");
            for (lane, (&k, &(sin, cos))) in self.trig.iter().enumerate() {
                let joint = k + 1;
                if sin {
                    writeln!(out, "let s{joint} = sin_q[{lane}];").expect("writing to a String");
                }
                if cos {
                    writeln!(out, "let c{joint} = cos_q[{lane}];").expect("writing to a String");
                }
            }
            return;
        }
        for (&k, &(sin, cos)) in &self.trig {
            let (joint, angle, real) = (k + 1, angle(k), &self.real);
            match (sin, cos) {
                (true, true) => {
                    writeln!(out, "let (s{joint}, c{joint}) = {real}::sin_cos({angle});")
                }
                (true, false) => writeln!(out, "let s{joint} = {real}::sin({angle});"),
                (false, _) => writeln!(out, "let c{joint} = {real}::cos({angle});"),
            }
            .expect("writing to a String");
        }
    }
}

/// A doc string written as a Rust string literal: a string's `Debug` form is one.
struct DocLiteral(&'static str);

impl std::fmt::Display for DocLiteral {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.0)
    }
}

/// The decimal digits of `n`, appended to `out` without the formatting machinery (temporaries
/// and array indices are most of a kernel's text).
fn push_number(out: &mut String, mut n: u32) {
    let mut digits = [0u8; 10];
    let mut start = digits.len();
    loop {
        start -= 1;
        digits[start] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend(digits[start..].iter().map(|&d| char::from(d)));
}

/// The `Params` field of each parameter of `symbols`, by index, as source text (`r#` for
/// keywords): worked out before emission, which writes text alone and so can run on any
/// thread (inside the macro, `proc_macro2` reaches the compiler from the macro's thread only).
pub fn parameter_fields(symbols: &SymbolTable) -> Vec<String> {
    symbols
        .parameters()
        .iter()
        .map(|name| parameter_ident(name).to_string())
        .collect()
}

/// The Rust field name of a parameter (`r#` for keywords).
pub fn parameter_ident(name: &str) -> Ident {
    if syn::parse_str::<Ident>(name).is_ok() {
        Ident::new(name, Span::call_site())
    } else {
        Ident::new_raw(name, Span::call_site())
    }
}

/// Whether `name` can be a field of the generated `Params`.
pub fn is_valid_parameter_name(name: &str) -> bool {
    let valid_ident = |n: &str| syn::parse_str::<Ident>(n).is_ok();
    valid_ident(name)
        || (!matches!(name, "self" | "Self" | "super" | "crate" | "_")
            && valid_ident(&format!("r#{name}")))
}

/// The return type of `kernel`'s function in scalar `t` (docs/design.md §4), naming the module's
/// sizes `NV`, `NF`, `NP`, `NB`.
pub(crate) fn return_type(kernel: Kernel, t: &TokenStream) -> TokenStream {
    Layout::of(kernel, Dims::default()).type_tokens(t)
}

/// The argument `input` of a kernel, in scalar `t`: `q: &[t; NQ]`, `standard: &[t; NP]`, or a
/// velocity-sized array.
pub(crate) fn argument(input: Input, t: &TokenStream) -> TokenStream {
    argument_text(input, &t.to_string())
        .parse()
        .expect("an argument is Rust")
}

/// [`argument`] as source text.
fn argument_text(input: Input, t: &str) -> String {
    let len = match input {
        Input::Q => "NQ",
        Input::Standard => "NP",
        _ => "NV",
    };
    format!("{}: &[{t}; {len}]", input.name())
}

/// The arguments of `kernel` in scalar `t`, each followed by a comma, as source text.
fn arguments(kernel: Kernel, t: &str) -> String {
    kernel
        .inputs()
        .iter()
        .map(|&input| argument_text(input, t) + ", ")
        .collect()
}

/// Emits `kernel` as a function computing `program`'s outputs, in a module of sizes `dims`,
/// as Rust source: one straight-line function, or for a large program a function calling its
/// parts in turn (module `split`: parts of about 1000 instructions above 15000).
pub(crate) fn emit_kernel(
    kernel: Kernel,
    program: &Program,
    dims: Dims,
    ctx: EmitContext<'_>,
) -> String {
    let layout = Layout::of(kernel, dims);
    assert_eq!(
        layout.len(),
        program.outputs.len(),
        "`{kernel}` computes one output per scalar of its result"
    );
    let bindings = Bindings::of(program);
    let emitter = Emitter {
        program,
        ctx,
        names: bindings.names,
        trig: bindings.trig,
        reads_standard: kernel.inputs().contains(&Input::Standard),
        real: format!("{}::Real", ctx.runtime),
        vector: program.vector_results(),
    };
    let t = match ctx.scalar {
        ScalarType::F64 => "f64",
        ScalarType::F32 => "f32",
        ScalarType::Generic => "T",
    };
    let (generics, params) = (emitter.generics(), emitter.params());
    let inputs = format!("{params}{}", arguments(kernel, t));
    let ret = layout.type_text(t);
    let signature = format!(
        "#[doc = {doc}]\n#[inline]\n#[allow(unused_variables, unused_parens, clippy::all, clippy::pedantic)]\npub fn {name}{generics}({inputs}) -> {ret} {{\n",
        doc = DocLiteral(kernel.summary()),
        name = kernel.name(),
    );
    let named: Vec<bool> = emitter.names.iter().map(Option::is_some).collect();
    let plan = split::plan(program, &named, &bindings.prologue);
    let mut body = emitter.body(kernel, &layout, (t, &ret), &named, plan.as_ref());
    let mut out = String::with_capacity(signature.len() + body.len() + 1024);
    out.push_str(&signature);
    // A split kernel is not dispatched: its parts are functions of their own, which a copy
    // compiled for AVX2 would still call in their baseline form.
    if plan.is_none() && program.instrs.len() >= DISPATCH_FROM {
        let names: Vec<&str> = (!params.is_empty())
            .then_some("p")
            .into_iter()
            .chain(kernel.inputs().iter().map(|input| input.name()))
            .collect();
        body.push('\n');
        out.push_str(&dispatching_body(
            &generics,
            &inputs,
            &ret,
            &names,
            &body,
            ctx.runtime,
        ));
    } else {
        out.push_str(&body);
    }
    out.push_str("\n}\n");
    out
}

/// Which values of a program the emitted code binds to a name.
pub(crate) struct Bindings {
    /// Number `n` of each value bound as `tn`: the results used more than once.
    pub names: Vec<Option<u32>>,
    /// Whether each instruction is a joint's sine or cosine, bound at the top (`s3`, `c3`).
    pub prologue: Vec<bool>,
    /// `sin`/`cos` of joint k: which of the two are used.
    pub trig: BTreeMap<u16, (bool, bool)>,
}

impl Bindings {
    /// The bindings of `program`, temporaries numbered in program order.
    pub fn of(program: &Program) -> Bindings {
        let uses = program.use_counts();
        let mut bindings = Bindings {
            names: vec![None; program.instrs.len()],
            prologue: vec![false; program.instrs.len()],
            trig: BTreeMap::new(),
        };
        let mut next = 0u32;
        for (t, &instr) in program.instrs.iter().enumerate() {
            if let Instr::Sin(Operand::Input(Symbol::Position(k)))
            | Instr::Cos(Operand::Input(Symbol::Position(k))) = instr
            {
                let entry = bindings.trig.entry(k).or_default();
                match instr {
                    Instr::Sin(_) => entry.0 = true,
                    _ => entry.1 = true,
                }
                bindings.prologue[t] = true;
                continue;
            }
            if uses[t] >= 2 {
                bindings.names[t] = Some(next);
                next += 1;
            }
        }
        bindings
    }
}

impl Emitter<'_> {
    /// The function's body: the joints' sines and cosines, then the values and the result,
    /// in one piece or, with a plan, as calls of the parts (`(t, ret)`: the scalar's and the
    /// result's type).
    fn body(
        &self,
        kernel: Kernel,
        layout: &Layout,
        (t, ret): (&str, &str),
        named: &[bool],
        plan: Option<&SplitPlan>,
    ) -> String {
        // Room for about 24 bytes of text per instruction (a kernel writes 15–25), so that the
        // body's text is seldom copied as it grows.
        let mut body = String::with_capacity(24 * self.program.instrs.len());
        self.write_trig_bindings(&mut body);
        match plan {
            None if *layout == Layout::Scalar => {
                for t in (0..self.program.instrs.len()).filter(|&t| named[t]) {
                    self.write_binding(t, &mut body);
                }
                self.write(self.program.outputs[0], &mut body);
            }
            None => self.write_stored_as_computed(layout, ret, named, &mut body),
            Some(plan) => {
                self.write_parts(kernel, plan, t, &mut body);
                let mut outputs = self
                    .program
                    .outputs
                    .iter()
                    .enumerate()
                    .map(|(k, &o)| match o {
                        Operand::Temp(_) => format!("slots[{k}]"),
                        _ => self.operand(o),
                    });
                layout.write_value(&mut outputs, &mut body);
            }
        }
        body
    }
}

impl Emitter<'_> {
    /// The named bindings in program order, each output stored into the result right after
    /// the last binding it reads, and the result: `let mut result = zeros; … let t7 = …;
    /// result[0][3] = t7 * c2; … result`. Returned as one array expression at the end, every
    /// output value stayed live, in a register or spilled to the stack, from its computation
    /// to the return: built for AVX2, the Panda arm's `F64x4` mass matrix read or wrote the
    /// stack 278 times per call before and 233 after, its `f64` one 211 and 199
    /// (docs/performance.md). The outputs that are zero keep the initial zeros; the compiler
    /// drops the others' initial zeros, overwritten before they are read.
    fn write_stored_as_computed(
        &self,
        layout: &Layout,
        ty: &str,
        named: &[bool],
        out: &mut String,
    ) {
        let last_binding = self.last_binding_read(named);
        let mut stored_after: Vec<Vec<usize>> = vec![Vec::new(); self.program.instrs.len() + 1];
        for (k, &o) in self.program.outputs.iter().enumerate() {
            if matches!(o, Operand::Const(c) if c.to_bits() == 0) {
                continue;
            }
            let after = o
                .temp()
                .and_then(|t| last_binding[t as usize])
                .map_or(0, |t| t + 1);
            stored_after[after].push(k);
        }
        let mut zero = String::new();
        self.constant(0.0, &mut zero);
        write!(out, "let mut result: {ty} = ").expect("writing to a String");
        layout.write_value(&mut std::iter::repeat(zero), out);
        out.push_str(";\n");
        let places = layout.places();
        let store = |outputs: &[usize], out: &mut String| {
            for &k in outputs {
                out.push_str("result");
                out.push_str(&places[k]);
                out.push_str(" = ");
                self.write(self.program.outputs[k], out);
                out.push_str(";\n");
            }
        };
        store(&stored_after[0], out);
        for (t, outputs) in stored_after[1..].iter().enumerate() {
            if named[t] {
                self.write_binding(t, out);
            }
            store(outputs, out);
        }
        out.push_str("result");
    }

    /// For each instruction, the latest named or prologue instruction its written-out value
    /// reads (itself when it is one), or `None` when it reads only inputs and constants.
    fn last_binding_read(&self, named: &[bool]) -> Vec<Option<usize>> {
        let mut last: Vec<Option<usize>> = Vec::with_capacity(self.program.instrs.len());
        for (t, &instr) in self.program.instrs.iter().enumerate() {
            let value = if named[t] || self.joint_trig(instr).is_some() {
                Some(t)
            } else {
                instr
                    .operands()
                    .filter_map(Operand::temp)
                    .filter_map(|u| last[u as usize])
                    .max()
            };
            last.push(value);
        }
        last
    }

    /// `let t = …;` of named instruction `t`, appended to `out`.
    fn write_binding(&self, t: usize, out: &mut String) {
        let n = self.names[t].expect("a named instruction");
        out.push_str("let t");
        push_number(out, n);
        out.push_str(" = ");
        self.write_instr(t, out);
        out.push_str(";\n");
    }

    /// The name a named or prologue value is bound to.
    fn value_name(&self, t: usize) -> String {
        match self.names[t] {
            Some(n) => format!("t{n}"),
            None => self
                .joint_trig(self.program.instrs[t])
                .expect("a named or prologue value")
                .to_string(),
        }
    }

    /// `<T: Real>` for a generic kernel.
    fn generics(&self) -> String {
        match self.ctx.scalar {
            ScalarType::Generic => format!("<T: {}>", self.real),
            _ => String::new(),
        }
    }

    /// `p: &Params, ` with runtime or base parameters.
    fn params(&self) -> &'static str {
        match self.ctx.parameters {
            ParameterMode::Runtime | ParameterMode::Base => "p: &Params, ",
            ParameterMode::Constant => "",
        }
    }

    /// The body of a split kernel: the slot array, the prologue's values stored in it, and a
    /// call of each part, every part a function in a module of its own.
    fn write_parts(&self, kernel: Kernel, plan: &SplitPlan, t: &str, out: &mut String) {
        let zero = match self.ctx.scalar {
            ScalarType::Generic => self.operand(Operand::Const(0.0)),
            _ => "0.0".to_owned(),
        };
        let text = "writing to a String";
        writeln!(out, "let mut slots = [{zero}; {}];", plan.len).expect(text);
        for &value in plan
            .slots
            .keys()
            .filter(|&&value| self.names[value].is_none())
        {
            let name = self.value_name(value);
            writeln!(out, "slots[{}] = {name};", plan.slots[&value]).expect(text);
        }
        let args = arguments(kernel, t);
        let inputs: String = kernel
            .inputs()
            .iter()
            .map(|input| format!("{}, ", input.name()))
            .collect();
        let param = match self.ctx.parameters {
            ParameterMode::Runtime | ParameterMode::Base => "p, ",
            ParameterMode::Constant => "",
        };
        for (p, statements) in plan.parts.iter().enumerate() {
            writeln!(
                out,
                "mod part{p} {{\nuse super::*;\n#[inline(never)]\n#[allow(unused_variables, unused_parens, clippy::all, clippy::pedantic)]\npub(super) fn run{generics}({params}{args}slots: &mut [{t}; {len}]) {{",
                generics = self.generics(),
                params = self.params(),
                len = plan.len,
            )
            .expect(text);
            for &value in &plan.imports[p] {
                let name = self.value_name(value);
                writeln!(out, "let {name} = slots[{}];", plan.slots[&value]).expect(text);
            }
            for &statement in statements {
                match statement {
                    Statement::Let(i) => {
                        self.write_binding(i, out);
                        if let Some(&s) = plan.slots.get(&i) {
                            writeln!(out, "slots[{s}] = {};", self.value_name(i)).expect(text);
                        }
                    }
                    Statement::Output { output, instr } => {
                        write!(out, "slots[{output}] = ").expect(text);
                        self.write(Operand::Temp(instr as u32), out);
                        out.push_str(";\n");
                    }
                }
            }
            writeln!(out, "}}\n}}\npart{p}::run({param}{inputs}&mut slots);").expect(text);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Operand::{Const, Input as In, Temp};

    const QD0: Operand = In(Symbol::Velocity(0));
    const QD1: Operand = In(Symbol::Velocity(1));
    const QD2: Operand = In(Symbol::Velocity(2));

    /// The emitted function of a scalar kernel computing `instrs` (the last is the output),
    /// without whitespace.
    fn emit(instrs: Vec<Instr>, scalar: ScalarType) -> String {
        let output = Temp(instrs.len() as u32 - 1);
        emit_outputs(instrs, vec![output], scalar)
    }

    fn emit_outputs(instrs: Vec<Instr>, outputs: Vec<Operand>, scalar: ScalarType) -> String {
        let ctx = EmitContext {
            fields: &[],
            scalar,
            parameters: ParameterMode::Constant,
            runtime: "::rt",
        };
        let program = Program { instrs, outputs };
        let dims = Dims {
            nv: 3,
            ..Dims::default()
        };
        emit_kernel(Kernel::KineticEnergy, &program, dims, ctx).replace(char::is_whitespace, "")
    }

    /// The function's body after its signature.
    fn body(code: &str) -> &str {
        &code[code.find("->f64{").map_or(0, |i| i + "->f64{".len())..]
    }

    #[test]
    fn right_nested_sums_and_products_keep_their_parentheses() {
        let sum = emit(
            vec![Instr::Add(QD1, QD2), Instr::Add(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&sum).starts_with("qd[0]+(qd[1]+qd[2])"), "{sum}");
        let left = emit(
            vec![Instr::Add(QD0, QD1), Instr::Add(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&left).starts_with("qd[0]+qd[1]+qd[2]"), "{left}");
        let product = emit(
            vec![Instr::Mul(QD1, QD2), Instr::Mul(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&product).starts_with("qd[0]*(qd[1]*qd[2])"),
            "{product}"
        );
        let difference = emit(
            vec![Instr::Sub(QD1, QD2), Instr::Sub(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&difference).starts_with("qd[0]-(qd[1]-qd[2])"),
            "{difference}"
        );
        let quotient = emit(
            vec![Instr::Mul(QD1, QD2), Instr::Div(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&quotient).starts_with("qd[0]/(qd[1]*qd[2])"),
            "{quotient}"
        );
    }

    /// Each output is stored right after the last binding it reads, a zero output not at
    /// all (the result starts as zeros), and the result is returned last.
    #[test]
    fn outputs_are_stored_as_soon_as_computed() {
        let program = Program {
            instrs: vec![
                Instr::Add(QD0, QD1),
                Instr::Mul(Temp(0), QD2),
                Instr::Mul(Temp(1), Temp(1)),
            ],
            outputs: vec![Temp(0), Const(0.0), Temp(2)],
        };
        let ctx = EmitContext {
            fields: &[],
            scalar: ScalarType::F64,
            parameters: ParameterMode::Constant,
            runtime: "::rt",
        };
        let dims = Dims {
            nv: 3,
            ..Dims::default()
        };
        let code = emit_kernel(Kernel::InverseDynamics, &program, dims, ctx)
            .replace(char::is_whitespace, "");
        let body = &code[code.find("->[f64;NV]{").expect("a body") + "->[f64;NV]{".len()..];
        assert_eq!(
            body,
            "letmutresult:[f64;NV]=[0.0,0.0,0.0];lett0=qd[0]+qd[1];result[0]=t0;\
             lett1=t0*qd[2];result[2]=t1*t1;result}",
        );
    }

    #[test]
    fn a_sum_inside_a_product_is_parenthesised_and_a_product_inside_a_sum_is_not() {
        let code = emit(
            vec![Instr::Add(QD0, QD1), Instr::Mul(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("(qd[0]+qd[1])*qd[2]"), "{code}");
        let code = emit(
            vec![Instr::Mul(QD0, QD1), Instr::Add(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("qd[0]*qd[1]+qd[2]"), "{code}");
    }

    #[test]
    fn negation_binds_tighter_than_products_and_wraps_sums() {
        let code = emit(
            vec![Instr::Add(QD0, QD1), Instr::Neg(Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("-(qd[0]+qd[1])"), "{code}");
        let code = emit(
            vec![Instr::Neg(QD0), Instr::Mul(Temp(0), QD1)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("-qd[0]*qd[1]"), "{code}");
        let code = emit(
            vec![Instr::Neg(QD1), Instr::Mul(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("qd[0]*-qd[1]"), "{code}");
    }

    #[test]
    fn negative_and_non_finite_constants() {
        let code = emit(vec![Instr::Mul(QD0, Const(-2.5))], ScalarType::F64);
        assert!(body(&code).starts_with("qd[0]*-2.5"), "{code}");
        let code = emit(vec![Instr::Sub(QD0, Const(-0.0))], ScalarType::F64);
        assert!(body(&code).starts_with("qd[0]--0.0"), "{code}");
        let code = emit_outputs(vec![], vec![Const(f64::NAN)], ScalarType::F64);
        assert!(code.contains("f64::NAN"), "{code}");
        let code = emit_outputs(vec![], vec![Const(f64::NEG_INFINITY)], ScalarType::F32);
        assert!(code.contains("-f32::INFINITY"), "{code}");
        let code = emit_outputs(vec![], vec![Const(0.5)], ScalarType::Generic);
        assert!(code.contains("<Tas::rt::Real>::from_f64(0.5)"), "{code}");
    }

    /// Sines of joints 1 to `joints`, summed.
    fn sines(joints: u16) -> Vec<Instr> {
        let mut instrs: Vec<Instr> = (0..joints)
            .map(|k| Instr::Sin(In(Symbol::Position(k))))
            .collect();
        instrs.push(Instr::Add(Temp(0), Temp(1)));
        for k in 2..u32::from(joints) {
            instrs.push(Instr::Add(Temp(instrs.len() as u32 - 1), Temp(k)));
        }
        instrs
    }

    #[test]
    fn an_odd_count_of_angles_is_padded_for_f64_and_f32_but_not_generic() {
        for scalar in [ScalarType::F64, ScalarType::F32] {
            let code = emit(sines(3), scalar);
            assert!(
                code.contains("::rt::Real::sin_cos_array(&[q[0],q[1],q[2],q[2]])"),
                "{code}"
            );
        }
        let code = emit(sines(3), ScalarType::Generic);
        assert!(
            code.contains("::rt::Real::sin_cos_array(&[q[0],q[1],q[2]])"),
            "{code}"
        );
        let even = emit(sines(2), ScalarType::F64);
        assert!(
            even.contains("::rt::Real::sin_cos_array(&[q[0],q[1]])"),
            "{even}"
        );
    }

    #[test]
    fn numbers_are_written_in_decimal() {
        for n in [0, 7, 10, 909, 123_456, u32::MAX] {
            let mut text = String::from("t");
            push_number(&mut text, n);
            assert_eq!(text, format!("t{n}"));
        }
    }

    #[test]
    fn emitted_code_names_only_core_types_and_the_runtime_path() {
        let code = emit(sines(3), ScalarType::Generic);
        assert!(
            !code.contains("rne_codegen") && !code.contains("std::"),
            "{code}"
        );
        assert!(code.contains("<T:::rt::Real>"), "{code}");
    }
}

//! A kernel's statements: its inputs read into locals, the joints' sines and cosines, one
//! `const double tN = …;` per instruction, and its results stored.

use std::collections::BTreeSet;
use std::fmt::Write;

use rne_symbolic::Symbol;

use super::text::c_double;
use super::TEXT;
use crate::kernel::{Input, Kernel};
use crate::program::{Instr, Operand, Program};

/// What a kernel's statements are written from.
pub(super) struct Body<'a> {
    kernel: Kernel,
    pub(super) program: &'a Program,
    /// The runtime parameters' struct fields, by symbol index.
    fields: &'a [String],
    /// Whether the function takes the runtime parameters `p`.
    takes_params: bool,
    /// Whether a `Symbol::Parameter(i)` is `standard[i]` (`base_parameters`) rather than a
    /// runtime parameter.
    reads_standard: bool,
    /// The joints whose sine and cosine are computed up front.
    trig: BTreeSet<u16>,
    /// For each instruction that is such a sine (`s<joint>`) or cosine (`c<joint>`), its
    /// letter and joint.
    prologue: Vec<Option<(char, u16)>>,
}

impl<'a> Body<'a> {
    pub(super) fn new(
        kernel: Kernel,
        program: &'a Program,
        fields: &'a [String],
        takes_params: bool,
    ) -> Body<'a> {
        let prologue: Vec<Option<(char, u16)>> = program
            .instrs
            .iter()
            .map(|instr| match *instr {
                Instr::Sin(Operand::Input(Symbol::Position(k))) => Some(('s', k)),
                Instr::Cos(Operand::Input(Symbol::Position(k))) => Some(('c', k)),
                _ => None,
            })
            .collect();
        Body {
            kernel,
            program,
            fields,
            takes_params,
            reads_standard: kernel.inputs().contains(&Input::Standard),
            trig: prologue.iter().flatten().map(|&(_, k)| k).collect(),
            prologue,
        }
    }

    /// Whether each instruction is computed up front (a joint's sine or cosine).
    pub(super) fn prologue_flags(&self) -> Vec<bool> {
        self.prologue.iter().map(Option::is_some).collect()
    }

    /// The whole body of an unsplit kernel reading `reads`: the inputs read into locals
    /// (before any result is written, so that an output array may be an input), the joints'
    /// sines and cosines, then each instruction, each result stored to its place (`places`,
    /// or returned when there is none) as soon as it is computed.
    pub(super) fn write_whole(
        &self,
        reads: &BTreeSet<Symbol>,
        places: &[(&str, usize)],
        out: &mut String,
    ) {
        self.write_unused(reads, out);
        self.write_locals(reads.iter().copied(), out);
        self.write_trig(out);
        let mut stored_after: Vec<Vec<usize>> = vec![Vec::new(); self.program.instrs.len() + 1];
        for (k, &o) in self.program.outputs.iter().enumerate() {
            let after = match o {
                Operand::Temp(t) if self.prologue[t as usize].is_none() => t as usize + 1,
                _ => 0,
            };
            stored_after[after].push(k);
        }
        let store = |outputs: &[usize], out: &mut String| {
            for &k in outputs {
                match places.get(k) {
                    Some((name, index)) => write!(out, "    {name}[{index}] = ").expect(TEXT),
                    None => out.push_str("    return "),
                }
                self.write_operand(self.program.outputs[k], out);
                out.push_str(";\n");
            }
        };
        store(&stored_after[0], out);
        for t in 0..self.program.instrs.len() {
            self.write_statement(t, out);
            store(&stored_after[t + 1], out);
        }
    }

    /// `(void)name;` for each array a function does not read of those it takes (an unused
    /// parameter is a warning), given the inputs it reads.
    pub(super) fn write_unused(&self, reads: &BTreeSet<Symbol>, out: &mut String) {
        let reads_params =
            !self.reads_standard && reads.iter().any(|s| matches!(s, Symbol::Parameter(_)));
        if self.takes_params && !reads_params {
            out.push_str("    (void)p;\n");
        }
        for &input in self.kernel.inputs() {
            if !reads.iter().any(|&s| input_of(s) == input) {
                writeln!(out, "    (void){};", input.name()).expect(TEXT);
            }
        }
    }

    /// `const double q_3 = q[3];` for each of `symbols`.
    pub(super) fn write_locals(&self, symbols: impl Iterator<Item = Symbol>, out: &mut String) {
        for symbol in symbols {
            out.push_str("    const double ");
            self.write_input(symbol, out);
            out.push_str(" = ");
            match symbol {
                Symbol::Parameter(i) if !self.reads_standard => {
                    write!(out, "p->{}", self.fields[usize::from(i)]).expect(TEXT)
                }
                other => {
                    let (array, index) = element(other, self.reads_standard);
                    write!(out, "{array}[{index}]").expect(TEXT)
                }
            }
            out.push_str(";\n");
        }
    }

    /// The joints' sines and cosines, each pair by one call (their angles' locals written).
    pub(super) fn write_trig(&self, out: &mut String) {
        for &k in &self.trig {
            let joint = k + 1;
            writeln!(out, "    double s{joint}, c{joint};").expect(TEXT);
        }
        for &k in &self.trig {
            let joint = k + 1;
            out.push_str("    rne_sin_cos(");
            self.write_input(Symbol::Position(k), out);
            writeln!(out, ", &s{joint}, &c{joint});").expect(TEXT);
        }
    }

    /// The angles the prologue reads.
    pub(super) fn trig_angles(&self) -> impl Iterator<Item = Symbol> + '_ {
        self.trig.iter().map(|&k| Symbol::Position(k))
    }

    /// `const double t7 = …;` of instruction `t`, unless it is computed up front.
    pub(super) fn write_statement(&self, t: usize, out: &mut String) {
        if self.prologue[t].is_none() {
            write!(out, "    const double t{t} = ").expect(TEXT);
            self.write_instr(self.program.instrs[t], out);
            out.push_str(";\n");
        }
    }

    /// The name of instruction `t`'s value: `t7`, or `s3` for the sine of joint 3.
    pub(super) fn value_name(&self, t: usize) -> String {
        match self.prologue[t] {
            Some((function, k)) => format!("{function}{}", k + 1),
            None => format!("t{t}"),
        }
    }

    /// The local holding input `symbol`: `q_3`, `standard_7`, `p_m1`.
    fn write_input(&self, symbol: Symbol, out: &mut String) {
        match symbol {
            Symbol::Parameter(i) if !self.reads_standard => {
                write!(out, "p_{}", self.fields[usize::from(i)]).expect(TEXT)
            }
            other => {
                let (array, index) = element(other, self.reads_standard);
                write!(out, "{array}_{index}").expect(TEXT)
            }
        }
    }

    /// An operand: a temporary, a joint's sine or cosine, an input's local or a constant.
    pub(super) fn write_operand(&self, operand: Operand, out: &mut String) {
        match operand {
            Operand::Temp(t) => out.push_str(&self.value_name(t as usize)),
            Operand::Const(c) => out.push_str(&c_double(c)),
            Operand::Input(symbol) => self.write_input(symbol, out),
            Operand::Lane { .. } => unreachable!("lanes are rejected before the body is written"),
        }
    }

    /// An instruction's expression: one operation on operands.
    fn write_instr(&self, instr: Instr, out: &mut String) {
        let binary = |a: Operand, op: &str, b: Operand, out: &mut String| {
            self.write_operand(a, out);
            out.push_str(op);
            self.write_operand(b, out);
        };
        let call = |function: &str, args: &[(bool, Operand)], out: &mut String| {
            out.push_str(function);
            out.push('(');
            for (k, &(negated, a)) in args.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                if negated {
                    out.push('-');
                }
                self.write_operand(a, out);
            }
            out.push(')');
        };
        match instr {
            Instr::Add(a, b) => binary(a, " + ", b, out),
            Instr::Sub(a, b) => binary(a, " - ", b, out),
            Instr::Mul(a, b) => binary(a, " * ", b, out),
            Instr::Div(a, b) => binary(a, " / ", b, out),
            Instr::Neg(a) => call("", &[(true, a)], out),
            Instr::Sin(a) => call("rne_sin", &[(false, a)], out),
            Instr::Cos(a) => call("rne_cos", &[(false, a)], out),
            Instr::Sqrt(a) => call("sqrt", &[(false, a)], out),
            Instr::Sign(a) => call("rne_sign", &[(false, a)], out),
            Instr::MulAdd(a, b, c) => {
                call("rne_mul_add", &[(false, a), (false, b), (false, c)], out)
            }
            Instr::MulSub(a, b, c) => {
                call("rne_mul_add", &[(false, a), (false, b), (true, c)], out)
            }
            Instr::NegMulAdd(a, b, c) => {
                call("rne_mul_add", &[(true, a), (false, b), (false, c)], out)
            }
        }
    }

    /// The inputs instruction `t` reads.
    pub(super) fn inputs_of(&self, t: usize) -> impl Iterator<Item = Symbol> {
        self.program.instrs[t].operands().filter_map(|o| match o {
            Operand::Input(symbol) => Some(symbol),
            _ => None,
        })
    }
}

/// The input array a symbol is an element of (`standard` for every parameter: only
/// `base_parameters` takes that array, and its parameters are elements of it).
fn input_of(symbol: Symbol) -> Input {
    match symbol {
        Symbol::Position(_) => Input::Q,
        Symbol::Velocity(_) => Input::Qd,
        Symbol::Acceleration(_) => Input::Qdd,
        Symbol::Force(_) => Input::Tau,
        Symbol::Parameter(_) | Symbol::Lane(_) => Input::Standard,
    }
}

/// The array and index of an input symbol (a parameter read as `standard[i]`).
fn element(symbol: Symbol, reads_standard: bool) -> (&'static str, u16) {
    match symbol {
        Symbol::Position(k) => ("q", k),
        Symbol::Velocity(k) => ("qd", k),
        Symbol::Acceleration(k) => ("qdd", k),
        Symbol::Force(k) => ("tau", k),
        Symbol::Parameter(i) if reads_standard => ("standard", i),
        other => unreachable!("{other:?} is not an element of an input array"),
    }
}

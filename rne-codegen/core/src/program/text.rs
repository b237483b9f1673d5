//! The text form of a [`Program`]: one instruction per line, then the outputs.
//!
//! ```text
//! t0 = mul q[0] q[1]
//! t1 = muladd t0 qd[2] 0.5
//! out[0] = t1
//! out[1] = -2.0
//! ```
//!
//! An instruction is `t<i> = <operation> <operands>`, numbered from 0 in program order, with
//! the operation's name in lower case (`add`, `sub`, `mul`, `div`, `neg`, `sin`, `cos`,
//! `sqrt`, `sign`, `muladd` a·b + c, `mulsub` a·b − c, `negmuladd` c − a·b). An operand is a
//! temporary `t<i>`, lane `l` of a vector temporary `t<i>[l]`, a constant (Rust's shortest
//! round-trip form of the `f64`: `2.0`, `-0.5`, `1e-10`, `NaN`, `inf`), or an input: `q[k]`,
//! `qd[k]`, `qdd[k]`, `tau[k]` of joint k, `p[k]` the parameter k and `e[k]` the lane seed k
//! ([`Symbol`]). Each output is `out[k] = <operand>`. The text parses back into the same
//! program ([`Program::from_str`](std::str::FromStr::from_str)), blank lines and lines starting
//! with `;` ignored; the optimiser's golden files (`tests/filetests/`) are written in it.

use std::fmt;
use std::str::FromStr;

use rne_symbolic::Symbol;

use super::{Instr, Operand, Program};

impl fmt::Display for Operand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Operand::Temp(t) => write!(f, "t{t}"),
            Operand::Lane { temp, lane } => write!(f, "t{temp}[{lane}]"),
            Operand::Const(c) => write!(f, "{c:?}"),
            Operand::Input(symbol) => {
                let (array, k) = match symbol {
                    Symbol::Position(k) => ("q", k),
                    Symbol::Velocity(k) => ("qd", k),
                    Symbol::Acceleration(k) => ("qdd", k),
                    Symbol::Force(k) => ("tau", k),
                    Symbol::Parameter(k) => ("p", k),
                    Symbol::Lane(k) => ("e", k),
                };
                write!(f, "{array}[{k}]")
            }
        }
    }
}

impl Instr {
    /// The operation's name in the text form.
    pub fn mnemonic(&self) -> &'static str {
        match self {
            Instr::Add(..) => "add",
            Instr::Sub(..) => "sub",
            Instr::Mul(..) => "mul",
            Instr::Div(..) => "div",
            Instr::Neg(_) => "neg",
            Instr::Sin(_) => "sin",
            Instr::Cos(_) => "cos",
            Instr::Sqrt(_) => "sqrt",
            Instr::Sign(_) => "sign",
            Instr::MulAdd(..) => "muladd",
            Instr::MulSub(..) => "mulsub",
            Instr::NegMulAdd(..) => "negmuladd",
        }
    }
}

impl fmt::Display for Instr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.mnemonic())?;
        for operand in self.operands() {
            write!(f, " {operand}")?;
        }
        Ok(())
    }
}

impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (t, instr) in self.instrs.iter().enumerate() {
            writeln!(f, "t{t} = {instr}")?;
        }
        for (k, output) in self.outputs.iter().enumerate() {
            writeln!(f, "out[{k}] = {output}")?;
        }
        Ok(())
    }
}

/// A line of program text that does not parse: its number (from 1) and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct ProgramTextError {
    /// The line, from 1.
    pub line: usize,
    /// What is wrong with it.
    pub message: String,
}

impl FromStr for Program {
    type Err = ProgramTextError;

    /// Parses the text form ([`Program`]'s `Display`): instructions numbered in order, each
    /// reading earlier temporaries only, then the outputs in order.
    fn from_str(text: &str) -> Result<Program, ProgramTextError> {
        let mut program = Program::default();
        let lines = text
            .lines()
            .enumerate()
            .map(|(k, line)| (k + 1, line.trim()));
        for (line, content) in lines.filter(|(_, l)| !l.is_empty() && !l.starts_with(';')) {
            let error = |message: String| ProgramTextError { line, message };
            let (target, value) = content.split_once(" = ").ok_or_else(|| {
                error(format!(
                    "expected `t<i> = …` or `out[k] = …`, got `{content}`"
                ))
            })?;
            if let Some(k) = index(target, "out[", "]") {
                expect_next(k, program.outputs.len(), "output").map_err(error)?;
                let operand = operand(value, program.instrs.len()).map_err(error)?;
                program.outputs.push(operand);
            } else if let Some(t) = index(target, "t", "") {
                if !program.outputs.is_empty() {
                    return Err(error("an instruction after the outputs".into()));
                }
                expect_next(t, program.instrs.len(), "instruction").map_err(error)?;
                let instr = instruction(value, program.instrs.len()).map_err(error)?;
                program.instrs.push(instr);
            } else {
                return Err(error(format!("`{target}` is neither `t<i>` nor `out[k]`")));
            }
        }
        Ok(program)
    }
}

/// The number `n` of `<prefix>n<suffix>`.
fn index(text: &str, prefix: &str, suffix: &str) -> Option<usize> {
    text.strip_prefix(prefix)?
        .strip_suffix(suffix)?
        .parse()
        .ok()
}

/// Whether `found` is the next number, `expected`.
fn expect_next(found: usize, expected: usize, what: &str) -> Result<(), String> {
    if found == expected {
        Ok(())
    } else {
        Err(format!("{what} {found} where {what} {expected} comes next"))
    }
}

/// The instruction `<operation> <operands>`, in a program of `defined` instructions so far.
fn instruction(text: &str, defined: usize) -> Result<Instr, String> {
    let mut words = text.split_whitespace();
    let name = words.next().unwrap_or_default();
    let operands = words
        .map(|word| operand(word, defined))
        .collect::<Result<Vec<_>, _>>()?;
    let instr = match (name, operands.as_slice()) {
        ("add", &[a, b]) => Instr::Add(a, b),
        ("sub", &[a, b]) => Instr::Sub(a, b),
        ("mul", &[a, b]) => Instr::Mul(a, b),
        ("div", &[a, b]) => Instr::Div(a, b),
        ("neg", &[a]) => Instr::Neg(a),
        ("sin", &[a]) => Instr::Sin(a),
        ("cos", &[a]) => Instr::Cos(a),
        ("sqrt", &[a]) => Instr::Sqrt(a),
        ("sign", &[a]) => Instr::Sign(a),
        ("muladd", &[a, b, c]) => Instr::MulAdd(a, b, c),
        ("mulsub", &[a, b, c]) => Instr::MulSub(a, b, c),
        ("negmuladd", &[a, b, c]) => Instr::NegMulAdd(a, b, c),
        _ => {
            return Err(format!(
                "`{text}` is no operation with its number of operands"
            ))
        }
    };
    Ok(instr)
}

/// The symbol of entry k of an input array.
type InputSymbol = fn(u16) -> Symbol;

/// The operand `text`, which may read the `defined` instructions before it.
fn operand(text: &str, defined: usize) -> Result<Operand, String> {
    let temp = |t: usize| {
        if t < defined {
            u32::try_from(t).map_err(|_| format!("`{text}`: too many instructions"))
        } else {
            Err(format!("`{text}` is not defined before it is read"))
        }
    };
    if let Some(t) = index(text, "t", "") {
        return Ok(Operand::Temp(temp(t)?));
    }
    if let Some((t, lane)) = text.strip_suffix(']').and_then(|t| t.split_once('[')) {
        if let (Some(t), Ok(lane)) = (index(t, "t", ""), lane.parse::<u8>()) {
            return Ok(Operand::Lane {
                temp: temp(t)?,
                lane,
            });
        }
        let inputs: [(&str, InputSymbol); 6] = [
            ("q", Symbol::Position),
            ("qd", Symbol::Velocity),
            ("qdd", Symbol::Acceleration),
            ("tau", Symbol::Force),
            ("p", Symbol::Parameter),
            ("e", Symbol::Lane),
        ];
        if let (Some((_, symbol)), Ok(k)) = (inputs.iter().find(|(a, _)| *a == t), lane.parse()) {
            return Ok(Operand::Input(symbol(k)));
        }
    }
    text.parse::<f64>()
        .map(Operand::Const)
        .map_err(|_| format!("`{text}` is no operand"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rne_symbolic::{ExprGraph, SymbolTable};

    /// Every operation and every kind of operand prints and parses back to the same program.
    #[test]
    fn programs_print_and_parse_back() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y"]));
        let root = g
            .parse_sexpr("(+ (/ (sin x) (cos Dy)) (* (sqrt DDx) (sign tau_y)))")
            .unwrap();
        let negated = g.parse_sexpr("(- (* -0.5 x))").unwrap();
        let mut program = Program::lower(&g, &[root, negated]).fuse_multiply_add();
        program.instrs.push(Instr::MulSub(
            Operand::Input(Symbol::Parameter(1)),
            Operand::Const(1e-10),
            Operand::Input(Symbol::Lane(2)),
        ));
        program.instrs.push(Instr::NegMulAdd(
            Operand::Temp(0),
            Operand::Const(f64::INFINITY),
            Operand::Const(-3.0),
        ));
        program.outputs.push(Operand::Lane { temp: 1, lane: 3 });
        program.outputs.push(Operand::Const(2.0));
        let text = program.to_string();
        assert_eq!(text.parse::<Program>(), Ok(program), "{text}");
        assert!(text.contains("t0 = sin q[0]\n"), "{text}");
        assert!(text.contains("mulsub p[1] 1e-10 e[2]"), "{text}");
    }

    /// A malformed line is an error naming it.
    #[test]
    fn bad_lines_are_errors_with_their_number() {
        for (text, line, message) in [
            (
                "t0 = sin q[0]\nt2 = cos q[0]",
                2,
                "instruction 2 where instruction 1 comes next",
            ),
            (
                "t0 = add q[0]",
                1,
                "`add q[0]` is no operation with its number of operands",
            ),
            ("t0 = neg t0", 1, "`t0` is not defined before it is read"),
            ("\n; note\nout[0] = x", 3, "`x` is no operand"),
            (
                "out[0] = 1.0\nt0 = sin q[0]",
                2,
                "an instruction after the outputs",
            ),
            ("y = 1", 1, "`y` is neither `t<i>` nor `out[k]`"),
        ] {
            let error = text.parse::<Program>().unwrap_err();
            assert_eq!(
                error,
                ProgramTextError {
                    line,
                    message: message.into()
                },
                "{text}"
            );
        }
    }
}

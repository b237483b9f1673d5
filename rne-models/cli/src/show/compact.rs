//! The compact form of the equations: the expression graph of the requested entries lowered to
//! a straight-line program, one operation a line, every quantity used more than once computed
//! once and named — the form Maple's `codegen[optimize]`, SymPyBotics and OpenSYMORO print for
//! models too large to expand (Khalil and Kleinfinger, *Minimum operations and minimum
//! parameters of the dynamic models of tree structure robots*, 1987). Names follow the thesis
//! (*Dynamics of robot manipulators by the Newton–Euler formulation*, Høifødt): `s1 = sin q1`,
//! `c1 = cos q1`, `Dq1` and `DDq1` the joint rates and accelerations, `t1, t2, …` the
//! intermediate quantities, and an entry computed by one operation used nowhere else under the
//! entry's own name.

use std::io::Write;

use rne_codegen_core::{Instr, Operand, Program};
use rne_symbolic::canonical::mathml;
use rne_symbolic::canonical::{PrintFormat, Printer};
use rne_symbolic::{BaseCoordinate, Coordinate, ExprGraph, Symbol, SymbolTable};

use super::entries::Section;
use super::sections::{label, mathml_label};
use super::Format;
use crate::CliError;

/// What was printed of a program.
#[derive(Copy, Clone, Debug)]
pub struct CompactPrinted {
    /// Lines of the program printed.
    pub lines: usize,
    /// Lines of the whole program (operations and the entries not named by one).
    pub total: usize,
}

/// Prints the program of `sections` in text, LaTeX or MathML, at most `max_size` bytes of it.
pub fn print(
    graph: &ExprGraph,
    sections: &[Section],
    format: Format,
    max_size: usize,
    out: &mut dyn Write,
) -> Result<CompactPrinted, CliError> {
    let keys: Vec<_> = sections.iter().flat_map(|s| s.entries.iter()).collect();
    let roots: Vec<_> = keys.iter().map(|(_, id)| *id).collect();
    let program = Program::lower(graph, &roots);
    let names = Names::new(&program, graph.symbols(), format, |k| match format {
        Format::Html => mathml_label(&keys[k].0),
        Format::Text | Format::Latex => label(&keys[k].0, format == Format::Latex),
    });
    let about = format!(
        "{} operations ({}), one a line; s_k = sin q_k, c_k = cos q_k, t_k intermediate quantities",
        program.op_count().total(),
        program.op_count()
    );
    match format {
        Format::Text => writeln!(out, "\n# {about}")?,
        Format::Latex => writeln!(out, "\n% {about}")?,
        Format::Html => writeln!(out, "<p>{}</p>", mathml::escape(&about))?,
    }
    let mut lines = names.lines(&program);
    let total = lines.len();
    let mut written = 0;
    let mut printed = 0;
    for line in lines.drain(..) {
        if written + line.len() > max_size {
            break;
        }
        out.write_all(line.as_bytes())?;
        written += line.len();
        printed += 1;
    }
    Ok(CompactPrinted {
        lines: printed,
        total,
    })
}

/// The name of every instruction's result and how operands print.
struct Names<'a> {
    temps: Vec<String>,
    /// Which output each instruction is named after, if any.
    named_output: Vec<Option<usize>>,
    outputs: Vec<String>,
    symbols: &'a SymbolTable,
    format: Format,
}

impl<'a> Names<'a> {
    fn new(
        program: &Program,
        symbols: &'a SymbolTable,
        format: Format,
        output_label: impl Fn(usize) -> String,
    ) -> Names<'a> {
        let uses = program.use_counts();
        let outputs: Vec<String> = (0..program.outputs.len()).map(output_label).collect();
        let mut named_output = vec![None; program.instrs.len()];
        for (k, o) in program.outputs.iter().enumerate() {
            if let Operand::Temp(t) = o {
                if uses[*t as usize] == 1 {
                    named_output[*t as usize] = Some(k);
                }
            }
        }
        let mut next = 0;
        let temps = program
            .instrs
            .iter()
            .enumerate()
            .map(
                |(t, instr)| match (named_output[t], abbreviation(symbols, instr)) {
                    (Some(k), _) => outputs[k].clone(),
                    (None, Some((letter, joint))) => subscript(letter, &joint, format),
                    (None, None) => {
                        next += 1;
                        subscript("t", &next.to_string(), format)
                    }
                },
            )
            .collect();
        Names {
            temps,
            named_output,
            outputs,
            symbols,
            format,
        }
    }

    /// Every line: one per instruction, then the entries no instruction is named after.
    fn lines(&self, program: &Program) -> Vec<String> {
        let (equals, end) = match self.format {
            Format::Text => (" = ".to_owned(), ""),
            Format::Latex => (" &= ".to_owned(), " \\\\"),
            Format::Html => (mathml::mo("="), ""),
        };
        let mut lines: Vec<String> = program
            .instrs
            .iter()
            .enumerate()
            .map(|(t, instr)| self.line(&self.temps[t], &equals, &self.instr(instr), end))
            .collect();
        for (k, o) in program.outputs.iter().enumerate() {
            let named = matches!(o, Operand::Temp(t) if self.named_output[*t as usize] == Some(k));
            if !named {
                lines.push(self.line(&self.outputs[k], &equals, &self.operand(*o), end));
            }
        }
        lines
    }

    /// `name = value`, one line of the program.
    fn line(&self, name: &str, equals: &str, value: &str, end: &str) -> String {
        match self.format {
            Format::Html => format!("{}\n", mathml::math(&format!("{name}{equals}{value}"))),
            Format::Text | Format::Latex => format!("{name}{equals}{value}{end}\n"),
        }
    }

    fn instr(&self, instr: &Instr) -> String {
        if self.format == Format::Html {
            return self.instr_mathml(instr);
        }
        let latex = self.format == Format::Latex;
        let o = |x: Operand| self.operand(x);
        let times = if latex { " \\, " } else { " * " };
        let function = |f: &str, x: Operand| match latex {
            true => format!("\\{f}({})", o(x)),
            false => format!("{f}({})", o(x)),
        };
        match *instr {
            Instr::Add(a, b) => format!("{} + {}", o(a), o(b)),
            Instr::Sub(a, b) => format!("{} - {}", o(a), o(b)),
            Instr::Mul(a, b) => format!("{}{times}{}", o(a), o(b)),
            Instr::Div(a, b) if latex => format!("\\frac{{{}}}{{{}}}", o(a), o(b)),
            Instr::Div(a, b) => format!("{} / {}", o(a), o(b)),
            Instr::Neg(a) => format!("-{}", o(a)),
            Instr::Sin(a) => function("sin", a),
            Instr::Cos(a) => function("cos", a),
            Instr::Sqrt(a) if latex => format!("\\sqrt{{{}}}", o(a)),
            Instr::Sqrt(a) => function("sqrt", a),
            Instr::Sign(a) if latex => format!("\\operatorname{{sign}}({})", o(a)),
            Instr::Sign(a) => function("sign", a),
            Instr::MulAdd(a, b, c) => format!("{}{times}{} + {}", o(a), o(b), o(c)),
            Instr::MulSub(a, b, c) => format!("{}{times}{} - {}", o(a), o(b), o(c)),
            Instr::NegMulAdd(a, b, c) => format!("{} - {}{times}{}", o(c), o(a), o(b)),
        }
    }

    /// One operation in MathML: `a + b`, `a · b`, a fraction, `sin(a)`, a square root.
    fn instr_mathml(&self, instr: &Instr) -> String {
        let o = |x: Operand| self.operand(x);
        let (plus, minus, times) = (mathml::mo("+"), mathml::minus(), mathml::mo("·"));
        match *instr {
            Instr::Add(a, b) => format!("{}{plus}{}", o(a), o(b)),
            Instr::Sub(a, b) => format!("{}{minus}{}", o(a), o(b)),
            Instr::Mul(a, b) => format!("{}{times}{}", o(a), o(b)),
            Instr::Div(a, b) => format!(
                "<mfrac>{}{}</mfrac>",
                mathml::mrow(&o(a)),
                mathml::mrow(&o(b))
            ),
            Instr::Neg(a) => format!("{minus}{}", o(a)),
            Instr::Sin(a) => mathml::function("sin", &o(a)),
            Instr::Cos(a) => mathml::function("cos", &o(a)),
            Instr::Sqrt(a) => format!("<msqrt>{}</msqrt>", o(a)),
            Instr::Sign(a) => mathml::function("sgn", &o(a)),
            Instr::MulAdd(a, b, c) => format!("{}{times}{}{plus}{}", o(a), o(b), o(c)),
            Instr::MulSub(a, b, c) => format!("{}{times}{}{minus}{}", o(a), o(b), o(c)),
            Instr::NegMulAdd(a, b, c) => format!("{}{minus}{}{times}{}", o(c), o(a), o(b)),
        }
    }

    fn operand(&self, operand: Operand) -> String {
        match operand {
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => self.temps[t as usize].clone(),
            Operand::Const(c) if self.format == Format::Html && c < 0.0 => mathml::parenthesised(
                &format!("{}{}", mathml::minus(), mathml::number(&format!("{}", -c))),
            ),
            Operand::Const(c) if self.format == Format::Html => mathml::number(&format!("{c}")),
            Operand::Const(c) if c < 0.0 => format!("({c})"),
            Operand::Const(c) => format!("{c}"),
            Operand::Input(s) => self.input(s),
        }
    }

    fn input(&self, symbol: Symbol) -> String {
        let j = match self.symbols.coordinate(symbol) {
            Some(Coordinate::Base(base)) => return self.base(symbol, base),
            Some(Coordinate::Joint(j)) => j,
            None => 0,
        };
        let (text, tex, markup) = match symbol {
            Symbol::Position(_) => ("q", "q", mathml::mi("q")),
            Symbol::Velocity(_) => ("Dq", "\\dot{q}", mathml::accented("q", '\u{2d9}')),
            Symbol::Acceleration(_) => ("DDq", "\\ddot{q}", mathml::accented("q", '\u{a8}')),
            Symbol::Force(_) => ("tau", "\\tau", mathml::mi("τ")),
            Symbol::Parameter(_) if self.format == Format::Html => {
                return mathml::identifier(&self.symbols.name(symbol))
            }
            Symbol::Parameter(_) | Symbol::Lane(_) => return self.symbols.name(symbol),
        };
        let index = (j + 1).to_string();
        match self.format {
            Format::Text => subscript(text, &index, self.format),
            Format::Latex => subscript(tex, &index, self.format),
            Format::Html => mathml::msub(&markup, &mathml::mn(&index)),
        }
    }
}

impl Names<'_> {
    /// A floating base's coordinate as the expanded equations print it (`qw`, `\omega_{x}`).
    fn base(&self, symbol: Symbol, base: BaseCoordinate) -> String {
        let format = match self.format {
            Format::Text => return base.name(),
            Format::Latex => PrintFormat::Latex,
            Format::Html => PrintFormat::MathMl,
        };
        Printer::new(self.symbols, format).print_symbol(symbol)
    }
}

/// The thesis's name of a joint's sine or cosine: `("s", "3")` for sin q3, the joints numbered
/// past a floating base's coordinates; `None` for any other instruction.
fn abbreviation(symbols: &SymbolTable, instr: &Instr) -> Option<(&'static str, String)> {
    let (letter, q) = match instr {
        Instr::Sin(Operand::Input(q @ Symbol::Position(_))) => ("s", q),
        Instr::Cos(Operand::Input(q @ Symbol::Position(_))) => ("c", q),
        _ => return None,
    };
    match symbols.coordinate(*q)? {
        Coordinate::Joint(j) => Some((letter, (u32::from(j) + 1).to_string())),
        Coordinate::Base(_) => None,
    }
}

/// `t12` in text, `t_{12}` in LaTeX, t with subscript 12 in MathML.
fn subscript(name: &str, index: &str, format: Format) -> String {
    match format {
        Format::Text => format!("{name}{index}"),
        Format::Latex => format!("{name}_{{{index}}}"),
        Format::Html => mathml::msub(&mathml::mi(name), &mathml::mn(index)),
    }
}

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
use rne_symbolic::{ExprGraph, Symbol, SymbolTable};

use super::entries::Section;
use super::sections::label;
use crate::CliError;

/// What was printed of a program.
#[derive(Copy, Clone, Debug)]
pub struct CompactPrinted {
    /// Lines of the program printed.
    pub lines: usize,
    /// Lines of the whole program (operations and the entries not named by one).
    pub total: usize,
}

/// Prints the program of `sections` in text or LaTeX, at most `max_size` bytes of it.
pub fn print(
    graph: &ExprGraph,
    sections: &[Section],
    latex: bool,
    max_size: usize,
    out: &mut dyn Write,
) -> Result<CompactPrinted, CliError> {
    let keys: Vec<_> = sections.iter().flat_map(|s| s.entries.iter()).collect();
    let roots: Vec<_> = keys.iter().map(|(_, id)| *id).collect();
    let program = Program::lower(graph, &roots);
    let names = Names::new(&program, graph.symbols(), latex, |k| {
        label(&keys[k].0, latex)
    });
    let comment = if latex { "%" } else { "#" };
    writeln!(
        out,
        "\n{comment} {} operations ({}), one a line; s_k = sin q_k, c_k = cos q_k, t_k intermediate quantities",
        program.op_count().total(),
        program.op_count()
    )?;
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
    latex: bool,
}

impl<'a> Names<'a> {
    fn new(
        program: &Program,
        symbols: &'a SymbolTable,
        latex: bool,
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
            .map(|(t, instr)| match (named_output[t], instr) {
                (Some(k), _) => outputs[k].clone(),
                (None, Instr::Sin(Operand::Input(Symbol::Position(j)))) => {
                    subscript("s", &(j + 1).to_string(), latex)
                }
                (None, Instr::Cos(Operand::Input(Symbol::Position(j)))) => {
                    subscript("c", &(j + 1).to_string(), latex)
                }
                _ => {
                    next += 1;
                    subscript("t", &next.to_string(), latex)
                }
            })
            .collect();
        Names {
            temps,
            named_output,
            outputs,
            symbols,
            latex,
        }
    }

    /// Every line: one per instruction, then the entries no instruction is named after.
    fn lines(&self, program: &Program) -> Vec<String> {
        let (equals, end) = if self.latex {
            (" &= ", " \\\\")
        } else {
            (" = ", "")
        };
        let mut lines: Vec<String> = program
            .instrs
            .iter()
            .enumerate()
            .map(|(t, instr)| format!("{}{equals}{}{end}\n", self.temps[t], self.instr(instr)))
            .collect();
        for (k, o) in program.outputs.iter().enumerate() {
            let named = matches!(o, Operand::Temp(t) if self.named_output[*t as usize] == Some(k));
            if !named {
                lines.push(format!(
                    "{}{equals}{}{end}\n",
                    self.outputs[k],
                    self.operand(*o)
                ));
            }
        }
        lines
    }

    fn instr(&self, instr: &Instr) -> String {
        let o = |x: Operand| self.operand(x);
        let times = if self.latex { " \\, " } else { " * " };
        let function = |f: &str, x: Operand| match self.latex {
            true => format!("\\{f}({})", o(x)),
            false => format!("{f}({})", o(x)),
        };
        match *instr {
            Instr::Add(a, b) => format!("{} + {}", o(a), o(b)),
            Instr::Sub(a, b) => format!("{} - {}", o(a), o(b)),
            Instr::Mul(a, b) => format!("{}{times}{}", o(a), o(b)),
            Instr::Div(a, b) if self.latex => format!("\\frac{{{}}}{{{}}}", o(a), o(b)),
            Instr::Div(a, b) => format!("{} / {}", o(a), o(b)),
            Instr::Neg(a) => format!("-{}", o(a)),
            Instr::Sin(a) => function("sin", a),
            Instr::Cos(a) => function("cos", a),
            Instr::Sqrt(a) if self.latex => format!("\\sqrt{{{}}}", o(a)),
            Instr::Sqrt(a) => function("sqrt", a),
            Instr::Sign(a) if self.latex => format!("\\operatorname{{sign}}({})", o(a)),
            Instr::Sign(a) => function("sign", a),
            Instr::MulAdd(a, b, c) => format!("{}{times}{} + {}", o(a), o(b), o(c)),
            Instr::MulSub(a, b, c) => format!("{}{times}{} - {}", o(a), o(b), o(c)),
            Instr::NegMulAdd(a, b, c) => format!("{} - {}{times}{}", o(c), o(a), o(b)),
        }
    }

    fn operand(&self, operand: Operand) -> String {
        match operand {
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => self.temps[t as usize].clone(),
            Operand::Const(c) if c < 0.0 => format!("({c})"),
            Operand::Const(c) => format!("{c}"),
            Operand::Input(s) => self.input(s),
        }
    }

    fn input(&self, symbol: Symbol) -> String {
        let (text, tex, j) = match symbol {
            Symbol::Position(j) => ("q", "q", j),
            Symbol::Velocity(j) => ("Dq", "\\dot{q}", j),
            Symbol::Acceleration(j) => ("DDq", "\\ddot{q}", j),
            Symbol::Force(j) => ("tau", "\\tau", j),
            Symbol::Parameter(_) | Symbol::Lane(_) => return self.symbols.name(symbol),
        };
        subscript(
            if self.latex { tex } else { text },
            &(j + 1).to_string(),
            self.latex,
        )
    }
}

/// `t12` in text, `t_{12}` in LaTeX.
fn subscript(name: &str, index: &str, latex: bool) -> String {
    match latex {
        true => format!("{name}_{{{index}}}"),
        false => format!("{name}{index}"),
    }
}

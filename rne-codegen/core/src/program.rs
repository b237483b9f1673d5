//! The straight-line program a kernel is emitted from, and its lowering from the graph.
//!
//! Lowering turns the hash-consed DAG (where common subexpressions are already shared and
//! constants folded) into SSA instructions in topological order, absorbing negations into
//! subtractions: `a + (−b)` becomes `a − b`, and a negation is only computed when something
//! other than an addition uses it. Only the nodes the outputs need are lowered (dead-code
//! elimination).

use std::collections::HashMap;

use rne_symbolic::{ExprGraph, Id, Node, OpCount, Real, Symbol};

/// An operand: a previous instruction's result, a constant or an input.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Operand {
    /// The result of instruction `i`.
    Temp(u32),
    /// A constant.
    Const(f64),
    /// A joint variable or a runtime parameter.
    Input(Symbol),
}

/// One operation.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Instr {
    /// `a + b`.
    Add(Operand, Operand),
    /// `a − b`.
    Sub(Operand, Operand),
    /// `a · b`.
    Mul(Operand, Operand),
    /// `a / b`.
    Div(Operand, Operand),
    /// `−a`.
    Neg(Operand),
    /// `sin a`.
    Sin(Operand),
    /// `cos a`.
    Cos(Operand),
    /// `sqrt a`.
    Sqrt(Operand),
    /// `sign a`.
    Sign(Operand),
}

impl Instr {
    /// The operands, in order.
    pub fn operands(&self) -> Vec<Operand> {
        match *self {
            Instr::Add(a, b) | Instr::Sub(a, b) | Instr::Mul(a, b) | Instr::Div(a, b) => vec![a, b],
            Instr::Neg(a) | Instr::Sin(a) | Instr::Cos(a) | Instr::Sqrt(a) | Instr::Sign(a) => {
                vec![a]
            }
        }
    }
}

/// A straight-line program: instructions in dependency order and the outputs.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Program {
    /// Instructions; an instruction only uses earlier ones.
    pub instrs: Vec<Instr>,
    /// The values returned, in order.
    pub outputs: Vec<Operand>,
}

impl Program {
    /// Lowers the graph nodes needed by `outputs`.
    pub fn lower(graph: &ExprGraph, outputs: &[Id]) -> Program {
        let nodes = graph.reachable(outputs);
        let mut negation_needed: HashMap<Id, bool> = HashMap::new();
        for &id in &nodes {
            let node = graph.node(id);
            let absorbs = matches!(node, Node::Add(..));
            for child in node.children() {
                if matches!(graph.node(child), Node::Neg(_)) {
                    *negation_needed.entry(child).or_default() |= !absorbs;
                }
            }
        }
        for &o in outputs {
            if matches!(graph.node(o), Node::Neg(_)) {
                negation_needed.insert(o, true);
            }
        }

        let mut program = Program::default();
        let mut operand: HashMap<Id, Operand> = HashMap::new();
        for &id in &nodes {
            let op = |c: Id| operand[&c];
            let value = match graph.node(id) {
                Node::Const(c) => Operand::Const(c.value()),
                Node::Symbol(s) => Operand::Input(s),
                Node::Neg(a) => {
                    if !negation_needed.get(&id).copied().unwrap_or(false) {
                        continue;
                    }
                    program.push(Instr::Neg(op(a)))
                }
                Node::Add(a, b) => {
                    let instr = match (graph.node(a), graph.node(b)) {
                        (_, Node::Neg(nb)) => Instr::Sub(op(a), op(nb)),
                        (Node::Neg(na), _) => Instr::Sub(op(b), op(na)),
                        _ => Instr::Add(op(a), op(b)),
                    };
                    program.push(instr)
                }
                Node::Mul(a, b) => program.push(Instr::Mul(op(a), op(b))),
                Node::Div(a, b) => program.push(Instr::Div(op(a), op(b))),
                Node::Sin(a) => program.push(Instr::Sin(op(a))),
                Node::Cos(a) => program.push(Instr::Cos(op(a))),
                Node::Sqrt(a) => program.push(Instr::Sqrt(op(a))),
                Node::Sign(a) => program.push(Instr::Sign(op(a))),
            };
            operand.insert(id, value);
        }
        program.outputs = outputs.iter().map(|o| operand[o]).collect();
        program
    }

    fn push(&mut self, instr: Instr) -> Operand {
        self.instrs.push(instr);
        Operand::Temp(self.instrs.len() as u32 - 1)
    }

    /// The operations one call performs (each instruction once).
    pub fn op_count(&self) -> OpCount {
        let mut count = OpCount::default();
        for instr in &self.instrs {
            match instr {
                Instr::Add(..) | Instr::Sub(..) => count.add += 1,
                Instr::Mul(..) => count.mul += 1,
                Instr::Div(..) => count.div += 1,
                Instr::Neg(_) => count.neg += 1,
                Instr::Sin(_) => count.sin += 1,
                Instr::Cos(_) => count.cos += 1,
                Instr::Sqrt(_) => count.sqrt += 1,
                Instr::Sign(_) => count.sign += 1,
            }
        }
        count
    }

    /// How many times each instruction's result is used (outputs count as uses).
    pub fn use_counts(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.instrs.len()];
        let operands = self
            .instrs
            .iter()
            .flat_map(Instr::operands)
            .chain(self.outputs.iter().copied());
        for operand in operands {
            if let Operand::Temp(t) = operand {
                uses[t as usize] += 1;
            }
        }
        uses
    }

    /// Evaluates the program in any [`Real`] scalar, operation by operation as the emitted Rust
    /// does — in `f64` the results are bit-for-bit those of the generated function.
    pub fn eval<T: Real>(&self, input: impl Fn(Symbol) -> T) -> Vec<T> {
        let mut temps: Vec<T> = Vec::with_capacity(self.instrs.len());
        let value = |o: Operand, temps: &[T]| match o {
            Operand::Temp(t) => temps[t as usize],
            Operand::Const(c) => T::from_f64(c),
            Operand::Input(s) => input(s),
        };
        for instr in &self.instrs {
            let v = |o| value(o, &temps);
            let x = match *instr {
                Instr::Add(a, b) => v(a) + v(b),
                Instr::Sub(a, b) => v(a) - v(b),
                Instr::Mul(a, b) => v(a) * v(b),
                Instr::Div(a, b) => v(a) / v(b),
                Instr::Neg(a) => -v(a),
                Instr::Sin(a) => v(a).sin(),
                Instr::Cos(a) => v(a).cos(),
                Instr::Sqrt(a) => v(a).sqrt(),
                Instr::Sign(a) => v(a).sign(),
            };
            temps.push(x);
        }
        self.outputs.iter().map(|&o| value(o, &temps)).collect()
    }
}

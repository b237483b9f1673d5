//! A latency model of the emitted arithmetic: when each value of a kernel is ready, in
//! cycles from the call, if the processor ran every operation as soon as its operands were
//! ready. The optimiser orders sums by it ([`crate::distribute_constants`]) and `rne stats`
//! reports each kernel's critical path with it ([`Program::critical_path`]): the time a
//! kernel cannot go below however many execution units the core has.
//!
//! The cycle counts are those of a current x86-64 core (Agner Fog, *Instruction tables*,
//! 2022: addition, multiplication and fused multiply-add 3–4 cycles, division ~13, square
//! root ~20); a joint's sine and cosine, computed with the runtime's polynomial `sin_cos`,
//! are ~40.

use rne_symbolic::Node;

use crate::program::{Instr, Operand, Program};

/// The cycles from an operation's last operand to its result.
fn cycles(operation: Operation) -> u32 {
    match operation {
        Operation::Leaf => 0,
        Operation::Sign => 1,
        Operation::Arithmetic => 3,
        Operation::Fused => 4,
        Operation::Division => 13,
        Operation::SquareRoot => 20,
        Operation::Trigonometric => 40,
    }
}

/// The kinds of operation the model tells apart.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Operation {
    /// An input or a constant: ready at the call.
    Leaf,
    /// Negation or sign: a bit operation.
    Sign,
    /// Addition, subtraction, multiplication.
    Arithmetic,
    /// Fused multiply-add.
    Fused,
    Division,
    SquareRoot,
    /// Sine or cosine.
    Trigonometric,
}

/// The cycles graph node `node` takes after its last operand.
pub(crate) fn node_cycles(node: Node) -> u32 {
    cycles(match node {
        Node::Const(_) | Node::Symbol(_) => Operation::Leaf,
        Node::Neg(_) | Node::Sign(_) => Operation::Sign,
        Node::Add(..) | Node::Mul(..) => Operation::Arithmetic,
        Node::Div(..) => Operation::Division,
        Node::Sqrt(_) => Operation::SquareRoot,
        Node::Sin(_) | Node::Cos(_) => Operation::Trigonometric,
    })
}

/// The cycles instruction `instr` takes after its last operand.
pub(crate) fn instr_cycles(instr: Instr) -> u32 {
    cycles(match instr {
        Instr::Neg(_) | Instr::Sign(_) => Operation::Sign,
        Instr::Add(..) | Instr::Sub(..) | Instr::Mul(..) => Operation::Arithmetic,
        Instr::MulAdd(..) | Instr::MulSub(..) | Instr::NegMulAdd(..) => Operation::Fused,
        Instr::Div(..) => Operation::Division,
        Instr::Sqrt(_) => Operation::SquareRoot,
        Instr::Sin(_) | Instr::Cos(_) => Operation::Trigonometric,
    })
}

impl Program {
    /// The critical path in modelled cycles: when the last output is ready if every
    /// instruction ran as soon as its operands were (module docs). With the operation count
    /// it bounds the kernel's time from both sides: no faster than this path, no faster than
    /// the operations divided by the arithmetic units.
    pub fn critical_path(&self) -> u32 {
        let mut ready: Vec<u32> = Vec::with_capacity(self.instrs.len());
        let at = |o: Operand, ready: &[u32]| match o {
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => ready[t as usize],
            Operand::Const(_) | Operand::Input(_) => 0,
        };
        for &instr in &self.instrs {
            let operands = instr.operands().map(|o| at(o, &ready)).max().unwrap_or(0);
            ready.push(operands + instr_cycles(instr));
        }
        self.outputs
            .iter()
            .map(|&o| at(o, &ready))
            .max()
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use crate::program::Program;
    use rne_symbolic::{ExprGraph, SymbolTable};

    fn program(text: &str) -> Program {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]));
        let root = g.parse_sexpr(text).unwrap();
        Program::lower(&g, &[root])
    }

    /// The path follows the longest chain of dependent operations, not their number.
    #[test]
    fn the_critical_path_is_the_longest_chain() {
        assert_eq!(program("x").critical_path(), 0);
        // Three independent products summed in two levels: 3 + 3 + 3.
        assert_eq!(
            program("(+ (+ (* x y) (* y z)) (* x z))").critical_path(),
            9
        );
        // sin (40) then a product (3) then a division (13).
        assert_eq!(program("(/ (* (sin x) y) z)").critical_path(), 56);
    }
}

//! An order of a program's instructions that keeps few values alive at once, so that a
//! register allocator that takes the instructions in order (Cranelift's) spills less.
//!
//! Bottom-up list scheduling for register pressure (the "register reduction" heuristic of
//! Goodman and Hsu, *Code scheduling and register allocation in large basic blocks*, ICS 1988):
//! the program is ordered from its end. An instruction is ready once every instruction that
//! reads its value has been placed. Placing it ends its value's life (seen from the end) and
//! starts the lives of its operands not yet alive; of the ready instructions, the one that
//! frees most and starts fewest is placed, the latest in the program's order on a tie.
//! Only the order changes: every instruction keeps its operation and operands, so every value
//! and every bit of the results is the same.

use std::collections::BinaryHeap;

use crate::program::{Operand, Program};

/// The most operands an instruction reads (a multiply-add's three).
const MOST_OPERANDS: i32 = 3;

impl Program {
    /// The program with its instructions in an order of low register pressure (module docs);
    /// the outputs are the same values.
    pub fn in_register_order(&self) -> Program {
        let order = RegisterOrder::new(self).run();
        self.reordered(&order)
    }

    /// The program with its instructions in `order` (a permutation in which every instruction
    /// comes after the ones it reads), renumbered.
    fn reordered(&self, order: &[u32]) -> Program {
        let mut index = vec![0u32; self.instrs.len()];
        for (new, &old) in order.iter().enumerate() {
            index[old as usize] = new as u32;
        }
        let renumber = |o: Operand| match o {
            Operand::Temp(t) => Operand::Temp(index[t as usize]),
            Operand::Lane { temp, lane } => Operand::Lane {
                temp: index[temp as usize],
                lane,
            },
            other => other,
        };
        Program {
            instrs: order
                .iter()
                .map(|&old| self.instrs[old as usize].map_operands(renumber))
                .collect(),
            outputs: self.outputs.iter().map(|&o| renumber(o)).collect(),
        }
    }
}

/// The state of the bottom-up scheduling of one program.
struct RegisterOrder {
    /// Each instruction's distinct operands that are instructions' values, instruction after
    /// instruction: those of instruction `i` at `reads[read_start[i]..read_start[i + 1]]`.
    reads: Vec<u32>,
    read_start: Vec<u32>,
    /// The instructions reading each value, likewise by `reader_start`.
    readers: Vec<u32>,
    reader_start: Vec<u32>,
    /// How many of each value's readers are still to be placed.
    readers_left: Vec<u32>,
    /// Whether each value is alive below the point reached: read below, not yet computed.
    alive: Vec<bool>,
    /// The ready instructions by score ([`RegisterOrder::score`] + [`MOST_OPERANDS`]), the
    /// latest on top. A score only rises, so an instruction found in a lower heap than its
    /// score's was moved up and is skipped there.
    ready: [BinaryHeap<u32>; (MOST_OPERANDS + 2) as usize],
    /// Each instruction's score while it is ready.
    score: Vec<Option<i32>>,
}

impl RegisterOrder {
    fn new(program: &Program) -> RegisterOrder {
        let n = program.instrs.len();
        let mut reads = Vec::with_capacity(2 * n);
        let mut read_start = Vec::with_capacity(n + 1);
        let mut readers_left = vec![0u32; n];
        for instr in &program.instrs {
            read_start.push(reads.len() as u32);
            for t in instr.operands().filter_map(Operand::temp) {
                if !reads[*read_start.last().unwrap() as usize..].contains(&t) {
                    reads.push(t);
                    readers_left[t as usize] += 1;
                }
            }
        }
        read_start.push(reads.len() as u32);
        let mut reader_start = Vec::with_capacity(n + 1);
        let mut total = 0;
        for &count in &readers_left {
            reader_start.push(total);
            total += count;
        }
        reader_start.push(total);
        let mut filled = reader_start.clone();
        let mut readers = vec![0u32; total as usize];
        for i in 0..n {
            for &t in &reads[read_start[i] as usize..read_start[i + 1] as usize] {
                readers[filled[t as usize] as usize] = i as u32;
                filled[t as usize] += 1;
            }
        }
        let mut order = RegisterOrder {
            reads,
            read_start,
            readers,
            reader_start,
            readers_left,
            alive: vec![false; n],
            ready: Default::default(),
            score: vec![None; n],
        };
        for i in 0..n {
            if order.readers_left[i] == 0 {
                order.make_ready(i as u32);
            }
        }
        order
    }

    /// Instruction `i`'s distinct operands that are instructions' values.
    fn reads_of(&self, i: u32) -> std::ops::Range<usize> {
        self.read_start[i as usize] as usize..self.read_start[i as usize + 1] as usize
    }

    /// Values freed minus values started by placing `i` now.
    fn score(&self, i: u32) -> i32 {
        let started = self.reads[self.reads_of(i)]
            .iter()
            .filter(|&&t| !self.alive[t as usize])
            .count() as i32;
        i32::from(self.alive[i as usize]) - started
    }

    fn make_ready(&mut self, i: u32) {
        let score = self.score(i);
        self.score[i as usize] = Some(score);
        self.ready[(score + MOST_OPERANDS) as usize].push(i);
    }

    /// The instructions in the order found, first to last.
    fn run(mut self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.score.len());
        while let Some(i) = self.next() {
            order.push(i);
            self.place(i);
        }
        order.reverse();
        order
    }

    /// The ready instruction of highest score, the latest on a tie.
    fn next(&mut self) -> Option<u32> {
        for bucket in (0..self.ready.len()).rev() {
            while let Some(i) = self.ready[bucket].pop() {
                if self.score[i as usize] == Some(bucket as i32 - MOST_OPERANDS) {
                    return Some(i);
                }
            }
        }
        None
    }

    /// Places `i` above everything placed so far: its operands come alive, and the values
    /// whose last reader it was become ready.
    fn place(&mut self, i: u32) {
        self.score[i as usize] = None;
        for k in self.reads_of(i) {
            let t = self.reads[k];
            if !self.alive[t as usize] {
                self.alive[t as usize] = true;
                self.raise_ready_readers(t);
            }
            self.readers_left[t as usize] -= 1;
            if self.readers_left[t as usize] == 0 {
                self.make_ready(t);
            }
        }
    }

    /// Value `t` came alive: each ready reader of it starts one value fewer.
    fn raise_ready_readers(&mut self, t: u32) {
        let range =
            self.reader_start[t as usize] as usize..self.reader_start[t as usize + 1] as usize;
        for k in range {
            let reader = self.readers[k];
            if let Some(score) = self.score[reader as usize] {
                self.score[reader as usize] = Some(score + 1);
                self.ready[(score + 1 + MOST_OPERANDS) as usize].push(reader);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::program::Program;
    use rne_symbolic::{ExprGraph, Symbol, SymbolTable};

    fn lowered(outputs: &[&str]) -> Program {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]));
        let roots: Vec<_> = outputs.iter().map(|o| g.parse_sexpr(o).unwrap()).collect();
        Program::lower(&g, &roots)
    }

    /// The most values alive at once: computed, read later (outputs are written when computed).
    fn peak_alive(program: &Program) -> usize {
        let mut last_read = vec![0usize; program.instrs.len()];
        for (k, instr) in program.instrs.iter().enumerate() {
            for t in instr.operands().filter_map(|o| o.temp()) {
                last_read[t as usize] = k;
            }
        }
        (0..program.instrs.len())
            .map(|k| (0..k).filter(|&t| last_read[t] >= k).count())
            .max()
            .unwrap_or(0)
    }

    const SHARED: [&str; 4] = [
        "(* (sin x) (cos y))",
        "(/ (+ (* (sin x) (cos y)) (* z (sin z))) (+ 2 (* (cos x) (cos x))))",
        "(- (sqrt (+ 1 (* y y))) (* (sin x) (cos y)))",
        "(+ (* 3 (sign z)) (+ (* x (sin z)) (* (cos x) (cos y))))",
    ];

    /// Reordering moves instructions only: the same outputs, bit for bit, with and without
    /// fused multiply-adds, and every instruction after the ones it reads (`eval` reads each
    /// operand from the values computed before it).
    #[test]
    fn the_register_order_computes_the_same_bits() {
        let input = |s: Symbol| match s {
            Symbol::Position(k) => 0.3 + 0.7 * f64::from(k),
            Symbol::Velocity(k) => -1.1 + 0.4 * f64::from(k),
            _ => 0.5,
        };
        for fused in [false, true] {
            let mut program = lowered(&SHARED);
            if fused {
                program = program.fuse_multiply_add();
            }
            let ordered = program.in_register_order();
            assert_eq!(ordered.instrs.len(), program.instrs.len());
            assert_eq!(ordered.op_count(), program.op_count());
            let bits = |p: &Program| {
                p.eval_f64(&input)
                    .iter()
                    .map(|v| v.to_bits())
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&ordered), bits(&program), "fused: {fused}");
        }
    }

    /// Values the graph's order computes long before their use are computed next to it: the
    /// four products of `tests/filetests/order_pressure.test` are alive together in the
    /// lowering's order, at most three values are in the register order.
    #[test]
    fn the_register_order_keeps_fewer_values_alive() {
        let program = lowered(&[
            "(* x y)",
            "(* y z)",
            "(* x z)",
            "(* z z)",
            "(+ (+ (* x y) (* y z)) (+ (* x z) (* z z)))",
        ]);
        assert_eq!(peak_alive(&program), 4);
        assert_eq!(peak_alive(&program.in_register_order()), 3);
        // And never more than the lowering's order on the shared expressions.
        let shared = lowered(&SHARED);
        assert!(peak_alive(&shared.in_register_order()) <= peak_alive(&shared));
    }
}

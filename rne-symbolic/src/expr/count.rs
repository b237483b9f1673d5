//! Operation counts of expression DAGs.

use std::fmt;
use std::ops::Add;

use super::graph::ExprGraph;
use super::node::{Id, Node};

/// Number of arithmetic operations needed to evaluate a set of expressions once, each shared
/// node counted once. A negation feeding an addition is a subtraction, and counted as one
/// addition; other negations are counted separately.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct OpCount {
    /// Multiplications.
    pub mul: usize,
    /// Additions and subtractions.
    pub add: usize,
    /// Divisions.
    pub div: usize,
    /// Negations that are not absorbed into a subtraction.
    pub neg: usize,
    /// Sines.
    pub sin: usize,
    /// Cosines.
    pub cos: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Signs (Coulomb friction).
    pub sign: usize,
}

impl OpCount {
    /// Total number of operations of any kind.
    pub fn total(&self) -> usize {
        self.mul + self.add + self.div + self.neg + self.sin + self.cos + self.sqrt + self.sign
    }

    /// Estimated cost in units of one addition, the cost model the code generator reports:
    /// addition, multiplication and negation 1, division and square root 4 (their latency
    /// relative to a multiplication on current x86-64 and AArch64 cores, throughput aside),
    /// and a sine–cosine pair 10 (the polynomial evaluation of `trig::sin_cos`, shared by
    /// the two), i.e. 5 each; a sign 2 (two comparisons and selects).
    pub fn cost(&self) -> usize {
        self.add
            + self.mul
            + self.neg
            + 4 * (self.div + self.sqrt)
            + 5 * (self.sin + self.cos)
            + 2 * self.sign
    }
}

impl Add for OpCount {
    type Output = OpCount;
    fn add(self, o: OpCount) -> OpCount {
        OpCount {
            mul: self.mul + o.mul,
            add: self.add + o.add,
            div: self.div + o.div,
            neg: self.neg + o.neg,
            sin: self.sin + o.sin,
            cos: self.cos + o.cos,
            sqrt: self.sqrt + o.sqrt,
            sign: self.sign + o.sign,
        }
    }
}

impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} mul, {} add, {} div, {} neg, {} sin, {} cos, {} sqrt",
            self.mul, self.add, self.div, self.neg, self.sin, self.cos, self.sqrt
        )?;
        if self.sign > 0 {
            write!(f, ", {} sign", self.sign)?;
        }
        Ok(())
    }
}

impl ExprGraph {
    /// Operations needed to evaluate `outputs` from the symbols, sharing common subexpressions.
    pub fn op_count(&self, outputs: &[Id]) -> OpCount {
        let nodes = self.reachable(outputs);
        let mut count = OpCount::default();
        // A negation is free when every use of it is an addition (which becomes a subtraction).
        let mut materialised = vec![false; nodes.last().map_or(0, |id| id.index() + 1)];
        for &o in outputs {
            materialised[o.index()] = true;
        }
        for &id in &nodes {
            let node = self.node(id);
            if !matches!(node, Node::Add(..)) {
                for c in node.children() {
                    if matches!(self.node(c), Node::Neg(_)) {
                        materialised[c.index()] = true;
                    }
                }
            }
        }
        for &id in &nodes {
            match self.node(id) {
                Node::Const(_) | Node::Symbol(_) => {}
                Node::Add(..) => count.add += 1,
                Node::Mul(..) => count.mul += 1,
                Node::Div(..) => count.div += 1,
                Node::Neg(_) => count.neg += usize::from(materialised[id.index()]),
                Node::Sin(_) => count.sin += 1,
                Node::Cos(_) => count.cos += 1,
                Node::Sqrt(_) => count.sqrt += 1,
                Node::Sign(_) => count.sign += 1,
            }
        }
        count
    }
}

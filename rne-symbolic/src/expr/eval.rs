//! Evaluation of expressions at a point, in any [`Real`] scalar type.

use super::graph::ExprGraph;
use super::node::{Id, Node, Symbol};
use crate::Real;

impl ExprGraph {
    /// The nodes needed to compute `outputs`, in increasing id order (children first).
    pub fn reachable(&self, outputs: &[Id]) -> Vec<Id> {
        let Some(max) = outputs.iter().max() else {
            return Vec::new();
        };
        let mut needed = vec![false; max.index() + 1];
        for o in outputs {
            needed[o.index()] = true;
        }
        for i in (0..needed.len()).rev() {
            if needed[i] {
                for c in self.node(Id::from_index(i)).children() {
                    needed[c.index()] = true;
                }
            }
        }
        needed
            .iter()
            .enumerate()
            .filter(|(_, &n)| n)
            .map(|(i, _)| Id::from_index(i))
            .collect()
    }

    /// Evaluates `outputs` with symbol values from `value`.
    pub fn eval<T: Real>(&self, outputs: &[Id], value: impl Fn(Symbol) -> T) -> Vec<T> {
        Evaluator::new(self, outputs).eval(self, value)
    }
}

/// A compiled evaluation order for a fixed set of outputs, reusable across many points.
#[derive(Clone, Debug)]
pub struct Evaluator {
    order: Vec<Id>,
    slot: Vec<u32>,
    outputs: Vec<Id>,
}

impl Evaluator {
    /// Prepares the evaluation of `outputs`.
    pub fn new(graph: &ExprGraph, outputs: &[Id]) -> Evaluator {
        let order = graph.reachable(outputs);
        let mut slot = vec![u32::MAX; order.last().map_or(0, |id| id.index() + 1)];
        for (k, id) in order.iter().enumerate() {
            slot[id.index()] = k as u32;
        }
        Evaluator {
            order,
            slot,
            outputs: outputs.to_vec(),
        }
    }

    /// Number of nodes evaluated per call.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Whether there is nothing to evaluate.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Evaluates the outputs at the point given by `value`.
    pub fn eval<T: Real>(&self, graph: &ExprGraph, value: impl Fn(Symbol) -> T) -> Vec<T> {
        let mut values: Vec<T> = Vec::with_capacity(self.order.len());
        for &id in &self.order {
            let v = |c: Id| values[self.slot[c.index()] as usize];
            let x = match graph.node(id) {
                Node::Const(c) => T::from_f64(c.value()),
                Node::Symbol(s) => value(s),
                Node::Add(a, b) => v(a) + v(b),
                Node::Mul(a, b) => v(a) * v(b),
                Node::Div(a, b) => v(a) / v(b),
                Node::Neg(a) => -v(a),
                Node::Sin(a) => v(a).sin(),
                Node::Cos(a) => v(a).cos(),
                Node::Sqrt(a) => v(a).sqrt(),
                Node::Sign(a) => v(a).sign(),
            };
            values.push(x);
        }
        self.outputs
            .iter()
            .map(|o| values[self.slot[o.index()] as usize])
            .collect()
    }
}

//! Symbolic differentiation.

use rustc_hash::{FxHashMap, FxHashSet};

use super::graph::ExprGraph;
use super::node::{Id, Node, Symbol};

/// Differentiates expressions of a graph with respect to one symbol, remembering the
/// derivative of every node it has visited so that the derivatives of many outputs share work.
///
/// The nodes already differentiated are closed under taking children, so each call visits
/// only the nodes below `expr` that no earlier call reached: differentiating k outputs costs
/// the size of their union, not k times the graph.
#[derive(Debug)]
pub struct Differentiator {
    /// The symbol whose derivative is one; `None` when the seeds are given
    /// ([`Differentiator::along`]).
    wrt: Option<Symbol>,
    memo: FxHashMap<Id, Id>,
}

impl Differentiator {
    /// A differentiator with respect to `wrt`.
    pub fn new(wrt: Symbol) -> Differentiator {
        Differentiator {
            wrt: Some(wrt),
            memo: FxHashMap::default(),
        }
    }

    /// A differentiator along a direction: the derivative of each symbol of `seeds` is the
    /// node given with it, of every other symbol zero (a Jacobian–vector product, the
    /// direction's components being the seeds).
    pub fn along(seeds: &[(Symbol, Id)], graph: &mut ExprGraph) -> Differentiator {
        let mut memo: FxHashMap<Id, Id> = FxHashMap::default();
        for &(symbol, seed) in seeds {
            memo.insert(graph.symbol(symbol), seed);
        }
        Differentiator { wrt: None, memo }
    }

    /// ∂expr/∂wrt (or along the seeds), built in `graph` (chain rule; sin' = cos, cos' = −sin, sqrt' = 1/(2 sqrt)).
    pub fn derivative(&mut self, graph: &mut ExprGraph, expr: Id) -> Id {
        if let Some(&d) = self.memo.get(&expr) {
            return d;
        }
        for id in self.new_nodes(graph, expr) {
            let d = |c: Id| self.memo[&c];
            let derivative = match graph.node(id) {
                Node::Const(_) => graph.zero(),
                Node::Symbol(s) if Some(s) == self.wrt => graph.one(),
                Node::Symbol(_) => graph.zero(),
                Node::Add(a, b) => {
                    let (da, db) = (d(a), d(b));
                    graph.add(da, db)
                }
                Node::Mul(a, b) => {
                    let (da, db) = (d(a), d(b));
                    let left = graph.mul(da, b);
                    let right = graph.mul(a, db);
                    graph.add(left, right)
                }
                Node::Div(a, b) => {
                    // (a/b)' = (a' − (a/b) b') / b
                    let (da, db) = (d(a), d(b));
                    let quotient = graph.div(a, b);
                    let correction = graph.mul(quotient, db);
                    let numerator = graph.sub(da, correction);
                    graph.div(numerator, b)
                }
                Node::Neg(a) => {
                    let da = d(a);
                    graph.neg(da)
                }
                Node::Sin(a) => {
                    let da = d(a);
                    let c = graph.cos(a);
                    graph.mul(c, da)
                }
                Node::Cos(a) => {
                    let da = d(a);
                    let s = graph.sin(a);
                    let ds = graph.mul(s, da);
                    graph.neg(ds)
                }
                // Zero wherever it is differentiable (everywhere but at 0).
                Node::Sign(_) => graph.zero(),
                Node::Sqrt(a) => {
                    let da = d(a);
                    let two = graph.constant(2.0);
                    let denominator = graph.mul(two, id);
                    graph.div(da, denominator)
                }
            };
            self.memo.insert(id, derivative);
        }
        self.memo[&expr]
    }

    /// The nodes below `expr` (itself included) without a derivative yet, in increasing id
    /// order (children first): a depth-first walk that stops at differentiated nodes.
    fn new_nodes(&self, graph: &ExprGraph, expr: Id) -> Vec<Id> {
        let mut seen: FxHashSet<Id> = FxHashSet::default();
        let mut stack = vec![expr];
        seen.insert(expr);
        let mut found = Vec::new();
        while let Some(id) = stack.pop() {
            found.push(id);
            for child in graph.node(id).children() {
                if !self.memo.contains_key(&child) && seen.insert(child) {
                    stack.push(child);
                }
            }
        }
        found.sort_unstable();
        found
    }
}

impl ExprGraph {
    /// ∂expr/∂wrt.
    pub fn derivative(&mut self, expr: Id, wrt: Symbol) -> Id {
        Differentiator::new(wrt).derivative(self, expr)
    }
}

//! Substituting expressions for symbols, in place.

use super::graph::ExprGraph;
use super::node::{Id, Node, Symbol};

impl ExprGraph {
    /// `roots` with every symbol `s` for which `image(s)` is `Some(e)` replaced by `e` (a node
    /// of this graph), rebuilt through the simplifying constructors so that constants fold
    /// again (`(x + q)|q=0` is `x`). Symbols without an image stay.
    pub fn substitute(&mut self, roots: &[Id], image: impl Fn(Symbol) -> Option<Id>) -> Vec<Id> {
        let nodes = self.reachable(roots);
        let mut rebuilt = vec![None; nodes.last().map_or(0, |id| id.index() + 1)];
        for id in nodes {
            let r = |c: Id| rebuilt[c.index()].expect("children are rebuilt first");
            let node = self.node(id);
            let new = match node {
                Node::Const(_) => id,
                Node::Symbol(s) => image(s).unwrap_or(id),
                Node::Add(a, b) => self.add(r(a), r(b)),
                Node::Mul(a, b) => self.mul(r(a), r(b)),
                Node::Div(a, b) => self.div(r(a), r(b)),
                Node::Neg(a) => self.neg(r(a)),
                Node::Sin(a) => self.sin(r(a)),
                Node::Cos(a) => self.cos(r(a)),
                Node::Sqrt(a) => self.sqrt(r(a)),
                Node::Sign(a) => self.sign(r(a)),
            };
            rebuilt[id.index()] = Some(new);
        }
        roots
            .iter()
            .map(|r| rebuilt[r.index()].expect("roots are rebuilt"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::SymbolTable;

    #[test]
    fn substituted_expressions_fold_again() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["q1", "q2"]));
        let (x, y) = (g.symbol(Symbol::Position(0)), g.symbol(Symbol::Position(1)));
        let s = g.sin(y);
        let xs = g.mul(x, s);
        let sum = g.add(xs, y);
        let zero = g.zero();
        let two = g.constant(2.0);
        let out = g.substitute(&[sum, xs], |sym| match sym {
            Symbol::Position(1) => Some(zero),
            Symbol::Position(0) => Some(two),
            _ => None,
        });
        assert_eq!(out, vec![zero, zero], "2 sin 0 + 0 folds to 0");
        let kept = g.substitute(&[sum], |_| None);
        assert_eq!(kept, vec![sum], "no image: the same node");
    }
}

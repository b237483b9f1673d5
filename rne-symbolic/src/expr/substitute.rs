//! Substitution of expressions for symbols.

use rustc_hash::FxHashMap;

use super::graph::ExprGraph;
use super::node::{Id, Node, Symbol};

impl ExprGraph {
    /// `outputs` with each symbol of `values` replaced by the node given with it.
    ///
    /// Every node below the outputs that reads a replaced symbol is rebuilt through the
    /// simplifying constructors, children first; a node that reads none is kept as it is, so
    /// the result shares it with whatever else uses it. The values are as any other nodes:
    /// the rebuilt expressions may fold constants into them or cancel terms across them,
    /// which is why a derivative taken with a symbol constant is taken *before* the symbol
    /// is replaced (forward dynamics' derivatives, [`crate::dynamics::derivatives`]).
    pub fn substitute(&mut self, outputs: &[Id], values: &[(Symbol, Id)]) -> Vec<Id> {
        let mut image: FxHashMap<Id, Id> = FxHashMap::default();
        for id in self.reachable(outputs) {
            let node = self.node(id);
            let replaced = match node {
                Node::Symbol(s) => values.iter().find(|(v, _)| *v == s).map(|&(_, x)| x),
                _ => None,
            };
            if let Some(value) = replaced {
                image.insert(id, value);
                continue;
            }
            if !node.children().any(|c| image.contains_key(&c)) {
                continue;
            }
            let child = |c: Id| image.get(&c).copied().unwrap_or(c);
            let rebuilt = match node {
                Node::Const(_) | Node::Symbol(_) => id,
                Node::Add(a, b) => self.add(child(a), child(b)),
                Node::Mul(a, b) => self.mul(child(a), child(b)),
                Node::Div(a, b) => self.div(child(a), child(b)),
                Node::Neg(a) => self.neg(child(a)),
                Node::Sin(a) => self.sin(child(a)),
                Node::Cos(a) => self.cos(child(a)),
                Node::Sqrt(a) => self.sqrt(child(a)),
                Node::Sign(a) => self.sign(child(a)),
            };
            image.insert(id, rebuilt);
        }
        outputs
            .iter()
            .map(|o| image.get(o).copied().unwrap_or(*o))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::expr::{ExprGraph, Symbol, SymbolTable};

    /// `x·y + sin x` with x := y + 1 is `(y + 1)·y + sin(y + 1)`, and a node that does not
    /// read x (`y·y`) is the same node afterwards.
    #[test]
    fn replaced_symbols_are_rebuilt_and_other_nodes_kept() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y"]));
        let e = g.parse_sexpr("(+ (* x y) (sin x))").unwrap();
        let untouched = g.parse_sexpr("(* y y)").unwrap();
        let value = g.parse_sexpr("(+ y 1)").unwrap();
        let out = g.substitute(&[e, untouched], &[(Symbol::Position(0), value)]);
        let expected = g.parse_sexpr("(+ (* (+ y 1) y) (sin (+ y 1)))").unwrap();
        assert_eq!(out, vec![expected, untouched]);
    }

    /// The rebuilt nodes go through the simplifying constructors: x·2 with x := 0.5·y folds
    /// to the constant chain's product, 1·y = y.
    #[test]
    fn rebuilt_nodes_are_simplified() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y"]));
        let e = g.parse_sexpr("(* 2 x)").unwrap();
        let value = g.parse_sexpr("(* 0.5 y)").unwrap();
        let out = g.substitute(&[e], &[(Symbol::Position(0), value)]);
        assert_eq!(out, vec![g.symbol(Symbol::Position(1))]);
    }
}

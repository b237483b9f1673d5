//! Rebuilding expressions through the graph's simplifying constructors: substituting a symbol
//! (the joint variable at q = 0) and copying a model's expressions from the scratch graph the
//! spec is read into to the model's own graph (folding parameters into constants on request).

use std::collections::HashMap;

use crate::expr::{ExprGraph, Id, Mat3, Node, Symbol, Vec3};

/// Whether `expr` contains `symbol`.
pub(crate) fn mentions(graph: &ExprGraph, expr: Id, symbol: Symbol) -> bool {
    graph
        .reachable(&[expr])
        .into_iter()
        .any(|id| graph.node(id) == Node::Symbol(symbol))
}

/// `expr` with `symbol` replaced by `value` (a node of the same graph), rebuilt through the
/// simplifying constructors so that, e.g., `(d + q)|q=0` is `d`.
pub(crate) fn substitute(graph: &mut ExprGraph, expr: Id, symbol: Symbol, value: Id) -> Id {
    let mut image = HashMap::new();
    for id in graph.reachable(&[expr]) {
        let node = graph.node(id);
        let rebuilt = match node {
            Node::Symbol(s) if s == symbol => value,
            _ => rebuild(graph, node, &image),
        };
        image.insert(id, rebuilt);
    }
    image.get(&expr).copied().unwrap_or(expr)
}

/// Copies expressions from one graph into a new one, sharing the work across calls.
pub(crate) struct Transplant<'a, F> {
    from: &'a ExprGraph,
    to: ExprGraph,
    image: HashMap<Id, Id>,
    symbol: F,
}

impl<'a, F: FnMut(&mut ExprGraph, Symbol) -> Id> Transplant<'a, F> {
    /// A copier from `from` into `to` that maps every symbol through `symbol` (which builds
    /// its image in the target).
    pub(crate) fn new(from: &'a ExprGraph, to: ExprGraph, symbol: F) -> Transplant<'a, F> {
        Transplant {
            from,
            to,
            image: HashMap::new(),
            symbol,
        }
    }

    /// The image of `expr`.
    pub(crate) fn scalar(&mut self, expr: Id) -> Id {
        if let Some(&done) = self.image.get(&expr) {
            return done;
        }
        for id in self.from.reachable(&[expr]) {
            if self.image.contains_key(&id) {
                continue;
            }
            let rebuilt = match self.from.node(id) {
                Node::Symbol(s) => (self.symbol)(&mut self.to, s),
                node => rebuild(&mut self.to, node, &self.image),
            };
            self.image.insert(id, rebuilt);
        }
        self.image.get(&expr).copied().unwrap_or(expr)
    }

    /// The image of a vector.
    pub(crate) fn vector(&mut self, v: Vec3) -> Vec3 {
        v.map(|x| self.scalar(x))
    }

    /// The image of a matrix.
    pub(crate) fn matrix(&mut self, m: Mat3) -> Mat3 {
        m.map(|row| self.vector(row))
    }

    /// The target graph.
    pub(crate) fn finish(self) -> ExprGraph {
        self.to
    }
}

/// `node` rebuilt in `graph` with its children replaced by their images; a child without an
/// image (which the children-first order of `reachable` rules out) is kept as it is.
fn rebuild(graph: &mut ExprGraph, node: Node, image: &HashMap<Id, Id>) -> Id {
    let child = |c: Id| image.get(&c).copied().unwrap_or(c);
    match node {
        Node::Const(c) => graph.constant(c.value()),
        Node::Symbol(s) => graph.symbol(s),
        Node::Add(a, b) => graph.add(child(a), child(b)),
        Node::Mul(a, b) => graph.mul(child(a), child(b)),
        Node::Div(a, b) => graph.div(child(a), child(b)),
        Node::Neg(a) => graph.neg(child(a)),
        Node::Sin(a) => graph.sin(child(a)),
        Node::Cos(a) => graph.cos(child(a)),
        Node::Sqrt(a) => graph.sqrt(child(a)),
        Node::Sign(a) => graph.sign(child(a)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::SymbolTable;

    #[test]
    fn substitution_simplifies() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["q"]));
        let q = g.symbol(Symbol::Position(0));
        let d = g.symbol(Symbol::Parameter(0));
        let sum = g.add(d, q);
        let zero = g.zero();
        assert_eq!(substitute(&mut g, sum, Symbol::Position(0), zero), d);
        let c = g.cos(q);
        let product = g.mul(c, d);
        assert_eq!(substitute(&mut g, product, Symbol::Position(0), zero), d);
        assert!(mentions(&g, product, Symbol::Position(0)));
        assert!(!mentions(&g, d, Symbol::Position(0)));
    }

    #[test]
    fn transplant_folds_parameters() {
        let mut from = ExprGraph::default();
        let a = from.symbol(Symbol::Parameter(0));
        let two = from.constant(2.0);
        let e = from.mul(a, two);
        let s = from.sin(e);
        let mut copier = Transplant::new(&from, ExprGraph::default(), |g: &mut ExprGraph, _| {
            g.constant(std::f64::consts::FRAC_PI_4)
        });
        let image = copier.scalar(s);
        assert_eq!(copier.finish().as_const(image), Some(1.0));
    }
}

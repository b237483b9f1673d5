//! Reverse-mode (adjoint) symbolic differentiation: the gradient of one expression with
//! respect to many symbols in one backward sweep over the graph (Griewank & Walther,
//! *Evaluating Derivatives*, 2nd ed., SIAM 2008, §3.2, "the reverse mode").
//!
//! [`Differentiator`](super::Differentiator) is the forward mode: one sweep per symbol,
//! every output's derivative sharing it. The reverse mode is one sweep per output, every
//! symbol's derivative sharing it. For n outputs and m symbols the first builds m sweeps and
//! the second n; which is cheaper depends on how much of the graph each sweep touches, so the
//! dynamics build both and keep the cheaper ([`crate::dynamics::derivatives`]).

use super::graph::ExprGraph;
use super::node::{Id, Node, Symbol};

impl ExprGraph {
    /// `[∂expr/∂wrt₀, ∂expr/∂wrt₁, …]`, zero where `expr` does not depend on the symbol.
    ///
    /// Adjoints flow from `expr` to the symbols through the nodes that depend on one of `wrt`
    /// (others have no derivative to carry): for `a + b` the adjoint ā passes to both, for
    /// `a·b` as `ā·b` and `ā·a`, for `a/b` as `ā/b` and `−ā·(a/b)/b`, for `sin a` as
    /// `ā·cos a`, for `cos a` as `−ā·sin a`, for `sqrt a` as `ā/(2 sqrt a)`; `sign` is flat.
    /// A node's contributions are summed in the order its users are visited (decreasing
    /// id), so the result depends on the graph alone.
    pub fn gradient(&mut self, expr: Id, wrt: &[Symbol]) -> Vec<Id> {
        let one = self.one();
        self.gradient_seeded(&[(expr, one)], wrt)
    }

    /// The gradient of Σ_i wᵢ·exprᵢ for `seeds` (exprᵢ, wᵢ), the weights wᵢ taken as constants
    /// (a vector–Jacobian product): one backward sweep whose
    /// adjoints start at wᵢ on each exprᵢ. With a lane seed eₗ on each of several
    /// expressions, lane l of each partial is that of the expression seeded with eₗ
    /// ([`crate::dynamics::LanePartials`]).
    pub fn gradient_seeded(&mut self, seeds: &[(Id, Id)], wrt: &[Symbol]) -> Vec<Id> {
        let mut sweep = Sweep::new(self, seeds, wrt);
        let nodes = std::mem::take(&mut sweep.nodes);
        let zero = self.zero();
        let mut gradient = vec![zero; wrt.len()];
        for &id in nodes.iter().rev() {
            if !sweep.depends(id) {
                continue;
            }
            let k = sweep.at(id);
            let terms = std::mem::take(&mut sweep.contributions[k]);
            let adjoint = self.sum(terms);
            if let Node::Symbol(s) = self.node(id) {
                let k = wrt.iter().position(|&w| w == s).expect("a symbol of wrt");
                gradient[k] = adjoint;
            } else {
                self.pass_adjoint(&mut sweep, id, adjoint);
            }
        }
        gradient
    }

    /// Passes the adjoint `adjoint` of the operation `id` to its operands that depend on a
    /// symbol, each times the operation's partial derivative with respect to it.
    fn pass_adjoint(&mut self, sweep: &mut Sweep, id: Id, adjoint: Id) {
        match self.node(id) {
            Node::Const(_) | Node::Sign(_) | Node::Symbol(_) => {}
            Node::Add(a, b) => {
                sweep.pass(a, adjoint);
                sweep.pass(b, adjoint);
            }
            Node::Neg(a) => sweep.pass(a, self.neg(adjoint)),
            Node::Mul(a, b) => {
                if sweep.depends(a) {
                    sweep.pass(a, self.mul(adjoint, b));
                }
                if sweep.depends(b) {
                    sweep.pass(b, self.mul(adjoint, a));
                }
            }
            Node::Div(a, b) => {
                if sweep.depends(a) {
                    sweep.pass(a, self.div(adjoint, b));
                }
                if sweep.depends(b) {
                    let scaled = self.mul(adjoint, id);
                    let quotient = self.div(scaled, b);
                    sweep.pass(b, self.neg(quotient));
                }
            }
            Node::Sin(a) => {
                let c = self.cos(a);
                sweep.pass(a, self.mul(adjoint, c));
            }
            Node::Cos(a) => {
                let s = self.sin(a);
                let product = self.mul(adjoint, s);
                sweep.pass(a, self.neg(product));
            }
            Node::Sqrt(a) => {
                let two = self.constant(2.0);
                let denominator = self.mul(two, id);
                sweep.pass(a, self.div(adjoint, denominator));
            }
        }
    }
}

/// The state of one backward sweep: the nodes below the seeded expressions (operands first)
/// and, by position among them, whether each depends on a symbol differentiated for and the
/// adjoint contributions it has received so far.
struct Sweep {
    nodes: Vec<Id>,
    /// Each node's position in `nodes`, by node index (`u32::MAX` off the sweep). Tables by
    /// position are much shorter than the graph below the expressions when other kernels'
    /// nodes sit in between.
    position: Vec<u32>,
    depends: Vec<bool>,
    contributions: Vec<Vec<Id>>,
}

impl Sweep {
    /// The sweep of `seeds` with respect to `wrt`, each seeded expression that depends on
    /// one of them holding its weight as its first contribution.
    fn new(graph: &ExprGraph, seeds: &[(Id, Id)], wrt: &[Symbol]) -> Sweep {
        let exprs: Vec<Id> = seeds.iter().map(|&(expr, _)| expr).collect();
        let nodes = graph.reachable(&exprs);
        let top = exprs.iter().map(|e| e.index()).max().unwrap_or(0);
        let mut position = vec![u32::MAX; top + 1];
        for (k, id) in nodes.iter().enumerate() {
            position[id.index()] = k as u32;
        }
        let mut sweep = Sweep {
            depends: vec![false; nodes.len()],
            contributions: vec![Vec::new(); nodes.len()],
            nodes,
            position,
        };
        for k in 0..sweep.nodes.len() {
            sweep.depends[k] = match graph.node(sweep.nodes[k]) {
                Node::Symbol(s) => wrt.contains(&s),
                node => node.children().any(|c| sweep.depends(c)),
            };
        }
        for &(expr, weight) in seeds {
            if sweep.depends(expr) {
                let k = sweep.at(expr);
                sweep.contributions[k].push(weight);
            }
        }
        sweep
    }

    /// `id`'s position in the sweep.
    fn at(&self, id: Id) -> usize {
        self.position[id.index()] as usize
    }

    /// Whether `id` depends on a symbol differentiated for.
    fn depends(&self, id: Id) -> bool {
        self.depends[self.at(id)]
    }

    /// Adds `value` to the adjoint of `child` if it depends on a symbol.
    fn pass(&mut self, child: Id, value: Id) {
        if self.depends(child) {
            let k = self.at(child);
            self.contributions[k].push(value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Differentiator, SymbolTable};
    use super::*;

    /// The reverse mode builds, for every symbol, an expression of the same value as the
    /// forward mode's derivative.
    #[test]
    fn the_gradient_equals_the_forward_derivatives() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]));
        let cases = [
            "(* (sin x) (cos y))",
            "(+ (* x (* x y)) (- (sqrt (+ z 3))))",
            "(/ (* (cos (* x z)) y) (+ 2 (* y y)))",
            "(+ (* (sign x) y) (* 3 (- z)))",
        ];
        let wrt = [0, 1, 2].map(Symbol::Position);
        let point = [0.7, -1.3, 0.4];
        let value = |s: Symbol| match s {
            Symbol::Position(k) => point[k as usize],
            _ => f64::NAN,
        };
        for text in cases {
            let expr = g.parse_sexpr(text).unwrap();
            let reverse = g.gradient(expr, &wrt);
            for (k, &symbol) in wrt.iter().enumerate() {
                let forward = Differentiator::new(symbol).derivative(&mut g, expr);
                let values = g.eval::<f64>(&[reverse[k], forward], value);
                assert!(
                    (values[0] - values[1]).abs() <= 1e-14 * values[1].abs().max(1.0),
                    "∂{text}/∂{symbol:?}: reverse {} forward {}",
                    values[0],
                    values[1]
                );
            }
        }
    }

    /// One seeded sweep is the weighted sum of the separate gradients: ∇(w₁e₁ + w₂e₂) with
    /// the weights held constant, even where the weights depend on the symbols themselves.
    #[test]
    fn a_seeded_sweep_is_the_weighted_sum_of_the_gradients() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y"]));
        let e1 = g.parse_sexpr("(* (sin x) (cos y))").unwrap();
        let e2 = g.parse_sexpr("(+ (* x y) (sqrt (+ y 4)))").unwrap();
        let w1 = g.parse_sexpr("(+ x 2)").unwrap();
        let w2 = g.constant(-3.0);
        let wrt = [Symbol::Position(0), Symbol::Position(1)];
        let seeded = g.gradient_seeded(&[(e1, w1), (e2, w2)], &wrt);
        let (g1, g2) = (g.gradient(e1, &wrt), g.gradient(e2, &wrt));
        let value = |s: Symbol| match s {
            Symbol::Position(0) => 0.9,
            Symbol::Position(1) => -0.4,
            _ => f64::NAN,
        };
        let v = g.eval::<f64>(&[seeded.clone(), g1, g2, vec![w1, w2]].concat(), value);
        for k in 0..2 {
            let expected = v[6] * v[2 + k] + v[7] * v[4 + k];
            assert!(
                (v[k] - expected).abs() <= 1e-14,
                "∂/∂{k}: {} against {expected}",
                v[k]
            );
        }
    }

    /// Symbols the expression does not depend on, and those left out of `wrt`, get nothing:
    /// a constant zero, and no adjoint node is built for them.
    #[test]
    fn absent_symbols_have_zero_gradient_and_cost_nothing() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]));
        let expr = g.parse_sexpr("(+ (* (sin x) (cos y)) (* y y))").unwrap();
        g.zero();
        g.one();
        let before = g.len();
        let gradient = g.gradient(expr, &[Symbol::Position(2)]);
        assert!(g.is_zero(gradient[0]));
        assert_eq!(g.len(), before, "nothing depends on z: no node is built");
        let only_x = g.gradient(expr, &[Symbol::Position(0)]);
        let cos_y = g.parse_sexpr("(cos y)").unwrap();
        let cos_x = g.parse_sexpr("(cos x)").unwrap();
        assert_eq!(
            g.node(only_x[0]),
            Node::Mul(cos_y.min(cos_x), cos_y.max(cos_x))
        );
    }
}

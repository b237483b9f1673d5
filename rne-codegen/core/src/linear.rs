//! Linear combinations: constant factors distributed over sums that are used once, equal
//! terms merged, and equal coefficients factored out again.
//!
//! The recursion produces sums scaled by constants — `m (a + α × c + ω × (ω × c))`, with
//! numeric parameters folded — whose terms carry constants of their own. Written out as a
//! linear combination `Σ cᵢ tᵢ + c₀` of non-linear terms tᵢ, the products of constants fold
//! into one coefficient per term, terms with the same tᵢ merge, and terms sharing a
//! coefficient are summed before one multiplication. Sums are rebuilt by adding the two terms
//! that are ready first, again and again: terms ready together form a balanced tree, log₂ n
//! additions deep instead of n − 1, and a term that is ready late (the recursion's value
//! from the previous link) is added last — the recursion's long sums sit on the critical
//! path of the kernels, and their depth is latency. The pass never adds an
//! operation: every coefficient group costs at most the multiplications the original tree
//! spent on it, and the additions are one fewer than the terms, as in the original sum. Limits: only sums
//! used once are opened (a shared sum is computed once and stays a term); no factor other
//! than a constant is distributed or collected; the evaluation order of the sums changes,
//! which changes rounding in the last bits.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use rne_symbolic::{ExprGraph, Id, Node};

use crate::latency::node_cycles;

/// Rewrites the expressions `roots` (kernel outputs) into linear-combination form, adding the
/// new nodes to `graph`; returns the new roots.
pub fn distribute_constants(graph: &mut ExprGraph, roots: &[Id]) -> Vec<Id> {
    let nodes = graph.reachable(roots);
    let size = nodes.last().map_or(0, |id| id.index() + 1);
    let mut uses = vec![0u32; size];
    let mut parent_is_linear = vec![true; size];
    for &id in &nodes {
        let node = graph.node(id);
        let linear = is_linear(graph, node);
        for child in node.children() {
            uses[child.index()] += 1;
            parent_is_linear[child.index()] &= linear;
        }
    }
    for &root in roots {
        uses[root.index()] += 2;
    }
    // A linear node used once, by a linear node, is opened inside its parent's combination.
    let mut opened = vec![false; size];
    for &id in &nodes {
        let k = id.index();
        opened[k] = is_linear(graph, graph.node(id)) && uses[k] == 1 && parent_is_linear[k];
    }

    let mut rebuilt: Vec<Option<Id>> = vec![None; size];
    let mut depths = Depths::default();
    let mut combination = Combination::default();
    for &id in &nodes {
        if opened[id.index()] {
            continue;
        }
        let node = graph.node(id);
        let new = if is_linear(graph, node) {
            combination.collect(graph, id, &opened);
            combination.build(graph, &rebuilt, &mut depths)
        } else {
            let r = |c: Id| rebuilt[c.index()].expect("children are rebuilt first");
            match node {
                Node::Const(_) | Node::Symbol(_) => id,
                Node::Mul(a, b) => graph.mul(r(a), r(b)),
                Node::Div(a, b) => graph.div(r(a), r(b)),
                Node::Sin(a) => graph.sin(r(a)),
                Node::Cos(a) => graph.cos(r(a)),
                Node::Sqrt(a) => graph.sqrt(r(a)),
                Node::Sign(a) => graph.sign(r(a)),
                Node::Add(..) | Node::Neg(_) => unreachable!("linear nodes are handled above"),
            }
        };
        rebuilt[id.index()] = Some(new);
    }
    roots
        .iter()
        .map(|r| rebuilt[r.index()].expect("roots are rebuilt"))
        .collect()
}

/// Additions, negations and products with a constant.
fn is_linear(graph: &ExprGraph, node: Node) -> bool {
    match node {
        Node::Add(..) | Node::Neg(_) => true,
        Node::Mul(a, b) => graph.as_const(a).is_some() || graph.as_const(b).is_some(),
        _ => false,
    }
}

/// `Σ cᵢ tᵢ + constant`, terms in order of first appearance, with the buffers that build it:
/// one is kept for every combination of a rewrite, so that a combination allocates nothing
/// once the buffers have grown to the longest sum.
#[derive(Default)]
struct Combination {
    terms: Vec<(f64, Id)>,
    constant: f64,
    /// The walk's stack: a node and the factor it is scaled by.
    stack: Vec<(Id, f64)>,
    /// The coefficients' magnitudes, one per group, in order of first appearance.
    magnitudes: Vec<f64>,
    /// Each merged term's group (an index into `magnitudes`).
    group_of: Vec<usize>,
    /// One group's signed terms, then the signed products of the groups.
    members: Vec<(bool, Id)>,
    products: Vec<(bool, Id)>,
    sum: SumBuffers,
}

impl Combination {
    /// Opens `root` and every opened linear node below it.
    fn collect(&mut self, graph: &ExprGraph, root: Id, opened: &[bool]) {
        self.terms.clear();
        self.constant = 0.0;
        self.stack.clear();
        self.stack.push((root, 1.0));
        while let Some((id, scale)) = self.stack.pop() {
            let open = id == root || opened[id.index()];
            match graph.node(id) {
                Node::Const(c) => self.constant += scale * c.value(),
                Node::Add(a, b) if open => {
                    self.stack.push((b, scale));
                    self.stack.push((a, scale));
                }
                Node::Neg(a) if open => self.stack.push((a, -scale)),
                Node::Mul(a, b) if open => {
                    let (k, x) = match graph.as_const(a) {
                        Some(k) => (k, b),
                        None => (
                            graph.as_const(b).expect("a linear product has a constant"),
                            a,
                        ),
                    };
                    self.stack.push((x, scale * k));
                }
                _ => self.terms.push((scale, id)),
            }
        }
    }

    /// Builds the combination from the rebuilt terms: equal terms merged, terms grouped by
    /// the magnitude of their coefficient, one multiplication per group.
    fn build(&mut self, graph: &mut ExprGraph, rebuilt: &[Option<Id>], depths: &mut Depths) -> Id {
        self.merge(rebuilt);
        self.group();
        self.products.clear();
        for (group, &magnitude) in self.magnitudes.iter().enumerate() {
            self.members.clear();
            let terms = self.terms.iter().zip(&self.group_of);
            self.members.extend(
                terms
                    .filter(|&(_, &g)| g == group)
                    .map(|(&(c, t), _)| (c < 0.0, t)),
            );
            let (negative, sum) = balanced_sum(graph, &self.members, depths, &mut self.sum);
            let k = graph.constant(magnitude);
            self.products.push((negative, graph.mul(k, sum)));
        }
        if self.constant != 0.0 || self.products.is_empty() {
            let constant = graph.constant(self.constant.abs());
            self.products.push((self.constant < 0.0, constant));
        }
        let (negative, total) = balanced_sum(graph, &self.products, depths, &mut self.sum);
        if negative {
            graph.neg(total)
        } else {
            total
        }
    }

    /// Each term's group: the terms whose coefficients have the same magnitude, groups in
    /// order of first appearance.
    fn group(&mut self) {
        self.magnitudes.clear();
        self.group_of.clear();
        for &(c, _) in &self.terms {
            let magnitude = c.abs();
            let group = match self.magnitudes.iter().position(|&m| m == magnitude) {
                Some(group) => group,
                None => {
                    self.magnitudes.push(magnitude);
                    self.magnitudes.len() - 1
                }
            };
            self.group_of.push(group);
        }
    }

    /// The terms with each rebuilt, equal ones merged (their coefficients added in the
    /// terms' order, at the first one's place) and those whose coefficient is zero dropped.
    fn merge(&mut self, rebuilt: &[Option<Id>]) {
        let mut merged = 0;
        for k in 0..self.terms.len() {
            let (c, t) = self.terms[k];
            let t = rebuilt[t.index()].expect("terms are rebuilt first");
            match self.terms[..merged].iter_mut().find(|(_, u)| *u == t) {
                Some((existing, _)) => *existing += c,
                None => {
                    self.terms[merged] = (c, t);
                    merged += 1;
                }
            }
        }
        self.terms.truncate(merged);
        self.terms.retain(|&(c, _)| c != 0.0);
    }
}

/// The heap and the partial sums of [`balanced_sum`], kept from one sum to the next.
#[derive(Default)]
struct SumBuffers {
    ready: BinaryHeap<Reverse<(u32, usize)>>,
    pending: Vec<(bool, Id)>,
}

/// `±(±t₁ ± t₂ ± …)` summed by always adding the two terms that are ready first (least
/// [`Depths`]), so that the sum's result is ready as early as its terms allow: n terms of
/// equal depth become a balanced tree, log₂ n additions deep rather than n − 1, and a term
/// that arrives late — the recursion's value from the previous link — is added last, after
/// the others have been summed while it was computed. Merging the two least is optimal for
/// this "maximum plus one" cost (Golumbic, "Combinatorial merging", IEEE Trans. Computers
/// 25(11), 1976). Ties keep the terms' order. Returns the sign to apply and the sum.
fn balanced_sum(
    graph: &mut ExprGraph,
    terms: &[(bool, Id)],
    depths: &mut Depths,
    buffers: &mut SumBuffers,
) -> (bool, Id) {
    // One term is the sum; two are added in the order the merging below would take them
    // (the one ready first, the first of the two on a tie), without its heap.
    match *terms {
        [] => panic!("a sum has a term"),
        [term] => return term,
        [a, b] if depths.of(graph, b.1) < depths.of(graph, a.1) => return signed_sum(graph, b, a),
        [a, b] => return signed_sum(graph, a, b),
        _ => {}
    }
    let SumBuffers { ready, pending } = buffers;
    ready.clear();
    pending.clear();
    for &term in terms {
        ready.push(Reverse((depths.of(graph, term.1), pending.len())));
        pending.push(term);
    }
    loop {
        let Reverse((_, first)) = ready.pop().expect("a term is pending");
        let Some(Reverse((_, second))) = ready.pop() else {
            return pending[first];
        };
        let sum = signed_sum(graph, pending[first], pending[second]);
        ready.push(Reverse((depths.of(graph, sum.1), pending.len())));
        pending.push(sum);
    }
}

/// `±a ± b` as a sign to apply and an addition or subtraction.
fn signed_sum(graph: &mut ExprGraph, first: (bool, Id), second: (bool, Id)) -> (bool, Id) {
    match (first, second) {
        ((sa, a), (sb, b)) if sa == sb => (sa, graph.add(a, b)),
        ((false, a), (true, b)) => (false, graph.sub(a, b)),
        ((true, a), (false, b)) => (false, graph.sub(b, a)),
        _ => unreachable!("two signs"),
    }
}

/// When each node's value is ready, in cycles from the kernel's start, by the latency model
/// of [`crate::latency`]; only the order matters here.
#[derive(Default)]
struct Depths {
    /// By node index; `u32::MAX` where not computed yet.
    ready: Vec<u32>,
    /// The walk's stack, kept between calls so that a depth costs no allocation (a call per
    /// term and per partial sum of every sum rebuilt).
    stack: Vec<Id>,
}

impl Depths {
    const UNKNOWN: u32 = u32::MAX;

    fn known(&self, id: Id) -> Option<u32> {
        self.ready
            .get(id.index())
            .copied()
            .filter(|&r| r != Self::UNKNOWN)
    }

    /// The cycle `id`'s value is ready at.
    fn of(&mut self, graph: &ExprGraph, id: Id) -> u32 {
        if let Some(ready) = self.known(id) {
            return ready;
        }
        if self.ready.len() < graph.len() {
            self.ready.resize(graph.len(), Self::UNKNOWN);
        }
        let mut stack = core::mem::take(&mut self.stack);
        stack.push(id);
        while let Some(&top) = stack.last() {
            if self.known(top).is_some() {
                stack.pop();
                continue;
            }
            let node = graph.node(top);
            let before = stack.len();
            stack.extend(node.children().filter(|&c| self.known(c).is_none()));
            if stack.len() > before {
                continue;
            }
            let operands = node
                .children()
                .map(|c| self.ready[c.index()])
                .max()
                .unwrap_or(0);
            self.ready[top.index()] = operands + node_cycles(node);
            stack.pop();
        }
        self.stack = stack;
        self.ready[id.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::distribute_constants;
    use crate::program::Program;
    use rne_symbolic::{ExprGraph, Symbol, SymbolTable};

    fn graph() -> ExprGraph {
        ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]))
    }

    fn rewrite(text: &str) -> String {
        let mut g = graph();
        let root = g.parse_sexpr(text).unwrap();
        let new = distribute_constants(&mut g, &[root]);
        g.to_sexpr(new[0])
    }

    #[test]
    fn constants_distribute_into_a_sum_used_once() {
        assert_eq!(rewrite("(* 2 (+ (* 3 x) (* 5 y)))"), "(+ (* x 6) (* y 10))");
    }

    #[test]
    fn equal_terms_merge_and_equal_coefficients_group() {
        assert_eq!(rewrite("(+ (* 2 x) (* 3 x))"), "(* x 5)");
        assert_eq!(rewrite("(+ (* 2 x) (* 2 (* y z)))"), "(* 2 (+ x (* y z)))");
        assert_eq!(rewrite("(- (* 2 x) (* 2 y))"), "(* 2 (+ x (- y)))");
    }

    /// Terms ready at the start are summed first and a term that needs a long computation is
    /// added last, so the sum's result waits for it by one addition only; terms ready
    /// together form a balanced tree. (The printed form orders the operands of `+` by node.)
    #[test]
    fn a_late_term_is_added_last() {
        assert_eq!(
            rewrite("(+ (sin (sin (* x y))) (+ x (+ y z)))"),
            "(+ (sin (sin (* x y))) (+ z (+ x y)))"
        );
        assert_eq!(
            rewrite("(+ (* x y) (+ (* y z) (+ (* x z) (* z z))))"),
            "(+ (+ (* x z) (* z z)) (+ (* x y) (* y z)))"
        );
    }

    #[test]
    fn shared_sums_stay_terms() {
        let mut g = graph();
        let shared = g.parse_sexpr("(+ x y)").unwrap();
        let three = g.constant(3.0);
        let a = g.mul(three, shared);
        let b = g.mul(shared, shared);
        let new = distribute_constants(&mut g, &[a, b]);
        assert_eq!(g.to_sexpr(new[0]), "(* (+ x y) 3)");
        assert_eq!(new[1], b);
    }

    /// The buffers kept from one combination to the next carry nothing over: each root of a
    /// rewrite, after a longer combination with more groups, comes out as it does alone.
    #[test]
    fn each_combination_is_rewritten_as_it_is_alone() {
        let texts = [
            "(+ (* 2 x) (* 3 y) (* 5 z) (* 7 (* x y)) 11)",
            "(* 4 (+ x y))",
            "(- (* 3 (sin x)) (* 3 (cos y)))",
        ];
        let alone: Vec<String> = texts.iter().map(|text| rewrite(text)).collect();
        let mut g = graph();
        let roots: Vec<_> = texts.iter().map(|t| g.parse_sexpr(t).unwrap()).collect();
        let together = distribute_constants(&mut g, &roots);
        let together: Vec<String> = together.iter().map(|&r| g.to_sexpr(r)).collect();
        assert_eq!(together, alone);
    }

    #[test]
    fn the_rewrite_keeps_the_value_and_never_adds_operations() {
        let cases = [
            "(* 0.5 (+ (* 3 (- x y)) (* 1.5 (* x z)) 7))",
            "(+ (* 2 (sin x)) (- (* 2 (cos y))) (* 4 (* 0.25 (sin x))))",
            "(* 9.81 (+ (* 0.3 (cos x)) (* 0.15 (+ (* (cos x) (cos y)) (- (* (sin x) (sin y)))))))",
            "(- (* (+ x (* 2 y)) z) (* 3 (+ (* 2 x) (- z))))",
        ];
        for text in cases {
            let mut g = graph();
            let root = g.parse_sexpr(text).unwrap();
            let before = Program::lower(&g, &[root]);
            let new = distribute_constants(&mut g, &[root]);
            let after = Program::lower(&g, &new);
            assert!(
                after.op_count().total() <= before.op_count().total(),
                "{text}: {} -> {}",
                before.op_count(),
                after.op_count()
            );
            for point in [[0.3, -1.2, 2.5], [1.0, 2.0, -0.5]] {
                let value = |s: Symbol| match s {
                    Symbol::Position(k) => point[k as usize],
                    _ => f64::NAN,
                };
                let (x, y) = (before.eval(value)[0], after.eval(value)[0]);
                assert!(
                    (x - y).abs() <= 1e-14 * x.abs().max(1.0),
                    "{text}: {x} vs {y}"
                );
            }
        }
    }
}

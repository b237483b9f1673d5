//! The hash-consed expression DAG and its simplifying constructors.

use hashbrown::hash_table::{Entry, HashTable};
use rustc_hash::FxBuildHasher;
use std::f64::consts::FRAC_PI_2;
use std::hash::BuildHasher;

use super::node::{Constant, Id, Node, Symbol};
use super::symbols::SymbolTable;

/// A hash-consed directed acyclic graph of scalar expressions.
///
/// Nodes live in an arena; only [`ExprGraph::split_off`] removes them, the newest first. Every
/// node is unique (structural sharing through a memo of node ids, hashed by their nodes), and its
/// children always come earlier in the arena, so `0..len()` is a topological order. The constructors (`add`, `mul`, `sin`, ...) fold
/// constants and apply identities that are exact in real arithmetic and never increase the
/// operation count: `x·0 = 0`, `x·1 = x`, `x + 0 = x`, `x + (−x) = 0`, `−(−x) = x`,
/// `sin(kπ/2)` and `cos(kπ/2)` exactly, and negations pulled outwards (`(−a)·b = −(a·b)`)
/// so that `a·b` and `−a·b` share their product.
///
/// The arena holds at most [`ExprGraph::node_limit`] nodes ([`NODE_LIMIT`] by default, about
/// half a gigabyte): past it, a constructor that would create a node returns the constant 0
/// instead and the graph remembers it ([`ExprGraph::limit_reached`]). What is built after
/// that is meaningless, but it is built quickly (the zeros fold everything they touch), so a
/// robot whose kernels would take minutes and gigabytes ends in an error instead — whoever
/// builds asks the graph once at the end.
#[derive(Clone, Debug)]
pub struct ExprGraph {
    nodes: Vec<Node>,
    /// Every node's id with its [`hash`], found by the hash and compared through `nodes`:
    /// eight bytes an entry where a map from nodes to ids would take twenty-four, and the
    /// table grows without reading the arena.
    memo: HashTable<Memo>,
    symbols: SymbolTable,
    /// The most nodes the arena takes.
    limit: usize,
    /// Whether a node was refused for the limit.
    limit_reached: bool,
    /// Whether `sin` and `cos` of a constant within a few ulps of a multiple of π/2 are
    /// exactly 0 or ±1 ([`ExprGraph::set_exact_right_angles`]).
    exact_right_angles: bool,
}

/// How close, in units of `f64::EPSILON` times max(|x|, 1), a constant angle x must be to a
/// multiple of π/2 for its sine and cosine to be taken as exactly 0 and ±1: the nearest `f64`
/// to π/2 (1.5707963267948966, as URDF files write it) is within one, `3 * 1.5707963267948966`
/// within two, so four covers every multiple a robot file writes while an angle meant to differ
/// from a right angle (by 10⁻¹² rad, say) keeps its sine and cosine.
pub const RIGHT_ANGLE_ULPS: f64 = 4.0;

/// The constant 0, which a graph at its node limit gives for every new node.
const ZERO: Node = Node::Const(Constant::ZERO);

/// The default [`ExprGraph::node_limit`]: 2²⁴ nodes, about 30 bytes each with the memo. The
/// largest kernels of the robots of example-robot-data stay well below it.
pub const NODE_LIMIT: usize = 1 << 24;

impl Default for ExprGraph {
    fn default() -> ExprGraph {
        ExprGraph::new(SymbolTable::default())
    }
}

/// An entry of the memo: a node's id and [`hash`].
#[derive(Copy, Clone, Debug)]
struct Memo {
    id: Id,
    hash: u32,
}

/// The memo's hash of a node: FxHash (keys are small integers and constants' bits, where a
/// DoS-resistant hash buys nothing), folded to 32 bits.
fn hash(node: &Node) -> u32 {
    let h = FxBuildHasher.hash_one(node);
    (h >> 32) as u32 ^ h as u32
}

/// The table's 64-bit hash of a 32-bit [`hash`]: a bijection on the low bits, which index the
/// table, that also fills the high bits, which the table keeps as tags.
fn spread(hash: u32) -> u64 {
    u64::from(hash).wrapping_mul(0x9e37_79b9_7f4a_7c15)
}

impl ExprGraph {
    /// An empty graph with the given symbol names.
    pub fn new(symbols: SymbolTable) -> ExprGraph {
        ExprGraph {
            nodes: Vec::new(),
            memo: HashTable::new(),
            symbols,
            limit: NODE_LIMIT,
            limit_reached: false,
            exact_right_angles: true,
        }
    }

    /// Whether `sin` and `cos` of a constant angle within [`RIGHT_ANGLE_ULPS`] ulps of a
    /// multiple of π/2 are exactly 0 or ±1 (the default), or the `f64` sine and cosine of the
    /// number as written (`cos(1.5707963267948966)` = 6.1e-17).
    pub fn exact_right_angles(&self) -> bool {
        self.exact_right_angles
    }

    /// Sets [`ExprGraph::exact_right_angles`] for the nodes built from now on
    /// ([`LoadOptions::exact_right_angles`](crate::spec::LoadOptions::exact_right_angles)).
    pub fn set_exact_right_angles(&mut self, exact: bool) {
        self.exact_right_angles = exact;
    }

    /// The most nodes this graph takes (type docs).
    pub fn node_limit(&self) -> usize {
        self.limit
    }

    /// Sets the most nodes this graph takes (type docs).
    pub fn set_node_limit(&mut self, limit: usize) {
        self.limit = limit;
    }

    /// Whether a node was refused because the graph had [`ExprGraph::node_limit`] nodes:
    /// then whatever was built since is meaningless (type docs).
    pub fn limit_reached(&self) -> bool {
        self.limit_reached
    }

    /// Names of the joint and parameter symbols.
    pub fn symbols(&self) -> &SymbolTable {
        &self.symbols
    }

    /// Mutable access to the symbol names (to add parameters while building a model).
    pub fn symbols_mut(&mut self) -> &mut SymbolTable {
        &mut self.symbols
    }

    /// Number of nodes in the arena.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the arena is empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.index()]
    }

    /// The value of a constant node, `None` for any other node.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(c) => Some(c.value()),
            _ => None,
        }
    }

    /// Whether `id` is the constant zero.
    pub fn is_zero(&self, id: Id) -> bool {
        self.as_const(id) == Some(0.0)
    }

    /// Whether `id` is the constant one.
    pub fn is_one(&self, id: Id) -> bool {
        self.as_const(id) == Some(1.0)
    }

    /// Removes the nodes built since the graph had `len` of them and returns them in order:
    /// the graph is as it was then, and [`ExprGraph::restore`] puts them back at the same ids.
    /// Trying two constructions one after the other costs the nodes of one, not a copy of
    /// the graph.
    pub fn split_off(&mut self, len: usize) -> Vec<Node> {
        let tail = self.nodes.split_off(len);
        for (k, node) in tail.iter().enumerate() {
            let id = Id::from_index(len + k);
            if let Ok(entry) = self.memo.find_entry(spread(hash(node)), |m| m.id == id) {
                entry.remove();
            }
        }
        tail
    }

    /// Appends nodes [`ExprGraph::split_off`] removed, when the graph has again the length it
    /// had then: each gets back its id.
    pub fn restore(&mut self, nodes: Vec<Node>) {
        for node in nodes {
            let (id, hash) = (Id::from_index(self.nodes.len()), hash(&node));
            let nodes = &self.nodes;
            debug_assert!(
                self.memo
                    .find(spread(hash), |m| nodes[m.id.index()] == node)
                    .is_none(),
                "restored onto another graph"
            );
            self.memo
                .insert_unique(spread(hash), Memo { id, hash }, |m| spread(m.hash));
            self.nodes.push(node);
        }
    }

    fn intern(&mut self, node: Node) -> Id {
        let (nodes, hash) = (&self.nodes, hash(&node));
        let entry = self.memo.entry(
            spread(hash),
            |m| m.hash == hash && nodes[m.id.index()] == node,
            |m| spread(m.hash),
        );
        match entry {
            Entry::Occupied(existing) => existing.get().id,
            Entry::Vacant(_) if nodes.len() >= self.limit && node != ZERO => {
                self.limit_reached = true;
                self.intern(ZERO)
            }
            Entry::Vacant(vacant) => {
                debug_assert!(node.children().all(|c| c.index() < nodes.len()));
                let id = Id::from_index(nodes.len());
                vacant.insert(Memo { id, hash });
                self.nodes.push(node);
                id
            }
        }
    }

    /// A constant. Non-finite values are accepted (they arise only from user data that
    /// evaluation would turn into NaN anyway) but never produced by folding.
    pub fn constant(&mut self, value: f64) -> Id {
        self.intern(Node::Const(Constant::new(value)))
    }

    /// The constant zero.
    pub fn zero(&mut self) -> Id {
        self.constant(0.0)
    }

    /// The constant one.
    pub fn one(&mut self) -> Id {
        self.constant(1.0)
    }

    /// A free variable.
    pub fn symbol(&mut self, symbol: Symbol) -> Id {
        self.intern(Node::Symbol(symbol))
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.node(a), self.node(b)) {
            (Node::Const(x), Node::Const(y)) => {
                if let Some(id) = self.fold(x.value() + y.value()) {
                    return id;
                }
            }
            (Node::Const(x), _) if x.value() == 0.0 => return b,
            (_, Node::Const(y)) if y.value() == 0.0 => return a,
            (Node::Neg(x), Node::Neg(y)) => {
                let sum = self.add(x, y);
                return self.neg(sum);
            }
            (Node::Neg(x), _) if x == b => return self.zero(),
            (_, Node::Neg(y)) if y == a => return self.zero(),
            _ => {}
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// `a − b`, stored as `a + (−b)`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.add(a, nb)
    }

    /// `−a`.
    pub fn neg(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(x) => self.constant(-x.value()),
            Node::Neg(x) => x,
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `a · b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.node(a), self.node(b)) {
            (Node::Const(x), Node::Const(y)) => {
                if let Some(id) = self.fold(x.value() * y.value()) {
                    return id;
                }
            }
            (Node::Const(x), _) | (_, Node::Const(x)) if x.value() == 0.0 => return self.zero(),
            (Node::Const(x), _) if x.value() == 1.0 => return b,
            (_, Node::Const(y)) if y.value() == 1.0 => return a,
            (Node::Neg(x), _) => {
                let product = self.mul(x, b);
                return self.neg(product);
            }
            (_, Node::Neg(y)) => {
                let product = self.mul(a, y);
                return self.neg(product);
            }
            (Node::Const(x), _) if x.value() < 0.0 => {
                let c = self.constant(-x.value());
                let product = self.mul(c, b);
                return self.neg(product);
            }
            (_, Node::Const(y)) if y.value() < 0.0 => {
                let c = self.constant(-y.value());
                let product = self.mul(a, c);
                return self.neg(product);
            }
            (Node::Const(x), Node::Mul(p, r)) | (Node::Mul(p, r), Node::Const(x)) => {
                let inner = match (self.as_const(p), self.as_const(r)) {
                    (Some(y), _) => Some((y, r)),
                    (_, Some(y)) => Some((y, p)),
                    _ => None,
                };
                if let Some((y, rest)) = inner {
                    if let Some(c) = self.fold(x.value() * y) {
                        return self.mul(c, rest);
                    }
                }
            }
            _ => {}
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    /// `a · a`.
    pub fn square(&mut self, a: Id) -> Id {
        self.mul(a, a)
    }

    /// `a / b`. Division by a power of two becomes an exact multiplication.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        match (self.node(a), self.node(b)) {
            (Node::Const(x), Node::Const(y)) => {
                if let Some(id) = self.fold(x.value() / y.value()) {
                    return id;
                }
            }
            (_, Node::Const(y)) if y.value() == 1.0 => return a,
            (Node::Const(x), _) if x.value() == 0.0 && !self.is_zero(b) => return a,
            (Node::Neg(x), _) => {
                let quotient = self.div(x, b);
                return self.neg(quotient);
            }
            (_, Node::Neg(y)) => {
                let quotient = self.div(a, y);
                return self.neg(quotient);
            }
            (_, Node::Const(y)) if is_power_of_two(y.value()) => {
                let reciprocal = self.constant(1.0 / y.value());
                return self.mul(a, reciprocal);
            }
            _ => {}
        }
        self.intern(Node::Div(a, b))
    }

    /// `sin a`, exact for constant multiples of π/2.
    pub fn sin(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(x) => self.trig_constant(x.value(), 0),
            Node::Neg(x) => {
                let s = self.sin(x);
                self.neg(s)
            }
            _ => self.intern(Node::Sin(a)),
        }
    }

    /// `cos a`, exact for constant multiples of π/2.
    pub fn cos(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(x) => self.trig_constant(x.value(), 1),
            Node::Neg(x) => self.cos(x),
            _ => self.intern(Node::Cos(a)),
        }
    }

    /// `sqrt a`.
    pub fn sqrt(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            if x >= 0.0 {
                return self.constant(x.sqrt());
            }
        }
        self.intern(Node::Sqrt(a))
    }

    /// `sign a` (−1, 0 or 1): folded for constants, `sign(−x) = −sign x`, and idempotent.
    pub fn sign(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            });
        }
        match self.node(a) {
            Node::Neg(x) => {
                let s = self.sign(x);
                self.neg(s)
            }
            Node::Sign(_) => a,
            _ => self.intern(Node::Sign(a)),
        }
    }

    /// Sum of a list (zero when empty), accumulated left to right.
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Id>) -> Id {
        let mut total = self.zero();
        for t in terms {
            total = self.add(total, t);
        }
        total
    }

    fn fold(&mut self, value: f64) -> Option<Id> {
        value.is_finite().then(|| self.constant(value))
    }

    /// sin (phase 0) or cos (phase 1) of a constant; exact at multiples of π/2 (within
    /// [`RIGHT_ANGLE_ULPS`]) unless [`ExprGraph::exact_right_angles`] is off.
    fn trig_constant(&mut self, x: f64, phase: i64) -> Id {
        let k = (x / FRAC_PI_2).round();
        let tolerance = RIGHT_ANGLE_ULPS * f64::EPSILON * x.abs().max(1.0);
        if self.exact_right_angles && k.abs() < 1e15 && (k * FRAC_PI_2 - x).abs() <= tolerance {
            let exact = [0.0, 1.0, 0.0, -1.0][((k as i64 + phase).rem_euclid(4)) as usize];
            return self.constant(exact);
        }
        self.constant(if phase == 0 { x.sin() } else { x.cos() })
    }
}

fn is_power_of_two(x: f64) -> bool {
    if !x.is_normal() {
        return false;
    }
    let bits = x.abs().to_bits();
    bits & ((1u64 << 52) - 1) == 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn graph() -> (ExprGraph, Id, Id) {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["q1", "q2"]));
        let x = g.symbol(Symbol::Position(0));
        let y = g.symbol(Symbol::Position(1));
        (g, x, y)
    }

    #[test]
    fn identical_expressions_share_one_node() {
        let (mut g, x, y) = graph();
        let a = g.mul(x, y);
        let b = g.mul(y, x);
        assert_eq!(a, b);
        let before = g.len();
        let c = g.add(a, x);
        let d = g.add(x, b);
        assert_eq!(c, d);
        assert_eq!(g.len(), before + 1);
    }

    #[test]
    fn split_off_forgets_nodes_and_restore_shares_them_again() {
        let (mut g, x, y) = graph();
        let start = g.len();
        let product = g.mul(x, y);
        let sum = g.add(product, x);
        let tail = g.split_off(start);
        assert_eq!(g.len(), start);
        // The memo forgot the nodes: the product is built anew, at the first free id (a
        // remembered one would be found, pointing past the arena, and not pushed).
        let again = g.mul(x, y);
        assert_eq!((again, g.len()), (product, start + 1));
        g.split_off(start);
        g.restore(tail);
        assert_eq!(g.len(), start + 2);
        // Restored nodes are found again rather than built twice, and the removed one is gone.
        assert_eq!(g.mul(y, x), product);
        assert_eq!(g.add(x, product), sum);
        assert_eq!(g.len(), start + 2);
        let sine = g.sin(x);
        assert_eq!(sine.index(), start + 2);
    }

    #[test]
    fn multiplicative_and_additive_identities_fold() {
        let (mut g, x, _) = graph();
        let zero = g.zero();
        let one = g.one();
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.add(x, zero), x);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        assert_eq!(g.add(x, nx), zero);
        let minus_one = g.constant(-1.0);
        assert_eq!(g.mul(minus_one, x), nx);
    }

    #[test]
    fn negation_is_pulled_out_of_products() {
        let (mut g, x, y) = graph();
        let nx = g.neg(x);
        let xy = g.mul(x, y);
        let p = g.mul(nx, y);
        assert_eq!(g.node(p), Node::Neg(xy));
        let minus_two = g.constant(-2.0);
        let two = g.constant(2.0);
        let two_x = g.mul(two, x);
        let q = g.mul(minus_two, x);
        assert_eq!(g.node(q), Node::Neg(two_x));
    }

    #[test]
    fn trig_of_multiples_of_half_pi_is_exact() {
        let (mut g, _, _) = graph();
        for (angle, s, c) in [
            (0.0, 0.0, 1.0),
            (FRAC_PI_2, 1.0, 0.0),
            (PI, 0.0, -1.0),
            (-FRAC_PI_2, -1.0, 0.0),
        ] {
            let a = g.constant(angle);
            let sa = g.sin(a);
            let ca = g.cos(a);
            assert_eq!(g.as_const(sa), Some(s), "sin({angle})");
            assert_eq!(g.as_const(ca), Some(c), "cos({angle})");
        }
        let third = g.constant(PI / 3.0);
        let c = g.cos(third);
        assert!((g.as_const(c).unwrap() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn literal_angles_keep_the_f64_sine_and_cosine_of_a_right_angle() {
        let (mut g, _, _) = graph();
        g.set_exact_right_angles(false);
        let a = g.constant(FRAC_PI_2);
        let c = g.cos(a);
        assert_eq!(g.as_const(c), Some(FRAC_PI_2.cos()));
        assert!(g.as_const(c).unwrap() != 0.0);
        g.set_exact_right_angles(true);
        let b = g.constant(3.0 * FRAC_PI_2);
        let s = g.sin(b);
        assert_eq!(g.as_const(s), Some(-1.0));
    }

    #[test]
    fn constants_fold_and_division_by_powers_of_two_is_multiplication() {
        let (mut g, x, _) = graph();
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let six = g.mul(two, three);
        assert_eq!(g.as_const(six), Some(6.0));
        let half_x = g.div(x, two);
        let half = g.constant(0.5);
        assert_eq!(g.node(half_x), Node::Mul(x.min(half), x.max(half)));
        let zero = g.zero();
        let by_zero = g.div(x, zero);
        assert_eq!(g.node(by_zero), Node::Div(x, zero));
        let nested = g.mul(two, half_x);
        assert_eq!(nested, x);
    }
}

//! Expansion of expressions into canonical polynomials.

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

use super::atom::{Angle, Atom};
use super::budget::WorkBudget;
use super::error::CanonicalError;
use super::polynomial::Polynomial;
use crate::expr::{ExprGraph, Id, Node};

/// Largest |n| for which `sin(n x)` and `cos(n x)` are expanded by the multiple-angle
/// formulas; larger or fractional multiples stay inside an [`Angle::Expr`].
const MAX_MULTIPLE: f64 = 32.0;

impl Polynomial {
    /// The canonical form of the expression `expr` of `graph`.
    ///
    /// Products are expanded fully. `sin` and `cos` of an integer combination of symbols plus
    /// a constant, `sin(Σ n_k x_k + c)`, are expanded by the angle-addition and multiple-angle
    /// formulas into s_k = sin x_k and c_k = cos x_k, with the constant's sine and cosine exact
    /// at multiples of π/2 (the rule of [`ExprGraph::sin`]); any other part of an argument
    /// becomes an [`Angle::Expr`]. Square roots of non-constant polynomials become
    /// [`Atom::Sqrt`] atoms. Division is allowed by a monomial free of sines and cosines
    /// (a mass, a length, a constant); it gives negative exponents.
    ///
    /// Every node is expanded once (memoised over the DAG), and an intermediate result is
    /// dropped as soon as its last user has been expanded.
    pub fn from_expr(graph: &ExprGraph, expr: Id) -> Result<Polynomial, CanonicalError> {
        let mut forms = Polynomial::from_exprs(graph, &[expr])?;
        Ok(forms.pop().unwrap_or_default())
    }

    /// The canonical forms of several expressions, sharing the work on common
    /// subexpressions (e.g. all torques of a robot at once).
    pub fn from_exprs(graph: &ExprGraph, exprs: &[Id]) -> Result<Vec<Polynomial>, CanonicalError> {
        let forms =
            Expansion::new(graph, exprs, usize::MAX).run(exprs, &mut WorkBudget::unlimited())?;
        Ok(forms.into_iter().map(Option::unwrap_or_default).collect())
    }

    /// The canonical forms of several expressions, as [`Polynomial::from_exprs`], each `None`
    /// where it would have more than `max_terms` terms or where its expansion would take more
    /// work than `work` has left: the expansion of a node stops as soon as its form, or a
    /// product's pairs of terms ([`WORK_PER_TERM`] per allowed term), would pass the bound, or
    /// its cost (the terms it multiplies, adds or copies) would pass what is left of `work`,
    /// and every node using it is `None` too. The time and memory taken are then bounded
    /// whatever the expressions: what `rne show` prints of a robot whose equations run to
    /// megabytes. `work` is spent by what was expanded, and may be shared by several calls.
    pub fn from_exprs_within(
        graph: &ExprGraph,
        exprs: &[Id],
        max_terms: usize,
        work: &mut WorkBudget,
    ) -> Result<Vec<Option<Polynomial>>, CanonicalError> {
        Expansion::new(graph, exprs, max_terms).run(exprs, work)
    }
}

/// How many pairs of terms a product may multiply per term [`Polynomial::from_exprs_within`]
/// allows: the work of a product whose result could still fit after its terms merge.
pub const WORK_PER_TERM: usize = 64;

/// `cos θ + i sin θ` as a pair of polynomials: products of phasors add angles.
#[derive(Clone)]
struct Phasor {
    cos: Polynomial,
    sin: Polynomial,
}

impl Phasor {
    fn zero_angle() -> Phasor {
        Phasor {
            cos: Polynomial::one(),
            sin: Polynomial::zero(),
        }
    }

    fn of(angle: Angle) -> Phasor {
        Phasor {
            cos: Polynomial::atom(Atom::Cos(angle.clone())),
            sin: Polynomial::atom(Atom::Sin(angle)),
        }
    }

    /// cos(a + b) = cos a cos b − sin a sin b, sin(a + b) = sin a cos b + cos a sin b.
    fn times(&self, other: &Phasor) -> Phasor {
        Phasor {
            cos: &(&self.cos * &other.cos) - &(&self.sin * &other.sin),
            sin: &(&self.sin * &other.cos) + &(&self.cos * &other.sin),
        }
    }

    /// The phasor of the negated angle.
    fn conj(self) -> Phasor {
        Phasor {
            cos: self.cos,
            sin: -self.sin,
        }
    }

    /// The phasor of `n` times the angle (n ≥ 0), by repeated squaring.
    fn pow(&self, n: u32) -> Phasor {
        let mut result = Phasor::zero_angle();
        let mut base = self.clone();
        let mut n = n;
        while n > 0 {
            if n & 1 == 1 {
                result = result.times(&base);
            }
            n >>= 1;
            if n > 0 {
                base = base.times(&base);
            }
        }
        result
    }
}

/// The phasor of an angle given by its canonical polynomial.
fn phasor(angle: &Polynomial) -> Phasor {
    let mut result = Phasor::zero_angle();
    let mut rest = Polynomial::zero();
    for (m, c) in angle.terms() {
        let symbol = match m.factors() {
            [(Atom::Symbol(s), 1)] if c.fract() == 0.0 && c.abs() <= MAX_MULTIPLE => Some(*s),
            _ => None,
        };
        if let Some(s) = symbol {
            let multiple = Phasor::of(Angle::Symbol(s)).pow(c.abs() as u32);
            result = result.times(&if c < 0.0 { multiple.conj() } else { multiple });
        } else if m.is_one() {
            let (sin, cos) = sin_cos_constant(c);
            result = result.times(&Phasor {
                cos: Polynomial::constant(cos),
                sin: Polynomial::constant(sin),
            });
        } else {
            rest.add_reduced(m.clone(), c);
        }
    }
    if !rest.is_empty() {
        let negative = rest.terms().next().is_some_and(|(_, c)| c < 0.0);
        let rest = if negative { -rest } else { rest };
        let other = Phasor::of(Angle::Expr(Arc::new(rest)));
        result = result.times(&if negative { other.conj() } else { other });
    }
    result
}

/// `(sin x, cos x)` of a constant, exact at multiples of π/2 (as [`ExprGraph::sin`] folds).
fn sin_cos_constant(x: f64) -> (f64, f64) {
    let k = (x / FRAC_PI_2).round();
    if k.abs() < 1e15 && (k * FRAC_PI_2 - x).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0) {
        return [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)]
            [(k as i64).rem_euclid(4) as usize];
    }
    x.sin_cos()
}

/// A bound on the terms of the cosine and of the sine in the phasor of `angle` (see
/// [`phasor`]): `cos(n x)` and `sin(n x)` have at most |n|/2 + 1 terms, a constant's or a
/// structural angle's one, and each angle sum at most doubles the product of its parts'.
fn phasor_size(angle: &Polynomial) -> usize {
    let mut size: usize = 1;
    let mut parts = 0u32;
    let mut rest = false;
    for (m, c) in angle.terms() {
        match m.factors() {
            [(Atom::Symbol(_), 1)] if c.fract() == 0.0 && c.abs() <= MAX_MULTIPLE => {
                size = size.saturating_mul(c.abs() as usize / 2 + 1);
                parts += 1;
            }
            [] => parts += 1,
            _ => rest = true,
        }
    }
    parts += u32::from(rest);
    size.saturating_mul(
        1usize
            .checked_shl(parts.saturating_sub(1))
            .unwrap_or(usize::MAX),
    )
}

/// One expansion run over the nodes needed by a set of outputs.
struct Expansion<'g> {
    graph: &'g ExprGraph,
    /// The needed nodes, children before parents (by index).
    nodes: Vec<Id>,
    /// Position in `values` of each node index (`u32::MAX` for nodes not needed).
    slot: Vec<u32>,
    /// Expanded form of each needed node, `None` before it is expanded and after its last use.
    values: Vec<Option<Polynomial>>,
    /// Remaining uses of each needed node (parent edges, plus one per output).
    uses: Vec<u32>,
    /// Phasors of trigonometric arguments, shared by `sin a` and `cos a`.
    phasors: HashMap<Id, Phasor>,
    /// The most terms a form may have ([`Polynomial::from_exprs_within`]).
    max_terms: usize,
    /// Whether each needed node's form passed `max_terms` (its value is then the zero
    /// placeholder).
    over: Vec<bool>,
}

impl<'g> Expansion<'g> {
    fn new(graph: &'g ExprGraph, outputs: &[Id], max_terms: usize) -> Expansion<'g> {
        let order = graph.reachable(outputs);
        let mut slot = vec![u32::MAX; order.last().map_or(0, |id| id.index() + 1)];
        for (k, id) in order.iter().enumerate() {
            slot[id.index()] = k as u32;
        }
        let mut uses = vec![0; order.len()];
        for &id in &order {
            for c in graph.node(id).children() {
                uses[slot[c.index()] as usize] += 1;
            }
        }
        for o in outputs {
            uses[slot[o.index()] as usize] += 1;
        }
        let values = vec![None; order.len()];
        Expansion {
            graph,
            slot,
            values,
            uses,
            phasors: HashMap::new(),
            max_terms,
            over: vec![false; order.len()],
            nodes: order,
        }
    }

    fn run(
        mut self,
        outputs: &[Id],
        work: &mut WorkBudget,
    ) -> Result<Vec<Option<Polynomial>>, CanonicalError> {
        for id in self.schedule(outputs) {
            let value = match self.within_budget(id, work) {
                true => Some(self.expand(id)?),
                false => None,
            };
            let over = value.as_ref().map_or(true, |v| v.len() > self.max_terms);
            let value = if over {
                Polynomial::zero()
            } else {
                value.unwrap_or_default()
            };
            for c in self.graph.node(id).children() {
                let k = self.slot[c.index()] as usize;
                self.uses[k] -= 1;
                if self.uses[k] == 0 {
                    self.values[k] = None;
                }
            }
            let k = self.slot[id.index()] as usize;
            self.values[k] = Some(value);
            self.over[k] = over;
        }
        Ok(outputs
            .iter()
            .map(|o| (!self.over[self.slot[o.index()] as usize]).then(|| self.get(*o).clone()))
            .collect())
    }

    /// The needed nodes in the order they are expanded: output by output, the outputs of
    /// fewest estimated terms first ([`Expansion::term_estimates`]), each output's nodes not yet
    /// scheduled children first. When the work budget runs out, the outputs expanded by then
    /// are the cheap ones, not the first ones: a humanoid's gravity torques, not the first
    /// of its joint torques.
    fn schedule(&self, outputs: &[Id]) -> Vec<Id> {
        let estimate = self.term_estimates();
        let mut roots = outputs.to_vec();
        roots.sort_by(|a, b| estimate[self.slot(*a)].total_cmp(&estimate[self.slot(*b)]));
        let mut done = vec![false; self.values.len()];
        let mut order = Vec::with_capacity(self.values.len());
        for root in roots {
            let mut stack = vec![(root, false)];
            while let Some((id, children_done)) = stack.pop() {
                if done[self.slot(id)] {
                    continue;
                }
                if children_done {
                    done[self.slot(id)] = true;
                    order.push(id);
                    continue;
                }
                stack.push((id, true));
                let pending = self
                    .graph
                    .node(id)
                    .children()
                    .filter(|c| !done[self.slot(*c)]);
                stack.extend(pending.map(|c| (c, false)));
            }
        }
        order
    }

    /// An upper bound on each needed node's terms before like terms merge, by slot: a sum adds
    /// its operands' bounds, a product multiplies them, the sine or cosine of an angle of n
    /// terms has 2^(n−1) (saturating at infinity). It orders the outputs, nothing more.
    fn term_estimates(&self) -> Vec<f64> {
        let mut estimate = vec![1.0; self.values.len()];
        for &id in &self.nodes {
            let of = |c: Id| estimate[self.slot(c)];
            estimate[self.slot(id)] = match self.graph.node(id) {
                Node::Const(_) | Node::Symbol(_) => 1.0,
                Node::Add(a, b) => of(a) + of(b),
                Node::Mul(a, b) => of(a) * of(b),
                Node::Neg(a) | Node::Div(a, _) | Node::Sqrt(a) | Node::Sign(a) => of(a),
                Node::Sin(a) | Node::Cos(a) => 2f64.powf(of(a) - 1.0),
            };
        }
        estimate
    }

    /// The position in `values` of a needed node.
    fn slot(&self, id: Id) -> usize {
        self.slot[id.index()] as usize
    }

    /// Whether `id` may be expanded: none of its children passed the bound, a product
    /// multiplies at most [`WORK_PER_TERM`] pairs of terms per allowed term, and `work` has
    /// the node's cost left (which it then spends).
    fn within_budget(&self, id: Id, work: &mut WorkBudget) -> bool {
        let node = self.graph.node(id);
        if node
            .children()
            .any(|c| self.over[self.slot[c.index()] as usize])
        {
            return false;
        }
        let cost = self.cost(node);
        let allowed = match node {
            Node::Mul(..) | Node::Sin(_) | Node::Cos(_) => {
                cost <= self.max_terms.saturating_mul(WORK_PER_TERM)
            }
            _ => true,
        };
        allowed && work.spend(cost)
    }

    /// The work of expanding `node` from its children's forms, in terms handled: a product's
    /// pairs, a sum's operands, a copy's terms; for a sine or cosine whose argument's phasor
    /// is not known yet, the square of an estimate of the phasor's terms (its products).
    fn cost(&self, node: Node) -> usize {
        let len = |id: Id| self.get(id).len();
        let terms = match node {
            Node::Const(_) | Node::Symbol(_) => 0,
            Node::Add(a, b) => len(a).saturating_add(len(b)),
            Node::Mul(a, b) => len(a).saturating_mul(len(b)),
            Node::Neg(a) | Node::Div(a, _) | Node::Sqrt(a) | Node::Sign(a) => len(a),
            Node::Sin(a) | Node::Cos(a) => match self.phasors.get(&a) {
                Some(p) => p.cos.len().max(p.sin.len()),
                None => phasor_size(self.get(a)).saturating_mul(phasor_size(self.get(a))),
            },
        };
        terms.saturating_add(1)
    }

    fn get(&self, id: Id) -> &Polynomial {
        self.values[self.slot[id.index()] as usize]
            .as_ref()
            .expect("children are expanded before their parents")
    }

    /// The value of `id`, moved out when the caller is its last user, cloned otherwise.
    fn take(&mut self, id: Id) -> Polynomial {
        let k = self.slot[id.index()] as usize;
        if self.uses[k] == 1 {
            self.values[k]
                .take()
                .expect("children are expanded before their parents")
        } else {
            self.get(id).clone()
        }
    }

    fn expand(&mut self, id: Id) -> Result<Polynomial, CanonicalError> {
        Ok(match self.graph.node(id) {
            Node::Const(c) if !c.value().is_finite() => {
                return Err(CanonicalError::NonFiniteConstant {
                    node: id,
                    value: c.value(),
                })
            }
            Node::Const(c) => Polynomial::constant(c.value()),
            Node::Symbol(s) => Polynomial::symbol(s),
            Node::Add(a, b) if a == b => self.get(a).scale(2.0),
            Node::Add(a, b) => {
                let (owned, other) = if self.uses[self.slot[b.index()] as usize] == 1 {
                    (b, a)
                } else {
                    (a, b)
                };
                let mut sum = self.take(owned);
                sum += self.get(other);
                sum
            }
            Node::Mul(a, b) => self.get(a) * self.get(b),
            Node::Neg(a) => -self.take(a),
            Node::Div(a, b) => self.divide(id, a, b)?,
            Node::Sin(a) => self.phasor(a).sin.clone(),
            Node::Cos(a) => self.phasor(a).cos.clone(),
            Node::Sqrt(a) => match self.get(a).as_constant() {
                Some(x) if x >= 0.0 => Polynomial::constant(x.sqrt()),
                _ => Polynomial::atom(Atom::Sqrt(Arc::new(self.get(a).clone()))),
            },
            Node::Sign(a) => match self.get(a).as_constant() {
                Some(x) => Polynomial::constant(if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }),
                _ => Polynomial::atom(Atom::Sign(Arc::new(self.get(a).clone()))),
            },
        })
    }

    fn phasor(&mut self, argument: Id) -> &Phasor {
        if !self.phasors.contains_key(&argument) {
            let p = phasor(self.get(argument));
            self.phasors.insert(argument, p);
        }
        &self.phasors[&argument]
    }

    /// `a / b` for a divisor that expands to a monomial free of sines and cosines.
    fn divide(&self, node: Id, a: Id, b: Id) -> Result<Polynomial, CanonicalError> {
        let divisor = self.get(b);
        let mut terms = divisor.terms();
        let (monomial, c) = match (terms.next(), terms.next()) {
            (None, _) => return Err(CanonicalError::DivisionByZero { node }),
            (Some(term), None) => term,
            (Some(_), Some(_)) => {
                return Err(CanonicalError::NonMonomialDivisor {
                    node,
                    terms: divisor.len(),
                })
            }
        };
        if monomial
            .factors()
            .iter()
            .any(|(atom, _)| atom.is_trigonometric())
        {
            return Err(CanonicalError::TrigonometricDivisor { node });
        }
        let reciprocal = monomial.recip();
        let mut quotient = Polynomial::zero();
        for (m, cm) in self.get(a).terms() {
            quotient.add_reduced(m * &reciprocal, cm / c);
        }
        Ok(quotient)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::Monomial;
    use crate::expr::{Symbol, SymbolTable};
    use proptest::prelude::*;

    fn graph() -> ExprGraph {
        let mut symbols = SymbolTable::with_joints(["q1", "q2", "q3"]);
        for p in ["m1", "m2", "l1", "alpha"] {
            symbols.push_parameter(p);
        }
        ExprGraph::new(symbols)
    }

    fn canonical(g: &mut ExprGraph, text: &str) -> Result<Polynomial, CanonicalError> {
        let id = g.parse_sexpr(text).unwrap();
        Polynomial::from_expr(g, id)
    }

    fn assert_same(a: &str, b: &str) {
        let mut g = graph();
        let (pa, pb) = (canonical(&mut g, a).unwrap(), canonical(&mut g, b).unwrap());
        assert_eq!(pa, pb, "{a}  vs  {b}");
    }

    /// A product that rounds differently in two orders cancels: `(0.1·0.2)·0.3·s1 −
    /// 0.1·(0.2·0.3)·s1` differs by an ulp in `f64`, and is 0 in the canonical form.
    #[test]
    fn products_rounded_in_two_orders_cancel() {
        let (a, b) = ((0.1 * 0.2) * 0.3, 0.1 * (0.2 * 0.3));
        assert_ne!(a, b, "the example must round differently");
        let text = format!("(- (* {a} (sin q1)) (* {b} (sin q1)))");
        let mut g = graph();
        assert!(canonical(&mut g, &text).unwrap().is_empty());
        let kept = format!("(- (* {a} (sin q1)) (* 0.0061 (sin q1)))");
        assert_eq!(
            canonical(&mut g, &kept).unwrap().len(),
            1,
            "a real difference stays"
        );
    }

    /// Past the term budget a form is `None`, and so is every form built from it; what stays
    /// within is the full canonical form.
    #[test]
    fn forms_past_the_budget_are_none_and_the_others_complete() {
        let mut g = graph();
        let small = g.parse_sexpr("(* m1 (cos q1))").unwrap();
        let big = g
            .parse_sexpr("(* (* (+ (+ m1 m2) (+ l1 alpha)) (+ (+ m1 m2) (+ l1 alpha))) (+ (+ m1 m2) (+ l1 alpha)))")
            .unwrap();
        let bigger = g.add(big, small);
        let forms = Polynomial::from_exprs_within(
            &g,
            &[small, big, bigger],
            10,
            &mut WorkBudget::unlimited(),
        )
        .unwrap();
        assert_eq!(forms[0], Some(Polynomial::from_expr(&g, small).unwrap()));
        assert_eq!(forms[1], None, "(a + b + c + d)^3 has 20 terms");
        assert_eq!(forms[2], None);
        let all =
            Polynomial::from_exprs_within(&g, &[big], 20, &mut WorkBudget::unlimited()).unwrap();
        assert_eq!(all[0].as_ref().map(Polynomial::len), Some(20));
    }

    /// Work past the budget is refused: the forms that need it are `None`, those that were
    /// expanded before are complete, and no more work is spent than allowed.
    #[test]
    fn forms_past_the_work_budget_are_none_and_the_spending_bounded() {
        let mut g = graph();
        let small = g.parse_sexpr("(* m1 (cos q1))").unwrap();
        let big = g
            .parse_sexpr("(* (+ (+ m1 m2) (+ l1 alpha)) (+ (+ m1 (cos q2)) (+ l1 (sin q3))))")
            .unwrap();
        let mut unlimited = WorkBudget::unlimited();
        let all = Polynomial::from_exprs_within(&g, &[small, big], 100, &mut unlimited).unwrap();
        assert_eq!(
            all[1].as_ref().map(Polynomial::len),
            Some(15),
            "4 by 4 products, m1 l1 twice"
        );
        let needed = unlimited.spent();
        let mut short = WorkBudget::new(needed - 1);
        let forms = Polynomial::from_exprs_within(&g, &[small, big], 100, &mut short).unwrap();
        assert_eq!(
            forms[0], all[0],
            "the small form comes first and is complete"
        );
        assert_eq!(forms[1], None, "the product of 4 by 4 terms does not fit");
        assert!(short.exhausted() && short.spent() < needed);
        let mut exact = WorkBudget::new(needed);
        let forms = Polynomial::from_exprs_within(&g, &[small, big], 100, &mut exact).unwrap();
        assert_eq!(forms, all);
        assert!(!exact.exhausted());
    }

    #[test]
    fn pythagoras_reduces_to_one() {
        assert_same("(+ (* (sin q1) (sin q1)) (* (cos q1) (cos q1)))", "1");
        assert_same(
            "(+ (* (sin (+ q1 q2)) (sin (+ q1 q2))) (* (cos (+ q1 q2)) (cos (+ q1 q2))))",
            "1",
        );
        assert_same(
            "(+ (* (sin (* q1 q2)) (sin (* q1 q2))) (* (cos (* q1 q2)) (cos (* q1 q2))))",
            "1",
        );
    }

    #[test]
    fn angle_sums_expand_by_the_addition_formulas() {
        assert_same(
            "(cos (+ q1 q2))",
            "(- (* (cos q1) (cos q2)) (* (sin q1) (sin q2)))",
        );
        assert_same(
            "(sin (+ q1 q2))",
            "(+ (* (sin q1) (cos q2)) (* (cos q1) (sin q2)))",
        );
        assert_same(
            "(sin (- q1 q2))",
            "(- (* (sin q1) (cos q2)) (* (cos q1) (sin q2)))",
        );
        assert_same(
            "(* (sin (+ q1 q2)) (sin (- q1 q2)))",
            "(- (* (sin q1) (sin q1)) (* (sin q2) (sin q2)))",
        );
        assert_same(
            "(sin (+ q1 alpha))",
            "(+ (* (sin q1) (cos alpha)) (* (cos q1) (sin alpha)))",
        );
    }

    #[test]
    fn multiple_angles_expand() {
        assert_same("(sin (* 2 q1))", "(* 2 (sin q1) (cos q1))");
        assert_same(
            "(cos (* 3 q1))",
            "(- (* 4 (cos q1) (cos q1) (cos q1)) (* 3 (cos q1)))",
        );
        assert_same("(cos (* -2 q2))", "(- (* 2 (cos q2) (cos q2)) 1)");
    }

    #[test]
    fn constant_offsets_are_exact_at_multiples_of_half_pi() {
        assert_same("(sin (- q2 1.5707963267948966))", "(- (cos q2))");
        assert_same("(cos (+ q2 3.141592653589793))", "(- (cos q2))");
        assert_same(
            "(sin (+ (- q2 1.5707963267948966) 4.71238898038469))",
            "(- (sin q2))",
        );
        let mut g = graph();
        let p = canonical(&mut g, "(sin (+ q1 0.5))").unwrap();
        let c1 = Monomial::atom(Atom::cos_of(Symbol::Position(0)));
        assert_eq!(p.term_coefficient(&c1), 0.5f64.sin());
    }

    #[test]
    fn other_arguments_become_structural_angles() {
        assert_same("(sin (- (* q1 q2)))", "(- (sin (* q2 q1)))");
        assert_same("(cos (- (* q1 q2)))", "(cos (* q2 q1))");
        assert_same(
            "(sin (+ q3 (* q1 q2)))",
            "(+ (* (sin q3) (cos (* q1 q2))) (* (cos q3) (sin (* q1 q2))))",
        );
        assert_same("(sin (* 0.5 q1))", "(sin (* q1 0.5))");
    }

    #[test]
    fn square_roots_square_to_their_argument() {
        assert_same("(* (sqrt (+ l1 m1)) (sqrt (+ m1 l1)))", "(+ l1 m1)");
        assert_same("(sqrt 4)", "2");
        assert_same("(/ (* m1 (sqrt l1)) (sqrt l1))", "m1");
    }

    #[test]
    fn division_by_a_monomial_gives_negative_exponents() {
        assert_same("(/ (* m1 (+ l1 q1)) m1)", "(+ l1 q1)");
        assert_same("(* (/ 1 (* m1 m1)) m1)", "(/ 1 m1)");
        assert_same("(/ (* 6 q1) 3)", "(* 2 q1)");
        let mut g = graph();
        let p = canonical(&mut g, "(/ 1 m2)").unwrap();
        let m2 = Atom::Symbol(g.symbols().lookup("m2").unwrap());
        assert_eq!(p.terms().next().unwrap().0.exponent(&m2), -1);
    }

    #[test]
    fn division_by_anything_else_is_an_error() {
        let mut g = graph();
        assert!(matches!(
            canonical(&mut g, "(/ q1 (+ m1 m2))"),
            Err(CanonicalError::NonMonomialDivisor { terms: 2, .. })
        ));
        assert!(matches!(
            canonical(&mut g, "(/ q1 (cos q2))"),
            Err(CanonicalError::TrigonometricDivisor { .. })
        ));
        assert!(matches!(
            canonical(&mut g, "(/ q1 (- m1 m1))"),
            Err(CanonicalError::DivisionByZero { .. })
        ));
        let zero = g
            .parse_sexpr("(- (* (sin q1) (sin q1)) (- 1 (* (cos q1) (cos q1))))")
            .unwrap();
        let q1 = g.parse_sexpr("q1").unwrap();
        let by_zero = g.div(q1, zero);
        assert!(matches!(
            Polynomial::from_expr(&g, by_zero),
            Err(CanonicalError::DivisionByZero { .. })
        ));
        let inf = g.constant(f64::INFINITY);
        assert!(matches!(
            Polynomial::from_expr(&g, inf),
            Err(CanonicalError::NonFiniteConstant { .. })
        ));
    }

    #[test]
    fn shared_subexpressions_are_expanded_once_and_outputs_kept() {
        let mut g = graph();
        let mut x = g.parse_sexpr("(+ (cos q1) (* m1 (sin q2)))").unwrap();
        let mut outputs = vec![x];
        for _ in 0..3 {
            x = g.mul(x, x);
            outputs.push(x);
        }
        let forms = Polynomial::from_exprs(&g, &outputs).unwrap();
        assert_eq!(forms[1], &forms[0] * &forms[0]);
        assert_eq!(forms[3], forms[2].pow(2));
        assert_eq!(forms.len(), outputs.len());
    }

    /// Random expressions over three joints and two parameters, with divisions by a
    /// parameter only.
    fn expression() -> impl Strategy<Value = String> {
        let leaf = prop_oneof![
            Just("q1".to_string()),
            Just("q2".to_string()),
            Just("q3".to_string()),
            Just("m1".to_string()),
            Just("l1".to_string()),
            (-3i32..4).prop_map(|k| k.to_string()),
            Just("1.5707963267948966".to_string()),
        ];
        leaf.prop_recursive(5, 40, 3, |inner| {
            prop_oneof![
                (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("(+ {a} {b})")),
                (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("(- {a} {b})")),
                (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("(* {a} {b})")),
                inner.clone().prop_map(|a| format!("(/ {a} m1)")),
                inner.clone().prop_map(|a| format!("(sin {a})")),
                inner.clone().prop_map(|a| format!("(cos {a})")),
                inner
                    .clone()
                    .prop_map(|a| format!("(sqrt (+ 2 (* {a} {a})))")),
            ]
        })
    }

    fn value(s: Symbol) -> f64 {
        match s {
            Symbol::Position(k) => [0.3, -1.1, 2.0][k as usize],
            Symbol::Parameter(k) => [1.7, 0.4, 0.9, 0.2][k as usize],
            _ => 0.0,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn canonical_form_evaluates_like_the_expression(text in expression()) {
            let mut g = graph();
            let id = g.parse_sexpr(&text).unwrap();
            let p = Polynomial::from_expr(&g, id).unwrap();
            let expected = g.eval(&[id], value)[0];
            let got = p.eval(value);
            let scale = 1.0 + expected.abs() + p.eval(|s| value(s).abs()).abs();
            prop_assert!((got - expected).abs() <= 1e-9 * scale, "{text}: {got} vs {expected}");
        }

        #[test]
        fn canonical_form_survives_a_round_trip_through_the_graph(text in expression()) {
            let mut g = graph();
            let id = g.parse_sexpr(&text).unwrap();
            let p = Polynomial::from_expr(&g, id).unwrap();
            let back = p.to_expr(&mut g);
            let q = Polynomial::from_expr(&g, back).unwrap();
            prop_assert!(q.approx_eq(&p, 1e-14), "{text}");
        }
    }
}

//! Canonical polynomials: sums of monomials with `f64` coefficients, and their arithmetic.

use std::cmp::Ordering;
use std::collections::btree_map::Entry;
use std::collections::BTreeMap;
use std::hash::{Hash, Hasher};
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use super::atom::Atom;
use super::monomial::Monomial;
use crate::expr::{ExprGraph, Id, Symbol};
use crate::Real;

/// A polynomial in [`Atom`]s with `f64` coefficients, in canonical form.
///
/// Invariants, kept by every operation:
/// - terms are stored in a `BTreeMap` keyed by [`Monomial`], so iteration order is fixed;
/// - no coefficient is zero (a sum that cancels, exactly or to round-off, removes the term:
///   [`CANCELLATION_ULPS`]);
/// - every `sin` atom has exponent 0 or 1, because `sin²(x)` is rewritten as `1 − cos²(x)`,
///   and every square root has a positive exponent of at most 1, because `sqrt(p)² = p`.
///
/// Over atoms whose angles are symbols, this is a normal form of trigonometric polynomials:
/// the monomials `c^n` and `s c^n` of each angle are linearly independent functions, so two
/// expressions are equal as functions if and only if their canonical forms are equal (with
/// exact coefficient arithmetic; `f64` rounding can leave differences of a few ulps, see
/// [`approx_eq`](Polynomial::approx_eq)).
///
/// Equality (`==`) compares coefficients exactly, bit for bit.
#[derive(Clone, Debug, Default)]
pub struct Polynomial {
    terms: BTreeMap<Monomial, f64>,
}

impl Polynomial {
    /// The zero polynomial.
    pub fn zero() -> Polynomial {
        Polynomial::default()
    }

    /// The constant 1.
    pub fn one() -> Polynomial {
        Polynomial::constant(1.0)
    }

    /// A constant.
    pub fn constant(value: f64) -> Polynomial {
        Polynomial::from_term(value, Monomial::one())
    }

    /// A bare symbol.
    pub fn symbol(symbol: Symbol) -> Polynomial {
        Polynomial::atom(Atom::Symbol(symbol))
    }

    /// A single atom.
    pub fn atom(atom: Atom) -> Polynomial {
        Polynomial::from_term(1.0, Monomial::atom(atom))
    }

    /// `coefficient · monomial`, brought into canonical form (`sin² = 1 − cos²`,
    /// `sqrt(p)² = p`). Negative exponents of sines and cosines are kept as they are: they are
    /// outside the normal form, and [`from_expr`](Polynomial::from_expr) never produces them.
    pub fn from_term(coefficient: f64, monomial: Monomial) -> Polynomial {
        let mut p = Polynomial::zero();
        p.add_reduced(monomial, coefficient);
        p
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value of a constant polynomial (zero included), `None` otherwise.
    pub fn as_constant(&self) -> Option<f64> {
        match self.terms.len() {
            0 => Some(0.0),
            1 => self.terms.get(&Monomial::one()).copied(),
            _ => None,
        }
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there are no terms (the zero polynomial).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The terms, in canonical (increasing monomial) order.
    pub fn terms(&self) -> impl Iterator<Item = (&Monomial, f64)> + '_ {
        self.terms.iter().map(|(m, &c)| (m, c))
    }

    /// The coefficient of exactly this monomial (0 when absent).
    pub fn term_coefficient(&self, monomial: &Monomial) -> f64 {
        self.terms.get(monomial).copied().unwrap_or(0.0)
    }

    /// Collects terms with respect to the atoms selected by `is_variable`: the result maps
    /// each product of selected atoms that occurs to its coefficient, a polynomial in the
    /// other atoms. The key [`Monomial::one`] holds the part free of selected atoms.
    ///
    /// With [`Atom::is_joint_rate`], a torque τ_i splits into M_ij (key q̈_j), the velocity
    /// products and the gravity part g_i (key 1).
    pub fn collect(&self, is_variable: impl Fn(&Atom) -> bool) -> BTreeMap<Monomial, Polynomial> {
        let mut groups: BTreeMap<Monomial, Polynomial> = BTreeMap::new();
        for (m, &c) in &self.terms {
            let (key, rest) = m.split(&is_variable);
            groups.entry(key).or_default().terms.insert(rest, c);
        }
        groups
    }

    /// The coefficient of `key` in the polynomial viewed as a polynomial in the atoms selected
    /// by `is_variable` (`key` should hold selected atoms only): one entry of
    /// [`collect`](Polynomial::collect), zero when absent. E.g. with [`Atom::is_joint_rate`],
    /// key q̈_j gives M_ij from τ_i, and key 1 gives the gravity part.
    pub fn coefficient(&self, key: &Monomial, is_variable: impl Fn(&Atom) -> bool) -> Polynomial {
        let mut part = Polynomial::zero();
        for (m, &c) in &self.terms {
            let (selected, rest) = m.split(&is_variable);
            if &selected == key {
                part.terms.insert(rest, c);
            }
        }
        part
    }

    /// `factor · self`.
    pub fn scale(&self, factor: f64) -> Polynomial {
        let mut p = Polynomial::zero();
        for (m, &c) in &self.terms {
            add_term(&mut p.terms, m.clone(), c * factor);
        }
        p
    }

    /// `self^n`, by repeated squaring.
    pub fn pow(&self, n: u32) -> Polynomial {
        let mut result = Polynomial::one();
        let mut base = self.clone();
        let mut n = n;
        while n > 0 {
            if n & 1 == 1 {
                result = &result * &base;
            }
            n >>= 1;
            if n > 0 {
                base = &base * &base;
            }
        }
        result
    }

    /// The largest absolute value of a coefficient (0 for the zero polynomial).
    pub fn max_abs_coefficient(&self) -> f64 {
        self.terms.values().fold(0.0, |m, c| m.max(c.abs()))
    }

    /// The largest absolute difference between coefficients of the same monomial, a monomial
    /// absent from one side counting as coefficient 0. Zero exactly when the polynomials are
    /// equal (for finite coefficients).
    pub fn max_abs_difference(&self, other: &Polynomial) -> f64 {
        let mut max: f64 = 0.0;
        for (m, &c) in &self.terms {
            max = max.max((c - other.term_coefficient(m)).abs());
        }
        for (m, &c) in &other.terms {
            if !self.terms.contains_key(m) {
                max = max.max(c.abs());
            }
        }
        max
    }

    /// Whether the polynomials agree to relative accuracy `rel` in the max-norm of their
    /// coefficient vectors: `max_abs_difference ≤ rel · max(|self|, |other|)`. This is the
    /// comparison for coefficients computed from inexact parameters, where a product can come
    /// out a few ulps apart along two paths and a cancellation can leave a tiny residue.
    pub fn approx_eq(&self, other: &Polynomial, rel: f64) -> bool {
        let scale = self.max_abs_coefficient().max(other.max_abs_coefficient());
        self.max_abs_difference(other) <= rel * scale
    }

    /// Builds the polynomial in `graph`: a sum of products, terms in canonical order,
    /// negative coefficients as subtractions and negative exponents as one division per term.
    pub fn to_expr(&self, graph: &mut ExprGraph) -> Id {
        let mut total = graph.zero();
        for (m, &c) in &self.terms {
            let mut numerator = graph.constant(c.abs());
            let mut denominator = graph.one();
            for (atom, e) in m.factors() {
                let a = atom.to_expr(graph);
                for _ in 0..e.unsigned_abs() {
                    if *e > 0 {
                        numerator = graph.mul(numerator, a);
                    } else {
                        denominator = graph.mul(denominator, a);
                    }
                }
            }
            let term = graph.div(numerator, denominator);
            total = if c < 0.0 {
                graph.sub(total, term)
            } else {
                graph.add(total, term)
            };
        }
        total
    }

    /// The value at a point, in any [`Real`] type.
    pub fn eval<T: Real>(&self, value: impl Fn(Symbol) -> T) -> T {
        self.eval_with(&value)
    }

    pub(super) fn eval_with<T: Real>(&self, value: &dyn Fn(Symbol) -> T) -> T {
        let mut total = T::zero();
        for (m, &c) in &self.terms {
            let mut term = T::from_f64(c);
            for (atom, e) in m.factors() {
                let a = atom.eval(value);
                for _ in 0..e.unsigned_abs() {
                    term = if *e > 0 { term * a } else { term / a };
                }
            }
            total += term;
        }
        total
    }

    /// Adds `coefficient · monomial`, applying the canonical-form rewrites to the monomial.
    pub(super) fn add_reduced(&mut self, monomial: Monomial, coefficient: f64) {
        if coefficient == 0.0 {
            return;
        }
        if !monomial.needs_reduction() {
            add_term(&mut self.terms, monomial, coefficient);
            return;
        }
        let mut base = Vec::new();
        let mut factor = Polynomial::one();
        for (atom, e) in monomial.factors() {
            match atom {
                // sin^e = sin^(e mod 2) (1 − cos²)^(e div 2)
                Atom::Sin(angle) if *e >= 2 => {
                    let cos2 =
                        Polynomial::from_term(1.0, Monomial::power(Atom::Cos(angle.clone()), 2));
                    factor = &factor * &(&Polynomial::one() - &cos2).pow((*e / 2) as u32);
                }
                // sqrt(p)^e = sqrt(p)^(e mod 2) p^(e div 2)
                Atom::Sqrt(p) if *e >= 2 => factor = &factor * &p.pow((*e / 2) as u32),
                _ => {
                    base.push((atom.clone(), *e));
                    continue;
                }
            }
            if e % 2 == 1 {
                base.push((atom.clone(), 1));
            }
        }
        let base = Monomial::from_sorted(base);
        for (m, c) in factor.terms {
            self.add_reduced(&base * &m, coefficient * c);
        }
    }
}

/// How far below its operands, in units of `f64::EPSILON` times the larger of them, a sum of
/// two coefficients must be for the term to cancel (`add_term`).
///
/// Folded numeric coefficients are products of the robot file's numbers rounded in whatever
/// order the recursion met them, so a term that cancels in real arithmetic (the UR5's first
/// gravity torque, which is identically 0 because its axis is vertical) can leave a residue of
/// an ulp or so of the coefficients it came from: `0.17446825035 − 0.17446825035000002` is
/// 2.8·10⁻¹⁷. A sum that small has lost every significant digit (its relative error is 100 %),
/// so it is the zero it stands for. Coefficients of symbolic parameters are small integers and
/// dyadic fractions, whose sums are exact: their cancellations are exact zeros either way.
pub const CANCELLATION_ULPS: f64 = 16.0;

/// Whether `a + b` is zero or lost every digit to cancellation ([`CANCELLATION_ULPS`]).
fn cancels(a: f64, b: f64) -> bool {
    let sum = a + b;
    sum == 0.0 || sum.abs() <= CANCELLATION_ULPS * f64::EPSILON * a.abs().max(b.abs())
}

/// Adds `c` to the coefficient of `m`, removing the term when it cancels ([`cancels`]).
fn add_term(terms: &mut BTreeMap<Monomial, f64>, m: Monomial, c: f64) {
    if c == 0.0 {
        return;
    }
    match terms.entry(m) {
        Entry::Vacant(e) => {
            e.insert(c);
        }
        Entry::Occupied(mut e) => {
            if cancels(*e.get(), c) {
                e.remove();
            } else {
                *e.get_mut() += c;
            }
        }
    }
}

impl From<Monomial> for Polynomial {
    fn from(monomial: Monomial) -> Polynomial {
        Polynomial::from_term(1.0, monomial)
    }
}

impl PartialEq for Polynomial {
    fn eq(&self, other: &Polynomial) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Polynomial {}

impl PartialOrd for Polynomial {
    fn partial_cmp(&self, other: &Polynomial) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Polynomial {
    /// Lexicographic over the terms in canonical order, coefficients by `f64::total_cmp`:
    /// an arbitrary but fixed order, so that atoms holding polynomials can be sorted.
    fn cmp(&self, other: &Polynomial) -> Ordering {
        for ((ma, ca), (mb, cb)) in self.terms.iter().zip(&other.terms) {
            let ord = ma.cmp(mb).then_with(|| ca.total_cmp(cb));
            if ord != Ordering::Equal {
                return ord;
            }
        }
        self.terms.len().cmp(&other.terms.len())
    }
}

impl Hash for Polynomial {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.terms.len().hash(state);
        for (m, c) in &self.terms {
            m.hash(state);
            c.to_bits().hash(state);
        }
    }
}

impl Add for &Polynomial {
    type Output = Polynomial;
    fn add(self, other: &Polynomial) -> Polynomial {
        let mut sum = self.clone();
        sum += other;
        sum
    }
}

impl Sub for &Polynomial {
    type Output = Polynomial;
    fn sub(self, other: &Polynomial) -> Polynomial {
        let mut difference = self.clone();
        difference -= other;
        difference
    }
}

impl Mul for &Polynomial {
    type Output = Polynomial;
    fn mul(self, other: &Polynomial) -> Polynomial {
        if let Some(c) = self.as_constant() {
            return other.scale(c);
        }
        if let Some(c) = other.as_constant() {
            return self.scale(c);
        }
        let mut product = Polynomial::zero();
        for (ma, &ca) in &self.terms {
            for (mb, &cb) in &other.terms {
                product.add_reduced(ma * mb, ca * cb);
            }
        }
        product
    }
}

impl Neg for &Polynomial {
    type Output = Polynomial;
    fn neg(self) -> Polynomial {
        Polynomial {
            terms: self.terms.iter().map(|(m, &c)| (m.clone(), -c)).collect(),
        }
    }
}

impl Add for Polynomial {
    type Output = Polynomial;
    fn add(mut self, other: Polynomial) -> Polynomial {
        self += &other;
        self
    }
}

impl Sub for Polynomial {
    type Output = Polynomial;
    fn sub(mut self, other: Polynomial) -> Polynomial {
        self -= &other;
        self
    }
}

impl Mul for Polynomial {
    type Output = Polynomial;
    fn mul(self, other: Polynomial) -> Polynomial {
        &self * &other
    }
}

impl Neg for Polynomial {
    type Output = Polynomial;
    fn neg(mut self) -> Polynomial {
        for c in self.terms.values_mut() {
            *c = -*c;
        }
        self
    }
}

impl AddAssign<&Polynomial> for Polynomial {
    fn add_assign(&mut self, other: &Polynomial) {
        for (m, &c) in &other.terms {
            add_term(&mut self.terms, m.clone(), c);
        }
    }
}

impl SubAssign<&Polynomial> for Polynomial {
    fn sub_assign(&mut self, other: &Polynomial) {
        for (m, &c) in &other.terms {
            add_term(&mut self.terms, m.clone(), -c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::testing::{graph, planar_elbow, ELBOW_PARAMETERS};

    fn s(k: u16) -> Polynomial {
        Polynomial::atom(Atom::sin_of(Symbol::Position(k)))
    }

    fn c(k: u16) -> Polynomial {
        Polynomial::atom(Atom::cos_of(Symbol::Position(k)))
    }

    fn x(k: u16) -> Polynomial {
        Polynomial::symbol(Symbol::Parameter(k))
    }

    #[test]
    fn arithmetic_follows_the_ring_laws() {
        let (a, b) = (&x(0) + &c(1), &x(1) - &s(0));
        let square = (&a + &b).pow(2);
        let expanded = &(&a.pow(2) + &(&a * &b).scale(2.0)) + &b.pow(2);
        assert_eq!(square, expanded);
        assert!((&a - &a).is_zero());
        assert_eq!(-&a + a.clone(), Polynomial::zero());
        assert!(a.scale(0.0).is_zero());
        assert_eq!(&a * &Polynomial::one(), a);
        assert_eq!(Polynomial::constant(3.0).as_constant(), Some(3.0));
        assert_eq!(Polynomial::zero().as_constant(), Some(0.0));
        assert_eq!(a.as_constant(), None);
    }

    #[test]
    fn sines_never_appear_squared() {
        let cube = s(0).pow(3);
        assert_eq!(cube, &s(0) - &(&s(0) * &c(0).pow(2)));
        let p = (&s(0) + &s(1)).pow(4);
        for (m, _) in p.terms() {
            for (atom, e) in m.factors() {
                assert!(!matches!(atom, Atom::Sin(_)) || *e == 1, "{m:?}");
            }
        }
        assert_eq!(&s(0).pow(2) + &c(0).pow(2), Polynomial::one());
        let raw = Polynomial::from_term(2.0, Monomial::power(Atom::sin_of(Symbol::Position(0)), 2));
        assert_eq!(raw, (&Polynomial::one() - &c(0).pow(2)).scale(2.0));
    }

    #[test]
    fn exact_cancellation_drops_the_term() {
        let p = &(&x(0) * &c(0)) + &x(1);
        let q = &p - &(&x(0) * &c(0));
        assert_eq!(q.len(), 1);
        assert_eq!(q, x(1));
    }

    #[test]
    fn collect_splits_a_torque_into_mass_matrix_velocity_and_gravity_parts() {
        let mut g = graph(&["q1", "q2"], &ELBOW_PARAMETERS);
        let tau = planar_elbow(&mut g);
        let tau1 = Polynomial::from_expr(&g, tau[0]).unwrap();
        let groups = tau1.collect(Atom::is_joint_rate);
        let keys: Vec<String> = groups
            .keys()
            .map(|k| format!("{:?}", k.factors()))
            .collect();
        assert_eq!(groups.len(), 5, "{keys:?}");
        let ddq1 = Monomial::atom(Atom::Symbol(Symbol::Acceleration(0)));
        assert_eq!(tau1.coefficient(&ddq1, Atom::is_joint_rate), groups[&ddq1]);
        let gravity = tau1.coefficient(&Monomial::one(), Atom::is_joint_rate);
        assert!(gravity
            .terms()
            .all(|(m, _)| m.factors().iter().all(|(a, _)| !a.is_joint_rate())));
        let mut sum = Polynomial::zero();
        for (key, coefficient) in &groups {
            sum += &(&Polynomial::from(key.clone()) * coefficient);
        }
        assert_eq!(sum, tau1);
        assert!(tau1
            .coefficient(
                &Monomial::atom(Atom::Symbol(Symbol::Velocity(0))),
                Atom::is_joint_rate
            )
            .is_zero());
    }

    #[test]
    fn approximate_comparison_tolerates_rounding_only() {
        let p = &(&x(0) * &c(0)).scale(0.1) + &x(1).scale(100.0);
        let q = &(&x(0) * &c(0)).scale(0.1 * (1.0 + 4.0 * f64::EPSILON)) + &x(1).scale(100.0);
        assert_ne!(p, q);
        assert!(p.max_abs_difference(&q) > 0.0 && p.max_abs_difference(&q) < 1e-16);
        assert!(p.approx_eq(&q, 1e-15));
        let r = &p + &Polynomial::constant(1e-9);
        assert_eq!(p.max_abs_difference(&r), 1e-9);
        assert!(!p.approx_eq(&r, 1e-12));
        assert_eq!(p.max_abs_difference(&p), 0.0);
    }

    #[test]
    fn term_order_is_canonical_whatever_the_construction_order() {
        let a = &(&x(1) + &c(0)) + &(&s(1) * &x(0));
        let b = &(&(&s(1) * &x(0)) + &x(1)) + &c(0);
        assert_eq!(a, b);
        let ta: Vec<_> = a.terms().map(|(m, c)| (m.clone(), c)).collect();
        let tb: Vec<_> = b.terms().map(|(m, c)| (m.clone(), c)).collect();
        assert_eq!(ta, tb);
        let order: Vec<Monomial> = [
            [
                (Atom::Symbol(Symbol::Parameter(0)), 1),
                (Atom::sin_of(Symbol::Position(1)), 1),
            ]
            .to_vec(),
            [(Atom::Symbol(Symbol::Parameter(1)), 1)].to_vec(),
            [(Atom::cos_of(Symbol::Position(0)), 1)].to_vec(),
        ]
        .map(Monomial::from_iter)
        .to_vec();
        assert_eq!(ta.into_iter().map(|(m, _)| m).collect::<Vec<_>>(), order);
    }

    #[test]
    fn evaluation_and_reconstruction_agree_with_the_graph() {
        let mut g = graph(&["q1", "q2"], &ELBOW_PARAMETERS);
        let tau = planar_elbow(&mut g);
        let forms = Polynomial::from_exprs(&g, &tau).unwrap();
        let value = |s: Symbol| match s {
            Symbol::Position(k) => [0.4, -1.3][k as usize],
            Symbol::Velocity(k) => [0.7, 2.1][k as usize],
            Symbol::Acceleration(k) => [-0.2, 0.9][k as usize],
            Symbol::Parameter(k) => 0.5 + f64::from(k) / 3.0,
            Symbol::Force(_) => 0.0,
            Symbol::Lane(_) => f64::NAN,
        };
        let direct = g.eval(&tau, value);
        let rebuilt: Vec<Id> = forms.iter().map(|p| p.to_expr(&mut g)).collect();
        let via_graph = g.eval(&rebuilt, value);
        for i in 0..2 {
            assert!((forms[i].eval(value) - direct[i]).abs() < 1e-12);
            assert!((via_graph[i] - direct[i]).abs() < 1e-12);
        }
    }
}

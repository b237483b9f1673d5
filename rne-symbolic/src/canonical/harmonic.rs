//! Printed terms in the harmonic basis: products of joint sines and cosines rewritten as
//! sines and cosines of integer combinations of joint positions.
//!
//! The product-to-sum formulas
//!
//! ```text
//! cos a cos b = ½ cos(a − b) + ½ cos(a + b)      sin a sin b = ½ cos(a − b) − ½ cos(a + b)
//! sin a cos b = ½ sin(a + b) + ½ sin(a − b)      cos a sin b = ½ sin(a + b) − ½ sin(a − b)
//! ```
//!
//! turn every product of s_k and c_k into a sum of single harmonics `cos(n·q)` and
//! `sin(n·q)`, n an integer vector whose first non-zero entry is positive. That basis is
//! unique too, so the contraction is exact and complete rather than greedy: `c1 c2 − s1 s2`
//! becomes c12, `s12 c3 + c12 s3` becomes s123, and whatever does not contract to a single
//! harmonic stays visibly separate (`c2²` prints as `0.5 + 0.5 cos(2 q2)`, the form of the
//! thesis's Maple output for the IRB 140 in Appendix B, which used `combine(trig)`).
//! Sines and cosines of parameters (twist angles) and of other expressions are not joint
//! harmonics: they stay ordinary factors.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use super::atom::{Angle, Atom};
use super::polynomial::Polynomial;
use crate::expr::Symbol;

/// `sin(n·q)` or `cos(n·q)` for an integer vector n over the joints.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(super) struct Harmonic {
    /// Whether this is a sine.
    pub(super) sine: bool,
    /// The non-zero entries of n as (joint index, multiple), by joint; the first is positive.
    pub(super) frequencies: Vec<(u16, i32)>,
}

/// A factor of a printed term.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(super) enum Factor {
    /// Any atom that is not a joint sine or cosine.
    Atom(Atom),
    /// A joint harmonic (always with exponent 1).
    Harmonic(Harmonic),
}

/// A printed term: a coefficient times powers of factors.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Term {
    /// The coefficient.
    pub(super) coefficient: f64,
    /// The factors and their exponents (none zero).
    pub(super) factors: BTreeMap<Factor, i32>,
}

/// The terms of `p` in the harmonic basis, in a fixed order. A coefficient that cancels to
/// within rounding of the contributions to it (`|Σ c| ≤ 4 ε Σ |c|`) is dropped: with numeric
/// parameters, `c1 c2` and `s1 s2` may carry coefficients a few ulps apart, and the residue
/// `1e-17 cos(q1 − q2)` is noise, not information.
pub(super) fn harmonic_terms(p: &Polynomial) -> Vec<Term> {
    let mut sums: BTreeMap<BTreeMap<Factor, i32>, (f64, f64)> = BTreeMap::new();
    for (monomial, c) in p.terms() {
        let mut factors = BTreeMap::new();
        let mut harmonics: BTreeMap<Option<Harmonic>, f64> = BTreeMap::from([(None, 1.0)]);
        for (atom, e) in monomial.factors() {
            match joint_trig(atom) {
                Some((sine, joint)) if *e > 0 => {
                    for _ in 0..*e {
                        harmonics = times(&harmonics, sine, joint);
                    }
                }
                _ => {
                    factors.insert(Factor::Atom(atom.clone()), *e);
                }
            }
        }
        for (h, hc) in harmonics {
            let mut term_factors = factors.clone();
            if let Some(h) = h {
                term_factors.insert(Factor::Harmonic(h), 1);
            }
            let sum = sums.entry(term_factors).or_insert((0.0, 0.0));
            sum.0 += c * hc;
            sum.1 += (c * hc).abs();
        }
    }
    sums.into_iter()
        .filter(|(_, (sum, magnitude))| sum.abs() > 4.0 * f64::EPSILON * magnitude)
        .map(|(factors, (coefficient, _))| Term {
            coefficient,
            factors,
        })
        .collect()
}

/// A bound on the work of printing `p` ([`harmonic_terms`] and what follows): a term whose
/// joint sines and cosines have total degree d spreads into at most 2^(d − 1) harmonics, built
/// in d doublings, so it costs at most 2^(d + 1); a structural atom (`sqrt(…)`, `sin(…)` of
/// another argument) is printed, with its own polynomial, wherever it occurs. The bound is
/// found without expanding anything, in time linear in the terms (each structural atom's
/// polynomial is visited once).
pub(super) fn print_work(p: &Polynomial) -> usize {
    print_work_memo(p, &mut HashMap::new())
}

fn print_work_memo(p: &Polynomial, seen: &mut HashMap<*const Polynomial, usize>) -> usize {
    let mut work: usize = 1;
    for (monomial, _) in p.terms() {
        let mut degree: u32 = 0;
        let mut nested: usize = 0;
        for (atom, e) in monomial.factors() {
            if joint_trig(atom).is_some() && *e > 0 {
                degree = degree.saturating_add(e.unsigned_abs());
                continue;
            }
            let inner = match atom {
                Atom::Sin(Angle::Expr(q)) | Atom::Cos(Angle::Expr(q)) => q,
                Atom::Sqrt(q) | Atom::Sign(q) => q,
                _ => continue,
            };
            let key = Arc::as_ptr(inner);
            let cost = match seen.get(&key) {
                Some(&cost) => cost,
                None => {
                    let cost = print_work_memo(inner, seen);
                    seen.insert(key, cost);
                    cost
                }
            };
            nested = nested.saturating_add(cost);
        }
        let spread = 1usize
            .checked_shl(degree.saturating_add(1))
            .unwrap_or(usize::MAX);
        work = work.saturating_add(spread).saturating_add(nested);
    }
    work
}

/// `(is sine, joint)` of s_k or c_k.
fn joint_trig(atom: &Atom) -> Option<(bool, u16)> {
    match atom {
        Atom::Sin(Angle::Symbol(Symbol::Position(k))) => Some((true, *k)),
        Atom::Cos(Angle::Symbol(Symbol::Position(k))) => Some((false, *k)),
        _ => None,
    }
}

/// A sum of harmonics (`None` is the constant 1) times s_joint or c_joint.
fn times(
    sum: &BTreeMap<Option<Harmonic>, f64>,
    sine: bool,
    joint: u16,
) -> BTreeMap<Option<Harmonic>, f64> {
    let mut out = BTreeMap::new();
    let mut add = |(h, c): (Option<Harmonic>, f64)| *out.entry(h).or_insert(0.0) += c;
    let unit = [(joint, 1)];
    for (h, &c) in sum {
        let Some(h) = h else {
            add(normalised(sine, unit.to_vec(), c));
            continue;
        };
        let plus = combine(&h.frequencies, joint, 1);
        let minus = combine(&h.frequencies, joint, -1);
        let half = 0.5 * c;
        let products = match (h.sine, sine) {
            (false, false) => [(false, minus, half), (false, plus, half)],
            (true, true) => [(false, minus, half), (false, plus, -half)],
            (true, false) => [(true, plus, half), (true, minus, half)],
            (false, true) => [(true, plus, half), (true, minus, -half)],
        };
        for (s, f, coefficient) in products {
            add(normalised(s, f, coefficient));
        }
    }
    out.retain(|_, c| *c != 0.0);
    out
}

/// The frequencies `a ± e_joint`.
fn combine(a: &[(u16, i32)], joint: u16, sign: i32) -> Vec<(u16, i32)> {
    let mut f = a.to_vec();
    match f.binary_search_by_key(&joint, |&(j, _)| j) {
        Ok(i) => {
            f[i].1 += sign;
            if f[i].1 == 0 {
                f.remove(i);
            }
        }
        Err(i) => f.insert(i, (joint, sign)),
    }
    f
}

/// `coefficient · sin/cos(f·q)` with f's first entry made positive; `cos 0 = 1` is `None`
/// and `sin 0 = 0` has coefficient 0.
fn normalised(sine: bool, mut f: Vec<(u16, i32)>, coefficient: f64) -> (Option<Harmonic>, f64) {
    if f.is_empty() {
        return (None, if sine { 0.0 } else { coefficient });
    }
    let mut coefficient = coefficient;
    if f[0].1 < 0 {
        for entry in &mut f {
            entry.1 = -entry.1;
        }
        if sine {
            coefficient = -coefficient;
        }
    }
    (
        Some(Harmonic {
            sine,
            frequencies: f,
        }),
        coefficient,
    )
}

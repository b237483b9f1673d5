//! How a sum of printed terms is factored for reading: a common factor of all terms, then
//! greedy grouping by the most frequent non-trigonometric factor.
//!
//! `I1 + I2 + l1² m2 + lc1² m1 + lc2² m2 + 2 l1 lc2 m2 c2` is laid out as
//! `I1 + I2 + lc1² m1 + m2 (l1² + lc2² + 2 l1 lc2 c2)`: the factor that occurs in the most
//! terms (at least two) is pulled out of those terms, each group then loses what all its
//! terms share, and the search repeats on the terms left over. Groups are one level deep,
//! and the choice is greedy (the most frequent factor first, ties to the smaller [`Factor`]
//! in its derived order, i.e. parameters in spec order), not a search for the shortest form.

use std::collections::BTreeMap;

use super::harmonic::{Factor, Term};

/// An item of a laid-out sum.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Item {
    /// A single term.
    Term(Term),
    /// `common · (terms)`.
    Group {
        /// What the grouped terms share, with their common coefficient.
        common: Term,
        /// The grouped terms divided by `common`.
        terms: Vec<Term>,
    },
}

/// Splits `terms` into what they all share and the cofactors. The shared part holds every
/// factor with a positive exponent in all terms (at its smallest exponent) and a coefficient:
/// the common magnitude when all coefficients have the same magnitude, else 1, negated when
/// all coefficients are negative.
pub(super) fn common_factor(terms: &[Term]) -> (Term, Vec<Term>) {
    let mut factors: BTreeMap<Factor, i32> = match terms.first() {
        Some(t) => t
            .factors
            .iter()
            .filter(|(_, &e)| e > 0)
            .map(|(f, &e)| (f.clone(), e))
            .collect(),
        None => BTreeMap::new(),
    };
    for t in terms {
        factors = factors
            .into_iter()
            .filter_map(|(f, e)| {
                t.factors
                    .get(&f)
                    .map(|&g| (f, e.min(g)))
                    .filter(|(_, e)| *e > 0)
            })
            .collect();
    }
    let magnitude = terms.first().map_or(1.0, |t| t.coefficient.abs());
    let magnitude = if terms.iter().all(|t| t.coefficient.abs() == magnitude) {
        magnitude
    } else {
        1.0
    };
    let sign = if !terms.is_empty() && terms.iter().all(|t| t.coefficient < 0.0) {
        -1.0
    } else {
        1.0
    };
    let common = Term {
        coefficient: sign * magnitude,
        factors,
    };
    let cofactors = terms
        .iter()
        .map(|t| {
            let mut rest = t.factors.clone();
            for (f, e) in &common.factors {
                let remaining = rest[f] - e;
                if remaining == 0 {
                    rest.remove(f);
                } else {
                    rest.insert(f.clone(), remaining);
                }
            }
            Term {
                coefficient: t.coefficient / common.coefficient,
                factors: rest,
            }
        })
        .collect();
    (common, cofactors)
}

/// Lays out a sum: groups by frequent factors, then the remaining single terms.
pub(super) fn group(terms: Vec<Term>) -> Vec<Item> {
    let mut items = Vec::new();
    let mut rest = terms;
    while let Some(factor) = most_frequent_factor(&rest, items.is_empty()) {
        let (with, without): (Vec<Term>, Vec<Term>) = rest
            .into_iter()
            .partition(|t| t.factors.get(&factor).is_some_and(|&e| e > 0));
        let (common, terms) = common_factor(&with);
        items.push(Item::Group { common, terms });
        rest = without;
    }
    items.extend(rest.into_iter().map(Item::Term));
    items
}

/// The non-trigonometric factor with a positive exponent in the most terms, if it occurs in
/// at least two (and, when `first`, not in all of them: that is the common factor's job).
fn most_frequent_factor(terms: &[Term], first: bool) -> Option<Factor> {
    let mut counts: BTreeMap<&Factor, usize> = BTreeMap::new();
    for t in terms {
        for (f, &e) in &t.factors {
            if e > 0 && matches!(f, Factor::Atom(a) if !a.is_trigonometric()) {
                *counts.entry(f).or_insert(0) += 1;
            }
        }
    }
    let (factor, count) =
        counts
            .into_iter()
            .fold(None, |best: Option<(&Factor, usize)>, (f, n)| match best {
                Some((_, m)) if m >= n => best,
                _ => Some((f, n)),
            })?;
    (count >= 2 && !(first && count == terms.len())).then(|| factor.clone())
}

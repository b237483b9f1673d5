//! Products of powers of atoms.

use std::ops::Mul;

use super::atom::Atom;

/// A product of integer powers of distinct [`Atom`]s, kept sorted by atom with no zero
/// exponent, so that equal products are equal values. The empty product is 1.
///
/// A monomial on its own is not reduced: [`Polynomial::from_term`](super::Polynomial::from_term)
/// applies `sin² = 1 − cos²` and `sqrt(p)² = p` when it becomes part of a polynomial.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Monomial {
    factors: Vec<(Atom, i32)>,
}

impl Monomial {
    /// The empty product, 1.
    pub fn one() -> Monomial {
        Monomial::default()
    }

    /// A single atom.
    pub fn atom(atom: Atom) -> Monomial {
        Monomial::power(atom, 1)
    }

    /// `atom^exponent`.
    pub fn power(atom: Atom, exponent: i32) -> Monomial {
        let factors = if exponent == 0 {
            Vec::new()
        } else {
            vec![(atom, exponent)]
        };
        Monomial { factors }
    }

    /// Whether this is the empty product.
    pub fn is_one(&self) -> bool {
        self.factors.is_empty()
    }

    /// The atoms and their exponents, in increasing atom order.
    pub fn factors(&self) -> &[(Atom, i32)] {
        &self.factors
    }

    /// The exponent of `atom` (0 when absent).
    pub fn exponent(&self, atom: &Atom) -> i32 {
        match self.factors.binary_search_by(|(a, _)| a.cmp(atom)) {
            Ok(i) => self.factors[i].1,
            Err(_) => 0,
        }
    }

    /// The reciprocal: every exponent negated.
    pub fn recip(&self) -> Monomial {
        Monomial {
            factors: self.factors.iter().map(|(a, e)| (a.clone(), -e)).collect(),
        }
    }

    /// Splits the product into the factors whose atoms satisfy `select` and the rest.
    pub fn split(&self, select: impl Fn(&Atom) -> bool) -> (Monomial, Monomial) {
        let (chosen, rest) = self.factors.iter().cloned().partition(|(a, _)| select(a));
        (Monomial { factors: chosen }, Monomial { factors: rest })
    }

    /// Whether the product holds `sin^e` or `sqrt(p)^e` with `e ≥ 2`, which canonical form
    /// rewrites.
    pub(super) fn needs_reduction(&self) -> bool {
        self.factors
            .iter()
            .any(|(a, e)| *e >= 2 && matches!(a, Atom::Sin(_) | Atom::Sqrt(_)))
    }

    /// Builds a monomial from factors already sorted by atom, distinct and non-zero.
    pub(super) fn from_sorted(factors: Vec<(Atom, i32)>) -> Monomial {
        debug_assert!(
            factors.windows(2).all(|w| w[0].0 < w[1].0) && factors.iter().all(|f| f.1 != 0)
        );
        Monomial { factors }
    }
}

impl Mul for &Monomial {
    type Output = Monomial;

    /// The product, exponents of equal atoms added (not reduced).
    fn mul(self, other: &Monomial) -> Monomial {
        let (a, b) = (&self.factors, &other.factors);
        let mut factors = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    factors.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    factors.push(b[j].clone());
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let e = a[i].1 + b[j].1;
                    if e != 0 {
                        factors.push((a[i].0.clone(), e));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        factors.extend_from_slice(&a[i..]);
        factors.extend_from_slice(&b[j..]);
        Monomial { factors }
    }
}

impl FromIterator<(Atom, i32)> for Monomial {
    /// The product of `atom^exponent` over the items (repeated atoms multiply).
    fn from_iter<I: IntoIterator<Item = (Atom, i32)>>(iter: I) -> Monomial {
        let mut factors: Vec<(Atom, i32)> = Vec::new();
        for (atom, exponent) in iter {
            match factors.binary_search_by(|(a, _)| a.cmp(&atom)) {
                Ok(i) => factors[i].1 += exponent,
                Err(i) => factors.insert(i, (atom, exponent)),
            }
        }
        factors.retain(|(_, e)| *e != 0);
        Monomial { factors }
    }
}

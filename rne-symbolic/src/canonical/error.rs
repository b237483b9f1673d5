//! Why an expression has no canonical polynomial form.

use crate::expr::Id;

/// An expression that [`Polynomial::from_expr`](super::Polynomial::from_expr) cannot bring into
/// canonical form. Each variant names the graph node at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CanonicalError {
    /// A division whose divisor expands to more than one term: the quotient is a rational
    /// function, not a polynomial.
    #[error("division at node {node} by a sum of {terms} terms; only monomials can divide")]
    NonMonomialDivisor {
        /// The division node.
        node: Id,
        /// Number of terms of the expanded divisor.
        terms: usize,
    },
    /// A division by a monomial that contains a sine or cosine: its reciprocal has no
    /// canonical form (the Pythagorean reduction works on non-negative powers only).
    #[error("division at node {node} by a monomial containing a sine or cosine")]
    TrigonometricDivisor {
        /// The division node.
        node: Id,
    },
    /// A division by an expression that expands to zero.
    #[error("division by zero at node {node}")]
    DivisionByZero {
        /// The division node.
        node: Id,
    },
    /// An infinite or NaN constant.
    #[error("non-finite constant {value} at node {node}")]
    NonFiniteConstant {
        /// The constant node.
        node: Id,
        /// Its value.
        value: f64,
    },
}

//! The indeterminates of canonical polynomials.

use std::sync::Arc;

use super::polynomial::Polynomial;
use crate::expr::{ExprGraph, Id, Symbol};
use crate::Real;

/// The argument of a trigonometric [`Atom`].
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Angle {
    /// A symbol: the position q_k of a revolute joint, or a parameter such as a twist angle.
    Symbol(Symbol),
    /// Any other argument: what is left of it once its integer multiples of symbols and its
    /// constant have been expanded away, in canonical form and with a positive first
    /// coefficient (`sin(−x) = −sin x`, `cos(−x) = cos x`).
    Expr(Arc<Polynomial>),
}

/// An indeterminate of a [`Polynomial`].
///
/// Atoms are structural values, independent of any graph: two expressions built separately
/// (even in different graphs) have equal atoms when their canonical forms agree.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Atom {
    /// A bare symbol: a prismatic joint position, a velocity, an acceleration, a generalised
    /// force or a parameter.
    Symbol(Symbol),
    /// `sin` of an angle. Its exponent is at most 1 in canonical form (`sin² = 1 − cos²`).
    Sin(Angle),
    /// `cos` of an angle.
    Cos(Angle),
    /// Square root of a polynomial that is not a constant. Its positive exponents are at
    /// most 1 in canonical form (`sqrt(p)² = p`).
    Sqrt(Arc<Polynomial>),
    /// Sign of a polynomial that is not a constant (Coulomb friction's sign(q̇)).
    Sign(Arc<Polynomial>),
}

impl Atom {
    /// `sin` of a symbol, e.g. s_k = sin q_k.
    pub fn sin_of(symbol: Symbol) -> Atom {
        Atom::Sin(Angle::Symbol(symbol))
    }

    /// `cos` of a symbol, e.g. c_k = cos q_k.
    pub fn cos_of(symbol: Symbol) -> Atom {
        Atom::Cos(Angle::Symbol(symbol))
    }

    /// Whether this is a sine or a cosine.
    pub fn is_trigonometric(&self) -> bool {
        matches!(self, Atom::Sin(_) | Atom::Cos(_))
    }

    /// Whether this is a joint velocity or acceleration: the atoms by which the torques are
    /// split into M(q) q̈, the velocity terms and g(q).
    pub fn is_joint_rate(&self) -> bool {
        matches!(
            self,
            Atom::Symbol(Symbol::Velocity(_) | Symbol::Acceleration(_))
        )
    }

    /// The symbol of a bare-symbol atom.
    pub fn symbol(&self) -> Option<Symbol> {
        match self {
            Atom::Symbol(s) => Some(*s),
            _ => None,
        }
    }

    /// Builds the atom in `graph`.
    pub(super) fn to_expr(&self, graph: &mut ExprGraph) -> Id {
        match self {
            Atom::Symbol(s) => graph.symbol(*s),
            Atom::Sin(angle) => {
                let a = angle.to_expr(graph);
                graph.sin(a)
            }
            Atom::Cos(angle) => {
                let a = angle.to_expr(graph);
                graph.cos(a)
            }
            Atom::Sqrt(p) => {
                let a = p.to_expr(graph);
                graph.sqrt(a)
            }
            Atom::Sign(p) => {
                let a = p.to_expr(graph);
                graph.sign(a)
            }
        }
    }

    /// The value of the atom at a point.
    pub(super) fn eval<T: Real>(&self, value: &dyn Fn(Symbol) -> T) -> T {
        match self {
            Atom::Symbol(s) => value(*s),
            Atom::Sin(angle) => angle.eval(value).sin(),
            Atom::Cos(angle) => angle.eval(value).cos(),
            Atom::Sqrt(p) => p.eval_with(value).sqrt(),
            Atom::Sign(p) => p.eval_with(value).sign(),
        }
    }
}

impl Angle {
    fn to_expr(&self, graph: &mut ExprGraph) -> Id {
        match self {
            Angle::Symbol(s) => graph.symbol(*s),
            Angle::Expr(p) => p.to_expr(graph),
        }
    }

    fn eval<T: Real>(&self, value: &dyn Fn(Symbol) -> T) -> T {
        match self {
            Angle::Symbol(s) => value(*s),
            Angle::Expr(p) => p.eval_with(value),
        }
    }
}

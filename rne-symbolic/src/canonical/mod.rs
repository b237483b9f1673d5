//! Canonical polynomial form of expressions, for exact comparison and readable printing.
//!
//! # Canonical form
//!
//! [`Polynomial::from_expr`] expands an expression of an [`ExprGraph`](crate::ExprGraph) into
//! a sum of monomials with `f64` coefficients over [`Atom`]s:
//! - bare symbols: prismatic joint positions, velocities, accelerations, forces, parameters
//!   (negative exponents allowed: division by a monomial such as a mass);
//! - `sin` and `cos` of a symbol, s_k and c_k: `sin`/`cos` of an integer combination of
//!   symbols plus a constant are expanded by the angle-addition and multiple-angle formulas,
//!   the constant's sine and cosine exact at multiples of π/2;
//! - structural atoms for the rest: `sin`/`cos` of any other argument ([`Angle::Expr`]) and
//!   square roots ([`Atom::Sqrt`]), holding the canonical form of their argument.
//!
//! `sin²` is rewritten as `1 − cos²` (and `sqrt(p)²` as `p`), so every sine has exponent at
//! most 1. That makes the form a normal form of trigonometric polynomials: two expressions are
//! equal as functions exactly when their canonical forms are equal, e.g. (4.45)'s M written
//! with `cos(q1 + q2)` or with `c1 c2 − s1 s2`. Atoms are values, not graph ids, so forms from
//! different graphs compare too. Division by a sum or by a sine or cosine is a
//! [`CanonicalError`].
//!
//! Limits: structural atoms are independent indeterminates (`sin(2x)` and `sin x` of a
//! non-symbol x, or `sqrt(a) sqrt(b)` and `sqrt(a b)`, are not related); equality is exact on
//! the `f64` coefficients, which is exact arithmetic for symbolic parameters (small integer
//! and dyadic coefficients) but not for folded numeric ones, which
//! [`Polynomial::approx_eq`] is for. A sum of coefficients that cancels to within
//! [`CANCELLATION_ULPS`] ulps of its operands is zero: the residue of two roundings of one
//! product, not a term.
//!
//! # Printing
//!
//! [`Printer`] and [`format_polynomial`] print a polynomial the way the thesis writes the
//! dynamics ((4.42), (4.45), Appendix B), byte-identical from run to run:
//!
//! ```text
//! (I1 + I2 + lc1^2 m1 + m2 (l1^2 + lc2^2 + 2 l1 lc2 c2)) DDq1 + (I2 + lc2 m2 (lc2 + l1 c2)) DDq2
//!     - 2 l1 lc2 m2 s2 Dq1 Dq2 - l1 lc2 m2 s2 Dq2^2 + g (lc1 m1 c1 + m2 (l1 c1 + lc2 c12))
//! ```
//!
//! - Terms are grouped by their accelerations (by joint), then velocity products (`Dq1^2`,
//!   `Dq1 Dq2`, `Dq2^2`, ...), then forces, then the rest.
//! - Products of joint sines and cosines are rewritten as single harmonics by the
//!   product-to-sum formulas (`c1 c2 − s1 s2` → `c12`, `s12 c3 + c12 s3` → `s123`). This is
//!   exact and complete, not a greedy pattern match, because the harmonic basis is unique too;
//!   what is not a sum of joints with unit multiples prints longhand, as the thesis's Maple
//!   output for the IRB 140 does: `c2^2` → `0.5 (1 + cos(2 q2))`, `sin(2 q2 + q3)`,
//!   `sin(q1 - q2)`.
//! - Abbreviations: a joint named `q<k>` has label `k`, any other joint its name; `s`/`c`
//!   followed by the labels of the summed joints, concatenated when all are single digits
//!   (`s1`, `c12`, `s123`), else after `_` and joined by `_` (`c_10_11`, `s_shoulder`,
//!   `c_shoulder_elbow`). LaTeX: `s_{1}`, `c_{12}`, `c_{10,11}`, `s_{\mathrm{shoulder}}`.
//! - Each group loses the factor its terms share (`g (...)`, a common coefficient, a common
//!   sign), and inside the parentheses terms are grouped, greedily and one level deep, by the
//!   parameter they most often share (`m2 (l1^2 + lc2^2 + 2 l1 lc2 c2)`).
//! - Factors print as parameters (natural order of names, `m2` before `m10`), prismatic
//!   positions, other functions, the harmonic, then forces, velocities, accelerations; terms
//!   without a harmonic come first.
//! - LaTeX names: joints `q_{k}`, `\dot{q}_{k}`, `\ddot{q}_{k}`, `\tau_{k}` (or
//!   `q_{\mathrm{name}}`); a parameter name splits into its leading letters and the rest: a
//!   Greek letter name becomes the letter (`theta0` → `\theta_{0}`), one or two letters
//!   followed by more give the first letter with the rest as subscript (`m2` → `m_{2}`,
//!   `lc2` → `l_{c2}`, `I1xx` → `I_{1xx}`), a longer word is set upright (`mass` →
//!   `\mathrm{mass}`, `link2` → `\mathrm{link}_{2}`).
//! - Numbers: integers as integers, others in shortest round-trip form or to a chosen number
//!   of significant digits ([`Printer::significant_digits`]), scientific below 10⁻⁴ and from
//!   10¹⁵.

mod atom;
mod budget;
mod error;
mod expand;
pub use expand::WORK_PER_TERM;
mod harmonic;
mod layout;
pub mod mathml;
mod monomial;
mod notation;
mod polynomial;
mod print;
#[cfg(test)]
mod testing;

pub use atom::{Angle, Atom};
pub use budget::WorkBudget;
pub use error::CanonicalError;
pub use monomial::Monomial;
pub use polynomial::{Polynomial, CANCELLATION_ULPS};
pub use print::{format_polynomial, PrintFormat, Printer};

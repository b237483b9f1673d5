//! Readable names of the standard parameters (m2, m2·cx2, I2zz, fv2, Ia2) and the exact
//! printing of the coefficients that combine them into base parameters.
//!
//! Bodies are numbered 1, 2, … in the regressor's order (moving bodies in model order, fixed
//! links merged into their parent, docs/design.md §4.4), which for the thesis's robots is the link
//! number; a joint's parameters carry the number of the body it moves.

use std::fmt::Write;

/// What a standard parameter is, for one body or joint.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ParameterKind {
    /// The mass m.
    Mass,
    /// A first moment m·c along axis 0, 1 or 2 (x, y, z).
    FirstMoment(usize),
    /// An entry of the inertia about the body frame's origin, (row, column) with row ≤ column.
    Inertia(usize, usize),
    /// Viscous friction f_v.
    Viscous,
    /// Coulomb friction f_c.
    Coulomb,
    /// Friction offset f_0.
    Offset,
    /// Armature I_a.
    Armature,
}

/// One standard parameter: its kind and the number of its body.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ParameterName {
    /// The body, numbered from 1.
    pub body: usize,
    /// Which parameter.
    pub kind: ParameterKind,
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl ParameterName {
    /// `m2`, `m2·cx2`, `I2xy`, `fv2`, `fc2`, `f02`, `Ia2`.
    pub fn text(&self) -> String {
        let b = self.body;
        match self.kind {
            ParameterKind::Mass => format!("m{b}"),
            ParameterKind::FirstMoment(a) => format!("m{b}·c{}{b}", AXES[a]),
            ParameterKind::Inertia(r, c) => format!("I{b}{}{}", AXES[r], AXES[c]),
            ParameterKind::Viscous => format!("fv{b}"),
            ParameterKind::Coulomb => format!("fc{b}"),
            ParameterKind::Offset => format!("f0{b}"),
            ParameterKind::Armature => format!("Ia{b}"),
        }
    }

    /// The same in LaTeX: `m_{2}`, `m_{2} c_{x2}`, `I_{2xy}`, `f_{v2}`, `I_{a2}`.
    pub fn latex(&self) -> String {
        let b = self.body;
        match self.kind {
            ParameterKind::Mass => format!("m_{{{b}}}"),
            ParameterKind::FirstMoment(a) => format!("m_{{{b}}} c_{{{}{b}}}", AXES[a]),
            ParameterKind::Inertia(r, c) => format!("I_{{{b}{}{}}}", AXES[r], AXES[c]),
            ParameterKind::Viscous => format!("f_{{v{b}}}"),
            ParameterKind::Coulomb => format!("f_{{c{b}}}"),
            ParameterKind::Offset => format!("f_{{0{b}}}"),
            ParameterKind::Armature => format!("I_{{a{b}}}"),
        }
    }
}

/// The readable names of the reference's parameter names (`link.m`, `link.mcx`, …, `link.Ia`,
/// see `Reference::parameter_names`), and the link name of each body number (index 0 is body
/// 1). `None` for a name the reference does not produce.
pub fn readable_names(names: &[String]) -> Option<(Vec<ParameterName>, Vec<String>)> {
    let mut bodies: Vec<String> = Vec::new();
    let mut out = Vec::with_capacity(names.len());
    for name in names {
        let (link, suffix) = name.rsplit_once('.')?;
        let kind = match suffix {
            "m" => ParameterKind::Mass,
            "mcx" => ParameterKind::FirstMoment(0),
            "mcy" => ParameterKind::FirstMoment(1),
            "mcz" => ParameterKind::FirstMoment(2),
            "Ixx" => ParameterKind::Inertia(0, 0),
            "Ixy" => ParameterKind::Inertia(0, 1),
            "Iyy" => ParameterKind::Inertia(1, 1),
            "Ixz" => ParameterKind::Inertia(0, 2),
            "Iyz" => ParameterKind::Inertia(1, 2),
            "Izz" => ParameterKind::Inertia(2, 2),
            "fv" => ParameterKind::Viscous,
            "fc" => ParameterKind::Coulomb,
            "f0" => ParameterKind::Offset,
            "Ia" => ParameterKind::Armature,
            _ => return None,
        };
        let body = match bodies.iter().position(|b| b == link) {
            Some(k) => k + 1,
            None => {
                bodies.push(link.to_owned());
                bodies.len()
            }
        };
        out.push(ParameterName { body, kind });
    }
    Some((out, bodies))
}

/// Relative distance below which a coefficient is *printed* as a short decimal or a fraction.
/// Printing only: an irrational coefficient falls this close to a short number with a
/// probability of about 1e-4, so values that are computed with are snapped only within the
/// much smaller tolerance the caller gives (`base::SHORT_VALUE_TOLERANCE`).
const PRINTED_EXACT: f64 = 1e-10;

/// The short number `x` stands for: a decimal of at most 6 significant digits or a fraction
/// with a denominator up to 64, within a relative `tolerance` of `x`. `None` if there is
/// none.
pub fn short_value(x: f64, tolerance: f64) -> Option<(f64, String)> {
    if x == 0.0 || !x.is_finite() {
        return None;
    }
    let close = |y: f64| (y - x).abs() <= tolerance * x.abs();
    let decimal = (1..=6).find_map(|digits| {
        let y: f64 = format!("{:.*e}", digits - 1, x).parse().ok()?;
        close(y).then(|| (y, plain(y)))
    });
    decimal.or_else(|| {
        (2..=64u32).find_map(|q| {
            let p = (x * f64::from(q)).round();
            let y = p / f64::from(q);
            (close(y) && p.abs() < 1e9).then(|| (y, format!("{p}/{q}")))
        })
    })
}

/// `x` printed short: [`short_value`]'s text within a relative 1e-10 if there is one, else a
/// decimal of at most 12 significant digits within as much, else all 17 digits.
pub fn exact_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    if let Some((_, text)) = short_value(x, PRINTED_EXACT) {
        return text;
    }
    (7..=12)
        .find_map(|digits| {
            let y: f64 = format!("{:.*e}", digits - 1, x).parse().ok()?;
            ((y - x).abs() <= PRINTED_EXACT * x.abs()).then(|| plain(y))
        })
        .unwrap_or_else(|| format!("{x:.16e}"))
}

/// A decimal without an exponent for 1e-4 ≤ |y| < 1e7 (Rust's shortest round-trip digits),
/// with one otherwise.
fn plain(y: f64) -> String {
    if (1e-4..1e7).contains(&y.abs()) {
        format!("{y}")
    } else {
        format!("{y:e}")
    }
}

/// `π[first] + Σ k π[d]` printed with the names given: `I1zz + 0.09·m2 - 0.3·m2·cx2`; terms
/// with a zero coefficient are left out, a unit coefficient (to the precision of
/// [`exact_number`]) is not written.
pub fn combination(terms: &[(usize, f64)], names: &[String]) -> String {
    let mut out = String::new();
    for (k, &(index, coefficient)) in terms.iter().filter(|t| t.1 != 0.0).enumerate() {
        let (sign, size) = if coefficient < 0.0 {
            ("-", -coefficient)
        } else {
            ("+", coefficient)
        };
        match (k, sign) {
            (0, "-") => out.push('-'),
            (0, _) => {}
            _ => {
                let _ = write!(out, " {sign} ");
            }
        }
        let text = exact_number(size);
        if text != "1" {
            let _ = write!(out, "{text}·");
        }
        out.push_str(&names[index]);
    }
    if out.is_empty() {
        out.push('0');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products of lengths computed in floating point print as the decimals they are.
    #[test]
    fn computed_coefficients_print_exactly() {
        assert_eq!(exact_number(0.3 * 0.3), "0.09");
        assert_eq!(exact_number(0.352 * 0.36 * 0.38), "0.0481536");
        assert_eq!(exact_number(-0.3 * (1.0 + 1e-13)), "-0.3");
        assert_eq!(exact_number(1.0 / 3.0), "1/3");
        assert_eq!(exact_number(2.5e-7), "2.5e-7");
        assert_eq!(exact_number(std::f64::consts::PI), "3.1415926536");
    }

    /// The reference's names map to numbered readable names, bodies numbered in order of
    /// appearance, joint parameters on their body's number; link names may contain dots.
    #[test]
    fn reference_names_become_readable() {
        let names: Vec<String> = ["a.m", "a.mcx", "b.1.Iyz", "b.1.fv", "a.Ia"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        let (readable, bodies) = readable_names(&names).expect("known suffixes");
        let text: Vec<String> = readable.iter().map(ParameterName::text).collect();
        assert_eq!(text, ["m1", "m1·cx1", "I2yz", "fv2", "Ia1"]);
        assert_eq!(bodies, ["a", "b.1"]);
        assert_eq!(readable[1].latex(), "m_{1} c_{x1}");
        assert!(readable_names(&["a.bogus".to_string()]).is_none());
    }

    /// Signs, unit coefficients and zeros in a printed combination.
    #[test]
    fn combinations_print_signs_and_units() {
        let names: Vec<String> = ["I1zz", "m2", "m2·cx2"].map(String::from).to_vec();
        assert_eq!(
            combination(&[(0, 1.0), (1, 0.09), (2, -0.3)], &names),
            "I1zz + 0.09·m2 - 0.3·m2·cx2"
        );
        assert_eq!(combination(&[(2, -1.0), (1, 0.0)], &names), "-m2·cx2");
    }
}

//! Names and numbers in printed polynomials: joint labels and the thesis's abbreviations
//! (`s1`, `c12`, `s_shoulder`), LaTeX identifiers (`lc2` → `l_{c2}`), and coefficients. The
//! rules are stated in the `canonical` module docs.

use super::harmonic::Harmonic;
use super::mathml;
use super::print::PrintFormat;
use crate::expr::{BaseCoordinate, BaseQuantity, SymbolTable};

/// Greek letter names a parameter name may start with, and the letters (LaTeX `\alpha`,
/// MathML `α`).
pub(super) const GREEK: [(&str, char); 35] = [
    ("alpha", 'α'),
    ("beta", 'β'),
    ("gamma", 'γ'),
    ("delta", 'δ'),
    ("epsilon", 'ϵ'),
    ("varepsilon", 'ε'),
    ("zeta", 'ζ'),
    ("eta", 'η'),
    ("theta", 'θ'),
    ("vartheta", 'ϑ'),
    ("iota", 'ι'),
    ("kappa", 'κ'),
    ("lambda", 'λ'),
    ("mu", 'μ'),
    ("nu", 'ν'),
    ("xi", 'ξ'),
    ("pi", 'π'),
    ("rho", 'ρ'),
    ("sigma", 'σ'),
    ("tau", 'τ'),
    ("upsilon", 'υ'),
    ("phi", 'ϕ'),
    ("varphi", 'φ'),
    ("chi", 'χ'),
    ("psi", 'ψ'),
    ("omega", 'ω'),
    ("Gamma", 'Γ'),
    ("Delta", 'Δ'),
    ("Theta", 'Θ'),
    ("Lambda", 'Λ'),
    ("Xi", 'Ξ'),
    ("Pi", 'Π'),
    ("Sigma", 'Σ'),
    ("Phi", 'Φ'),
    ("Psi", 'Ψ'),
];

/// The label of joint `k`: its number for a joint named `q<number>`, else its name.
pub(super) fn joint_label(symbols: &SymbolTable, joint: u16) -> String {
    let name = joint_name(symbols, joint);
    match numbered_joint(&name) {
        Some(number) => number.to_string(),
        None => name,
    }
}

/// The name of joint `k` (`q<k+1>` when the table has no name for it).
pub(super) fn joint_name(symbols: &SymbolTable, joint: u16) -> String {
    symbols.name(crate::expr::Symbol::Position(joint))
}

/// `Some(k)` for a name `q<k>` (digits, no leading zero).
pub(super) fn numbered_joint(name: &str) -> Option<&str> {
    let digits = name.strip_prefix('q')?;
    let valid = !digits.is_empty()
        && digits.bytes().all(|b| b.is_ascii_digit())
        && !digits.starts_with('0');
    valid.then_some(digits)
}

/// A joint variable in LaTeX with an accent (`""`, `"\dot"`, `"\ddot"`): `\dot{q}_{1}`.
pub(super) fn latex_joint(symbols: &SymbolTable, joint: u16, accent: &str) -> String {
    let base = if accent.is_empty() {
        "q".to_string()
    } else {
        format!("{accent}{{q}}")
    };
    format!("{base}_{{{}}}", latex_label(symbols, joint))
}

/// A floating base's coordinate in LaTeX: `x`, `q_{w}`, `\omega_{x}`, `\dot{v}_{z}`, `n_{y}`.
pub(super) fn latex_base(base: BaseCoordinate) -> String {
    let letter = match base.quantity {
        BaseQuantity::Position => return base.axis.to_string(),
        BaseQuantity::Orientation => "q",
        BaseQuantity::LinearVelocity => "v",
        BaseQuantity::AngularVelocity => "\\omega",
        BaseQuantity::LinearAcceleration => "\\dot{v}",
        BaseQuantity::AngularAcceleration => "\\dot{\\omega}",
        BaseQuantity::Force => "f",
        BaseQuantity::Moment => "n",
    };
    format!("{letter}_{{{}}}", base.axis)
}

/// A joint label for a LaTeX subscript: `1`, `\mathrm{shoulder}`.
pub(super) fn latex_label(symbols: &SymbolTable, joint: u16) -> String {
    let name = joint_name(symbols, joint);
    match numbered_joint(&name) {
        Some(number) => number.to_string(),
        None => format!("\\mathrm{{{}}}", escape(&name)),
    }
}

/// The thesis's abbreviation of a harmonic whose multiples are all 1 (`s12`), `None` for
/// any other harmonic.
pub(super) fn abbreviation(
    symbols: &SymbolTable,
    h: &Harmonic,
    format: PrintFormat,
) -> Option<String> {
    if h.frequencies.iter().any(|&(_, n)| n != 1) {
        return None;
    }
    if format == PrintFormat::MathMl {
        return Some(mathml::abbreviation(symbols, h));
    }
    let letter = if h.sine { 's' } else { 'c' };
    let labels: Vec<String> = h
        .frequencies
        .iter()
        .map(|&(j, _)| joint_label(symbols, j))
        .collect();
    let digits_only = labels
        .iter()
        .all(|l| l.len() == 1 && l.bytes().all(|b| b.is_ascii_digit()));
    let single_number = labels.len() == 1 && labels[0].bytes().all(|b| b.is_ascii_digit());
    Some(match format {
        PrintFormat::Text if digits_only || single_number => format!("{letter}{}", labels.concat()),
        PrintFormat::Text => format!("{letter}_{}", labels.join("_")),
        PrintFormat::Latex if digits_only => format!("{letter}_{{{}}}", labels.concat()),
        PrintFormat::Latex | PrintFormat::MathMl => {
            let labels: Vec<String> = h
                .frequencies
                .iter()
                .map(|&(j, _)| latex_label(symbols, j))
                .collect();
            format!("{letter}_{{{}}}", labels.join(","))
        }
    })
}

/// A parameter or joint name as a LaTeX identifier (rules in the module docs).
pub(super) fn latex_identifier(name: &str) -> String {
    let split = name
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(name.len());
    let (head, tail) = name.split_at(split);
    let tail = escape(tail.strip_prefix('_').unwrap_or(tail));
    let subscript = |main: String| {
        if tail.is_empty() {
            main
        } else {
            format!("{main}_{{{tail}}}")
        }
    };
    if GREEK.iter().any(|(greek, _)| *greek == head) {
        subscript(format!("\\{head}"))
    } else if head.len() == 1 || (head.len() == 2 && !tail.is_empty()) {
        let (main, rest) = head.split_at(1);
        if rest.is_empty() {
            subscript(main.to_string())
        } else {
            format!("{main}_{{{rest}{tail}}}")
        }
    } else if head.is_empty() {
        format!("\\mathrm{{{}}}", escape(name))
    } else {
        subscript(format!("\\mathrm{{{head}}}"))
    }
}

/// Escapes the characters LaTeX treats specially in identifiers.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if matches!(c, '_' | '#' | '$' | '%' | '&' | '{' | '}') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// A non-negative number as printed (rules in the module docs).
pub(super) fn number(x: f64, digits: Option<usize>, format: PrintFormat) -> String {
    let text = match digits {
        _ if x.fract() == 0.0 && x.abs() < 1e15 => format!("{}", x as i64),
        Some(d) => rounded(x, d.max(1)),
        None if (1e-4..1e15).contains(&x.abs()) => format!("{x}"),
        None => format!("{x:e}"),
    };
    match (format, text.split_once('e')) {
        (PrintFormat::MathMl, _) => mathml::number(&text),
        (PrintFormat::Latex, Some((mantissa, exponent))) => {
            format!("{mantissa} \\cdot 10^{{{exponent}}}")
        }
        _ => text,
    }
}

/// `x` rounded to `digits` significant digits, without trailing zeros.
fn rounded(x: f64, digits: usize) -> String {
    let scientific = format!("{:.*e}", digits - 1, x);
    let (mantissa, exponent) = scientific.split_once('e').unwrap_or((&scientific, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (-4..15).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        trim_zeros(format!("{x:.decimals$}"))
    } else {
        format!("{}e{exponent}", trim_zeros(mantissa.to_string()))
    }
}

fn trim_zeros(text: String) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

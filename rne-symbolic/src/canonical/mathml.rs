//! MathML, the mathematics markup browsers render natively (MathML Core): the elements a
//! printed polynomial is made of, and the names of the `canonical` module docs in it —
//! joints `q₁`, `q̇₁`, `q̈₁`, `τ₁`, parameters split as in LaTeX (`lc2` → l with subscript
//! c2, `theta0` → θ₀), the abbreviations `s₁₂`, numbers `1.2·10⁻⁵`. Text is escaped, so any
//! joint or parameter name can be written.

use super::harmonic::Harmonic;
use super::notation::{joint_name, numbered_joint, GREEK};
use crate::expr::{BaseCoordinate, BaseQuantity, SymbolTable};

/// `text` with `&`, `<`, `>` and `"` escaped, for element text and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

/// An identifier: `<mi>x</mi>` (one letter italic, longer names upright).
pub fn mi(text: &str) -> String {
    format!("<mi>{}</mi>", escape(text))
}

/// A number: `<mn>2</mn>`.
pub fn mn(text: &str) -> String {
    format!("<mn>{}</mn>", escape(text))
}

/// An operator: `<mo>+</mo>`.
pub fn mo(text: &str) -> String {
    format!("<mo>{}</mo>", escape(text))
}

/// Elements grouped as one: `<mrow>…</mrow>`.
pub fn mrow(inner: &str) -> String {
    format!("<mrow>{inner}</mrow>")
}

/// `markup` as one element: itself when it is one, else in an `<mrow>`.
fn element(markup: &str) -> String {
    if is_one_element(markup) {
        markup.to_owned()
    } else {
        mrow(markup)
    }
}

/// Whether `markup` is a single element: its first tag closes only at its end.
fn is_one_element(markup: &str) -> bool {
    if !markup.starts_with('<') || !markup.ends_with('>') {
        return false;
    }
    let mut depth = 0usize;
    let mut rest = markup;
    while let Some(open) = rest.find('<') {
        let Some(close) = rest[open..].find('>') else {
            return false;
        };
        let tag = &rest[open..open + close + 1];
        rest = &rest[open + close + 1..];
        match (tag.starts_with("</"), tag.ends_with("/>")) {
            (true, _) => depth = depth.saturating_sub(1),
            (false, true) => {}
            (false, false) => depth += 1,
        }
        if depth == 0 {
            return rest.is_empty();
        }
    }
    false
}

/// `base` with a subscript; both are markup, each made one element.
pub fn msub(base: &str, subscript: &str) -> String {
    format!("<msub>{}{}</msub>", element(base), element(subscript))
}

/// `base` with a superscript; both are markup, each made one element.
pub fn msup(base: &str, superscript: &str) -> String {
    format!("<msup>{}{}</msup>", element(base), element(superscript))
}

/// `inner` in parentheses.
pub fn parenthesised(inner: &str) -> String {
    mrow(&format!("<mo>(</mo>{inner}<mo>)</mo>"))
}

/// `name(argument)`: the function name upright, applied to the argument.
pub fn function(name: &str, argument: &str) -> String {
    format!("{}<mo>&#x2061;</mo>{}", mi(name), parenthesised(argument))
}

/// `letter` with an accent above: `˙` (U+02D9) for q̇, `¨` (U+00A8) for q̈.
pub fn accented(letter: &str, accent: char) -> String {
    format!(
        "<mover accent=\"true\">{}{}</mover>",
        mi(letter),
        mo(&accent.to_string())
    )
}

/// A displayed formula: `<math display="block">…</math>`.
pub fn math(inner: &str) -> String {
    format!("<math display=\"block\">{inner}</math>")
}

/// The minus sign (U+2212), as an operator.
pub fn minus() -> String {
    mo("\u{2212}")
}

/// A subscript or name part: digits as a number, anything else as an identifier.
pub fn script(text: &str) -> String {
    if !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit()) {
        mn(text)
    } else {
        mi(text)
    }
}

/// A number as printed in text (`0.5`, `1.2e-5`): the exponent as a power of ten.
pub fn number(text: &str) -> String {
    match text.split_once('e') {
        Some((mantissa, exponent)) => {
            let power = match exponent.strip_prefix('-') {
                Some(magnitude) => format!("{}{}", minus(), mn(magnitude)),
                None => mn(exponent),
            };
            mrow(&format!(
                "{}{}{}",
                mn(mantissa),
                mo("·"),
                msup(&mn("10"), &power)
            ))
        }
        None => mn(text),
    }
}

/// A parameter name as an identifier, by the LaTeX rule of the module docs: a Greek letter
/// name becomes the letter, one or two letters followed by more give the first letter with the
/// rest as subscript, a longer word is upright with what follows it as subscript.
pub fn identifier(name: &str) -> String {
    let split = name
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(name.len());
    let (head, tail) = name.split_at(split);
    let tail = tail.strip_prefix('_').unwrap_or(tail);
    let subscripted = |main: String| match tail {
        "" => main,
        tail => msub(&main, &script(tail)),
    };
    if let Some((_, letter)) = GREEK.iter().find(|(greek, _)| *greek == head) {
        subscripted(mi(&letter.to_string()))
    } else if head.len() == 1 || (head.len() == 2 && !tail.is_empty()) {
        let (main, rest) = head.split_at(1);
        match format!("{rest}{tail}") {
            rest if rest.is_empty() => mi(main),
            rest => msub(&mi(main), &script(&rest)),
        }
    } else if head.is_empty() {
        mi(name)
    } else {
        subscripted(mi(head))
    }
}

/// A floating base's coordinate: `x`, q with subscript `w`, ω with subscript `x`, v̇ with
/// subscript `z`.
pub(super) fn base(coordinate: BaseCoordinate) -> String {
    let axis = mi(&coordinate.axis.to_string());
    let letter = match coordinate.quantity {
        BaseQuantity::Position => return axis,
        BaseQuantity::Orientation => mi("q"),
        BaseQuantity::LinearVelocity => mi("v"),
        BaseQuantity::AngularVelocity => mi("ω"),
        BaseQuantity::LinearAcceleration => accented("v", '\u{2d9}'),
        BaseQuantity::AngularAcceleration => accented("ω", '\u{2d9}'),
        BaseQuantity::Force => mi("f"),
        BaseQuantity::Moment => mi("n"),
    };
    msub(&letter, &axis)
}

/// The subscript of joint `k`: its number for a joint named `q<number>`, else its name.
pub(super) fn joint_label(symbols: &SymbolTable, joint: u16) -> String {
    let name = joint_name(symbols, joint);
    match numbered_joint(&name) {
        Some(number) => mn(number),
        None => mi(&name),
    }
}

/// A joint variable with an accent (`None`, `Some('˙')` for q̇, `Some('¨')` for q̈) or
/// another letter (`τ`): `q` with the joint's label as subscript.
pub(super) fn joint(
    symbols: &SymbolTable,
    joint: u16,
    letter: &str,
    accent: Option<char>,
) -> String {
    let base = match accent {
        Some(dots) => accented(letter, dots),
        None => mi(letter),
    };
    msub(&base, &joint_label(symbols, joint))
}

/// The thesis's abbreviation of a harmonic whose multiples are all 1: `s` or `c` with the
/// joints' labels as subscript, run together when all are single digits (`c₁₂`), else
/// separated by commas.
pub(super) fn abbreviation(symbols: &SymbolTable, h: &Harmonic) -> String {
    let letter = if h.sine { "s" } else { "c" };
    let names: Vec<String> = h
        .frequencies
        .iter()
        .map(|&(j, _)| joint_name(symbols, j))
        .collect();
    let digits: Option<Vec<&str>> = names
        .iter()
        .map(|n| numbered_joint(n).filter(|d| d.len() == 1))
        .collect();
    let subscript = match digits {
        Some(digits) => mn(&digits.concat()),
        None => {
            let labels: Vec<String> = h
                .frequencies
                .iter()
                .map(|&(j, _)| joint_label(symbols, j))
                .collect();
            labels.join(&mo(","))
        }
    };
    msub(&mi(letter), &subscript)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_numbers_escape_and_split_as_in_latex() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
        assert_eq!(identifier("m2"), "<msub><mi>m</mi><mn>2</mn></msub>");
        assert_eq!(identifier("lc2"), "<msub><mi>l</mi><mi>c2</mi></msub>");
        assert_eq!(identifier("g"), "<mi>g</mi>");
        assert_eq!(identifier("alpha"), "<mi>α</mi>");
        assert_eq!(identifier("mass"), "<mi>mass</mi>");
        assert_eq!(identifier("m<1"), "<msub><mi>m</mi><mi>&lt;1</mi></msub>");
        assert_eq!(number("0.5"), "<mn>0.5</mn>");
        assert_eq!(
            number("1.2e-5"),
            "<mrow><mn>1.2</mn><mo>·</mo><msup><mn>10</mn><mrow><mo>\u{2212}</mo><mn>5</mn></mrow></msup></mrow>"
        );
    }

    #[test]
    fn joints_take_their_number_or_their_name_as_subscript() {
        let symbols = SymbolTable::with_joints(["q1", "q2", "elbow"]);
        assert_eq!(
            joint(&symbols, 0, "q", Some('˙')),
            "<msub><mover accent=\"true\"><mi>q</mi><mo>˙</mo></mover><mn>1</mn></msub>"
        );
        assert_eq!(
            joint(&symbols, 2, "q", None),
            "<msub><mi>q</mi><mi>elbow</mi></msub>"
        );
        let both = Harmonic {
            sine: false,
            frequencies: vec![(0, 1), (1, 1)],
        };
        assert_eq!(
            abbreviation(&symbols, &both),
            "<msub><mi>c</mi><mn>12</mn></msub>"
        );
        let named = Harmonic {
            sine: true,
            frequencies: vec![(1, 1), (2, 1)],
        };
        assert_eq!(
            abbreviation(&symbols, &named),
            "<msub><mi>s</mi><mrow><mn>2</mn><mo>,</mo><mi>elbow</mi></mrow></msub>"
        );
    }
}

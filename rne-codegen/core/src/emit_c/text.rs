//! C text: identifiers, comments, string literals and double constants.

/// The keywords of C99 to C23 and of C++ to C++20: no parameter may be named after one, since
/// the source is compiled as both.
const KEYWORDS: [&str; 98] = [
    "alignas",
    "alignof",
    "and",
    "and_eq",
    "asm",
    "auto",
    "bitand",
    "bitor",
    "bool",
    "break",
    "case",
    "catch",
    "char",
    "char8_t",
    "char16_t",
    "char32_t",
    "class",
    "co_await",
    "co_return",
    "co_yield",
    "compl",
    "concept",
    "const",
    "const_cast",
    "consteval",
    "constexpr",
    "constinit",
    "continue",
    "decltype",
    "default",
    "delete",
    "do",
    "double",
    "dynamic_cast",
    "else",
    "enum",
    "explicit",
    "export",
    "extern",
    "false",
    "float",
    "for",
    "friend",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "mutable",
    "namespace",
    "new",
    "noexcept",
    "not",
    "not_eq",
    "nullptr",
    "operator",
    "or",
    "or_eq",
    "private",
    "protected",
    "public",
    "register",
    "reinterpret_cast",
    "requires",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "static_cast",
    "struct",
    "switch",
    "template",
    "this",
    "thread_local",
    "throw",
    "true",
    "try",
    "typedef",
    "typeid",
    "typename",
    "typeof",
    "typeof_unqual",
    "union",
    "unsigned",
    "using",
    "virtual",
    "void",
    "volatile",
    "wchar_t",
    "while",
    "xor",
    "xor_eq",
    "_Bool",
    "_Complex",
    "_Imaginary",
];

/// `name` as a C identifier: ASCII letters (lower-cased) and digits kept, anything else `_`,
/// and `robot_` in front of a name that would start with a digit or an underscore or be
/// empty: `panda-arm` is `panda_arm`, `UR5` is `ur5`.
pub fn c_identifier(name: &str) -> String {
    let mut id: String = name
        .chars()
        .map(|c| match c {
            'a'..='z' | '0'..='9' => c,
            'A'..='Z' => c.to_ascii_lowercase(),
            _ => '_',
        })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_lowercase()) {
        id.insert_str(0, "robot_");
    }
    id
}

/// Whether `name` can name a struct field in both C and C++: letters, digits and
/// underscores, not starting with a digit, and no keyword.
pub(super) fn is_c_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !KEYWORDS.contains(&name)
}

/// `text` as a block comment (`/**` for documentation), one ` * ` line per line, each line
/// longer than 96 columns wrapped at its spaces; a `*/` in it is broken up.
pub(super) fn c_comment(text: &str, doc: bool) -> String {
    let mut comment = String::from(if doc { "/**" } else { "/*" });
    for line in text.replace("*/", "* /").lines() {
        let mut rest = line;
        loop {
            comment.push_str("\n *");
            if rest.is_empty() {
                break;
            }
            comment.push(' ');
            // The last space within the width (in bytes, which only wraps lines with
            // non-ASCII characters a little early).
            let cut = (rest.len() > 93)
                .then(|| {
                    rest.char_indices()
                        .take_while(|&(i, _)| i <= 93)
                        .filter(|&(i, c)| c == ' ' && i > 0)
                        .last()
                })
                .flatten()
                .map(|(i, _)| i);
            match cut {
                Some(cut) => {
                    comment.push_str(&rest[..cut]);
                    rest = &rest[cut + 1..];
                }
                None => {
                    comment.push_str(rest);
                    break;
                }
            }
        }
    }
    comment.push_str("\n */\n");
    comment
}

/// `text` as a C string literal: printable ASCII as itself, except `"`, `\` and `?` (no
/// trigraphs) escaped, and every other byte as a three-digit octal escape.
pub(super) fn c_string(text: &str) -> String {
    let mut literal = String::from("\"");
    for byte in text.bytes() {
        match byte {
            b'"' | b'\\' | b'?' => {
                literal.push('\\');
                literal.push(char::from(byte));
            }
            0x20..=0x7e => literal.push(char::from(byte)),
            _ => literal.push_str(&format!("\\{byte:03o}")),
        }
    }
    literal.push('"');
    literal
}

/// `value` as a C expression of type double that is exactly it: the shortest decimal that
/// rounds to it (in exponent form when that is shorter), parenthesised when negative (so that
/// `a - (-2.5)` reads as it must); `NAN` and `INFINITY` of `<math.h>` otherwise.
pub(super) fn c_double(value: f64) -> String {
    let magnitude = if value.is_nan() {
        "NAN".to_owned()
    } else if value.is_infinite() {
        "INFINITY".to_owned()
    } else {
        let plain = format!("{}", value.abs());
        let exponent = format!("{:e}", value.abs());
        let mut shortest = if exponent.len() < plain.len() {
            exponent
        } else {
            plain
        };
        if !shortest.contains(['.', 'e']) {
            shortest.push_str(".0");
        }
        shortest
    };
    if value.is_sign_negative() && !value.is_nan() {
        format!("(-{magnitude})")
    } else {
        magnitude
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers_are_lower_case_c_names() {
        assert_eq!(c_identifier("panda-arm"), "panda_arm");
        assert_eq!(c_identifier("UR5"), "ur5");
        assert_eq!(c_identifier("irb140-3dof"), "irb140_3dof");
        assert_eq!(c_identifier("3dof"), "robot_3dof");
        assert_eq!(c_identifier("_x"), "robot__x");
        assert_eq!(c_identifier(""), "robot_");
        assert_eq!(c_identifier("bras à 6 axes"), "bras___6_axes");
    }

    #[test]
    fn parameter_names_are_checked_against_both_languages() {
        for good in ["m1", "_x", "link2_Izz", "L"] {
            assert!(is_c_identifier(good), "{good}");
        }
        for bad in ["", "1m", "m.1", "class", "double", "new", "restrict", "r#m"] {
            assert!(!is_c_identifier(bad), "{bad}");
        }
    }

    /// Every constant reads back as itself: the shortest round trip, in whichever form is
    /// shorter, always a floating constant.
    #[test]
    fn constants_are_exact_and_short() {
        assert_eq!(c_double(2.0), "2.0");
        assert_eq!(c_double(-0.5), "(-0.5)");
        assert_eq!(c_double(-0.0), "(-0.0)");
        assert_eq!(c_double(1e-7), "1e-7");
        assert_eq!(c_double(1.5e300), "1.5e300");
        assert_eq!(c_double(0.1), "0.1");
        assert_eq!(c_double(f64::NEG_INFINITY), "(-INFINITY)");
        assert_eq!(c_double(f64::NAN), "NAN");
        for value in [
            0.1,
            1.0 / 3.0,
            6.123_233_995_736_766e-17,
            123_456_789.0,
            5e-324,
            f64::MAX,
        ] {
            let text = c_double(value);
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                value.to_bits(),
                "{text}"
            );
        }
    }

    #[test]
    fn strings_and_comments_cannot_end_early() {
        assert_eq!(c_string("a\"b\\c??=é"), "\"a\\\"b\\\\c\\?\\?=\\303\\251\"");
        assert_eq!(
            c_comment("x */ y\n\nz", false),
            "/*\n * x * / y\n *\n * z\n */\n"
        );
        let long = ["word"; 30].join(" ");
        let wrapped = c_comment(&long, true);
        assert!(wrapped.starts_with("/**\n * word"), "{wrapped}");
        assert!(wrapped.lines().all(|l| l.len() <= 96), "{wrapped}");
        assert_eq!(wrapped.matches("word").count(), 30);
    }
}

//! Expression strings of the spec format (docs/design.md §2.1), parsed by recursive descent
//! straight into an [`ExprGraph`] through its simplifying constructors.
//!
//! ```text
//! sum      := product (('+' | '-') product)*
//! product  := unary (('*' | '/') unary)*
//! unary    := '-' unary | '+' unary | power
//! power    := atom ('^' unary)?              right-associative; -x^2 = -(x^2)
//! atom     := number | name | function '(' sum ')' | '(' sum ')'
//! function := sqrt | sin | cos
//! rotation := factor ('*' factor)*           factor := (Rx | Ry | Rz) '(' sum ')'
//! ```
//!
//! `pi` is π; every other name is looked up through [`Names`]. An exponent must fold to a
//! constant: an integer (expanded into products, negative ones into a quotient) or 0.5 (a square
//! root). Anything else is an error, as is nesting deeper than [`MAX_DEPTH`].

use std::f64::consts::PI;

use crate::expr::{ExprGraph, Id};
use crate::model::Axis;

/// Names with a fixed meaning in expressions, which parameters and joint variables may not take.
pub(crate) const RESERVED: &[&str] = &["pi", "sqrt", "sin", "cos", "Rx", "Ry", "Rz"];

/// The deepest nesting of parentheses and unary operators accepted.
pub(crate) const MAX_DEPTH: usize = 64;

/// The largest magnitude of an integer exponent.
const MAX_EXPONENT: f64 = 64.0;

/// How the names of an expression are resolved.
pub(crate) trait Names {
    /// The expression `name` stands for, or why it may not appear here.
    fn resolve(&self, graph: &mut ExprGraph, name: &str) -> Result<Id, String>;
}

/// Whether `name` is an identifier: a letter or `_`, then letters, digits and `_`.
pub(crate) fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Parses a scalar expression into `graph`.
pub(crate) fn parse_expression(
    graph: &mut ExprGraph,
    text: &str,
    names: &dyn Names,
) -> Result<Id, String> {
    let mut parser = Parser::new(graph, text, names)?;
    let id = parser.sum()?;
    parser.expect_end()?;
    Ok(id)
}

/// Parses a product of elementary rotations, `Rz(q1) * Rx(pi/2)`, into its factors in order.
pub(crate) fn parse_rotation(
    graph: &mut ExprGraph,
    text: &str,
    names: &dyn Names,
) -> Result<Vec<(Axis, Id)>, String> {
    let mut parser = Parser::new(graph, text, names)?;
    let mut factors = vec![parser.rotation_factor()?];
    while parser.eat(Token::Op('*')) {
        factors.push(parser.rotation_factor()?);
    }
    parser.expect_end()?;
    Ok(factors)
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Op(char),
}

fn tokenize(text: &str) -> Result<Vec<Token>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while let Some(&c) = chars.get(i) {
        let start = i;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            while chars
                .get(i)
                .is_some_and(|c| c.is_ascii_digit() || *c == '.')
            {
                i += 1;
            }
            if chars.get(i).is_some_and(|c| *c == 'e' || *c == 'E') {
                let sign = usize::from(chars.get(i + 1).is_some_and(|c| *c == '+' || *c == '-'));
                if chars.get(i + 1 + sign).is_some_and(char::is_ascii_digit) {
                    i += 1 + sign;
                    while chars.get(i).is_some_and(char::is_ascii_digit) {
                        i += 1;
                    }
                }
            }
            let literal: String = chars[start..i].iter().collect();
            match literal.parse::<f64>() {
                Ok(value) if value.is_finite() => tokens.push(Token::Number(value)),
                Ok(_) => return Err(format!("number {literal} is out of range")),
                Err(_) => return Err(format!("'{literal}' is not a number")),
            }
        } else if c.is_ascii_alphabetic() || c == '_' {
            while chars
                .get(i)
                .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
            {
                i += 1;
            }
            tokens.push(Token::Name(chars[start..i].iter().collect()));
        } else if "+-*/^()".contains(c) {
            tokens.push(Token::Op(c));
            i += 1;
        } else {
            return Err(format!("unexpected character '{c}'"));
        }
    }
    Ok(tokens)
}

struct Parser<'a> {
    graph: &'a mut ExprGraph,
    text: &'a str,
    names: &'a dyn Names,
    tokens: Vec<Token>,
    next: usize,
    depth: usize,
}

impl<'a> Parser<'a> {
    fn new(
        graph: &'a mut ExprGraph,
        text: &'a str,
        names: &'a dyn Names,
    ) -> Result<Parser<'a>, String> {
        let tokens = tokenize(text).map_err(|detail| malformed(text, &detail))?;
        Ok(Parser {
            graph,
            text,
            names,
            tokens,
            next: 0,
            depth: 0,
        })
    }

    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.next)
    }

    fn eat(&mut self, token: Token) -> bool {
        let found = self.peek() == Some(&token);
        if found {
            self.next += 1;
        }
        found
    }

    fn malformed(&self, detail: &str) -> String {
        malformed(self.text, detail)
    }

    /// "at the end" or "at `token`", for messages.
    fn here(&self) -> String {
        match self.peek() {
            None => "at the end".to_owned(),
            Some(Token::Number(x)) => format!("at '{x}'"),
            Some(Token::Name(n)) => format!("at '{n}'"),
            Some(Token::Op(c)) => format!("at '{c}'"),
        }
    }

    fn expect_end(&self) -> Result<(), String> {
        match self.peek() {
            None => Ok(()),
            Some(_) => Err(self.malformed(&format!("expected an operator {}", self.here()))),
        }
    }

    fn expect(&mut self, c: char) -> Result<(), String> {
        if self.eat(Token::Op(c)) {
            Ok(())
        } else {
            Err(self.malformed(&format!("expected '{c}' {}", self.here())))
        }
    }

    fn enter(&mut self) -> Result<(), String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.malformed(&format!("nested deeper than {MAX_DEPTH} levels")));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<Id, String> {
        let mut total = self.product()?;
        loop {
            if self.eat(Token::Op('+')) {
                let term = self.product()?;
                total = self.graph.add(total, term);
            } else if self.eat(Token::Op('-')) {
                let term = self.product()?;
                total = self.graph.sub(total, term);
            } else {
                return Ok(total);
            }
        }
    }

    fn product(&mut self) -> Result<Id, String> {
        let mut total = self.unary()?;
        loop {
            if self.eat(Token::Op('*')) {
                let factor = self.unary()?;
                total = self.graph.mul(total, factor);
            } else if self.eat(Token::Op('/')) {
                let factor = self.unary()?;
                total = self.graph.div(total, factor);
            } else {
                return Ok(total);
            }
        }
    }

    fn unary(&mut self) -> Result<Id, String> {
        self.enter()?;
        let value = if self.eat(Token::Op('-')) {
            let operand = self.unary()?;
            self.graph.neg(operand)
        } else if self.eat(Token::Op('+')) {
            self.unary()?
        } else {
            self.power()?
        };
        self.depth -= 1;
        Ok(value)
    }

    fn power(&mut self) -> Result<Id, String> {
        let base = self.atom()?;
        if !self.eat(Token::Op('^')) {
            return Ok(base);
        }
        let exponent = self.unary()?;
        let Some(n) = self.graph.as_const(exponent) else {
            return Err(self.bad_power("the exponent is not a constant"));
        };
        if n == 0.5 {
            return Ok(self.graph.sqrt(base));
        }
        if n.fract() != 0.0 {
            return Err(self.bad_power(&format!("got {n}")));
        }
        if n.abs() > MAX_EXPONENT {
            return Err(self.bad_power(&format!("got {n}, larger than {MAX_EXPONENT}")));
        }
        let magnitude = integer_power(self.graph, base, n.abs() as u32);
        if n < 0.0 {
            let one = self.graph.one();
            Ok(self.graph.div(one, magnitude))
        } else {
            Ok(magnitude)
        }
    }

    fn bad_power(&self, detail: &str) -> String {
        format!(
            "non-integer power in \"{}\": an exponent must be an integer or 0.5, {detail}",
            self.text
        )
    }

    fn atom(&mut self) -> Result<Id, String> {
        match self.peek().cloned() {
            Some(Token::Number(x)) => {
                self.next += 1;
                Ok(self.graph.constant(x))
            }
            Some(Token::Op('(')) => {
                self.next += 1;
                self.enter()?;
                let inner = self.sum()?;
                self.expect(')')?;
                self.depth -= 1;
                Ok(inner)
            }
            Some(Token::Name(name)) => {
                self.next += 1;
                if self.peek() == Some(&Token::Op('(')) {
                    return self.call(&name);
                }
                match name.as_str() {
                    "pi" => Ok(self.graph.constant(PI)),
                    "sqrt" | "sin" | "cos" | "Rx" | "Ry" | "Rz" => {
                        Err(self.malformed(&format!("'{name}' is a function: write {name}(...)")))
                    }
                    _ => self
                        .names
                        .resolve(self.graph, &name)
                        .map_err(|e| format!("{e} in \"{}\"", self.text)),
                }
            }
            _ => Err(self.malformed(&format!("expected a number, a name or '(' {}", self.here()))),
        }
    }

    fn call(&mut self, function: &str) -> Result<Id, String> {
        let apply: fn(&mut ExprGraph, Id) -> Id = match function {
            "sqrt" => ExprGraph::sqrt,
            "sin" => ExprGraph::sin,
            "cos" => ExprGraph::cos,
            "Rx" | "Ry" | "Rz" => {
                return Err(
                    self.malformed(&format!("a rotation '{function}(...)' is not a number"))
                );
            }
            _ => return Err(self.malformed(&format!("unknown function '{function}'"))),
        };
        let argument = self.argument()?;
        Ok(apply(self.graph, argument))
    }

    /// `'(' sum ')'`.
    fn argument(&mut self) -> Result<Id, String> {
        self.expect('(')?;
        self.enter()?;
        let inner = self.sum()?;
        self.expect(')')?;
        self.depth -= 1;
        Ok(inner)
    }

    fn rotation_factor(&mut self) -> Result<(Axis, Id), String> {
        let axis = match self.peek() {
            Some(Token::Name(n)) if n == "Rx" => Axis::X,
            Some(Token::Name(n)) if n == "Ry" => Axis::Y,
            Some(Token::Name(n)) if n == "Rz" => Axis::Z,
            _ => {
                return Err(format!(
                    "malformed rotation \"{}\": expected Rx(..), Ry(..) or Rz(..) {}",
                    self.text,
                    self.here()
                ))
            }
        };
        self.next += 1;
        Ok((axis, self.argument()?))
    }
}

fn malformed(text: &str, detail: &str) -> String {
    format!("malformed expression \"{text}\": {detail}")
}

/// `base^n` by repeated squaring (`x^3 = x · (x · x)`).
fn integer_power(graph: &mut ExprGraph, base: Id, n: u32) -> Id {
    let mut result = graph.one();
    let mut square = base;
    let mut k = n;
    while k > 0 {
        if k & 1 == 1 {
            result = graph.mul(result, square);
        }
        k >>= 1;
        if k > 0 {
            square = graph.square(square);
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{Symbol, SymbolTable};

    /// Resolves `a`, `b` to parameters 0 and 1, `q1` to joint 0; anything else is unknown.
    struct TestNames;

    impl Names for TestNames {
        fn resolve(&self, graph: &mut ExprGraph, name: &str) -> Result<Id, String> {
            match name {
                "a" => Ok(graph.symbol(Symbol::Parameter(0))),
                "b" => Ok(graph.symbol(Symbol::Parameter(1))),
                "q1" => Ok(graph.symbol(Symbol::Position(0))),
                _ => Err(format!("unknown symbol '{name}'")),
            }
        }
    }

    fn graph() -> ExprGraph {
        let mut symbols = SymbolTable::with_joints(["q1"]);
        symbols.push_parameter("a");
        symbols.push_parameter("b");
        ExprGraph::new(symbols)
    }

    fn sexpr(text: &str) -> String {
        let mut g = graph();
        let id = parse_expression(&mut g, text, &TestNames).unwrap();
        g.to_sexpr(id)
    }

    fn error(text: &str) -> String {
        parse_expression(&mut graph(), text, &TestNames).unwrap_err()
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(sexpr("a + b * 2"), "(+ a (* b 2))");
        assert_eq!(sexpr("(a + b) * 2"), "(* (+ a b) 2)");
        assert_eq!(sexpr("a - b - 1"), "(+ (+ a (- b)) -1)");
        assert_eq!(sexpr("a / b / 3"), "(/ (/ a b) 3)");
        assert_eq!(sexpr("-a^2"), "(- (* a a))");
        assert_eq!(sexpr("2^3^2"), "512");
        assert_eq!(sexpr("+a"), "a");
    }

    #[test]
    fn numbers_and_pi() {
        assert_eq!(sexpr("1.5e-3"), "0.0015");
        assert_eq!(sexpr(".5"), "0.5");
        assert_eq!(sexpr("2E2"), "200");
        assert_eq!(sexpr("pi/2"), format!("{}", PI / 2.0));
    }

    #[test]
    fn powers_expand_into_products() {
        assert_eq!(sexpr("a^3"), "(* a (* a a))");
        assert_eq!(sexpr("a^0"), "1");
        assert_eq!(sexpr("a^-1"), "(/ 1 a)");
        assert_eq!(sexpr("a^0.5"), "(sqrt a)");
        assert_eq!(sexpr("a^(1/2)"), "(sqrt a)");
    }

    #[test]
    fn functions_and_joint_variables() {
        assert_eq!(sexpr("sqrt(a / b)"), "(sqrt (/ a b))");
        assert_eq!(
            sexpr("cos(q1 - pi/2)"),
            format!("(cos (+ q1 {}))", -PI / 2.0)
        );
        assert_eq!(sexpr("sin(-q1)"), "(- (sin q1))");
    }

    #[test]
    fn malformed_expressions_are_errors() {
        assert_eq!(
            error("a +"),
            "malformed expression \"a +\": expected a number, a name or '(' at the end"
        );
        assert_eq!(
            error("(a"),
            "malformed expression \"(a\": expected ')' at the end"
        );
        assert_eq!(
            error("a b"),
            "malformed expression \"a b\": expected an operator at 'b'"
        );
        assert_eq!(
            error("a # b"),
            "malformed expression \"a # b\": unexpected character '#'"
        );
        assert_eq!(
            error("1.2.3"),
            "malformed expression \"1.2.3\": '1.2.3' is not a number"
        );
        assert_eq!(
            error(""),
            "malformed expression \"\": expected a number, a name or '(' at the end"
        );
        assert_eq!(
            error("tan(a)"),
            "malformed expression \"tan(a)\": unknown function 'tan'"
        );
        assert_eq!(
            error("sin"),
            "malformed expression \"sin\": 'sin' is a function: write sin(...)"
        );
        assert_eq!(
            error("1e999"),
            "malformed expression \"1e999\": number 1e999 is out of range"
        );
    }

    #[test]
    fn unknown_symbols_and_bad_powers_are_errors() {
        assert_eq!(error("2 * x"), "unknown symbol 'x' in \"2 * x\"");
        assert_eq!(
            error("a^1.5"),
            "non-integer power in \"a^1.5\": an exponent must be an integer or 0.5, got 1.5"
        );
        assert_eq!(
            error("a^b"),
            "non-integer power in \"a^b\": an exponent must be an integer or 0.5, the exponent is not a constant"
        );
        assert!(error("a^100").contains("larger than 64"));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let deep = format!("{}a{}", "(".repeat(10_000), ")".repeat(10_000));
        assert!(error(&deep).contains("nested deeper than 64 levels"));
        assert!(error(&"-".repeat(10_000)).contains("nested deeper"));
    }

    #[test]
    fn rotations_are_products_of_elementary_factors() {
        let mut g = graph();
        let factors = parse_rotation(&mut g, "Rz(q1) * Rx(pi/2) * Rz(pi/2)", &TestNames).unwrap();
        let axes: Vec<Axis> = factors.iter().map(|f| f.0).collect();
        assert_eq!(axes, [Axis::Z, Axis::X, Axis::Z]);
        assert_eq!(g.to_sexpr(factors[0].1), "q1");
        assert_eq!(g.as_const(factors[2].1), Some(PI / 2.0));
        let bad = parse_rotation(&mut g, "Rz(q1) Rx(1)", &TestNames).unwrap_err();
        assert_eq!(
            bad,
            "malformed expression \"Rz(q1) Rx(1)\": expected an operator at 'Rx'"
        );
        let bad = parse_rotation(&mut g, "Rq(1)", &TestNames).unwrap_err();
        assert_eq!(
            bad,
            "malformed rotation \"Rq(1)\": expected Rx(..), Ry(..) or Rz(..) at 'Rq'"
        );
        let bad = parse_expression(&mut g, "Rz(1)", &TestNames).unwrap_err();
        assert!(
            bad.contains("a rotation 'Rz(...)' is not a number"),
            "{bad}"
        );
    }

    #[test]
    fn identifiers() {
        assert!(is_identifier("lc1x"));
        assert!(is_identifier("_a"));
        assert!(!is_identifier("1a"));
        assert!(!is_identifier("a b"));
        assert!(!is_identifier(""));
    }
}

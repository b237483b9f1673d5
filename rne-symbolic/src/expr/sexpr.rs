//! S-expression printing and parsing, so that tests read `"(+ x (* 2 y))"`.

use super::graph::ExprGraph;
use super::node::{Id, Node};

/// Why an s-expression did not parse.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SexprError {
    /// The text ended inside a list.
    #[error("unexpected end of s-expression")]
    UnexpectedEnd,
    /// A `)` with no matching `(`, or text after the expression.
    #[error("unexpected `{0}` in s-expression")]
    Unexpected(String),
    /// A name that is neither a number nor a known symbol.
    #[error("unknown symbol `{0}`")]
    UnknownSymbol(String),
    /// An operator with the wrong number of arguments.
    #[error("`{op}` does not take {count} argument(s)")]
    Arity {
        /// The operator.
        op: String,
        /// How many arguments it was given.
        count: usize,
    },
}

impl ExprGraph {
    /// Prints `id` as an s-expression: `(+ a b)`, `(* a b)`, `(/ a b)`, `(- a)`, `(sin a)`,
    /// `(cos a)`, `(sqrt a)`, numbers in shortest round-trip form, symbols by name.
    pub fn to_sexpr(&self, id: Id) -> String {
        let mut out = String::new();
        self.write_sexpr(id, &mut out);
        out
    }

    fn write_sexpr(&self, id: Id, out: &mut String) {
        let list = |op: &str, args: &[Id], out: &mut String| {
            out.push('(');
            out.push_str(op);
            for &a in args {
                out.push(' ');
                self.write_sexpr(a, out);
            }
            out.push(')');
        };
        match self.node(id) {
            Node::Const(c) => out.push_str(&format!("{}", c.value())),
            Node::Symbol(s) => out.push_str(&self.symbols().name(s)),
            Node::Add(a, b) => list("+", &[a, b], out),
            Node::Mul(a, b) => list("*", &[a, b], out),
            Node::Div(a, b) => list("/", &[a, b], out),
            Node::Neg(a) => list("-", &[a], out),
            Node::Sin(a) => list("sin", &[a], out),
            Node::Cos(a) => list("cos", &[a], out),
            Node::Sqrt(a) => list("sqrt", &[a], out),
            Node::Sign(a) => list("sign", &[a], out),
        }
    }

    /// Parses an s-expression into this graph (through the simplifying constructors).
    /// `(+ a b c)` and `(* a b c)` take any number of arguments, `(- a b)` subtracts.
    pub fn parse_sexpr(&mut self, text: &str) -> Result<Id, SexprError> {
        let tokens = tokenize(text);
        let mut pos = 0;
        let id = self.parse_tokens(&tokens, &mut pos)?;
        match tokens.get(pos) {
            None => Ok(id),
            Some(t) => Err(SexprError::Unexpected(t.clone())),
        }
    }

    fn parse_tokens(&mut self, tokens: &[String], pos: &mut usize) -> Result<Id, SexprError> {
        let token = tokens.get(*pos).ok_or(SexprError::UnexpectedEnd)?.clone();
        *pos += 1;
        if token == ")" {
            return Err(SexprError::Unexpected(token));
        }
        if token != "(" {
            if let Ok(value) = token.parse::<f64>() {
                return Ok(self.constant(value));
            }
            let symbol = self
                .symbols()
                .lookup(&token)
                .ok_or(SexprError::UnknownSymbol(token))?;
            return Ok(self.symbol(symbol));
        }
        let op = tokens.get(*pos).ok_or(SexprError::UnexpectedEnd)?.clone();
        *pos += 1;
        let mut args = Vec::new();
        loop {
            match tokens.get(*pos).map(String::as_str) {
                None => return Err(SexprError::UnexpectedEnd),
                Some(")") => {
                    *pos += 1;
                    break;
                }
                Some(_) => args.push(self.parse_tokens(tokens, pos)?),
            }
        }
        let arity = || SexprError::Arity {
            op: op.clone(),
            count: args.len(),
        };
        Ok(match (op.as_str(), args.as_slice()) {
            ("+", [first, rest @ ..]) => rest.iter().fold(*first, |acc, &x| self.add(acc, x)),
            ("*", [first, rest @ ..]) => rest.iter().fold(*first, |acc, &x| self.mul(acc, x)),
            ("-", [a]) => self.neg(*a),
            ("-", [a, b]) => self.sub(*a, *b),
            ("/", [a, b]) => self.div(*a, *b),
            ("sin", [a]) => self.sin(*a),
            ("cos", [a]) => self.cos(*a),
            ("sqrt", [a]) => self.sqrt(*a),
            ("sign", [a]) => self.sign(*a),
            _ => return Err(arity()),
        })
    }
}

fn tokenize(text: &str) -> Vec<String> {
    text.replace('(', " ( ")
        .replace(')', " ) ")
        .split_whitespace()
        .map(str::to_owned)
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::expr::{ExprGraph, SymbolTable};

    fn graph() -> ExprGraph {
        ExprGraph::new(SymbolTable::with_joints(["x", "y"]))
    }

    #[test]
    fn printing_then_parsing_gives_the_same_node() {
        let mut g = graph();
        for text in [
            "(+ x (* 2 y))",
            "(sin (- x))",
            "(/ Dx (+ y 3))",
            "(sqrt (cos DDy))",
        ] {
            let id = g.parse_sexpr(text).unwrap();
            let printed = g.to_sexpr(id);
            assert_eq!(
                g.parse_sexpr(&printed).unwrap(),
                id,
                "{text} printed as {printed}"
            );
        }
    }

    #[test]
    fn parsing_applies_the_simplifying_constructors() {
        let mut g = graph();
        let cases = [
            ("(* x 0)", "0"),
            ("(+ x 0)", "x"),
            ("(- (- x))", "x"),
            ("(* x 1)", "x"),
            ("(+ x (- x))", "0"),
            ("(sin 0)", "0"),
            ("(cos 1.5707963267948966)", "0"),
            ("(* 2 (* 3 x))", "(* x 6)"),
            ("(* (- x) y)", "(- (* x y))"),
        ];
        for (input, expected) in cases {
            let id = g.parse_sexpr(input).unwrap();
            assert_eq!(g.to_sexpr(id), expected, "{input}");
        }
    }

    #[test]
    fn malformed_input_is_an_error_not_a_panic() {
        let mut g = graph();
        for text in ["", "(", ")", "(+ x", "(foo x)", "(sin x y)", "z", "x y"] {
            assert!(g.parse_sexpr(text).is_err(), "{text:?} should not parse");
        }
    }
}

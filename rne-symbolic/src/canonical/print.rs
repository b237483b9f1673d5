//! Printing polynomials for people (the rules are in the `canonical` module docs): the
//! torque is split into groups by its motion atoms, each group's coefficient is rewritten in
//! the harmonic basis (`harmonic`), laid out (`layout`) and written with the names and
//! numbers of `notation`. The output depends only on the polynomial and the symbol table.

use std::collections::BTreeMap;

use super::atom::{Angle, Atom};
use super::budget::WorkBudget;
use super::harmonic::{harmonic_terms, print_work, Factor, Harmonic, Term};
use super::layout::{common_factor, group, Item};
use super::mathml;
use super::monomial::Monomial;
use super::notation::{
    abbreviation, joint_name, latex_base, latex_identifier, latex_joint, latex_label, number,
};
use super::polynomial::Polynomial;
use crate::expr::{Coordinate, Symbol, SymbolTable};

/// Plain text (`l1 lc2 m2 s2 Dq1 Dq2`), LaTeX
/// (`l_{1} l_{c2} m_{2} s_{2} \dot{q}_{1} \dot{q}_{2}`) or MathML.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum PrintFormat {
    /// Plain text, with the names of the symbol table (`Dq1` for q̇1, `DDq1` for q̈1).
    #[default]
    Text,
    /// LaTeX math-mode source.
    Latex,
    /// MathML presentation markup (the `mathml` module's names), the content of a `<math>`
    /// element: browsers render it natively.
    MathMl,
}

/// Prints polynomials over the symbols of a [`SymbolTable`].
#[derive(Clone, Debug)]
pub struct Printer<'a> {
    symbols: &'a SymbolTable,
    format: PrintFormat,
    digits: Option<usize>,
}

/// `p` printed in `format` (coefficients in shortest round-trip form): the one-call form of
/// [`Printer::print`].
pub fn format_polynomial(p: &Polynomial, symbols: &SymbolTable, format: PrintFormat) -> String {
    Printer::new(symbols, format).print(p)
}

/// A signed piece of a printed sum: `(negative, text without the sign)`.
type Chunk = (bool, String);

/// Order of a factor within a product: a class, then a key within the class.
type FactorKey = (u8, Vec<KeyPart>);

/// A piece of a sort key; numbers compare as numbers ("natural" order of names).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum KeyPart {
    Number(i64),
    Text(String),
}

impl<'a> Printer<'a> {
    /// A printer writing coefficients in shortest round-trip form.
    pub fn new(symbols: &'a SymbolTable, format: PrintFormat) -> Printer<'a> {
        Printer {
            symbols,
            format,
            digits: None,
        }
    }

    /// Rounds printed coefficients to `digits` significant digits (for numeric parameters,
    /// whose products print as `79.42636800000001` otherwise).
    pub fn significant_digits(self, digits: usize) -> Printer<'a> {
        Printer {
            digits: Some(digits.max(1)),
            ..self
        }
    }

    /// The polynomial as one line of text.
    pub fn print(&self, p: &Polynomial) -> String {
        let mut groups: Vec<(Monomial, Polynomial)> = p.collect(is_motion).into_iter().collect();
        groups.sort_by_cached_key(|(key, _)| group_order(key));
        let mut chunks = Vec::new();
        for (key, coefficient) in &groups {
            self.push_group(key, coefficient, &mut chunks);
        }
        self.join(chunks)
    }

    /// The polynomial as [`print`](Printer::print) writes it, if a bound on the work of doing
    /// so (its terms spread into harmonics, 2^(d + 1) for a term of trigonometric degree d,
    /// structural atoms printed where they occur) is left in `work`, which then spends it;
    /// `None`, and nothing spent, otherwise. The bound is found without expanding anything,
    /// so a polynomial whose printed form would run to gigabytes is refused in time linear in
    /// its terms.
    pub fn print_within(&self, p: &Polynomial, work: &mut WorkBudget) -> Option<String> {
        work.spend(print_work(p)).then(|| self.print(p))
    }

    /// The chunks of one group: `coefficient · key`.
    fn push_group(&self, key: &Monomial, coefficient: &Polynomial, chunks: &mut Vec<Chunk>) {
        let key_factors: BTreeMap<Factor, i32> = key
            .factors()
            .iter()
            .map(|(a, e)| (Factor::Atom(a.clone()), *e))
            .collect();
        let terms = harmonic_terms(coefficient);
        if let [term] = terms.as_slice() {
            let mut term = term.clone();
            term.factors.extend(key_factors);
            chunks.push(self.term(&term));
            return;
        }
        if terms.is_empty() {
            return;
        }
        let (common, cofactors) = common_factor(&terms);
        if key.is_one() && common.factors.is_empty() && common.coefficient.abs() == 1.0 {
            chunks.extend(self.items(group(terms)));
            return;
        }
        let mut parts = self.product_parts(common.coefficient.abs(), &common.factors, false);
        parts.push(self.parenthesised(&self.join(self.items(group(cofactors)))));
        parts.extend(self.factor_list(&key_factors));
        chunks.push((common.coefficient < 0.0, parts.join(" ")));
    }

    /// Chunks of laid-out items: single terms first, then groups, each in term order.
    fn items(&self, items: Vec<Item>) -> Vec<Chunk> {
        let mut terms = Vec::new();
        let mut groups = Vec::new();
        for item in items {
            match item {
                Item::Term(t) => terms.push((self.term_key(&t), self.term(&t))),
                Item::Group {
                    common,
                    terms: inner,
                } => {
                    let inner: Vec<Chunk> = self
                        .sorted_terms(&inner)
                        .iter()
                        .map(|t| self.term(t))
                        .collect();
                    let mut parts =
                        self.product_parts(common.coefficient.abs(), &common.factors, false);
                    parts.push(self.parenthesised(&self.join(inner)));
                    groups.push((
                        self.term_key(&common),
                        (common.coefficient < 0.0, parts.join(" ")),
                    ));
                }
            }
        }
        terms.sort_by(|a, b| a.0.cmp(&b.0));
        groups.sort_by(|a, b| a.0.cmp(&b.0));
        terms
            .into_iter()
            .chain(groups)
            .map(|(_, chunk)| chunk)
            .collect()
    }

    fn sorted_terms<'t>(&self, terms: &'t [Term]) -> Vec<&'t Term> {
        let mut sorted: Vec<(_, &Term)> = terms.iter().map(|t| (self.term_key(t), t)).collect();
        sorted.sort_by(|a, b| a.0.cmp(&b.0));
        sorted.into_iter().map(|(_, t)| t).collect()
    }

    fn term(&self, t: &Term) -> Chunk {
        (
            t.coefficient < 0.0,
            self.product_parts(t.coefficient.abs(), &t.factors, true)
                .join(" "),
        )
    }

    /// The printed coefficient (omitted when 1, unless `alone` and nothing else follows) and
    /// the factors in print order.
    fn product_parts(
        &self,
        magnitude: f64,
        factors: &BTreeMap<Factor, i32>,
        alone: bool,
    ) -> Vec<String> {
        let mut parts = Vec::new();
        if magnitude != 1.0 || (alone && factors.is_empty()) {
            parts.push(number(magnitude, self.digits, self.format));
        }
        parts.extend(self.factor_list(factors));
        parts
    }

    fn factor_list(&self, factors: &BTreeMap<Factor, i32>) -> Vec<String> {
        let mut keyed: Vec<(FactorKey, i32, &Factor)> = factors
            .iter()
            .map(|(f, &e)| (self.factor_key(f), e, f))
            .collect();
        keyed.sort_by(|a, b| (&a.0, a.1).cmp(&(&b.0, b.1)));
        keyed
            .into_iter()
            .map(|(_, e, f)| self.power(f, e))
            .collect()
    }

    /// Sort key of a term: its harmonic first (none before any), then its other factors.
    fn term_key(&self, t: &Term) -> (Vec<FactorKey>, Vec<(FactorKey, i32)>) {
        let mut harmonics = Vec::new();
        let mut others = Vec::new();
        for (f, &e) in &t.factors {
            match f {
                Factor::Harmonic(_) => harmonics.push(self.factor_key(f)),
                Factor::Atom(_) => others.push((self.factor_key(f), e)),
            }
        }
        harmonics.sort();
        others.sort();
        (harmonics, others)
    }

    fn factor_key(&self, f: &Factor) -> FactorKey {
        let joint = |k: u16| vec![KeyPart::Number(i64::from(k))];
        match f {
            Factor::Atom(Atom::Symbol(s)) => match *s {
                Symbol::Parameter(_) => (0, natural(&self.symbols.name(*s))),
                Symbol::Position(k) => (1, joint(k)),
                Symbol::Force(k) => (4, joint(k)),
                Symbol::Velocity(k) => (5, joint(k)),
                Symbol::Acceleration(k) => (6, joint(k)),
                Symbol::Lane(k) => (7, joint(k)),
            },
            Factor::Atom(a) => (2, natural(&self.atom(a))),
            Factor::Harmonic(h) => {
                let mut key = vec![KeyPart::Number(h.frequencies.len() as i64)];
                for &(j, n) in &h.frequencies {
                    key.extend([KeyPart::Number(i64::from(j)), KeyPart::Number(i64::from(n))]);
                }
                key.push(KeyPart::Number(i64::from(h.sine)));
                (3, key)
            }
        }
    }

    fn power(&self, f: &Factor, exponent: i32) -> String {
        let base = match f {
            Factor::Harmonic(h) => self.harmonic(h),
            Factor::Atom(a) => self.atom(a),
        };
        match (exponent, self.format) {
            (1, _) => base,
            (e, PrintFormat::Text) => format!("{base}^{e}"),
            (e, PrintFormat::Latex) => format!("{base}^{{{e}}}"),
            (e, PrintFormat::MathMl) if e < 0 => mathml::msup(
                &base,
                &format!(
                    "{}{}",
                    mathml::minus(),
                    mathml::mn(&e.unsigned_abs().to_string())
                ),
            ),
            (e, PrintFormat::MathMl) => mathml::msup(&base, &mathml::mn(&e.to_string())),
        }
    }

    fn atom(&self, a: &Atom) -> String {
        match a {
            Atom::Symbol(s) => self.symbol(*s),
            Atom::Sin(angle) | Atom::Cos(angle) => {
                let sine = matches!(a, Atom::Sin(_));
                let argument = match angle {
                    Angle::Symbol(Symbol::Position(k)) => {
                        return self.harmonic(&Harmonic {
                            sine,
                            frequencies: vec![(*k, 1)],
                        })
                    }
                    Angle::Symbol(s) => self.symbol(*s),
                    Angle::Expr(p) => self.print(p),
                };
                self.function(if sine { "sin" } else { "cos" }, &argument)
            }
            Atom::Sqrt(p) => match self.format {
                PrintFormat::Text => format!("sqrt({})", self.print(p)),
                PrintFormat::Latex => format!("\\sqrt{{{}}}", self.print(p)),
                PrintFormat::MathMl => format!("<msqrt>{}</msqrt>", self.print(p)),
            },
            Atom::Sign(p) => match self.format {
                PrintFormat::Text => format!("sign({})", self.print(p)),
                PrintFormat::Latex => format!("\\operatorname{{sgn}}({})", self.print(p)),
                PrintFormat::MathMl => mathml::function("sgn", &self.print(p)),
            },
        }
    }

    /// One symbol as this printer writes it: `Dq1`, `\dot{q}_{1}`, or q̇₁ in MathML.
    pub fn print_symbol(&self, s: Symbol) -> String {
        self.symbol(s)
    }

    fn symbol(&self, s: Symbol) -> String {
        let joint = |k, letter, accent| mathml::joint(self.symbols, k, letter, accent);
        let s = match (self.format, self.symbols.coordinate(s)) {
            (PrintFormat::Text, _) => return self.symbols.name(s),
            (PrintFormat::Latex, Some(Coordinate::Base(base))) => return latex_base(base),
            (PrintFormat::MathMl, Some(Coordinate::Base(base))) => return mathml::base(base),
            (_, Some(Coordinate::Joint(j))) => same_kind(s, self.symbols.joint_position(j)),
            (_, None) => s,
        };
        match (self.format, s) {
            (PrintFormat::Text, _) => self.symbols.name(s),
            (PrintFormat::Latex, Symbol::Position(k)) => latex_joint(self.symbols, k, ""),
            (PrintFormat::Latex, Symbol::Velocity(k)) => latex_joint(self.symbols, k, "\\dot"),
            (PrintFormat::Latex, Symbol::Acceleration(k)) => latex_joint(self.symbols, k, "\\ddot"),
            (PrintFormat::Latex, Symbol::Force(k)) => {
                format!("\\tau_{{{}}}", latex_label(self.symbols, k))
            }
            (PrintFormat::Latex, Symbol::Parameter(_)) => latex_identifier(&self.symbols.name(s)),
            (PrintFormat::Latex, Symbol::Lane(k)) => format!("e_{{{k}}}"),
            (PrintFormat::MathMl, Symbol::Position(k)) => joint(k, "q", None),
            (PrintFormat::MathMl, Symbol::Velocity(k)) => joint(k, "q", Some('\u{2d9}')),
            (PrintFormat::MathMl, Symbol::Acceleration(k)) => joint(k, "q", Some('\u{a8}')),
            (PrintFormat::MathMl, Symbol::Force(k)) => joint(k, "τ", None),
            (PrintFormat::MathMl, Symbol::Parameter(_)) => {
                mathml::identifier(&self.symbols.name(s))
            }
            (PrintFormat::MathMl, Symbol::Lane(k)) => {
                mathml::msub(&mathml::mi("e"), &mathml::mn(&k.to_string()))
            }
        }
    }

    /// `s12`, or `cos(2 q2 + q3)` when the multiples are not all 1.
    fn harmonic(&self, h: &Harmonic) -> String {
        if let Some(short) = abbreviation(self.symbols, h, self.format) {
            return short;
        }
        let chunks = h.frequencies.iter().map(|&(j, n)| {
            let joint = match self.format {
                PrintFormat::Text => joint_name(self.symbols, j),
                PrintFormat::Latex => latex_joint(self.symbols, j, ""),
                PrintFormat::MathMl => self.symbol(Symbol::Position(j)),
            };
            match n.abs() {
                1 => (n < 0, joint),
                m => (
                    n < 0,
                    format!("{} {joint}", number(f64::from(m), None, self.format)),
                ),
            }
        });
        let argument = self.join(chunks.collect());
        self.function(if h.sine { "sin" } else { "cos" }, &argument)
    }

    fn function(&self, name: &str, argument: &str) -> String {
        match self.format {
            PrintFormat::Text => format!("{name}({argument})"),
            PrintFormat::Latex => format!("\\{name}\\left({argument}\\right)"),
            PrintFormat::MathMl => mathml::function(name, argument),
        }
    }

    fn parenthesised(&self, text: &str) -> String {
        match self.format {
            PrintFormat::Text => format!("({text})"),
            PrintFormat::Latex => format!("\\left({text}\\right)"),
            PrintFormat::MathMl => mathml::parenthesised(text),
        }
    }

    /// `a - b + c` from signed chunks (`0` when there are none), with MathML's operators.
    fn join(&self, chunks: Vec<Chunk>) -> String {
        if self.format != PrintFormat::MathMl {
            return join(chunks);
        }
        let mut out = String::new();
        for (i, (negative, text)) in chunks.into_iter().enumerate() {
            match (i, negative) {
                (_, true) => out.push_str(&mathml::minus()),
                (0, false) => {}
                (_, false) => out.push_str(&mathml::mo("+")),
            }
            out.push_str(&text);
        }
        if out.is_empty() {
            out.push_str(&mathml::mn("0"));
        }
        out
    }
}

/// The atoms a torque is grouped by: velocities, accelerations and generalised forces.
fn is_motion(a: &Atom) -> bool {
    matches!(
        a,
        Atom::Symbol(Symbol::Velocity(_) | Symbol::Acceleration(_) | Symbol::Force(_))
    )
}

/// Order of the groups: accelerations, velocity products, forces, the rest; within a class
/// by the joints involved, with multiplicity.
fn group_order(key: &Monomial) -> (u8, Vec<(u16, u8)>) {
    let mut class = 3;
    let mut joints = Vec::new();
    for (a, e) in key.factors() {
        let (kind, joint) = match a.symbol() {
            Some(Symbol::Acceleration(k)) => (0, k),
            Some(Symbol::Velocity(k)) => (1, k),
            Some(Symbol::Force(k)) => (2, k),
            _ => continue,
        };
        class = class.min(kind);
        joints.extend(std::iter::repeat((joint, kind)).take(e.unsigned_abs() as usize));
    }
    joints.sort();
    (class, joints)
}

/// A name split into text and number runs, so that `m2` sorts before `m10`.
fn natural(name: &str) -> Vec<KeyPart> {
    let mut parts = Vec::new();
    let mut rest = name;
    while let Some(c) = rest.chars().next() {
        let digit = c.is_ascii_digit();
        let end = rest
            .find(|d: char| d.is_ascii_digit() != digit)
            .unwrap_or(rest.len());
        let (run, tail) = rest.split_at(end);
        parts.push(match run.parse::<i64>() {
            Ok(n) if digit => KeyPart::Number(n),
            _ => KeyPart::Text(run.to_string()),
        });
        rest = tail;
    }
    parts
}

/// `a - b + c` from signed chunks; `0` when there are none.
fn join(chunks: Vec<Chunk>) -> String {
    let mut out = String::new();
    for (i, (negative, text)) in chunks.into_iter().enumerate() {
        match (i, negative) {
            (0, true) => out.push('-'),
            (0, false) => {}
            (_, true) => out.push_str(" - "),
            (_, false) => out.push_str(" + "),
        }
        out.push_str(&text);
    }
    if out.is_empty() {
        out.push('0');
    }
    out
}

/// `symbol`'s kind (velocity, acceleration, force) at the index of the joint's `position` in
/// q: the notation helpers name a joint by its index in q, which on a floating base is not its
/// index in v.
fn same_kind(symbol: Symbol, position: Symbol) -> Symbol {
    let Symbol::Position(k) = position else {
        return symbol;
    };
    match symbol {
        Symbol::Position(_) => Symbol::Position(k),
        Symbol::Velocity(_) => Symbol::Velocity(k),
        Symbol::Acceleration(_) => Symbol::Acceleration(k),
        Symbol::Force(_) => Symbol::Force(k),
        Symbol::Parameter(_) | Symbol::Lane(_) => symbol,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::testing::{
        graph, irb140, planar_elbow, ELBOW_PARAMETERS, IRB140_PARAMETERS, THESIS_M, THESIS_TAU,
    };
    use crate::expr::ExprGraph;

    fn elbow_graph() -> ExprGraph {
        graph(&["q1", "q2"], &ELBOW_PARAMETERS)
    }

    fn parse(g: &mut ExprGraph, text: &str) -> Polynomial {
        let id = g.parse_sexpr(text).unwrap();
        Polynomial::from_expr(g, id).unwrap()
    }

    fn text(g: &ExprGraph, p: &Polynomial) -> String {
        format_polynomial(p, g.symbols(), PrintFormat::Text)
    }

    fn latex(g: &ExprGraph, p: &Polynomial) -> String {
        format_polynomial(p, g.symbols(), PrintFormat::Latex)
    }

    /// Printing within a budget refuses, spending nothing, what its bound says it cannot
    /// afford, and prints what it can exactly as `print` does: the product of twelve joint
    /// cosines spreads into 2^11 harmonics, the bound 2^13 per term.
    #[test]
    fn printing_within_a_budget_refuses_whole_what_it_cannot_afford() {
        let joints: Vec<String> = (1..=12).map(|k| format!("q{k}")).collect();
        let joints: Vec<&str> = joints.iter().map(String::as_str).collect();
        let mut g = graph(&joints, &ELBOW_PARAMETERS);
        let cosines: Vec<String> = joints.iter().map(|q| format!("(cos {q})")).collect();
        let product = cosines[1..]
            .iter()
            .fold(cosines[0].clone(), |a, c| format!("(* {a} {c})"));
        let p = parse(&mut g, &product);
        let small = parse(&mut g, "(* m1 (cos q1))");
        let printer = Printer::new(g.symbols(), PrintFormat::Text);
        let mut short = WorkBudget::new(1 << 13);
        assert_eq!(printer.print_within(&p, &mut short), None);
        assert_eq!(short.spent(), 0);
        assert!(short.exhausted());
        let mut enough = WorkBudget::new(1 << 14);
        let printed = printer.print_within(&p, &mut enough).unwrap();
        assert_eq!(printed, printer.print(&p));
        let harmonics = printed.matches("cos(").count() + printed.matches("c_").count();
        assert_eq!(harmonics, 1 << 11, "{printed}");
        let mut budget = WorkBudget::new(8);
        assert_eq!(
            printer.print_within(&small, &mut budget).as_deref(),
            Some("m1 c1")
        );
    }

    #[test]
    fn cos_of_a_sum_expands_then_prints_back_contracted() {
        let mut g = elbow_graph();
        let p = parse(&mut g, "(cos (+ q1 q2))");
        let expanded = parse(&mut g, "(- (* (cos q1) (cos q2)) (* (sin q1) (sin q2)))");
        assert_eq!(p, expanded);
        assert_eq!(p.len(), 2);
        assert_eq!(text(&g, &p), "c12");
        assert_eq!(latex(&g, &p), "c_{12}");
        let p = parse(
            &mut g,
            "(* lc2 (+ (* (sin q1) (cos q2)) (* (cos q1) (sin q2))))",
        );
        assert_eq!(text(&g, &p), "lc2 s12");
    }

    #[test]
    fn sums_of_three_joints_contract_and_the_rest_prints_longhand() {
        let mut g = graph(&["q1", "q2", "q3"], &["m1"]);
        let p = parse(&mut g, "(+ (sin (+ q1 q2 q3)) (* m1 (cos (+ q2 q3))))");
        assert_eq!(text(&g, &p), "m1 c23 + s123");
        let p = parse(&mut g, "(* (cos q2) (cos q2))");
        assert_eq!(text(&g, &p), "0.5 (1 + cos(2 q2))");
        let p = parse(
            &mut g,
            "(+ (* (sin q1) (cos q2)) (- (* (cos q1) (sin q2))))",
        );
        assert_eq!(text(&g, &p), "sin(q1 - q2)");
        assert_eq!(latex(&g, &p), "\\sin\\left(q_{1} - q_{2}\\right)");
    }

    #[test]
    fn mass_matrix_prints_like_the_thesis() {
        let mut g = elbow_graph();
        let m11 = parse(&mut g, THESIS_M[0][0]);
        assert_eq!(
            text(&g, &m11),
            "I1 + I2 + lc1^2 m1 + m2 (l1^2 + lc2^2 + 2 l1 lc2 c2)"
        );
    }

    #[test]
    fn printing_is_deterministic_and_independent_of_construction() {
        let mut g = elbow_graph();
        let tau = planar_elbow(&mut g);
        let derived = Polynomial::from_expr(&g, tau[0]).unwrap();
        let mut h = elbow_graph();
        let thesis = parse(&mut h, THESIS_TAU[0]);
        let first = text(&g, &derived);
        for _ in 0..3 {
            assert_eq!(text(&g, &derived), first);
        }
        assert_eq!(text(&h, &thesis), first);
        assert_eq!(latex(&h, &thesis), latex(&g, &derived));
    }

    #[test]
    fn joints_not_named_q_k_use_their_names() {
        let mut g = graph(&["shoulder", "elbow"], &["m", "alpha"]);
        let p = parse(&mut g, "(+ (* m (sin shoulder) Dshoulder Delbow) (cos (+ shoulder elbow)) (* (sin alpha) DDelbow))");
        assert_eq!(
            text(&g, &p),
            "sin(alpha) DDelbow + m s_shoulder Dshoulder Delbow + c_shoulder_elbow"
        );
        assert_eq!(
            latex(&g, &p),
            "\\sin\\left(\\alpha\\right) \\ddot{q}_{\\mathrm{elbow}} \
             + m s_{\\mathrm{shoulder}} \\dot{q}_{\\mathrm{shoulder}} \\dot{q}_{\\mathrm{elbow}} \
             + c_{\\mathrm{shoulder},\\mathrm{elbow}}"
        );
    }

    #[test]
    fn latex_identifiers_follow_the_documented_rule() {
        use crate::canonical::notation::latex_identifier;
        let cases = [
            ("m2", "m_{2}"),
            ("lc2", "l_{c2}"),
            ("I1xx", "I_{1xx}"),
            ("g", "g"),
            ("alpha", "\\alpha"),
            ("theta0", "\\theta_{0}"),
            ("mass", "\\mathrm{mass}"),
            ("link2", "\\mathrm{link}_{2}"),
            ("m_link", "m_{link}"),
            ("l_a_b", "l_{a\\_b}"),
        ];
        for (name, expected) in cases {
            assert_eq!(latex_identifier(name), expected, "{name}");
        }
    }

    #[test]
    fn numbers_print_exactly_or_to_the_chosen_digits() {
        let mut g = graph(&["q1"], &["m1"]);
        let p = parse(
            &mut g,
            "(+ (* 79.42636800000001 m1) (* 0.000012 (cos q1)) -3)",
        );
        assert_eq!(text(&g, &p), "-3 + 79.42636800000001 m1 + 1.2e-5 c1");
        let rounded = Printer::new(g.symbols(), PrintFormat::Text)
            .significant_digits(4)
            .print(&p);
        assert_eq!(rounded, "-3 + 79.43 m1 + 1.2e-5 c1");
        let latex = Printer::new(g.symbols(), PrintFormat::Latex)
            .significant_digits(4)
            .print(&p);
        assert_eq!(latex, "-3 + 79.43 m_{1} + 1.2 \\cdot 10^{-5} c_{1}");
        assert_eq!(text(&g, &Polynomial::zero()), "0");
        let quotient = parse(&mut g, "(/ (* 2 q1) m1)");
        assert_eq!(text(&g, &quotient), "2 m1^-1 q1");
    }

    /// Whether every opened tag of `markup` closes, in order.
    fn balanced(markup: &str) -> bool {
        let mut open = Vec::new();
        for tag in markup.split('<').skip(1) {
            let name = tag.split(['>', ' ']).next().unwrap_or("");
            match name.strip_prefix('/') {
                Some(closed) if open.pop() != Some(closed) => return false,
                Some(_) => {}
                None => open.push(name),
            }
        }
        open.is_empty()
    }

    #[test]
    fn mathml_writes_the_thesis_terms_as_elements() {
        let mut g = elbow_graph();
        let m11 = parse(&mut g, THESIS_M[0][0]);
        let printed = Printer::new(g.symbols(), PrintFormat::MathMl).print(&m11);
        let sub = |a: &str, b: &str| format!("<msub>{a}{b}</msub>");
        let (i1, i2) = (
            sub("<mi>I</mi>", "<mn>1</mn>"),
            sub("<mi>I</mi>", "<mn>2</mn>"),
        );
        let (l1, lc1) = (
            sub("<mi>l</mi>", "<mn>1</mn>"),
            sub("<mi>l</mi>", "<mi>c1</mi>"),
        );
        let (m1, m2) = (
            sub("<mi>m</mi>", "<mn>1</mn>"),
            sub("<mi>m</mi>", "<mn>2</mn>"),
        );
        let (lc2, c2) = (
            sub("<mi>l</mi>", "<mi>c2</mi>"),
            sub("<mi>c</mi>", "<mn>2</mn>"),
        );
        let square = |x: &str| format!("<msup>{x}<mn>2</mn></msup>");
        let plus = "<mo>+</mo>";
        let expected = format!(
            "{i1}{plus}{i2}{plus}{} {m1}{plus}{m2} <mrow><mo>(</mo>{}{plus}{}{plus}<mn>2</mn> \
             {l1} {lc2} {c2}<mo>)</mo></mrow>",
            square(&lc1),
            square(&l1),
            square(&lc2)
        );
        assert_eq!(printed, expected);
        let tau = planar_elbow(&mut g);
        for t in Polynomial::from_exprs(&g, &tau).unwrap() {
            let printed = Printer::new(g.symbols(), PrintFormat::MathMl).print(&t);
            assert!(balanced(&printed), "{printed}");
            assert!(printed.contains("<mover accent=\"true\"><mi>q</mi><mo>\u{a8}</mo></mover>"));
        }
    }

    #[test]
    fn mathml_writes_longhand_harmonics_powers_and_zero() {
        let mut g = graph(&["q1", "q2", "q3"], &["m1"]);
        let p = parse(&mut g, "(+ (sin (+ (* 2 q2) (- q3))) (/ 3 m1))");
        let printed = Printer::new(g.symbols(), PrintFormat::MathMl).print(&p);
        assert_eq!(
            printed,
            "<mn>3</mn> <msup><msub><mi>m</mi><mn>1</mn></msub><mrow><mo>\u{2212}</mo><mn>1</mn></mrow></msup>\
             <mo>+</mo><mi>sin</mi><mo>&#x2061;</mo><mrow><mo>(</mo><mn>2</mn> \
             <msub><mi>q</mi><mn>2</mn></msub><mo>\u{2212}</mo><msub><mi>q</mi><mn>3</mn></msub><mo>)</mo></mrow>"
        );
        let zero = Printer::new(g.symbols(), PrintFormat::MathMl).print(&Polynomial::zero());
        assert_eq!(zero, "<mn>0</mn>");
    }

    #[test]
    fn snapshot_planar_elbow() {
        let mut g = elbow_graph();
        let tau = planar_elbow(&mut g);
        let tau = Polynomial::from_exprs(&g, &tau).unwrap();
        let mut out = String::new();
        for format in [PrintFormat::Text, PrintFormat::Latex] {
            for (i, t) in tau.iter().enumerate() {
                out += &format!(
                    "tau{} = {}\n",
                    i + 1,
                    format_polynomial(t, g.symbols(), format)
                );
            }
            for (i, t) in tau.iter().enumerate() {
                for j in 0..2 {
                    let key = Monomial::atom(Atom::Symbol(Symbol::Acceleration(j)));
                    let m = t.coefficient(&key, Atom::is_joint_rate);
                    out += &format!(
                        "M[{},{}] = {}\n",
                        i + 1,
                        j + 1,
                        format_polynomial(&m, g.symbols(), format)
                    );
                }
            }
            for (i, t) in tau.iter().enumerate() {
                let gravity = t.coefficient(&Monomial::one(), Atom::is_joint_rate);
                out += &format!(
                    "g{} = {}\n",
                    i + 1,
                    format_polynomial(&gravity, g.symbols(), format)
                );
            }
        }
        insta::assert_snapshot!(out);
    }

    #[test]
    fn snapshot_irb140_first_three_joints() {
        let mut g = graph(&["q1", "q2", "q3"], &IRB140_PARAMETERS);
        let tau = irb140(&mut g);
        let tau = Polynomial::from_exprs(&g, &tau).unwrap();
        let mut out = String::new();
        for (i, t) in tau.iter().enumerate() {
            out += &format!(
                "tau{} = {}\n\n",
                i + 1,
                format_polynomial(t, g.symbols(), PrintFormat::Text)
            );
        }
        for (i, t) in tau.iter().enumerate() {
            for j in 0..3 {
                let key = Monomial::atom(Atom::Symbol(Symbol::Acceleration(j)));
                let m = t.coefficient(&key, Atom::is_joint_rate);
                out += &format!(
                    "M[{},{}] = {}\n",
                    i + 1,
                    j + 1,
                    format_polynomial(&m, g.symbols(), PrintFormat::Latex)
                );
            }
        }
        insta::assert_snapshot!(out);
    }
}

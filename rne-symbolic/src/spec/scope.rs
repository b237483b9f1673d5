//! How the numbers of a spec become expressions: what each name means where it is written
//! (a parameter, the link's own joint variable, or an error), and the conversion of TOML
//! numbers and expression strings into graph nodes.

use std::collections::HashMap;

use super::document::Value;
use super::error::{SpecError, SpecErrorKind};
use super::expression::{is_identifier, parse_expression, Names, RESERVED};
use super::schema::{Number, ParameterSpec, Vector};
use crate::expr::{ExprGraph, Id, Symbol, Vec3};
use crate::input::MAX_SYMBOLS;
use crate::model::JointVariable;

/// Every name a spec defines: parameters (symbol `Parameter(k)`, k in spec order) and joint
/// variables (symbol `Position(k)`, k in joint order) with the link each one moves.
#[derive(Clone, Debug, Default)]
pub(crate) struct Namespace {
    parameters: HashMap<String, Symbol>,
    joints: HashMap<String, (Symbol, String)>,
}

impl Namespace {
    /// The names of `parameters` and of `joints` (moving the links named by `link_names`, in
    /// model order). Parameter names must be identifiers other than the reserved words.
    pub(crate) fn new(
        parameters: &[ParameterSpec<'_>],
        joints: &[JointVariable],
        link_names: &[&str],
    ) -> Result<Namespace, SpecError> {
        if parameters.len() > MAX_SYMBOLS {
            return Err(SpecError::new(
                SpecErrorKind::Format,
                format!("more than {MAX_SYMBOLS} parameters"),
            )
            .at_field("parameters"));
        }
        let mut space = Namespace::default();
        for (k, p) in parameters.iter().enumerate() {
            let name = &p.name.name;
            if !is_identifier(name) || RESERVED.contains(&name.as_str()) {
                return Err(SpecError::new(
                    SpecErrorKind::Format,
                    format!(
                        "parameter name '{name}' is not a name (letters, digits and _, not {})",
                        RESERVED.join(", ")
                    ),
                )
                .at_field(p.value.field.clone())
                .at_span(p.name.span.clone()));
            }
            space
                .parameters
                .insert(name.clone(), Symbol::Parameter(k as u16));
        }
        for (k, joint) in joints.iter().enumerate() {
            let link = link_names
                .get(joint.link)
                .copied()
                .unwrap_or_default()
                .to_owned();
            space
                .joints
                .insert(joint.name.clone(), (Symbol::Position(k as u16), link));
        }
        Ok(space)
    }

    /// The scope of a field of a link whose joint variable is `own` (`None`: of no link, or a
    /// fixed link); the joint variable may appear only when `joint_allowed`.
    pub(crate) fn scope(&self, own: Option<Symbol>, joint_allowed: bool) -> Scope<'_> {
        Scope {
            space: self,
            own,
            joint_allowed,
        }
    }
}

/// The meaning of names in one field.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Scope<'a> {
    space: &'a Namespace,
    own: Option<Symbol>,
    joint_allowed: bool,
}

impl Names for Scope<'_> {
    fn resolve(&self, graph: &mut ExprGraph, name: &str) -> Result<Id, String> {
        if let Some(&symbol) = self.space.parameters.get(name) {
            return Ok(graph.symbol(symbol));
        }
        match self.space.joints.get(name) {
            Some(&(symbol, _)) if Some(symbol) == self.own && self.joint_allowed => {
                Ok(graph.symbol(symbol))
            }
            Some(&(symbol, _)) if Some(symbol) == self.own => {
                Err(format!("joint variable '{name}' may not appear here"))
            }
            Some((_, link)) => Err(format!(
                "joint variable '{name}' of link '{link}' may not appear here"
            )),
            None => Err(format!("unknown symbol '{name}'")),
        }
    }
}

impl Scope<'_> {
    /// The same scope with the link's joint variable forbidden.
    pub(crate) fn without_joint(&self) -> Self {
        Scope {
            joint_allowed: false,
            ..*self
        }
    }

    /// The expression of a TOML number or expression string.
    pub(crate) fn number(
        &self,
        graph: &mut ExprGraph,
        number: &Number<'_>,
    ) -> Result<Id, SpecError> {
        match &number.item.value {
            Value::Integer(i) => Ok(graph.constant(*i as f64)),
            Value::Float(x) if x.is_finite() => Ok(graph.constant(*x)),
            Value::Float(x) => Err(SpecError::new(
                SpecErrorKind::Physics,
                format!("{x} is not a finite number"),
            )
            .at_field(number.field.clone())
            .at_span(number.item.span.clone())),
            Value::String(text) => parse_expression(graph, text, self).map_err(|message| {
                SpecError::new(SpecErrorKind::Expression, message)
                    .at_field(number.field.clone())
                    .at_span(number.item.span.clone())
            }),
            _ => Err(number
                .item
                .type_error("a number or an expression string", &number.field)),
        }
    }

    /// The expressions of three numbers.
    pub(crate) fn vector(
        &self,
        graph: &mut ExprGraph,
        vector: &Vector<'_>,
    ) -> Result<Vec3, SpecError> {
        let [x, y, z] = vector;
        Ok([
            self.number(graph, x)?,
            self.number(graph, y)?,
            self.number(graph, z)?,
        ])
    }

    /// The expression of an optional number, zero when absent.
    pub(crate) fn number_or_zero(
        &self,
        graph: &mut ExprGraph,
        number: Option<&Number<'_>>,
    ) -> Result<Id, SpecError> {
        match number {
            Some(n) => self.number(graph, n),
            None => Ok(graph.zero()),
        }
    }
}

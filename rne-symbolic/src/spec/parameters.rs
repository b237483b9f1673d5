//! The `[parameters]` table: each value a number or an expression over other parameters, in any
//! order. Definitions are ordered by their dependencies (a cycle is an error) and evaluated
//! numerically; every parameter keeps its own symbol `Parameter(k)` in the reader's graph.

use super::error::{SpecError, SpecErrorKind};
use super::schema::ParameterSpec;
use super::scope::Namespace;
use crate::expr::{ExprGraph, Id, Node, Symbol};
use crate::model::Parameter;

/// Builds every parameter's definition in `graph`, registers the names in its symbol table and
/// evaluates the values (derived parameters from the values they depend on).
pub(crate) fn define(
    graph: &mut ExprGraph,
    specs: &[ParameterSpec<'_>],
    space: &Namespace,
) -> Result<Vec<Parameter>, SpecError> {
    let scope = space.scope(None, false);
    let mut definitions = Vec::with_capacity(specs.len());
    for spec in specs {
        graph.symbols_mut().push_parameter(spec.name.name.clone());
        definitions.push(scope.number(graph, &spec.value)?);
    }
    let dependencies: Vec<Vec<usize>> = definitions
        .iter()
        .map(|&d| dependencies(graph, d))
        .collect();
    let order = evaluation_order(specs, &dependencies)?;
    let mut values = vec![f64::NAN; specs.len()];
    for k in order {
        let (Some(&definition), Some(spec)) = (definitions.get(k), specs.get(k)) else {
            continue;
        };
        let value = graph.eval::<f64>(&[definition], |s| match s {
            Symbol::Parameter(j) => values.get(j as usize).copied().unwrap_or(f64::NAN),
            _ => f64::NAN,
        });
        let value = value.first().copied().unwrap_or(f64::NAN);
        if !value.is_finite() {
            return Err(SpecError::new(
                SpecErrorKind::Physics,
                format!("parameter '{}' is not finite: {value}", spec.name.name),
            )
            .at_field(spec.value.field.clone()));
        }
        if let Some(slot) = values.get_mut(k) {
            *slot = value;
        }
    }
    Ok(specs
        .iter()
        .zip(values)
        .map(|(spec, value)| Parameter {
            name: spec.name.name.clone(),
            value,
        })
        .collect())
}

/// Indices of the parameters an expression uses.
fn dependencies(graph: &ExprGraph, definition: Id) -> Vec<usize> {
    graph
        .reachable(&[definition])
        .into_iter()
        .filter_map(|id| match graph.node(id) {
            Node::Symbol(Symbol::Parameter(j)) => Some(j as usize),
            _ => None,
        })
        .collect()
}

/// An order in which every parameter comes after those it uses (depth-first post-order);
/// a cycle is an error naming the parameters on it.
fn evaluation_order(
    specs: &[ParameterSpec<'_>],
    dependencies: &[Vec<usize>],
) -> Result<Vec<usize>, SpecError> {
    #[derive(Copy, Clone, PartialEq)]
    enum State {
        New,
        Active,
        Done,
    }
    let mut state = vec![State::New; specs.len()];
    let mut order = Vec::with_capacity(specs.len());
    for root in 0..specs.len() {
        if state.get(root) != Some(&State::New) {
            continue;
        }
        state[root] = State::Active;
        // (parameter, index of its next dependency to visit)
        let mut stack = vec![(root, 0)];
        while let Some((node, next)) = stack.last_mut() {
            let node = *node;
            match dependencies.get(node).and_then(|d| d.get(*next)) {
                Some(&dep) => {
                    *next += 1;
                    match state.get(dep) {
                        Some(State::New) => {
                            state[dep] = State::Active;
                            stack.push((dep, 0));
                        }
                        Some(State::Active) => return Err(cycle_error(specs, &stack, dep)),
                        _ => {}
                    }
                }
                None => {
                    state[node] = State::Done;
                    order.push(node);
                    stack.pop();
                }
            }
        }
    }
    Ok(order)
}

fn cycle_error(specs: &[ParameterSpec<'_>], stack: &[(usize, usize)], again: usize) -> SpecError {
    let start = stack
        .iter()
        .position(|&(p, _)| p == again)
        .unwrap_or_default();
    let name = |k: usize| specs.get(k).map_or("?", |s| s.name.name.as_str());
    let mut path: Vec<&str> = stack
        .get(start..)
        .unwrap_or_default()
        .iter()
        .map(|&(p, _)| name(p))
        .collect();
    path.push(name(again));
    let field = specs
        .get(again)
        .map(|s| s.value.field.clone())
        .unwrap_or_default();
    SpecError::new(
        SpecErrorKind::Expression,
        format!("parameter cycle: {}", path.join(" -> ")),
    )
    .at_field(field)
}

//! The dynamics as functions of given standard parameters, and of the base parameters alone
//! (`parameters: base`, docs/design.md §3 and §4.6).
//!
//! τ = Y(q, q̇, q̈) π is linear in the standard parameters, and with W₂ = W₁ K (Gautier 1991,
//! [`BaseParameters`]) τ = Y₁ (π₁ + K π₂) = Y₁ π_b. Every π with the same π_b gives the same
//! τ, so the dynamics are functions of π_b; one π per π_b is the particular solution
//!
//! ```text
//! π = P π_b:   π₁ = π_b,   π₂ = 0
//! ```
//!
//! (for a chain, Khalil and Kleinfinger's regrouping: the regrouped parameters are zero and
//! the ones they were added to carry the sums). Then π_b(P π_b) = π_b and Y P π_b = Y₁ π_b
//! identically, whatever the state: substituted into the recursion written in the standard
//! parameters ([`super::inertial_parameters`]), it gives τ, M, C, g, the bias and every
//! quantity built from them as exact functions of π_b. The bodies of P π_b need not be
//! physical (a regrouped mass is zero while the first moment it carried stays), which is why
//! the substitution goes through m, m c and the inertia about the origin, never through c.
//!
//! The potential energy is the one quantity the dynamics do not fix: only its gradient g(q)
//! is determined by π_b, so V(P π_b) differs from V(π) by a constant (the energy of the
//! regrouped parameters at the reference configuration); its differences are exact.

use crate::expr::{Id, Symbol};
use crate::model::Parameter;

use super::base_parameters::{identifiers, BaseParameters};
use super::inertial_parameters::BodyParameters;
use super::regressor::{regressor_columns, RegressorColumn, PARAMETERS_PER_BODY};
use super::SymbolicDynamics;

impl SymbolicDynamics {
    /// The dynamics with the standard parameters π (masses, first moments and inertias about
    /// the body origins; friction and armature of the joints) replaced by the expressions
    /// `standard`, in the order of [`Self::parameter_names`]. Every quantity built afterwards
    /// is a polynomial in them (rational for forward dynamics and M⁻¹).
    ///
    /// # Panics
    /// When `standard` does not have one entry per standard parameter, or when something was
    /// built already (choose this first, like [`Self::at_rest`]).
    pub fn with_standard_parameters(mut self, standard: &[Id]) -> SymbolicDynamics {
        let columns = regressor_columns(&self.model, self.friction);
        assert_eq!(
            columns.len(),
            standard.len(),
            "one expression per standard parameter"
        );
        assert!(
            self.full.is_none() && self.mass_matrix.is_none() && self.bias_torques.is_none(),
            "standard parameters are set before anything is built"
        );
        let bodies = (0..self.model.links.len())
            .map(|link| {
                let first = link * PARAMETERS_PER_BODY;
                BodyParameters::from_standard(std::array::from_fn(|p| standard[first + p]))
            })
            .collect();
        for (column, &value) in columns.iter().zip(standard) {
            match *column {
                RegressorColumn::Body { .. } => {}
                RegressorColumn::Friction { link, parameter } => {
                    if let Some(friction) = &mut self.model.links[link].friction {
                        match parameter {
                            0 => friction.viscous = value,
                            1 => friction.coulomb = value,
                            _ => friction.offset = value,
                        }
                    }
                }
                RegressorColumn::Armature { link } => {
                    self.model.links[link].armature = Some(value);
                }
            }
        }
        self.bodies = Some(bodies);
        self
    }

    /// The dynamics as functions of every standard parameter: parameter k is the symbol
    /// `Parameter(k)`, named by the identifier made from [`Self::parameter_names`]`[k]`
    /// ([`identifiers`]) with the model's value — the runtime counterpart of the regressor's
    /// π, against which [`Self::in_base_parameters`] is measured.
    ///
    /// # Panics
    /// When the model keeps parameters symbolic, or when something was built already.
    pub fn in_standard_parameters(&self) -> SymbolicDynamics {
        assert!(
            self.model.graph.symbols().parameters().is_empty(),
            "standard parameters replace numeric ones"
        );
        let mut scratch = self.clone();
        let standard = scratch.standard_parameters();
        let values = scratch.model.graph.eval::<f64>(&standard, |_| f64::NAN);
        let names = identifiers(&self.parameter_names());
        let mut dynamics = self.clone();
        let g = &mut dynamics.model.graph;
        let symbols: Vec<Id> = names
            .iter()
            .map(|name| {
                let symbol = g.symbols_mut().push_parameter(name.clone());
                g.symbol(symbol)
            })
            .collect();
        dynamics.model.parameters = names
            .into_iter()
            .zip(values)
            .map(|(name, value)| Parameter { name, value })
            .collect();
        dynamics.with_standard_parameters(&symbols)
    }

    /// The dynamics as functions of the base parameters alone (`parameters: base`): base
    /// parameter b is the symbol `Parameter(b)`, named in the graph's symbol table and in
    /// [`crate::RobotModel::parameters`] by a Rust identifier made from its name
    /// ([`BaseParameters::names`], [`identifiers`]), with the value π_b of the model's own
    /// parameters; the standard parameters are the particular solution π = P π_b. Returns the
    /// dynamics and the base parameters they were built from.
    ///
    /// # Panics
    /// When the model keeps parameters symbolic (the base parameters are found at numeric
    /// geometry), or when something was built already.
    pub fn in_base_parameters(&self) -> (SymbolicDynamics, BaseParameters) {
        assert!(
            self.model.graph.symbols().parameters().is_empty(),
            "base parameters are found for a model with numeric parameters"
        );
        let base = self.base_parameters();
        let mut scratch = self.clone();
        let standard = scratch.standard_parameters();
        let values = scratch.model.graph.eval::<f64>(&standard, |_| f64::NAN);
        let names = identifiers(&base.names(&self.parameter_names()));
        let mut dynamics = self.clone();
        let g = &mut dynamics.model.graph;
        let zero = g.zero();
        let mut particular = vec![zero; standard.len()];
        for (name, &kept) in names.iter().zip(&base.independent) {
            let symbol: Symbol = g.symbols_mut().push_parameter(name.clone());
            particular[kept] = g.symbol(symbol);
        }
        dynamics.model.parameters = names
            .into_iter()
            .zip(base.of(&values))
            .map(|(name, value)| Parameter { name, value })
            .collect();
        (dynamics.with_standard_parameters(&particular), base)
    }
}

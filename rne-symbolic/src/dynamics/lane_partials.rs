//! State derivatives built in lanes: the forward sweeps of [`Sweep::Forward`] four
//! directions at a time, each value of the sweep a vector whose lane l is the derivative
//! along the direction seeded with the unit vector e_l ([`Symbol::Lane`]).
//!
//! A forward sweep along ∂/∂q_j applies to its tangents the same linear maps whatever j is:
//! the rotations, inertias and velocities of the recursion, which are values of the state.
//! Carrying several directions together computes each of those products once per group of
//! directions rather than once per direction, and a kernel emitted with vector values does a
//! group's products in one instruction (vector forward mode; Griewank & Walther, "Evaluating
//! Derivatives", 2nd ed., §3.1). The values of the recursion itself are not vectors and are
//! computed once. Directions are grouped as (q_0, q̇_0, q_1, q̇_1, …): a position and a
//! velocity of one joint reach the same links, so a group's lanes are seldom zero where the
//! others are not. Each lane's value is the derivative the scalar forward sweep builds, to
//! the sign of zeros: a lane whose direction does not reach a value computes 0·x + … where
//! the scalar sweep writes nothing.
//!
//! A direction of q is a tangent direction ([`derivatives::tangent_directions`]): a joint's
//! moves its q, a free-flyer's move the base position and quaternion together, so the seed of
//! a configuration symbol is Σ_l w_l e_l over the lanes whose directions move it.
//!
//! [`Sweep::Forward`]: super::derivatives::Sweep::Forward

use std::collections::BTreeMap;

use super::derivatives;
use crate::expr::{Differentiator, ExprGraph, Id, Symbol};
use crate::model::StateLayout;

/// Directions carried together: an AVX register of `f64`.
pub const LANES: usize = 4;

/// A direction of the state space a lane carries.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Direction {
    /// Tangent direction k of the configuration (∂/∂q_k for a joint; NV of them).
    Position(usize),
    /// ∂/∂q̇_k.
    Velocity(usize),
}

/// The derivatives of some outputs along every direction of the state, built in lanes.
#[derive(Clone, Debug, PartialEq)]
pub struct LanePartials {
    /// The direction of each lane of each group: `groups[g][l]`, at most [`LANES`] a group.
    pub groups: Vec<Vec<Direction>>,
    /// `rows[i][g]`: the derivatives of output i along the directions of group g, a node
    /// whose lane l is the derivative along `groups[g][l]`.
    pub rows: Vec<Vec<Id>>,
}

impl LanePartials {
    /// Every direction of a state of `layout`, grouped.
    fn groups(layout: StateLayout) -> Vec<Vec<Direction>> {
        let directions: Vec<Direction> = (0..layout.nv())
            .flat_map(|k| [Direction::Position(k), Direction::Velocity(k)])
            .collect();
        directions.chunks(LANES).map(<[_]>::to_vec).collect()
    }

    /// The derivatives of `outputs` along every direction of the state, the nodes `held`
    /// constant ([`Differentiator::holding`]).
    pub fn build(
        g: &mut ExprGraph,
        outputs: &[Id],
        layout: StateLayout,
        held: &[Id],
    ) -> LanePartials {
        let groups = Self::groups(layout);
        let tangents = derivatives::tangent_directions(g, layout);
        let columns: Vec<Vec<Id>> = groups
            .iter()
            .map(|group| {
                // Each symbol's seed as its terms w e_l, by symbol (a deterministic order).
                let mut terms: BTreeMap<Symbol, Vec<Id>> = BTreeMap::new();
                for (l, &direction) in group.iter().enumerate() {
                    let lane = g.symbol(Symbol::Lane(l as u16));
                    match direction {
                        Direction::Position(k) => {
                            for &(c, weight) in &tangents[k] {
                                let term = g.mul(weight, lane);
                                terms
                                    .entry(Symbol::Position(c as u16))
                                    .or_default()
                                    .push(term);
                            }
                        }
                        Direction::Velocity(k) => {
                            terms
                                .entry(Symbol::Velocity(k as u16))
                                .or_default()
                                .push(lane);
                        }
                    }
                }
                let seeds: Vec<(Symbol, Id)> = terms
                    .into_iter()
                    .map(|(symbol, terms)| (symbol, g.sum(terms)))
                    .collect();
                let mut d = Differentiator::along(&seeds, held, g);
                outputs.iter().map(|&o| d.derivative(g, o)).collect()
            })
            .collect();
        let rows = (0..outputs.len())
            .map(|i| columns.iter().map(|column| column[i]).collect())
            .collect();
        LanePartials { groups, rows }
    }
}

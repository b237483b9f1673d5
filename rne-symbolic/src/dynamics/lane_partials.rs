//! State derivatives built in lanes: the sweeps of [`Sweep`] four at a time, each value of a
//! sweep a vector whose lane l belongs to the sweep seeded with the unit vector e_l
//! ([`Symbol::Lane`]).
//!
//! A forward sweep along ∂/∂q_j applies to its tangents the same linear maps whatever j is:
//! the rotations, inertias and velocities of the recursion, which are values of the state.
//! Carrying several directions together computes each of those products once per group of
//! directions rather than once per direction, and a kernel emitted with vector values does a
//! group's products in one instruction (vector forward mode; Griewank & Walther, "Evaluating
//! Derivatives", 2nd ed., §3.1). The values of the recursion itself are not vectors and are
//! computed once. Directions are grouped as (q_0, q̇_0, q_1, q̇_1, …): a position and a
//! velocity of one joint reach the same links, so a group's lanes are seldom zero where the
//! others are not. Reverse sweeps are carried the same way, four outputs a vector (vector
//! reverse mode, §3.3 there): the adjoint of each output τ_k starts as Σ_r w_rk e_r, and the
//! weights w can be the rows of −M⁻¹, which gives forward dynamics' derivatives
//! −M⁻¹ ∂τ/∂x directly. Each lane's value is the derivative the scalar sweep builds, to the
//! sign of zeros: a lane whose sweep does not reach a value computes 0·x + … where the
//! scalar sweep writes nothing.
//!
//! A direction of q is a tangent direction ([`derivatives::tangent_directions`]): a joint's
//! moves its q, a free-flyer's move the base position and quaternion together, so the seed of
//! a configuration symbol is Σ_l w_l e_l over the lanes whose directions move it.
//!
//! [`Sweep`]: super::derivatives::Sweep

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

/// The derivatives of some outputs along every direction of the state, built in lanes: each
/// derivative is one lane of one of [`vectors`](Self::vectors).
#[derive(Clone, Debug, PartialEq)]
pub struct LanePartials {
    /// The vectors that carry the derivatives.
    pub vectors: Vec<Id>,
    /// `dq[i][k]`: (index into `vectors`, lane) of output i's derivative along tangent
    /// direction k of the configuration.
    pub dq: Vec<Vec<(usize, u8)>>,
    /// `dv[i][k]`: the same for ∂/∂q̇_k.
    pub dv: Vec<Vec<(usize, u8)>>,
}

impl LanePartials {
    /// The forward sweeps in lanes: `rows[i][g]` is a vector whose lane l is the derivative
    /// of output i along `groups[g][l]` ([`LanePartials::from_rows`] places them). Rows are
    /// linear in the outputs lane by lane, so −M⁻¹ can be applied to them as to any column.
    pub fn forward_rows(
        g: &mut ExprGraph,
        outputs: &[Id],
        layout: StateLayout,
    ) -> (Vec<Vec<Direction>>, Vec<Vec<Id>>) {
        let directions: Vec<Direction> = (0..layout.nv())
            .flat_map(|k| [Direction::Position(k), Direction::Velocity(k)])
            .collect();
        let groups: Vec<Vec<Direction>> = directions.chunks(LANES).map(<[_]>::to_vec).collect();
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
                let mut d = Differentiator::along(&seeds, g);
                outputs.iter().map(|&o| d.derivative(g, o)).collect()
            })
            .collect();
        let rows = (0..outputs.len())
            .map(|i| columns.iter().map(|column| column[i]).collect())
            .collect();
        (groups, rows)
    }

    /// The partials [`forward_rows`](Self::forward_rows) built, placed.
    pub fn from_rows(groups: &[Vec<Direction>], rows: Vec<Vec<Id>>, nv: usize) -> LanePartials {
        let carrier = |direction: Direction| -> (usize, u8) {
            groups
                .iter()
                .enumerate()
                .find_map(|(g, group)| {
                    let lane = group.iter().position(|&d| d == direction)?;
                    Some((g, lane as u8))
                })
                .expect("every direction has a lane")
        };
        let place = |direction: fn(usize) -> Direction| -> Vec<Vec<(usize, u8)>> {
            (0..rows.len())
                .map(|i| {
                    (0..nv)
                        .map(|k| {
                            let (g, lane) = carrier(direction(k));
                            (i * groups.len() + g, lane)
                        })
                        .collect()
                })
                .collect()
        };
        LanePartials {
            dq: place(Direction::Position),
            dv: place(Direction::Velocity),
            vectors: rows.concat(),
        }
    }

    /// The reverse sweeps in lanes: one backward sweep per group of [`LANES`] rows of
    /// `weights` × ∂outputs/∂x, row r of the group seeded with e_r
    /// ([`ExprGraph::gradient_seeded`]: the seed of output k is Σ_r w(i_r, k) e_r, w being
    /// `weights`), its adjoints vectors whose lane r belongs to row i_r. `weights` is the identity for the
    /// outputs' own derivatives, −M⁻¹ for forward dynamics' (a vector–Jacobian product per
    /// row of −M⁻¹ ∂τ/∂x, M⁻¹ symmetric). ∂/∂q is taken along the tangent directions.
    pub fn reverse(
        g: &mut ExprGraph,
        outputs: &[Id],
        weights: &[Vec<Id>],
        layout: StateLayout,
    ) -> LanePartials {
        let symbols: Vec<Symbol> = (0..layout.nq())
            .map(|c| Symbol::Position(c as u16))
            .chain((0..layout.nv()).map(|k| Symbol::Velocity(k as u16)))
            .collect();
        let tangents = derivatives::tangent_directions(g, layout);
        let (nv, rows) = (layout.nv(), weights.len());
        let mut partials = LanePartials {
            vectors: Vec::new(),
            dq: vec![Vec::with_capacity(nv); rows],
            dv: vec![Vec::with_capacity(nv); rows],
        };
        let row_groups: Vec<Vec<usize>> = (0..rows)
            .collect::<Vec<_>>()
            .chunks(LANES)
            .map(<[_]>::to_vec)
            .collect();
        for group in row_groups {
            let lanes: Vec<Id> = (0..group.len())
                .map(|r| g.symbol(Symbol::Lane(r as u16)))
                .collect();
            let seeds: Vec<(Id, Id)> = outputs
                .iter()
                .enumerate()
                .map(|(k, &output)| {
                    let terms: Vec<Id> = group
                        .iter()
                        .zip(&lanes)
                        .map(|(&i, &lane)| g.mul(weights[i][k], lane))
                        .collect();
                    (output, g.sum(terms))
                })
                .collect();
            let gradient = g.gradient_seeded(&seeds, &symbols);
            let (by_position, by_velocity) = gradient.split_at(layout.nq());
            let first = partials.vectors.len();
            for weights in &tangents {
                let terms: Vec<Id> = weights
                    .iter()
                    .map(|&(c, w)| g.mul(w, by_position[c]))
                    .collect();
                partials.vectors.push(g.sum(terms));
            }
            partials.vectors.extend_from_slice(by_velocity);
            for (r, &i) in group.iter().enumerate() {
                for k in 0..nv {
                    partials.dq[i].push((first + k, r as u8));
                    partials.dv[i].push((first + nv + k, r as u8));
                }
            }
        }
        partials
    }
}

#[cfg(test)]
mod tests {
    use super::LanePartials;
    use crate::dynamics::{Matrix, SymbolicDynamics};
    use crate::expr::{ExprGraph, Id, Symbol};

    /// The values of `partials`' (∂/∂q, ∂/∂q̇) at `state`, each read from its lane.
    fn lane_values(g: &ExprGraph, partials: &LanePartials, state: [f64; 3]) -> Vec<f64> {
        let at = |lane: u8| {
            g.eval::<f64>(&partials.vectors, |s| match s {
                Symbol::Position(k) => state[0] + 0.3 * f64::from(k),
                Symbol::Velocity(k) => state[1] - 0.2 * f64::from(k),
                Symbol::Acceleration(k) => state[2] + 0.1 * f64::from(k),
                Symbol::Lane(l) => f64::from(u8::from(l == u16::from(lane))),
                _ => f64::NAN,
            })
        };
        let by_lane: Vec<Vec<f64>> = (0..4).map(at).collect();
        [&partials.dq, &partials.dv]
            .into_iter()
            .flatten()
            .flatten()
            .map(|&(v, lane)| by_lane[lane as usize][v])
            .collect()
    }

    /// Forward sweeps in lanes (four directions a vector) and reverse sweeps in lanes (four
    /// torques a vector) give, lane by lane, the scalar sweeps' ∂τ/∂q and ∂τ/∂q̇.
    #[test]
    fn both_sweeps_in_lanes_give_the_scalar_derivatives() {
        for robot in ["ur5.urdf", "panda-arm.urdf"] {
            let model = crate::dynamics::fixture_robot(robot);
            let mut d = SymbolicDynamics::new(&model);
            let tau = d.inverse_dynamics();
            let (dq, dv): (Matrix, Matrix) = d.inverse_dynamics_derivatives();
            let layout = d.layout();
            let g = &mut d.model.graph;
            let (groups, rows) = LanePartials::forward_rows(g, &tau, layout);
            let forward = LanePartials::from_rows(&groups, rows, layout.nv());
            let identity: Vec<Vec<Id>> = (0..tau.len())
                .map(|i| {
                    (0..tau.len())
                        .map(|k| if i == k { g.one() } else { g.zero() })
                        .collect()
                })
                .collect();
            let reverse = LanePartials::reverse(g, &tau, &identity, layout);
            for state in [[0.4, -1.1, 2.0], [-2.3, 0.7, -0.5]] {
                let scalar = g.eval::<f64>(&[dq.concat(), dv.concat()].concat(), |s| match s {
                    Symbol::Position(k) => state[0] + 0.3 * f64::from(k),
                    Symbol::Velocity(k) => state[1] - 0.2 * f64::from(k),
                    Symbol::Acceleration(k) => state[2] + 0.1 * f64::from(k),
                    _ => f64::NAN,
                });
                let scale = scalar.iter().fold(1.0f64, |m, x| m.max(x.abs()));
                for (name, partials) in [("forward", &forward), ("reverse", &reverse)] {
                    let lanes = lane_values(g, partials, state);
                    for (k, (a, b)) in lanes.iter().zip(&scalar).enumerate() {
                        assert!(
                            (a - b).abs() <= 1e-13 * scale,
                            "{robot} {name} entry {k}: {a} against {b}"
                        );
                    }
                }
            }
        }
    }
}

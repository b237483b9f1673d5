//! Derivatives of the dynamics for control and optimisation (docs/design.md §4): ∂τ/∂q, ∂τ/∂q̇,
//! ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹, by symbolic differentiation of the expression graph (exact, with
//! the subexpressions of τ and of its derivatives shared by hash-consing).
//!
//! The graph of τ is the Newton–Euler recursion itself, so differentiating it differentiates
//! the recursion: a forward sweep along q_j ([`Sweep::Forward`]) propagates ∂ω_i/∂q_j,
//! ∂α_i/∂q_j, ∂a_i/∂q_j out from joint j and ∂f_i/∂q_j back to the base, and builds nothing
//! for the links before j, whose motion does not depend on q_j (∂(·)_i/∂q_j = 0 for j not an
//! ancestor of i, as in Carpentier & Mansard's analytical derivatives, cited below). A
//! reverse sweep ([`Sweep::Reverse`]) propagates the adjoint of one τ_i back through the
//! forces of the links after i and the motion of every link, and builds all 2·NV partials of
//! τ_i at once. Which costs fewer operations depends on the robot (forward for UR5, reverse
//! for the Panda arm, whose full inertias make each forward sweep nearly a whole recursion),
//! so both are built and the cheaper kept.
//!
//! Derivatives with respect to q are taken in the tangent space, NV columns: a joint
//! column is ∂/∂q_j; a free-flyer's six columns are the derivatives along the perturbation
//! `q ⊕ δ` of Pinocchio's `integrate`, `p ← p + R δ_v` and `R ← R Exp(δ_ω)` (δ in the base
//! frame), taken through the quaternion: `∂quat/∂δ_ω,a = ½ quat ⊗ (e_a, 0)`.
//!
//! Forward dynamics is differentiated through inverse dynamics: τ(q, q̇, FD(q, q̇, τ)) = τ
//! gives ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ) (Carpentier & Mansard, "Analytical
//! derivatives of rigid body dynamics algorithms", RSS 2018, §III.C), the product with M⁻¹
//! taken through the LᵀDL factor of M when the factor has structural zeros (a branching tree,
//! or an arm whose geometry zeroes entries of M; they make the solve cheaper than the dense
//! M⁻¹: G1's forward-dynamics derivatives drop from 228k to 174k multiplications) and as a
//! product with M⁻¹ otherwise. ∂τ/∂x at q̈ = FD is the derivative of the recursion with q̈
//! constant: the recursion is differentiated with its accelerations the symbols q̈, and only
//! then are the nodes of FD substituted for them ([`ExprGraph::substitute`]). Building the
//! recursion on the nodes of FD first and holding them constant would not do: the graph's
//! simplifying constructors look through a node as they build on it (a constant times a
//! scaled u, `c₁·(c₂·u)`, becomes one product; a negation moves out of a product), so a
//! path of τ to u could bypass the held node and its derivative would be lost — which is
//! what happened on robots with a decoupled joint of constant inertia (a wheel, a gripper
//! finger) or a free rigid body.

use crate::expr::{Differentiator, ExprGraph, Id, Symbol};
use crate::model::StateLayout;
use crate::motion::quaternion_rotation;

use super::ldlt::LtdlFactor;

/// Rows of expressions.
type Matrix = Vec<Vec<Id>>;

/// How the partial derivatives of a kernel's outputs are built in the graph.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Sweep {
    /// One forward sweep per symbol ([`Differentiator`]): the derivative of the recursion
    /// propagated from the joint a symbol belongs to outwards, every output sharing it.
    Forward,
    /// One reverse sweep per output ([`ExprGraph::gradient`]): the adjoint of one torque
    /// propagated back through the recursion, every symbol sharing it.
    Reverse,
}

impl Sweep {
    /// The sweep to keep given the [`OpCount::cost`](crate::OpCount::cost) of the
    /// derivatives each builds: the reverse sweep when it is cheaper, the forward sweep on a
    /// tie.
    pub fn cheaper(forward_cost: usize, reverse_cost: usize) -> Sweep {
        if reverse_cost < forward_cost {
            Sweep::Reverse
        } else {
            Sweep::Forward
        }
    }
}

/// `(∂outputs/∂q, ∂outputs/∂q̇)`, each `outputs.len()` × NV, row i the derivatives of
/// `outputs[i]`; ∂/∂q in the tangent space (module docs), built by `sweep`.
pub fn state_jacobians(
    g: &mut ExprGraph,
    outputs: &[Id],
    layout: StateLayout,
    sweep: Sweep,
) -> (Matrix, Matrix) {
    let symbols = state_symbols(layout);
    // partials[s][i] = ∂outputs[i]/∂symbols[s].
    let partials: Vec<Vec<Id>> = match sweep {
        Sweep::Forward => forward_partials(g, outputs, &symbols, layout, &mut || None)
            .expect("a sweep without a bound is never given up"),
        Sweep::Reverse => {
            let rows: Vec<Vec<Id>> = outputs.iter().map(|&o| g.gradient(o, &symbols)).collect();
            transpose(&rows, symbols.len())
        }
    };
    jacobians_from_partials(g, &partials, layout, outputs.len())
}

/// [`state_jacobians`] by forward sweeps, given up (`None`) as soon as the derivatives built
/// so far that are final already cost more than `bound` says, when it says (the caller's
/// cost of the reverse sweeps, once known): the whole would cost more too, since a cost
/// only grows with the outputs it counts ([`ExprGraph::op_count`]), so the reverse sweeps
/// are the cheaper. The graph grows exactly as [`state_jacobians`] grows it, so a result,
/// when there is one, is the same.
pub fn forward_state_jacobians_within(
    g: &mut ExprGraph,
    outputs: &[Id],
    layout: StateLayout,
    bound: &mut dyn FnMut() -> Option<usize>,
) -> Option<(Matrix, Matrix)> {
    let symbols = state_symbols(layout);
    let partials = forward_partials(g, outputs, &symbols, layout, bound)?;
    Some(jacobians_from_partials(g, &partials, layout, outputs.len()))
}

/// q's symbols, then q̇'s.
fn state_symbols(layout: StateLayout) -> Vec<Symbol> {
    (0..layout.nq())
        .map(|c| Symbol::Position(c as u16))
        .chain((0..layout.nv()).map(|k| Symbol::Velocity(k as u16)))
        .collect()
}

/// `(∂outputs/∂q, ∂outputs/∂q̇)` from the partials with respect to `state_symbols`.
fn jacobians_from_partials(
    g: &mut ExprGraph,
    partials: &[Vec<Id>],
    layout: StateLayout,
    n: usize,
) -> (Matrix, Matrix) {
    let (positions, velocities) = partials.split_at(layout.nq());
    let dq = tangent_jacobian(g, positions, layout, n);
    (dq, transpose(velocities, n))
}

/// How many times a bounded forward sweep compares its cost so far with the bound: at each
/// quarter of the symbols (each comparison counts the operations built so far).
const BOUND_CHECKS: usize = 4;

/// One forward sweep per symbol, `partials[s][i]` = ∂outputs[i]/∂symbols[s]; `None` once the
/// final partials built so far cost more than `bound()` ([`forward_state_jacobians_within`]).
/// Final are the partials that are columns of the Jacobians as they are: the velocities' and
/// the joint positions' (the tangent directions of a free-flyer's seven configuration
/// symbols are combinations built after the sweeps).
fn forward_partials(
    g: &mut ExprGraph,
    outputs: &[Id],
    symbols: &[Symbol],
    layout: StateLayout,
    bound: &mut dyn FnMut() -> Option<usize>,
) -> Option<Vec<Vec<Id>>> {
    let every = symbols.len().div_ceil(BOUND_CHECKS).max(1);
    let mut partials: Vec<Vec<Id>> = Vec::with_capacity(symbols.len());
    for (k, &s) in symbols.iter().enumerate() {
        let mut d = Differentiator::new(s);
        partials.push(outputs.iter().map(|&o| d.derivative(g, o)).collect());
        let checkpoint = (k + 1) % every == 0 && k + 1 < symbols.len();
        if let Some(limit) = bound().filter(|_| checkpoint) {
            let final_so_far = partials[layout.q_offset().min(partials.len())..].concat();
            if g.op_count(&final_so_far).cost() > limit {
                return None;
            }
        }
    }
    Some(partials)
}

/// The tangent-space Jacobian from the partials with respect to the configuration symbols
/// (`partials[c][i]` = ∂output_i/∂q_c): row i, column k the derivative of output i along
/// tangent direction k (NV columns), Σ_c w_kc ∂output_i/∂q_c ([`tangent_directions`]).
fn tangent_jacobian(
    g: &mut ExprGraph,
    partials: &[Vec<Id>],
    layout: StateLayout,
    n: usize,
) -> Vec<Vec<Id>> {
    let columns: Vec<Vec<Id>> = tangent_directions(g, layout)
        .iter()
        .map(|weights| combine(g, partials, weights, n))
        .collect();
    transpose(&columns, n)
}

/// Each tangent direction k of the configuration (NV of them) as the weights (c, w_kc) of
/// the configuration symbols q_c it moves: dq_c = w_kc along direction k. A joint's direction
/// moves its own q by one; a free-flyer's six are the perturbation `q ⊕ δ` of Pinocchio's
/// `integrate` (module docs): `p ← p + R δ_v`, `R ← R Exp(δ_ω)`, through the quaternion.
pub fn tangent_directions(g: &mut ExprGraph, layout: StateLayout) -> Vec<Vec<(usize, Id)>> {
    let mut directions: Vec<Vec<(usize, Id)>> = Vec::with_capacity(layout.nv());
    if layout.floating {
        let position = |k: usize| Symbol::Position(k as u16);
        let quaternion: [Id; 4] = std::array::from_fn(|c| g.symbol(position(3 + c)));
        let rotation = quaternion_rotation(g, quaternion);
        // Linear: ∂/∂δ_v,a = Σ_c ∂/∂p_c R_ca.
        for a in 0..3 {
            directions.push((0..3).map(|c| (c, rotation[c][a])).collect());
        }
        // Angular: ∂quat/∂δ_a = ½ (w e_a + v × e_a, −v_a) with quat = (v, w).
        let [x, y, z, w] = quaternion;
        let half = g.constant(0.5);
        let (hx, hy, hz, hw) = (
            g.mul(half, x),
            g.mul(half, y),
            g.mul(half, z),
            g.mul(half, w),
        );
        let (nhx, nhy, nhz) = (g.neg(hx), g.neg(hy), g.neg(hz));
        // v × e_x = (0, z, −y), v × e_y = (−z, 0, x), v × e_z = (y, −x, 0).
        directions.push(vec![(3, hw), (4, hz), (5, nhy), (6, nhx)]);
        directions.push(vec![(3, nhz), (4, hw), (5, hx), (6, nhy)]);
        directions.push(vec![(3, hy), (4, nhx), (5, hw), (6, nhz)]);
    }
    let one = g.one();
    for j in 0..layout.ndof {
        directions.push(vec![(layout.q_offset() + j, one)]);
    }
    directions
}

/// `Σ_c weight_c · partials[c]`, entry by entry.
fn combine(g: &mut ExprGraph, partials: &[Vec<Id>], weights: &[(usize, Id)], n: usize) -> Vec<Id> {
    (0..n)
        .map(|i| {
            let terms: Vec<Id> = weights
                .iter()
                .map(|&(c, w)| g.mul(w, partials[c][i]))
                .collect();
            g.sum(terms)
        })
        .collect()
}

/// The Jacobian of `outputs` with respect to the symbols of `differentiators` (one per
/// column): row i, column k. Differentiators kept from one call to the next differentiate
/// what earlier outputs shared with these only once.
pub fn symbol_jacobian(
    g: &mut ExprGraph,
    outputs: &[Id],
    differentiators: &mut [Differentiator],
) -> Vec<Vec<Id>> {
    let columns: Vec<Vec<Id>> = differentiators
        .iter_mut()
        .map(|d| outputs.iter().map(|&o| d.derivative(g, o)).collect())
        .collect();
    transpose(&columns, outputs.len())
}

fn transpose(columns: &[Vec<Id>], rows: usize) -> Vec<Vec<Id>> {
    (0..rows)
        .map(|i| columns.iter().map(|column| column[i]).collect())
        .collect()
}

/// M⁻¹ from the LᵀDL factor of M, column by column (M x = e_j), symmetric: one `Id` per pair.
pub fn inverse(g: &mut ExprGraph, factor: &LtdlFactor) -> Vec<Vec<Id>> {
    let n = factor.len();
    let (zero, one) = (g.zero(), g.one());
    let mut inverse = vec![vec![zero; n]; n];
    for j in 0..n {
        let mut unit = vec![zero; n];
        unit[j] = one;
        let column = factor.solve(g, &unit);
        for i in j..n {
            inverse[i][j] = column[i];
            inverse[j][i] = column[i];
        }
    }
    inverse
}

/// `−M⁻¹ b` solved through the factor of M column by column, skipping the structural zeros of
/// L that a product with the dense M⁻¹ ([`negated_product`]) cannot.
fn negated_solve(g: &mut ExprGraph, factor: &LtdlFactor, b: &[Vec<Id>]) -> Vec<Vec<Id>> {
    let columns: Vec<Vec<Id>> = (0..b.first().map_or(0, Vec::len))
        .map(|k| {
            let column: Vec<Id> = b.iter().map(|row| g.neg(row[k])).collect();
            factor.solve(g, &column)
        })
        .collect();
    transpose(&columns, b.len())
}

/// `−M⁻¹ b`: solved through the factor of M when it has structural zeros (`negated_solve`),
/// else as the product with `inverse` (`negated_product`).
pub fn negated_inverse_times(
    g: &mut ExprGraph,
    factor: &LtdlFactor,
    inverse: &[Vec<Id>],
    b: &[Vec<Id>],
) -> Vec<Vec<Id>> {
    if factor.is_sparse(g) {
        negated_solve(g, factor, b)
    } else {
        negated_product(g, inverse, b)
    }
}

/// `−a b` for square matrices.
fn negated_product(g: &mut ExprGraph, a: &[Vec<Id>], b: &[Vec<Id>]) -> Vec<Vec<Id>> {
    let n = a.len();
    (0..n)
        .map(|i| {
            (0..b.first().map_or(0, Vec::len))
                .map(|j| {
                    let terms: Vec<Id> = (0..n).map(|k| g.mul(a[i][k], b[k][j])).collect();
                    let sum = g.sum(terms);
                    g.neg(sum)
                })
                .collect()
        })
        .collect()
}

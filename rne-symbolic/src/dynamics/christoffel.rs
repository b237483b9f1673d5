//! The time derivative of the mass matrix and the Christoffel symbols of the first kind, both
//! from ∂M/∂q.

use crate::expr::{Differentiator, ExprGraph, Id, Symbol};

/// ∂M/∂x_k for every velocity coordinate k, `dm[k][i][j]`, where x_k is the position symbol
/// whose rate is v_k (`positions[k]`), or nothing for the free-flyer's coordinates: M does not
/// depend on the base pose, and its base velocities are not the rates of any coordinate.
fn mass_matrix_gradient(
    g: &mut ExprGraph,
    m: &[Vec<Id>],
    positions: &[Option<Symbol>],
) -> Vec<Vec<Vec<Id>>> {
    let n = m.len();
    (0..n)
        .map(|k| {
            let Some(position) = positions[k] else {
                return vec![vec![g.zero(); n]; n];
            };
            let mut d = Differentiator::new(position);
            let mut dm = vec![vec![g.zero(); n]; n];
            for i in 0..n {
                for j in i..n {
                    let entry = d.derivative(g, m[i][j]);
                    dm[i][j] = entry;
                    dm[j][i] = entry;
                }
            }
            dm
        })
        .collect()
}

/// C(q, q̇) with C_ij = Σ_k Γ_ijk q̇_k and the Christoffel symbols of the first kind
/// Γ_ijk = ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i), on a model whose every velocity is the
/// rate of a coordinate (a fixed base).
///
/// This is the factorisation for which Ṁ − 2C is skew-symmetric (Ṁ = C + Cᵀ) with symmetric
/// symbols, which the Lyapunov argument of the thesis's section 6.4 ((6.60)–(6.61)) relies on;
/// the thesis's own C (4.46) gives the same C q̇ but not that property. It takes O(n³)
/// symbols: the generated kernel computes the same matrix by the recursion of `coriolis.rs`,
/// and this definition is the tests' oracle for it.
pub fn coriolis_matrix(
    g: &mut ExprGraph,
    m: &[Vec<Id>],
    qd: &[Id],
    positions: &[Option<Symbol>],
) -> Vec<Vec<Id>> {
    assert!(
        positions.iter().all(Option::is_some),
        "Christoffel symbols need a coordinate for every velocity"
    );
    let n = m.len();
    let dm = mass_matrix_gradient(g, m, positions);
    let half = g.constant(0.5);
    let mut c = vec![vec![g.zero(); n]; n];
    for i in 0..n {
        for j in 0..n {
            let mut terms = Vec::with_capacity(n);
            for k in 0..n {
                let sum = g.add(dm[k][i][j], dm[j][i][k]);
                let gamma2 = g.sub(sum, dm[i][j][k]);
                let gamma = g.mul(half, gamma2);
                terms.push(g.mul(gamma, qd[k]));
            }
            c[i][j] = g.sum(terms);
        }
    }
    c
}

/// Ṁ = Σ_k ∂M/∂x_k v_k (`positions` as for [`coriolis_matrix`]).
pub fn time_derivative(
    g: &mut ExprGraph,
    m: &[Vec<Id>],
    qd: &[Id],
    positions: &[Option<Symbol>],
) -> Vec<Vec<Id>> {
    let n = m.len();
    let dm = mass_matrix_gradient(g, m, positions);
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let terms: Vec<Id> = (0..n).map(|k| g.mul(dm[k][i][j], qd[k])).collect();
                    g.sum(terms)
                })
                .collect()
        })
        .collect()
}

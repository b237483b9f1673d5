//! The Christoffel form of the Coriolis matrix.

use crate::expr::{Differentiator, ExprGraph, Id, Node, Symbol};

/// ∂M/∂q_k for every k: `dm[k][i][j]`.
fn mass_matrix_gradient(g: &mut ExprGraph, m: &[Vec<Id>]) -> Vec<Vec<Vec<Id>>> {
    let n = m.len();
    (0..n)
        .map(|k| {
            let mut d = Differentiator::new(Symbol::Position(k as u16));
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
/// Γ_ijk = ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i).
///
/// This is the factorisation for which Ṁ − 2C is skew-symmetric (Ṁ = C + Cᵀ), which the
/// Lyapunov argument of the thesis's section 6.4 ((6.60)–(6.61)) relies on; the thesis's own
/// C (4.46) gives the same C q̇ but not that property.
pub fn coriolis_matrix(g: &mut ExprGraph, m: &[Vec<Id>], qd: &[Id]) -> Vec<Vec<Id>> {
    let n = m.len();
    let dm = mass_matrix_gradient(g, m);
    let half = g.constant(0.5);
    let mut c = vec![vec![g.zero(); n]; n];
    for i in 0..n {
        for j in 0..n {
            let mut terms = Vec::with_capacity(n);
            for k in 0..n {
                let sum = g.add(dm[k][i][j], dm[j][i][k]);
                let gamma2 = g.sub(sum, dm[i][j][k]);
                if matches!(g.node(gamma2), Node::Const(_)) && g.is_zero(gamma2) {
                    continue;
                }
                let gamma = g.mul(half, gamma2);
                terms.push(g.mul(gamma, qd[k]));
            }
            c[i][j] = g.sum(terms);
        }
    }
    c
}

/// Ṁ = Σ_k ∂M/∂q_k q̇_k.
pub fn time_derivative(g: &mut ExprGraph, m: &[Vec<Id>], qd: &[Id]) -> Vec<Vec<Id>> {
    let n = m.len();
    let dm = mass_matrix_gradient(g, m);
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

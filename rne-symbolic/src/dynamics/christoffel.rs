//! The Christoffel form of the Coriolis matrix.

use crate::expr::{Differentiator, ExprGraph, Id, Node, Symbol};

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
/// Γ_ijk = ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i).
///
/// This is the factorisation for which Ṁ − 2C is skew-symmetric (Ṁ = C + Cᵀ), which the
/// Lyapunov argument of the thesis's section 6.4 ((6.60)–(6.61)) relies on; the thesis's own
/// C (4.46) gives the same C q̇ but not that property.
///
/// On a floating base the base velocities are body-frame quasi-velocities, not rates of
/// coordinates: their equation is Euler–Poincaré's, `ṗ + V ×* p = F` with p the first six
/// rows of `M v`, so the base rows gain `V ×* p = K(p) V` with
/// `K(p) = [[0, −[f]×], [−[f]×, −[n]×]]` for `p = [f; n]`. K(p) is skew-symmetric, so
/// Ṁ − 2C stays skew (see `floating_tests.rs`).
pub fn coriolis_matrix(
    g: &mut ExprGraph,
    m: &[Vec<Id>],
    qd: &[Id],
    positions: &[Option<Symbol>],
) -> Vec<Vec<Id>> {
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
                if matches!(g.node(gamma2), Node::Const(_)) && g.is_zero(gamma2) {
                    continue;
                }
                let gamma = g.mul(half, gamma2);
                terms.push(g.mul(gamma, qd[k]));
            }
            c[i][j] = g.sum(terms);
        }
    }
    if positions.first().is_some_and(|p| p.is_none()) {
        add_base_momentum_transport(g, m, qd, &mut c);
    }
    c
}

/// Adds `K(p)` of [`coriolis_matrix`] to the free-flyer's 6×6 block of `c`.
fn add_base_momentum_transport(g: &mut ExprGraph, m: &[Vec<Id>], v: &[Id], c: &mut [Vec<Id>]) {
    let momentum: Vec<Id> = (0..6)
        .map(|i| {
            let terms: Vec<Id> = (0..v.len()).map(|j| g.mul(m[i][j], v[j])).collect();
            g.sum(terms)
        })
        .collect();
    let (f, n) = (
        [momentum[0], momentum[1], momentum[2]],
        [momentum[3], momentum[4], momentum[5]],
    );
    // −[a]×, row-major: [[0, a3, −a2], [−a3, 0, a1], [a2, −a1, 0]].
    let minus_skew = |g: &mut ExprGraph, a: [Id; 3]| -> [[Id; 3]; 3] {
        let z = g.zero();
        let na = a.map(|x| g.neg(x));
        [[z, a[2], na[1]], [na[2], z, a[0]], [a[1], na[0], z]]
    };
    let (kf, kn) = (minus_skew(g, f), minus_skew(g, n));
    for i in 0..3 {
        for j in 0..3 {
            c[i][3 + j] = g.add(c[i][3 + j], kf[i][j]);
            c[3 + i][j] = g.add(c[3 + i][j], kf[i][j]);
            c[3 + i][3 + j] = g.add(c[3 + i][3 + j], kn[i][j]);
        }
    }
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

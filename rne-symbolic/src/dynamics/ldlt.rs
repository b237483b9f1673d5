//! Symbolic LᵀDL factorisation of the mass matrix and the solve it gives.

use crate::expr::{ExprGraph, Id};

/// M = Lᵀ D L with L unit lower-triangular, factorised from the last row upwards
/// (Featherstone, Rigid Body Dynamics Algorithms, §6.5, "LTDL"). For a kinematic tree whose
/// joints are numbered parents first, this order creates no fill-in: an entry of M that is
/// structurally zero (two joints on different branches) stays a constant zero, so the
/// factorisation and the solve do no work for it.
#[derive(Clone, Debug)]
pub struct LtdlFactor {
    /// Strictly lower part: `l[i][j]` for j < i.
    l: Vec<Vec<Id>>,
    /// 1 / D_i.
    inverse_pivot: Vec<Id>,
}

impl LtdlFactor {
    /// Factorises the symmetric matrix `m` (row-major).
    pub fn new(g: &mut ExprGraph, m: &[Vec<Id>]) -> LtdlFactor {
        let n = m.len();
        let mut h: Vec<Vec<Id>> = m.to_vec();
        let mut inverse_pivot = vec![g.zero(); n];
        let one = g.one();
        for k in (0..n).rev() {
            inverse_pivot[k] = g.div(one, h[k][k]);
            // Down the row towards the first column: the update of row i reads h[k][j] for
            // j ≤ i, which must not have been scaled into L yet.
            for i in (0..k).rev() {
                if g.is_zero(h[k][i]) {
                    continue;
                }
                let a = g.mul(h[k][i], inverse_pivot[k]);
                for j in 0..=i {
                    let update = g.mul(a, h[k][j]);
                    h[i][j] = g.sub(h[i][j], update);
                }
                h[k][i] = a;
            }
        }
        let l = (0..n).map(|i| (0..i).map(|j| h[i][j]).collect()).collect();
        LtdlFactor { l, inverse_pivot }
    }

    /// The size of M.
    pub fn len(&self) -> usize {
        self.inverse_pivot.len()
    }

    /// Whether L has a structural zero (the tree branches, or the geometry zeroes an entry of
    /// M), so that solving through the factor skips work that a product with the dense M⁻¹
    /// does.
    pub fn is_sparse(&self, g: &ExprGraph) -> bool {
        self.l.iter().flatten().any(|&l| g.is_zero(l))
    }

    /// Solves M x = b: Lᵀ y = b (bottom-up), z = D⁻¹ y, L x = z (top-down).
    pub fn solve(&self, g: &mut ExprGraph, b: &[Id]) -> Vec<Id> {
        let n = b.len();
        let mut x = b.to_vec();
        for i in (0..n).rev() {
            for j in 0..i {
                let update = g.mul(self.l[i][j], x[i]);
                x[j] = g.sub(x[j], update);
            }
        }
        for i in 0..n {
            x[i] = g.mul(x[i], self.inverse_pivot[i]);
        }
        for i in 0..n {
            for j in 0..i {
                let update = g.mul(self.l[i][j], x[j]);
                x[i] = g.sub(x[i], update);
            }
        }
        x
    }
}

//! 3-vectors and 3×3 matrices of expressions, and the operations the recursion needs.

use super::graph::ExprGraph;
use super::node::Id;

/// A 3-vector of expressions.
pub type Vec3 = [Id; 3];
/// A 3×3 matrix of expressions, row-major.
pub type Mat3 = [[Id; 3]; 3];

impl ExprGraph {
    /// A vector of constants.
    pub fn const_vec(&mut self, v: [f64; 3]) -> Vec3 {
        v.map(|x| self.constant(x))
    }

    /// The zero vector.
    pub fn zero_vec(&mut self) -> Vec3 {
        self.const_vec([0.0; 3])
    }

    /// The identity matrix.
    pub fn identity(&mut self) -> Mat3 {
        let (z, o) = (self.zero(), self.one());
        [[o, z, z], [z, o, z], [z, z, o]]
    }

    /// `a + b`.
    pub fn vadd(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        [0, 1, 2].map(|i| self.add(a[i], b[i]))
    }

    /// `a − b`.
    pub fn vsub(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        [0, 1, 2].map(|i| self.sub(a[i], b[i]))
    }

    /// `−a`.
    pub fn vneg(&mut self, a: Vec3) -> Vec3 {
        a.map(|x| self.neg(x))
    }

    /// `s a`.
    pub fn vscale(&mut self, s: Id, a: Vec3) -> Vec3 {
        a.map(|x| self.mul(s, x))
    }

    /// `a · b`.
    pub fn dot(&mut self, a: Vec3, b: Vec3) -> Id {
        let terms = [0, 1, 2].map(|i| self.mul(a[i], b[i]));
        self.sum(terms)
    }

    /// `a × b`.
    pub fn cross(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        [(1, 2), (2, 0), (0, 1)].map(|(i, j)| {
            let p = self.mul(a[i], b[j]);
            let q = self.mul(a[j], b[i]);
            self.sub(p, q)
        })
    }

    /// `m v`.
    pub fn mat_vec(&mut self, m: &Mat3, v: Vec3) -> Vec3 {
        [0, 1, 2].map(|i| self.dot(m[i], v))
    }

    /// `mᵀ v`.
    pub fn mat_t_vec(&mut self, m: &Mat3, v: Vec3) -> Vec3 {
        let t = transpose(m);
        self.mat_vec(&t, v)
    }

    /// `a b`.
    pub fn mat_mul(&mut self, a: &Mat3, b: &Mat3) -> Mat3 {
        let bt = transpose(b);
        [0, 1, 2].map(|i| [0, 1, 2].map(|j| self.dot(a[i], bt[j])))
    }

    /// The similarity transform `r m rᵀ`.
    pub fn similarity(&mut self, r: &Mat3, m: &Mat3) -> Mat3 {
        let rm = self.mat_mul(r, m);
        let rt = transpose(r);
        self.mat_mul(&rm, &rt)
    }
}

/// `mᵀ`.
pub fn transpose(m: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[j][i]))
}

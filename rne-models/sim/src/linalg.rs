//! Small fixed-size linear algebra for the step loop: Cholesky factorisation and solve of the
//! symmetric positive definite mass matrix, matrix–vector products. Everything lives on the
//! stack; nothing allocates.

/// The lower-triangular Cholesky factor L of a symmetric positive definite matrix, M = L Lᵀ.
///
/// Only the lower triangle of `m` is read. Returns `None` when a pivot is not strictly positive
/// (or is NaN): the matrix is not positive definite to working precision.
pub fn cholesky<const N: usize>(m: &[[f64; N]; N]) -> Option<[[f64; N]; N]> {
    let mut l = [[0.0; N]; N];
    for j in 0..N {
        let d = m[j][j] - l[j][..j].iter().map(|x| x * x).sum::<f64>();
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        let ljj = d.sqrt();
        l[j][j] = ljj;
        for i in j + 1..N {
            let s: f64 = l[i][..j].iter().zip(&l[j][..j]).map(|(a, b)| a * b).sum();
            l[i][j] = (m[i][j] - s) / ljj;
        }
    }
    Some(l)
}

/// Solves L Lᵀ x = b by forward and back substitution, given the factor from [`cholesky`].
pub fn cholesky_solve<const N: usize>(l: &[[f64; N]; N], b: &[f64; N]) -> [f64; N] {
    let mut y = *b;
    for i in 0..N {
        for k in 0..i {
            y[i] -= l[i][k] * y[k];
        }
        y[i] /= l[i][i];
    }
    for i in (0..N).rev() {
        for k in i + 1..N {
            y[i] -= l[k][i] * y[k];
        }
        y[i] /= l[i][i];
    }
    y
}

/// Solves M x = b for a symmetric positive definite M; `None` if M is not positive definite.
pub fn solve_spd<const N: usize>(m: &[[f64; N]; N], b: &[f64; N]) -> Option<[f64; N]> {
    cholesky(m).map(|l| cholesky_solve(&l, b))
}

/// The product A x.
pub(crate) fn mat_vec<const N: usize>(a: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|i| dot(&a[i], x))
}

/// The product Aᵀ x.
pub(crate) fn mat_t_vec<const N: usize>(a: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|j| (0..N).map(|i| a[i][j] * x[i]).sum())
}

/// The inner product xᵀ y.
pub(crate) fn dot<const N: usize>(x: &[f64; N], y: &[f64; N]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The solve inverts an SPD matrix to rounding error, and LLᵀ reproduces M.
    #[test]
    fn cholesky_solves_spd_system() {
        let m = [[4.0, 1.0, 0.5], [1.0, 3.0, -0.2], [0.5, -0.2, 2.0]];
        let x = [1.0, -2.0, 0.25];
        let b = mat_vec(&m, &x);
        let got = solve_spd(&m, &b).unwrap();
        for i in 0..3 {
            assert!((got[i] - x[i]).abs() < 1e-15, "{got:?}");
        }
        let l = cholesky(&m).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let llt: f64 = (0..3).map(|k| l[i][k] * l[j][k]).sum();
                assert!((llt - m[i][j]).abs() < 1e-15);
            }
        }
        assert_eq!(mat_t_vec(&m, &x), mat_vec(&m, &x));
    }

    /// Indefinite, singular and NaN matrices are reported, not silently factored.
    #[test]
    fn cholesky_rejects_non_positive_definite() {
        assert!(cholesky(&[[1.0, 2.0], [2.0, 1.0]]).is_none());
        assert!(cholesky(&[[1.0, 1.0], [1.0, 1.0]]).is_none());
        assert!(cholesky(&[[f64::NAN, 0.0], [0.0, 1.0]]).is_none());
        assert!(cholesky(&[[-1.0]]).is_none());
    }
}

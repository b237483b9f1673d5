//! Dense Cholesky factorisation and solves in place on row-major slices, without allocation:
//! forward dynamics of coupled models (`M q̈ = τ − bias`) and `M⁻¹`.

use std::cmp::Ordering;

use nalgebra::RealField;

/// Factorises the symmetric positive-definite `n × n` matrix `a` (row-major) in place into its
/// Cholesky factor `L` (lower triangle; the upper triangle is left as it was). Returns `false`
/// if a pivot is not positive (M singular or not positive definite); `a` is then unusable.
pub(crate) fn factorize<T: RealField + Copy>(a: &mut [T], n: usize) -> bool {
    for j in 0..n {
        let mut pivot = a[j * n + j];
        for k in 0..j {
            pivot -= a[j * n + k] * a[j * n + k];
        }
        if pivot.partial_cmp(&T::zero()) != Some(Ordering::Greater) {
            return false;
        }
        let diagonal = pivot.sqrt();
        a[j * n + j] = diagonal;
        for i in j + 1..n {
            let mut entry = a[i * n + j];
            for k in 0..j {
                entry -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = entry / diagonal;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place, with `l` the output of [`factorize`].
pub(crate) fn solve<T: RealField + Copy>(l: &[T], n: usize, b: &mut [T]) {
    for i in 0..n {
        let mut x = b[i];
        for k in 0..i {
            x -= l[i * n + k] * b[k];
        }
        b[i] = x / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut x = b[i];
        for k in i + 1..n {
            x -= l[k * n + i] * b[k];
        }
        b[i] = x / l[i * n + i];
    }
}

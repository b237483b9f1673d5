//! Conversions between the kernels' arrays and nalgebra's statically sized vectors and
//! matrices (feature `nalgebra`). Kernel matrices are row-major `[[T; C]; R]`.

use nalgebra::{SMatrix, SVector, Scalar};

/// `[T; N]` as a column vector.
pub fn to_vector<T: Scalar + Copy, const N: usize>(a: &[T; N]) -> SVector<T, N> {
    SVector::from_fn(|i, _| a[i])
}

/// A column vector as `[T; N]`.
pub fn from_vector<T: Scalar + Copy, const N: usize>(v: &SVector<T, N>) -> [T; N] {
    core::array::from_fn(|i| v[i])
}

/// A row-major `[[T; C]; R]` as an R × C matrix.
pub fn to_matrix<T: Scalar + Copy, const R: usize, const C: usize>(
    a: &[[T; C]; R],
) -> SMatrix<T, R, C> {
    SMatrix::from_fn(|i, j| a[i][j])
}

/// An R × C matrix as a row-major `[[T; C]; R]`.
pub fn from_matrix<T: Scalar + Copy, const R: usize, const C: usize>(
    m: &SMatrix<T, R, C>,
) -> [[T; C]; R] {
    core::array::from_fn(|i| core::array::from_fn(|j| m[(i, j)]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrices_keep_rows_as_rows_and_round_trip() {
        let a = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]];
        let m = to_matrix(&a);
        assert_eq!(m[(0, 2)], 3.0);
        assert_eq!(m[(1, 0)], 4.0);
        assert_eq!(from_matrix(&m), a);
    }

    #[test]
    fn vectors_round_trip() {
        let a = [1.0f32, -2.0, 0.5];
        let v = to_vector(&a);
        assert_eq!(v[1], -2.0);
        assert_eq!(from_vector(&v), a);
    }
}

//! Helpers shared by the identification tests.

use nalgebra::DMatrix;

/// The numeric rank of `w` by SVD, columns scaled to unit norm (zero columns dropped) so that
/// the units of the parameters do not matter; the gap between the last kept singular value
/// and the first dropped one must be wide, or the rank would not be well defined.
pub fn numeric_rank(w: &DMatrix<f64>) -> usize {
    let columns: Vec<usize> = (0..w.ncols())
        .filter(|&c| w.column(c).norm() > 1e-12 * w.amax())
        .collect();
    let mut scaled = w.select_columns(&columns);
    for mut column in scaled.column_iter_mut() {
        let norm = column.norm();
        column /= norm;
    }
    let mut s: Vec<f64> = scaled.singular_values().iter().copied().collect();
    s.sort_by(|a, b| b.total_cmp(a));
    let rank = s.iter().filter(|&&x| x > 1e-8 * s[0]).count();
    if let (Some(&kept), Some(&dropped)) = (s.get(rank - 1), s.get(rank)) {
        assert!(
            kept > 1e-6 * s[0] && dropped < 1e-11 * s[0],
            "no clear rank gap: {kept:e} / {dropped:e} of {:e}",
            s[0]
        );
    }
    rank
}

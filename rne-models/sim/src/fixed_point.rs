//! When the fixed-point iterations of the implicit integrators (Gauss–Legendre, the Lie-group
//! variational one) stop.

/// Whether iteration `k` (from 1), whose largest scaled change is `change` after `previous`
/// at the iteration before, has converged: the change vanishes; or it stopped decreasing
/// while below `tolerance` (the round-off floor); or the contraction θ = change / previous
/// predicts a remaining error θ / (1 − θ) · change below the rounding unit (Hairer, Nørsett &
/// Wanner, *Solving ODEs II*, §IV.8, the stopping criterion of simplified Newton iterations).
pub(crate) fn converged(k: u32, change: f64, previous: f64, tolerance: f64) -> bool {
    let theta = change / previous;
    let floor = k > 1 && theta >= 1.0 && change <= tolerance;
    let negligible = k > 1 && theta < 1.0 && theta / (1.0 - theta) * change <= f64::EPSILON;
    change == 0.0 || floor || negligible
}

#[cfg(test)]
mod tests {
    use super::converged;

    #[test]
    fn stops_on_zero_change_on_the_floor_and_on_negligible_contraction() {
        assert!(converged(1, 0.0, f64::INFINITY, 1e-12));
        // Not decreasing any more, below the tolerance: the round-off floor.
        assert!(converged(3, 1e-14, 1e-14, 1e-12));
        // Not decreasing, above the tolerance: not converged (diverging).
        assert!(!converged(3, 1e-3, 1e-4, 1e-12));
        // Contracting by 1/10 with a change of 1e-16: the remaining error is below rounding.
        assert!(converged(2, 1e-16, 1e-15, 1e-12));
        // Contracting by 1/10 with a change of 1e-6: keep going.
        assert!(!converged(2, 1e-6, 1e-5, 1e-12));
        // The first iteration has no contraction to judge by.
        assert!(!converged(1, 1e-16, f64::INFINITY, 1e-12));
    }
}

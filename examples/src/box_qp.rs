//! The box-constrained quadratic programme of control-limited DDP: each step of the backward
//! pass minimises the local model of the cost over the controls that respect the limits,
//!
//!   min_δ ½ δᵀ H δ + gᵀ δ   subject to   lower ≤ δ ≤ upper,
//!
//! by the projected Newton method of Tassa, Mansard & Todorov, "Control-limited differential
//! dynamic programming", ICRA 2014, Algorithm 1 (after Bertsekas 1982): Newton steps on the
//! free variables, the clamped ones (at a bound, the gradient pushing outwards) held fixed,
//! with a projected Armijo line search.

use nalgebra::{Cholesky, Const, SMatrix, SVector};

/// Newton iterations at most; the active set of N variables settles in a few.
const MAX_ITERATIONS: usize = 100;
/// Stop when the gradient on the free variables is below this norm.
const GRADIENT_TOLERANCE: f64 = 1e-10;
/// Stop when an iteration improves the objective by less than this, relative.
const IMPROVEMENT_TOLERANCE: f64 = 1e-12;
/// Armijo's sufficient decrease: accept a step that achieves this fraction of the linear
/// prediction.
const ARMIJO: f64 = 0.1;
/// Step shrink factor of the line search.
const BACKTRACK: f64 = 0.6;
/// The line search gives up below this step.
const MIN_STEP: f64 = 1e-22;

/// The minimiser of a box-constrained QP and the factor DDP's feedback gains need.
#[derive(Clone, Debug)]
pub struct BoxQpSolution<const N: usize> {
    /// The minimiser δ.
    pub x: SVector<f64, N>,
    /// Which variables are free (not clamped at a bound) at δ.
    pub free: [bool; N],
    /// Cholesky factor of H restricted to the free variables (identity on the clamped ones).
    factor: Cholesky<f64, Const<N>>,
}

impl<const N: usize> BoxQpSolution<N> {
    /// The feedback gain K = −H_ff⁻¹ Q_ux on the free rows, zero on the clamped ones (Tassa,
    /// Mansard & Todorov 2014, section III-C): a clamped control does not respond to the state.
    pub fn feedback<const NX: usize>(&self, qux: &SMatrix<f64, N, NX>) -> SMatrix<f64, N, NX> {
        let mut rhs = *qux;
        for (i, &free) in self.free.iter().enumerate() {
            if !free {
                rhs.row_mut(i).fill(0.0);
            }
        }
        -self.factor.solve(&rhs)
    }
}

/// H is not positive definite on the free variables: DDP's regularisation must grow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotPositiveDefinite;

/// Minimises ½ δᵀ H δ + gᵀ δ over lower ≤ δ ≤ upper from the start `x0` (projected into the
/// box); `lower ≤ upper` elementwise.
pub fn solve_box_qp<const N: usize>(
    h: &SMatrix<f64, N, N>,
    g: &SVector<f64, N>,
    lower: &SVector<f64, N>,
    upper: &SVector<f64, N>,
    x0: &SVector<f64, N>,
) -> Result<BoxQpSolution<N>, NotPositiveDefinite> {
    let objective = |x: &SVector<f64, N>| 0.5 * x.dot(&(h * x)) + g.dot(x);
    let project = |x: SVector<f64, N>| x.zip_zip_map(lower, upper, |v, lo, hi| v.max(lo).min(hi));
    let mut x = project(*x0);
    let mut value = objective(&x);
    for _ in 0..MAX_ITERATIONS {
        let gradient = g + h * x;
        let free = free_set(&x, &gradient, lower, upper);
        if !free.contains(&true) {
            break;
        }
        let factor = factor_free(h, &free)?;
        let free_gradient = mask(&gradient, &free);
        if free_gradient.norm() < GRADIENT_TOLERANCE {
            break;
        }
        let direction = -factor.solve(&free_gradient);
        let slope = direction.dot(&gradient);
        let mut step = 1.0;
        let (candidate, candidate_value) = loop {
            let candidate = project(x + direction * step);
            let candidate_value = objective(&candidate);
            if (candidate_value - value) / (step * slope) >= ARMIJO {
                break (candidate, candidate_value);
            }
            step *= BACKTRACK;
            if step < MIN_STEP {
                return finish(h, g, x, lower, upper);
            }
        };
        let improvement = value - candidate_value;
        x = candidate;
        value = candidate_value;
        if improvement < IMPROVEMENT_TOLERANCE * value.abs().max(1.0) {
            break;
        }
    }
    finish(h, g, x, lower, upper)
}

/// The solution at `x`: its free set and the factor of H on it.
fn finish<const N: usize>(
    h: &SMatrix<f64, N, N>,
    g: &SVector<f64, N>,
    x: SVector<f64, N>,
    lower: &SVector<f64, N>,
    upper: &SVector<f64, N>,
) -> Result<BoxQpSolution<N>, NotPositiveDefinite> {
    let free = free_set(&x, &(g + h * x), lower, upper);
    let factor = factor_free(h, &free)?;
    Ok(BoxQpSolution { x, free, factor })
}

/// The variables not clamped: a variable is clamped when it sits at a bound and the gradient
/// points out of the box there.
fn free_set<const N: usize>(
    x: &SVector<f64, N>,
    gradient: &SVector<f64, N>,
    lower: &SVector<f64, N>,
    upper: &SVector<f64, N>,
) -> [bool; N] {
    core::array::from_fn(|i| {
        let at_lower = x[i] <= lower[i] && gradient[i] > 0.0;
        let at_upper = x[i] >= upper[i] && gradient[i] < 0.0;
        !(at_lower || at_upper)
    })
}

/// Cholesky factor of H with the clamped rows and columns replaced by those of the identity:
/// solving with it is solving with H_ff on the free variables and leaves the clamped ones at
/// their (zeroed) right-hand side.
fn factor_free<const N: usize>(
    h: &SMatrix<f64, N, N>,
    free: &[bool; N],
) -> Result<Cholesky<f64, Const<N>>, NotPositiveDefinite> {
    let restricted = SMatrix::<f64, N, N>::from_fn(|i, j| match (free[i], free[j]) {
        (true, true) => h[(i, j)],
        _ if i == j => 1.0,
        _ => 0.0,
    });
    Cholesky::new(restricted).ok_or(NotPositiveDefinite)
}

/// `v` with the entries of clamped variables set to zero.
fn mask<const N: usize>(v: &SVector<f64, N>, free: &[bool; N]) -> SVector<f64, N> {
    SVector::from_fn(|i, _| if free[i] { v[i] } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Vector2};

    fn bounds(b: f64) -> (Vector2<f64>, Vector2<f64>) {
        (Vector2::repeat(-b), Vector2::repeat(b))
    }

    #[test]
    fn an_interior_minimum_is_the_newton_step() {
        let h = Matrix2::new(4.0, 1.0, 1.0, 3.0);
        let g = Vector2::new(1.0, -2.0);
        let (lo, hi) = bounds(10.0);
        let solution = solve_box_qp(&h, &g, &lo, &hi, &Vector2::zeros()).unwrap();
        let unconstrained = -h.try_inverse().unwrap() * g;
        assert!((solution.x - unconstrained).norm() < 1e-12);
        assert_eq!(solution.free, [true, true]);
        let qux = Matrix2::new(1.0, 2.0, 3.0, 4.0);
        let k = solution.feedback(&qux);
        assert!(
            (k + h.try_inverse().unwrap() * qux).norm() < 1e-12,
            "K = −H⁻¹ Q_ux"
        );
    }

    /// Property: the solution satisfies the KKT conditions of the box QP — free variables have
    /// zero gradient, variables at the lower bound a non-negative one, at the upper bound a
    /// non-positive one — and clamped variables get zero feedback rows.
    #[test]
    fn a_clamped_solution_satisfies_the_kkt_conditions() {
        let h = Matrix2::new(2.0, 1.5, 1.5, 2.0);
        let g = Vector2::new(-30.0, -1.0);
        let (lo, hi) = bounds(1.0);
        let solution = solve_box_qp(&h, &g, &lo, &hi, &Vector2::new(0.3, 0.9)).unwrap();
        let gradient = g + h * solution.x;
        for i in 0..2 {
            let x = solution.x[i];
            assert!((lo[i]..=hi[i]).contains(&x));
            if solution.free[i] {
                assert!(gradient[i].abs() < 1e-9, "free gradient {}", gradient[i]);
            } else if x == lo[i] {
                assert!(gradient[i] >= 0.0);
            } else {
                assert_eq!(x, hi[i]);
                assert!(gradient[i] <= 0.0);
            }
        }
        assert_eq!(
            solution.free,
            [false, true],
            "δ₁ clamped at its upper bound"
        );
        let k = solution.feedback(&Matrix2::new(1.0, 2.0, 3.0, 4.0));
        assert_eq!(k.row(0).iter().copied().collect::<Vec<_>>(), [0.0, 0.0]);
        assert!((k[(1, 0)] + 3.0 / 2.0).abs() < 1e-12);
    }

    #[test]
    fn an_indefinite_hessian_is_reported() {
        let h = Matrix2::new(1.0, 0.0, 0.0, -1.0);
        let (lo, hi) = bounds(1.0);
        let result = solve_box_qp(&h, &Vector2::new(0.0, 0.1), &lo, &hi, &Vector2::zeros());
        assert_eq!(result.err(), Some(NotPositiveDefinite));
    }
}

//! Measurements of runs for the report, beyond [`Record::summary`]: the settling time of a
//! whole PD run, convergence to an equilibrium, the separation of two releases, link flips,
//! the turning points of a swing and the growth of the Lyapunov function.

use rne_sim::Record;

/// The settling time of a set-point run: the largest of the joints' 2 % settling times
/// ([`Record::settling_time`]: the earliest recorded time after which |qᵢ − q_ref,i| stays
/// within 2 % of joint i's step |q_ref,i − qᵢ(0)|), i.e. the time from which every joint stays in
/// its band. `None` if some joint is outside its band at the last sample, or does not move
/// (a zero step has a zero band).
pub fn settling_time<const N: usize>(record: &Record<N>, q_ref: &[f64; N]) -> Option<f64> {
    record
        .settling_time(q_ref)
        .into_iter()
        .try_fold(0.0_f64, |worst, t| t.map(|t| worst.max(t)))
}

/// The earliest recorded time from which every later sample has maxᵢ |qᵢ − targetᵢ| ≤ `tol`,
/// or `None` if the last sample is farther away.
pub fn time_within<const N: usize>(record: &Record<N>, target: &[f64; N], tol: f64) -> Option<f64> {
    let inside = |q: &[f64; N]| (0..N).all(|i| (q[i] - target[i]).abs() <= tol);
    let outside_after = record.q.iter().rposition(|q| !inside(q));
    match outside_after {
        None => record.t.first().copied(),
        Some(k) => record.t.get(k + 1).copied(),
    }
}

/// The separation maxᵢ |qᵢᵃ(t) − qᵢᵇ(t)| of two runs sampled at the same times.
pub fn separation<const N: usize>(a: &Record<N>, b: &Record<N>) -> Vec<f64> {
    a.q.iter()
        .zip(&b.q)
        .map(|(x, y)| (0..N).map(|i| (x[i] - y[i]).abs()).fold(0.0, f64::max))
        .collect()
}

/// The first recorded time at which joint `joint` has turned more than half a revolution from
/// its start, |qᵢ(t) − qᵢ(0)| > π: the link flips over.
pub fn first_flip<const N: usize>(record: &Record<N>, joint: usize) -> Option<f64> {
    let q0 = record.q.first()?[joint];
    let k = record
        .q
        .iter()
        .position(|q| (q[joint] - q0).abs() > std::f64::consts::PI)?;
    record.t.get(k).copied()
}

/// The turning points (local maxima when `maxima`, else minima) of joint `joint`, each refined
/// by the vertex of the parabola through the extreme sample and its two neighbours; sampling
/// alone would miss the true extreme by about ½ |q̈| (Δt/2)².
pub fn turning_points<const N: usize>(record: &Record<N>, joint: usize, maxima: bool) -> Vec<f64> {
    let sign = if maxima { 1.0 } else { -1.0 };
    let y: Vec<f64> = record.q.iter().map(|q| sign * q[joint]).collect();
    y.windows(3)
        .filter(|w| w[1] >= w[0] && w[1] > w[2])
        .map(|w| {
            let curvature = w[0] - 2.0 * w[1] + w[2];
            let vertex = if curvature < 0.0 {
                w[1] - (w[0] - w[2]).powi(2) / (8.0 * curvature)
            } else {
                w[1]
            };
            sign * vertex
        })
        .collect()
}

/// The largest increase V(tₖ₊₁) − V(tₖ) of the Lyapunov function (6.57) between consecutive
/// samples (negative if V strictly decreases), or `None` without a PD term.
pub fn largest_lyapunov_increase<const N: usize>(record: &Record<N>) -> Option<f64> {
    let v = record.lyapunov.as_ref()?;
    v.windows(2).map(|w| w[1] - w[0]).reduce(f64::max)
}

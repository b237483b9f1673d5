//! Panels of the thesis's figures built from run records: joint angles, torques, energies,
//! energy error and the Lyapunov function.

use rne_figures::time_series::{Curve, Panel};
use rne_sim::Record;

/// The joint angles qᵢ(t), with dashed set-points when `q_ref` is given (figures 6.2–6.21).
pub fn joint_angles<const N: usize>(record: &Record<N>, q_ref: Option<&[f64; N]>) -> Panel {
    joint_angles_until(record, q_ref, f64::INFINITY)
}

/// [`joint_angles`] for the samples with t ≤ `t_end` (figure 6.6: the first 20 seconds).
pub fn joint_angles_until<const N: usize>(
    record: &Record<N>,
    q_ref: Option<&[f64; N]>,
    t_end: f64,
) -> Panel {
    let n = record.t.partition_point(|&t| t <= t_end);
    let t = &record.t[..n];
    let mut curves: Vec<Curve> = (0..N)
        .map(|i| Curve::new(format!("q{}", i + 1), t, record.q[..n].iter().map(|q| q[i])))
        .collect();
    if let Some(q_ref) = q_ref {
        curves.extend((0..N).map(|i| Curve::reference(format!("q{} ref", i + 1), t, q_ref[i])));
    }
    Panel::new("q (rad)", curves)
}

/// The input torques uᵢ(t), with dashed motor limits ±u_max,i when given.
pub fn torques<const N: usize>(record: &Record<N>, u_max: Option<&[f64; N]>) -> Panel {
    let t = &record.t;
    let mut curves: Vec<Curve> = (0..N)
        .map(|i| Curve::new(format!("u{}", i + 1), t, record.u.iter().map(|u| u[i])))
        .collect();
    if let Some(u_max) = u_max {
        let mut limits: Vec<f64> = u_max.iter().flat_map(|&u| [u, -u]).collect();
        limits.sort_by(f64::total_cmp);
        limits.dedup();
        curves.extend(
            limits
                .into_iter()
                .map(|u| Curve::reference(format!("{u:+} limit"), t, u)),
        );
    }
    Panel::new("u (N·m)", curves)
}

/// Kinetic, potential and total energy (figures 6.8, 6.10, 6.17).
pub fn energies<const N: usize>(record: &Record<N>) -> Panel {
    let t = &record.t;
    Panel::new(
        "energy (J)",
        vec![
            Curve::new("kinetic", t, record.kinetic.iter().copied()),
            Curve::new("potential", t, record.potential.iter().copied()),
            Curve::new("total", t, record.total.iter().copied()),
        ],
    )
}

/// The energy error E(t) − E(0) of one or more runs of the same conservative system, each
/// labelled with its integrator.
pub fn energy_error<const N: usize>(runs: &[(&str, &Record<N>)]) -> Panel {
    let curves = runs
        .iter()
        .map(|(label, r)| {
            let e0 = r.total.first().copied().unwrap_or(0.0);
            Curve::new(*label, &r.t, r.total.iter().map(|e| e - e0))
        })
        .collect();
    Panel::new("E(t) − E(0) (J)", curves)
}

/// The Lyapunov function V = ½ q̇ᵀ M q̇ + ½ q̃ᵀ Kp q̃ (6.57) of PD runs, on a log scale.
pub fn lyapunov<const N: usize>(runs: &[(String, &Record<N>)]) -> Panel {
    let curves = runs
        .iter()
        .filter_map(|(label, r)| {
            let v = r.lyapunov.as_ref()?;
            Some(Curve::new(label.as_str(), &r.t, v.iter().copied()))
        })
        .collect();
    Panel::log("V (J)", curves)
}

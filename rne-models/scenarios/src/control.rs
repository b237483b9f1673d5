//! The PD-control scenarios (thesis sections 6.2.5, 6.3.4 and 6.4): set-point runs of the
//! planar elbow and the IRB 140, and the Lyapunov function along them.

use super::error::ScenarioError;
use super::experiments::{elbow_pd, irb140_pd};
use super::figures::{joint_angles, lyapunov, torques};
use super::measures::{largest_lyapunov_increase, settling_time};
use super::outcome::{Finding, Outcome, Table};
use super::parameters::*;
use rne_figures::time_series::Figure;
use rne_sim::{output_times, Record};

use super::catalogue::{per_joint, run_with, seconds, vector, RunOptions};
/// What distinguishes the PD runs of the two robots in the report.
struct PdSetup<'a, const N: usize> {
    name: &'a str,
    figure: &'a str,
    robot: &'a str,
    simulation: usize,
    q_ref: [f64; N],
    u_max: [f64; N],
    thesis_time: &'a str,
}

/// The report figures of a set-point run: settling time, overshoot, steady-state error, peak
/// torque against the limits, and the growth of V (6.57); `thesis_time` is what the thesis
/// reports for the settling time.
pub(super) fn pd_findings<const N: usize>(
    r: &Record<N>,
    q_ref: &[f64; N],
    u_max: &[f64; N],
    thesis_time: &str,
) -> Vec<Finding> {
    let s = r.summary(q_ref);
    let t_end = r.t.last().copied().unwrap_or(0.0);
    let limits: Vec<String> = s
        .max_abs_torque
        .iter()
        .zip(u_max)
        .map(|(u, max)| {
            if max.is_finite() {
                format!("{u:.1}/{max}")
            } else {
                format!("{u:.1}/no limit")
            }
        })
        .collect();
    let marginal = if thesis_time == "—" {
        "—"
    } else {
        "marginal"
    };
    let none = if thesis_time == "—" { "—" } else { "none" };
    vec![
        Finding::new(
            "settling time: all joints within 2 % of their step from then on",
            format!(
                "{} ({})",
                seconds(settling_time(r, q_ref), "not settled"),
                per_joint(&s.settling_time, |t| seconds(t, "not settled"))
            ),
            thesis_time,
        ),
        Finding::new(
            "overshoot, % of the step",
            per_joint(&s.overshoot, |o| format!("{:.2} %", 100.0 * o)),
            marginal,
        ),
        Finding::new(
            format!("steady-state error |q − q_ref| at {t_end} s"),
            per_joint(&s.steady_state_error, |e| format!("{e:.1e} rad")),
            none,
        ),
        Finding::new(
            "peak |u| / saturation limit",
            format!("{} N·m", limits.join(", ")),
            if thesis_time == "—" {
                "—"
            } else {
                "saturation at the motor limits"
            },
        ),
        Finding::new(
            "largest increase of V (6.57) between samples",
            format!("{:.1e} J", largest_lyapunov_increase(r).unwrap_or(f64::NAN)),
            if thesis_time == "—" {
                "—"
            } else {
                "V̇ = −q̇ᵀ Kd q̇ ≤ 0 (6.62)"
            },
        ),
    ]
}

/// The outcome of one PD run of the thesis: joint angles and torques, and the report figures.
fn pd_outcome<const N: usize>(setup: &PdSetup<'_, N>, r: &Record<N>) -> Outcome {
    let mut findings = vec![Finding::new(
        "set-point q_ref (chosen by rne), from q = q̇ = 0",
        format!("{} rad", vector(&setup.q_ref)),
        "not stated",
    )];
    findings.extend(pd_findings(
        r,
        &setup.q_ref,
        &setup.u_max,
        setup.thesis_time,
    ));
    let title = format!(
        "Figure {} — {} PD control, simulation {}: q_ref = {}",
        setup.figure,
        setup.robot,
        setup.simulation,
        vector(&setup.q_ref)
    );
    Outcome {
        scenario: setup.name.to_owned(),
        tables: vec![Table::of(format!("{}.csv", setup.name), r)],
        figures: vec![Figure {
            file: format!("fig{}-{}", setup.figure, setup.name),
            title,
            panels: vec![
                joint_angles(r, Some(&setup.q_ref)),
                torques(r, Some(&setup.u_max)),
            ],
        }],
        findings,
    }
}

/// Figures 6.12–6.15: planar-elbow PD run `k`.
pub(crate) fn elbow_pd_scenario(
    name: &str,
    k: usize,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let q_ref = ELBOW_SET_POINTS[k];
    let times = output_times(0.0, ELBOW_PD_END, SAMPLE);
    let solver = thesis_solver();
    let r = run_with(options, name, &solver, |i| elbow_pd(q_ref, i, &times))?;
    let figure = format!("6.{}", 12 + k);
    let setup = PdSetup {
        name,
        figure: &figure,
        robot: "planar elbow",
        simulation: k + 1,
        q_ref,
        u_max: ELBOW_U_MAX,
        thesis_time: "steady state in 3–4 s",
    };
    Ok(pd_outcome(&setup, &r))
}

/// Figures 6.19–6.21: IRB 140 PD run `k`.
pub(crate) fn irb140_pd_scenario(
    name: &str,
    k: usize,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let q_ref = IRB140_SET_POINTS[k];
    let times = output_times(0.0, IRB140_PD_END, SAMPLE);
    let solver = thesis_solver();
    let r = run_with(options, name, &solver, |i| irb140_pd(q_ref, i, &times))?;
    let figure = format!("6.{}", 19 + k);
    let setup = PdSetup {
        name,
        figure: &figure,
        robot: "IRB 140",
        simulation: k + 1,
        q_ref,
        u_max: IRB140_U_MAX,
        thesis_time: "converges in about 5 s",
    };
    Ok(pd_outcome(&setup, &r))
}

/// Section 6.4: the Lyapunov function along every PD run.
pub(crate) fn lyapunov_scenario(
    name: &str,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let solver = thesis_solver();
    let elbow_times = output_times(0.0, ELBOW_PD_END, SAMPLE);
    let mut elbow = Vec::new();
    for (k, q_ref) in ELBOW_SET_POINTS.into_iter().enumerate() {
        let label = format!("elbow {}", k + 1);
        let r = run_with(options, &label, &solver, |i| {
            elbow_pd(q_ref, i, &elbow_times)
        })?;
        elbow.push((label, r));
    }
    let irb_times = output_times(0.0, IRB140_PD_END, SAMPLE);
    let mut irb = Vec::new();
    for (k, q_ref) in IRB140_SET_POINTS.into_iter().enumerate() {
        let label = format!("IRB 140 {}", k + 1);
        let r = run_with(options, &label, &solver, |i| {
            irb140_pd(q_ref, i, &irb_times)
        })?;
        irb.push((label, r));
    }
    let mut findings: Vec<Finding> = elbow.iter().map(|(l, r)| lyapunov_finding(l, r)).collect();
    findings.extend(irb.iter().map(|(l, r)| lyapunov_finding(l, r)));
    let elbow_refs: Vec<(String, &Record<2>)> = elbow.iter().map(|(l, r)| (l.clone(), r)).collect();
    let irb_refs: Vec<(String, &Record<3>)> = irb.iter().map(|(l, r)| (l.clone(), r)).collect();
    let mut tables: Vec<Table> = elbow
        .iter()
        .enumerate()
        .map(|(k, (_, r))| Table::of(format!("{name}-elbow-pd-{}.csv", k + 1), r))
        .collect();
    tables.extend(
        irb.iter()
            .enumerate()
            .map(|(k, (_, r))| Table::of(format!("{name}-irb140-pd-{}.csv", k + 1), r)),
    );
    Ok(Outcome {
        scenario: name.to_owned(),
        tables,
        figures: vec![Figure {
            file: format!("sec6.4-{name}"),
            title: "Section 6.4 — V = T + 1/2 e'Kp e (e = q − q_ref) along the PD runs".into(),
            panels: vec![lyapunov(&elbow_refs), lyapunov(&irb_refs)],
        }],
        findings,
    })
}

/// How V (6.57) evolved along one PD run.
fn lyapunov_finding<const N: usize>(label: &str, r: &Record<N>) -> Finding {
    let v = r.lyapunov.as_deref().unwrap_or(&[]);
    let ratio = v.last().zip(v.first()).map_or(f64::NAN, |(l, f)| l / f);
    Finding::new(
        format!("{label}: largest increase of V between samples; V(end)/V(0)"),
        format!(
            "{:.1e} J; {ratio:.1e}",
            largest_lyapunov_increase(r).unwrap_or(f64::NAN)
        ),
        "V̇ = −q̇ᵀ Kd q̇ ≤ 0 (6.62)",
    )
}

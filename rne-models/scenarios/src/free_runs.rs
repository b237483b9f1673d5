//! The scenarios without feedback (thesis sections 6.2.2–6.2.4 and 6.3.3): the open-loop
//! torque, the released and damped double pendulum, and the IRB 140 joint-3 pendulum.

use std::f64::consts::PI;

use super::error::ScenarioError;
use super::experiments::{damped, irb140_pendulum, open_loop, released, upright_torque};
use super::figures::{energies, energy_error, joint_angles, joint_angles_until, torques};
use super::measures::{first_flip, separation, time_within, turning_points};
use super::outcome::{Finding, Outcome, Table};
use super::parameters::*;
use rne_figures::time_series::{Curve, Figure, Panel};
use rne_sim::{output_times, GaussLegendre, Record, Rk4};

use super::catalogue::{run_with, seconds, vector, RunOptions};
/// Figures 6.2 and 6.3: the open-loop torque τ = g(π, 0) from (q₁₀, 0).
pub(crate) fn open_loop_scenario(
    name: &str,
    figure: &str,
    q1_0: f64,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let (t_end, simulation) = if figure == "6.2" {
        (OPEN_LOOP_FROM_ZERO_END, 1)
    } else {
        (OPEN_LOOP_NEAR_UPRIGHT_END, 2)
    };
    let times = output_times(0.0, t_end, SAMPLE);
    let solver = thesis_solver();
    let r = run_with(options, name, &solver, |i| open_loop(q1_0, i, &times))?;
    let desired = [PI, 0.0];
    let tau = upright_torque();
    let distance = |q: &[f64; 2]| (q[0] - PI).abs().max(q[1].abs());
    let closest = r.q.iter().map(distance).fold(f64::INFINITY, f64::min);
    let peak_kinetic = r.kinetic.iter().copied().fold(0.0, f64::max);
    let mut findings = vec![Finding::new(
        "open-loop torque τ = g(π, 0) (6.27)–(6.28)",
        format!("{} N·m", vector(&tau)),
        "τ₁ = −(m₂ l₁ + l_c2 m₂ + m₁ l_c1) g = −88.29, τ₂ = −l_c2 m₂ g = −22.07",
    )];
    if simulation == 1 {
        findings.push(Finding::new(
            format!("closest approach max |q − (π, 0)| over {t_end} s"),
            format!("{closest:.3} rad"),
            "unstable almost instantly",
        ));
    } else {
        let left = r.q.iter().position(|q| distance(q) > 0.1).map(|k| r.t[k]);
        findings.push(Finding::new(
            "first time max |q − (π, 0)| > 0.1 rad",
            seconds(left, "never"),
            "stays near the desired position for a short time, then collapses",
        ));
    }
    findings.push(Finding::new(
        format!("peak kinetic energy over {t_end} s"),
        format!("{peak_kinetic:.0} J (the constant torque keeps doing work)"),
        "—",
    ));
    let title = format!(
        "Figure {figure} — Open-loop response, simulation {simulation}: τ = g(π, 0) from q = {}",
        vector(&r.q[0])
    );
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![Table::of(format!("{name}.csv"), &r)],
        figures: vec![Figure {
            file: format!("fig{figure}-{name}"),
            title,
            panels: vec![joint_angles(&r, Some(&desired)), torques(&r, None)],
        }],
        findings,
    })
}

/// Figures 6.4–6.7: the releases from q = 0 and from q₁ = 1e-6 and their divergence.
pub(crate) fn double_pendulum(name: &str, options: &RunOptions) -> Result<Outcome, ScenarioError> {
    let times = output_times(0.0, RELEASE_END, SAMPLE);
    let solver = thesis_solver();
    let a = run_with(options, "release from q = 0", &solver, |i| {
        released([0.0, 0.0], i, &times)
    })?;
    let b = run_with(options, "release from q1 = 1e-6", &solver, |i| {
        released([PERTURBED_Q1, 0.0], i, &times)
    })?;
    let findings = release_findings(&a, &b);
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![
            Table::of(format!("{name}-from-zero.csv"), &a),
            Table::of(format!("{name}-from-1e-6.csv"), &b),
        ],
        figures: release_figures(name, &a, &b),
        findings,
    })
}

/// The findings of figures 6.4–6.7: how soon the releases `a` (from q = 0) and `b` (from
/// q₁ = 1e-6) part, when each link first flips over, and their energy drift.
fn release_findings(a: &Record<2>, b: &Record<2>) -> Vec<Finding> {
    let gap = separation(a, b);
    let early = gap
        .iter()
        .zip(&a.t)
        .take_while(|(_, &t)| t <= 2.0)
        .map(|(g, _)| *g)
        .fold(0.0, f64::max);
    let apart = gap.iter().position(|&g| g > 1.0).map(|k| a.t[k]);
    let flips = |r: &Record<2>| {
        format!(
            "link 1: {}, link 2: {}",
            seconds(first_flip(r, 0), "none"),
            seconds(first_flip(r, 1), "none")
        )
    };
    vec![
        Finding::new(
            "largest separation max |qᵃ − qᵇ| over the first 2 s",
            format!("{early:.1e} rad"),
            "—",
        ),
        Finding::new(
            "first time the runs are 1 rad apart",
            seconds(apart, "never"),
            "“widely different results” (figures 6.4, 6.5)",
        ),
        Finding::new("first flip (|qᵢ − qᵢ(0)| > π), from q = 0", flips(a), "—"),
        Finding::new("first flip, from q₁ = 1e-6", flips(b), "—"),
        Finding::new(
            "energy drift max |E − E(0)|, ode45 setting (rtol 1e-10), 70 s",
            format!("{:.1e} J, {:.1e} J", a.energy_drift(), b.energy_drift()),
            "“stays constantly zero” (figure 6.8)",
        ),
    ]
}

/// Figures 6.4–6.7 of the releases `a` (from q = 0) and `b` (from q₁ = 1e-6): each run, the
/// first 20 s of `a`, and their divergence.
fn release_figures(name: &str, a: &Record<2>, b: &Record<2>) -> Vec<Figure> {
    let t = &a.t;
    let divergence = Figure {
        file: format!("fig6.4-6.5-{name}-divergence"),
        title: "Figures 6.4–6.5 — Divergence of the releases from q = 0 and q1 = 1e-6".into(),
        panels: vec![
            Panel::new(
                "q1 (rad)",
                vec![
                    Curve::new("q1, from q = 0", t, a.q.iter().map(|q| q[0])),
                    Curve::new("q1, from q1 = 1e-6", t, b.q.iter().map(|q| q[0])),
                ],
            ),
            Panel::log(
                "|qa − qb| (rad)",
                (0..2)
                    .map(|i| {
                        let d = a.q.iter().zip(&b.q).map(move |(x, y)| (x[i] - y[i]).abs());
                        Curve::new(format!("|Δq{}|", i + 1), t, d)
                    })
                    .collect(),
            ),
        ],
    };
    vec![
        Figure {
            file: format!("fig6.4-{name}-from-zero"),
            title: "Figures 6.4 and 6.7 — Pendulum released from q = 0, 70 s".into(),
            panels: vec![joint_angles(a, None)],
        },
        Figure {
            file: format!("fig6.5-{name}-from-1e-6"),
            title: "Figure 6.5 — Pendulum released from q1 = 0.000001, q2 = 0, 70 s".into(),
            panels: vec![joint_angles(b, None)],
        },
        Figure {
            file: format!("fig6.6-{name}-first-20-s"),
            title: "Figure 6.6 — Joint movements the first 20 seconds (from q = 0)".into(),
            panels: vec![joint_angles_until(a, None, 20.0)],
        },
        divergence,
    ]
}

/// Figure 6.8: the energy of the release from q = 0, at tight tolerance and at the thesis's,
/// and over 1000 s with the symplectic integrator.
pub(crate) fn release_energy(name: &str, options: &RunOptions) -> Result<Outcome, ScenarioError> {
    let times = output_times(0.0, RELEASE_END, SAMPLE);
    let tight = energy_solver(RELEASE_ENERGY_RTOL);
    let r = run_with(options, "release, rtol 1e-12", &tight, |i| {
        released([0.0, 0.0], i, &times)
    })?;
    let thesis = thesis_solver();
    let ode45 = run_with(options, "release, rtol 1e-10", &thesis, |i| {
        released([0.0, 0.0], i, &times)
    })?;
    let long_times = output_times(0.0, LONG_RUN_END, 0.1);
    let gl = GaussLegendre::new(GAUSS_LEGENDRE_STEP);
    let long = run_with(options, "release, Gauss-Legendre", &gl, |i| {
        released([0.0, 0.0], i, &long_times)
    })?;
    let rk4 = run_with(
        options,
        "release, RK4",
        &Rk4::new(GAUSS_LEGENDRE_STEP),
        |i| released([0.0, 0.0], i, &long_times),
    )?;
    let findings = energy_findings(&r, &ode45, &long, &rk4);
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![
            Table::of(format!("{name}.csv"), &r),
            Table::of(format!("{name}-gauss-legendre-1000-s.csv"), &long),
        ],
        figures: vec![
            Figure {
                file: format!("fig6.8-{name}"),
                title: "Figure 6.8 — The energy in the system (released from q = 0)".into(),
                panels: vec![
                    energies(&r),
                    energy_error(&[("Dormand–Prince rtol 1e-12, at its steps", &r)]),
                    energy_error(&[("ode45's method, rtol 1e-10, dense output", &ode45)]),
                ],
            },
            Figure {
                file: format!("fig6.8b-{name}-gauss-legendre-1000-s"),
                title: format!(
                    "Figure 6.8, extended — energy error over 1000 s, Gauss–Legendre, h = {} ms",
                    GAUSS_LEGENDRE_STEP * 1e3
                ),
                panels: vec![energy_error(&[("Gauss–Legendre, 2 stages", &long)])],
            },
        ],
        findings,
    })
}

/// The findings of figure 6.8: the energy exchanged and the drift of the release at tight
/// tolerance (`r`), at the thesis's (`ode45`), and over 1000 s with the symplectic integrator
/// (`long`) and with RK4 at the same step (`rk4`).
fn energy_findings(
    r: &Record<2>,
    ode45: &Record<2>,
    long: &Record<2>,
    rk4: &Record<2>,
) -> Vec<Finding> {
    let drift_until = |r: &Record<2>, t_end: f64| {
        let n = r.t.partition_point(|&t| t <= t_end);
        r.total[..n]
            .iter()
            .map(|e| (e - r.total[0]).abs())
            .fold(0.0, f64::max)
    };
    let half = long.len() / 2;
    let worst = |e: &[f64]| {
        e.iter()
            .map(|e| (e - long.total[0]).abs())
            .fold(0.0, f64::max)
    };
    let (first, second) = (worst(&long.total[..half]), worst(&long.total[half..]));
    let exchanged = r.kinetic.iter().copied().fold(0.0, f64::max);
    vec![
        Finding::new(
            "total energy E(0)",
            format!("{:.3e} J", r.total[0]),
            "zero by definition",
        ),
        Finding::new(
            "largest kinetic energy (energy exchanged)",
            format!("{exchanged:.2} J"),
            "—",
        ),
        Finding::new(
            "energy drift over 20 s, Dormand–Prince rtol 1e-12 sampled at its steps",
            format!("{:.1e} J", drift_until(r, 20.0)),
            "“stays constantly zero for all time”",
        ),
        Finding::new(
            "energy drift over 70 s, same",
            format!("{:.1e} J", r.energy_drift()),
            "“stays constantly zero for all time”",
        ),
        Finding::new(
            "energy drift over 70 s, ode45's method at rtol 1e-10, dense output",
            format!("{:.1e} J", ode45.energy_drift()),
            "—",
        ),
        Finding::new(
            format!(
                "Gauss–Legendre (order 4, h = {} ms), largest |E − E(0)| over 0–500 s and 500–1000 s",
                GAUSS_LEGENDRE_STEP * 1e3
            ),
            format!("{first:.1e} J and {second:.1e} J: bounded, no secular growth"),
            "—",
        ),
        Finding::new(
            "RK4 at the same step (not symplectic), E(1000 s) − E(0)",
            format!("{:.1e} J: a secular drift", rk4.total[rk4.len() - 1] - rk4.total[0]),
            "—",
        ),
    ]
}

/// Figure 6.10: the damped double pendulum settles hanging down.
pub(crate) fn damped_pendulum(name: &str, options: &RunOptions) -> Result<Outcome, ScenarioError> {
    let times = output_times(0.0, DAMPED_END, SAMPLE);
    let solver = thesis_solver();
    let r = run_with(options, name, &solver, |i| damped(i, &times))?;
    let end = r.q.last().copied().unwrap_or([f64::NAN; 2]);
    let error = (end[0] - HANGING_DOWN[0]).abs().max(end[1].abs());
    let bottom = r.potential.last().copied().unwrap_or(f64::NAN);
    let findings = vec![
        Finding::new(
            "time from which max |q − (−π/2, 0)| ≤ 0.01 rad",
            seconds(time_within(&r, &HANGING_DOWN, 1e-2), "not within 40 s"),
            "converges in about 25 s",
        ),
        Finding::new(
            "time from which max |q − (−π/2, 0)| ≤ 1e-3 rad",
            seconds(time_within(&r, &HANGING_DOWN, 1e-3), "not within 40 s"),
            "—",
        ),
        Finding::new(
            format!("max |q − (−π/2, 0)| at {DAMPED_END} s"),
            format!("{error:.1e} rad"),
            "—",
        ),
        Finding::new(
            "final total energy vs potential energy at the bottom",
            format!(
                "{:.4} J vs {bottom:.4} J",
                r.total.last().copied().unwrap_or(f64::NAN)
            ),
            "total ends equal to the potential energy at the equilibrium",
        ),
    ];
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![Table::of(format!("{name}.csv"), &r)],
        figures: vec![Figure {
            file: format!("fig6.10-{name}"),
            title: "Figure 6.10 — q1, q2 and the energy of the damped double pendulum, Kd = 1.5"
                .into(),
            panels: vec![joint_angles(&r, Some(&HANGING_DOWN)), energies(&r)],
        }],
        findings,
    })
}

/// Figures 6.16 and 6.17: the IRB 140 joint-3 pendulum and its energy.
pub(crate) fn irb140_pendulum_scenario(
    name: &str,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let times = output_times(0.0, IRB140_PENDULUM_END, SAMPLE);
    let tight = energy_solver(IRB140_ENERGY_RTOL);
    let r = run_with(options, "joint-3 pendulum, rtol 1e-13", &tight, |i| {
        irb140_pendulum(i, &times)
    })?;
    let matlab = matlab_ode45();
    let ode45 = run_with(options, "joint-3 pendulum, ode45", &matlab, |i| {
        irb140_pendulum(i, &times)
    })?;
    let spread = |r: &Record<1>| {
        let highs = turning_points(r, 0, true);
        let lows = turning_points(r, 0, false);
        let dev = |p: &[f64], target: f64| p.iter().map(|q| (q - target).abs()).fold(0.0, f64::max);
        dev(&highs, 0.0).max(dev(&lows, -PI))
    };
    let swings = turning_points(&r, 0, false).len();
    let findings = vec![
        Finding::new(
            "total energy E(0) (link 3 horizontal)",
            format!("{:.4} J", r.total[0]),
            "—",
        ),
        Finding::new(
            "energy drift over 20 s, Dormand–Prince rtol 1e-13 sampled at its steps",
            format!("{:.1e} J", r.energy_drift()),
            "oscillates with an amplitude of about 2 J (figure 6.17)",
        ),
        Finding::new(
            "energy drift over 20 s, ode45 as MATLAB runs it (RelTol 1e-10, default AbsTol 1e-6), interpolated",
            format!("{:.1e} J", ode45.energy_drift()),
            "about 2 J",
        ),
        Finding::new(
            format!(
                "turning points of q₃ ({swings} swings): largest distance from 0 and −π, parabola-refined"
            ),
            format!("{:.1e} rad (ode45 setting: {:.1e} rad)", spread(&r), spread(&ode45)),
            "angle error less than 0.003 rad, varying periodically",
        ),
    ];
    let t = &r.t;
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![
            Table::of(format!("{name}.csv"), &r),
            Table::of(format!("{name}-ode45.csv"), &ode45),
        ],
        figures: vec![
            Figure {
                file: format!("fig6.16-{name}"),
                title:
                    "Figure 6.16 — Oscillations in q3 in open loop (IRB 140, q1 = q2 = 0 locked)"
                        .into(),
                panels: vec![Panel::new(
                    "q3 (rad)",
                    vec![Curve::new("q3", t, r.q.iter().map(|q| q[0]))],
                )],
            },
            Figure {
                file: format!("fig6.17-{name}-energy"),
                title: "Figure 6.17 — Energy in open loop (IRB 140 joint-3 pendulum)".into(),
                panels: vec![
                    energies(&r),
                    energy_error(&[("Dormand–Prince rtol 1e-13, at its steps", &r)]),
                    energy_error(&[("ode45: RelTol 1e-10, AbsTol 1e-6, interpolated", &ode45)]),
                ],
            },
        ],
        findings,
    })
}

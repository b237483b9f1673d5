//! Conservative runs of the thesis's chapter 6 on the generated kernels: energy conservation of
//! the released double pendulum (figure 6.8) and of the IRB 140 joint-3 pendulum (figure 6.17),
//! and the sensitivity of the double pendulum to its initial state (figures 6.4, 6.5); beyond
//! the thesis, the momentum of the floating quadruped in zero gravity.

use std::f64::consts::PI;

use rne_scenarios::experiments::irb140_pendulum;
use rne_scenarios::experiments::released;
use rne_scenarios::measures::{separation, turning_points};
use rne_scenarios::parameters::{
    energy_solver, matlab_ode45, thesis_solver, GAUSS_LEGENDRE_STEP, IRB140_ENERGY_RTOL,
    LONG_RUN_END, PERTURBED_Q1, RELEASE_ENERGY_RTOL, SAMPLE,
};
use rne_scenarios::{find, RunOptions};
use rne_sim::{output_times, GaussLegendre, Rk4};

/// Figure 6.8: the double pendulum released from q = 0 (no input, no friction) keeps its total
/// energy E = 0 to max |E(t) − E(0)| ≤ 1e-9 J over 20 s with Dormand–Prince at rtol 1e-12
/// (atol 1e-14). The samples, every 10 ms, are the integrator's own step values
/// (`step_to_outputs`): the 4th-order dense output would add a few 1e-9 J between steps.
#[test]
fn released_double_pendulum_drifts_at_most_1e_9_j_over_20_s() {
    let times = output_times(0.0, 20.0, SAMPLE);
    let r = released([0.0, 0.0], &energy_solver(RELEASE_ENERGY_RTOL), &times).unwrap();
    let drift = r.energy_drift();
    eprintln!(
        "released, DP rtol 1e-12, 20 s: drift {drift:e} J, {:?}",
        r.stats
    );
    assert_eq!(r.total[0], 0.0);
    assert!(drift <= 1e-9, "energy drift {drift:e} J");
    // A large motion: tens of joules move between potential and kinetic energy.
    assert!(r.kinetic.iter().copied().fold(0.0, f64::max) > 30.0);
}

/// Figure 6.8 over 1000 s: the symplectic 2-stage Gauss–Legendre method (h = 5 ms, 2·10⁵
/// steps) keeps the energy error of the chaotic release bounded, with no secular growth: the
/// largest |E − E(0)| over the last 500 s is at most twice that over the first 500 s, and both
/// are below 2e-3 J (the error is O(h⁴); 88 J are exchanged). RK4 at the same step, not
/// symplectic, loses energy steadily, over 0.5 J (1.3 J measured): the bound is the method's,
/// not the problem's.
#[test]
fn released_double_pendulum_energy_stays_bounded_over_1000_s_with_gauss_legendre() {
    let times = output_times(0.0, LONG_RUN_END, 0.1);
    let r = released([0.0, 0.0], &GaussLegendre::new(GAUSS_LEGENDRE_STEP), &times).unwrap();
    let half = r.len() / 2;
    let worst = |e: &[f64]| e.iter().map(|e| (e - r.total[0]).abs()).fold(0.0, f64::max);
    let (first, second) = (worst(&r.total[..half]), worst(&r.total[half..]));
    eprintln!("GL4, 1000 s: {first:e} J over 0-500 s, {second:e} J over 500-1000 s");
    assert!(
        second <= 2.0 * first,
        "secular growth: {first:e} -> {second:e}"
    );
    assert!(first.max(second) <= 2e-3, "{first:e} {second:e}");

    let rk4 = released([0.0, 0.0], &Rk4::new(GAUSS_LEGENDRE_STEP), &times).unwrap();
    let lost = rk4.total[0] - rk4.total[rk4.len() - 1];
    eprintln!("RK4, 1000 s: E(0) - E(end) = {lost:e} J");
    assert!(lost > 0.5, "RK4 drifted only {lost:e} J");
}

/// Figures 6.16–6.17: the IRB 140 with joints 1–2 locked and link 3 released from q₃ = 0
/// conserves its energy (154 J) to ≤ 1e-9 J over 20 s with Dormand–Prince at rtol 1e-13,
/// sampled at its steps — where the thesis saw a 2 J oscillation. The swing returns to its
/// turning points q₃ = 0 and −π within 1e-6 rad (parabola-refined; the thesis saw up to
/// 3e-3 rad), and even ode45 as MATLAB runs it at RelTol 1e-10 (default AbsTol 1e-6,
/// interpolated output) stays below 1e-2 J: the thesis's 2 J is not ode45's error on this model.
#[test]
fn irb140_joint3_pendulum_drifts_at_most_1e_9_j_over_20_s() {
    let times = output_times(0.0, 20.0, SAMPLE);
    let r = irb140_pendulum(&energy_solver(IRB140_ENERGY_RTOL), &times).unwrap();
    let drift = r.energy_drift();
    eprintln!(
        "IRB 140 pendulum, DP rtol 1e-13, 20 s: drift {drift:e} J, {:?}",
        r.stats
    );
    assert!(drift <= 1e-9, "energy drift {drift:e} J");
    let highs = turning_points(&r, 0, true);
    let lows = turning_points(&r, 0, false);
    assert!(
        highs.len() >= 10 && lows.len() >= 10,
        "{} {}",
        highs.len(),
        lows.len()
    );
    for q in &highs {
        assert!(q.abs() < 1e-6, "turning point {q}");
    }
    for q in &lows {
        assert!((q + PI).abs() < 1e-6, "turning point {q}");
    }
    let ode45 = irb140_pendulum(&matlab_ode45(), &times).unwrap();
    eprintln!(
        "IRB 140 pendulum, ode45 setting: drift {:e} J",
        ode45.energy_drift()
    );
    assert!(ode45.energy_drift() < 1e-2);
}

/// Figures 6.4–6.5: the double pendulum is chaotic. Released from q = 0 and from q₁ = 1e-6 at
/// the thesis's tolerance (rtol 1e-10), the two runs stay within 1e-4 rad of each other for the
/// first 2 s, then separate: more than 1 rad apart at some time within 70 s.
#[test]
fn releases_from_zero_and_from_1e_6_stay_together_then_separate() {
    let times = output_times(0.0, 70.0, SAMPLE);
    let a = released([0.0, 0.0], &thesis_solver(), &times).unwrap();
    let b = released([PERTURBED_Q1, 0.0], &thesis_solver(), &times).unwrap();
    let gap = separation(&a, &b);
    let early = gap[..=200].iter().copied().fold(0.0, f64::max);
    let apart = gap.iter().position(|&g| g > 1.0).map(|k| a.t[k]);
    eprintln!("separation over the first 2 s: {early:e} rad; 1 rad apart at {apart:?} s");
    assert!(early > 0.0 && early < 1e-4, "{early:e}");
    assert!(apart.is_some());
}

/// `quadruped-in-space`: the floating quadruped swings its legs in zero gravity for 10 s under
/// the Lie-group variational integrator. No external force acts, so the total linear and
/// angular momentum about the world origin (the CSV's last six columns, every 10 ms) stays
/// that of t = 0 to 1e-12 (about 1e-14 measured: the integrator's discrete Noether theorem),
/// while the legs' reaction alone moves and turns the trunk and the joints swing widely.
#[test]
fn floating_quadruped_in_zero_gravity_keeps_its_momentum_while_its_trunk_moves() {
    let outcome = find("quadruped-in-space")
        .unwrap()
        .run(&RunOptions::default())
        .unwrap();
    let csv = &outcome.tables[0].csv;
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,x,y,z,turn,q1,q2,q3,q4,q5,q6,q7,q8,px,py,pz,Lx,Ly,Lz"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 1001);
    let momentum = |row: &[f64]| row[13..19].to_vec();
    let h0 = momentum(&rows[0]);
    assert!(h0[0] > 1.0, "the trunk starts drifting: p = {h0:?}");
    let drift = rows
        .iter()
        .flat_map(|r| {
            momentum(r)
                .into_iter()
                .zip(&h0)
                .map(|(h, h0)| (h - h0).abs())
        })
        .fold(0.0, f64::max);
    eprintln!("quadruped in zero gravity, 10 s: momentum drift {drift:e}");
    assert!(drift < 1e-12, "momentum drift {drift:e}");
    let last = rows.last().unwrap();
    let travel = last[1..4].iter().map(|x| x * x).sum::<f64>().sqrt();
    let turn = rows.iter().map(|r| r[4]).fold(0.0, f64::max);
    let swing = rows
        .iter()
        .flat_map(|r| r[5..13].iter().map(|q| q.abs()))
        .fold(0.0, f64::max);
    assert!(
        travel > 0.5 && turn > 0.5 && swing > 0.3,
        "{travel} m {turn} rad {swing} rad"
    );
}

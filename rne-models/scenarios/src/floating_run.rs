//! A floating-base robot in zero gravity (issue 11): rne-models' quadruped, free of the ground,
//! swings its legs for 10 s, integrated by the Lie-group variational integrator
//! ([`LieVariational`]). Nothing outside the robot pushes it, so its total momentum about the
//! world origin must stay what it was at the start (the discrete Noether theorem the integrator
//! is built on, Marsden and West 2001, section 1.3), while the trunk translates and turns
//! through the legs' reaction alone — the behaviour of a satellite's manipulator or of a legged
//! robot in flight.

use super::error::ScenarioError;
use super::outcome::{Finding, Outcome, Table};
use rne_figures::time_series::{Curve, Figure, Panel};
use rne_models::generated::scenes::quadruped_space::{Model, JOINTS, NQ, NV};
use rne_sim::{
    output_times, world_momentum, LieVariational, ManifoldState, Momentum, SimError, Stats,
};

/// Length of the run (s).
const DURATION: f64 = 10.0;
/// The integrator's step (s).
const STEP: f64 = 1e-3;
/// Output spacing (s).
const SAMPLE: f64 = 0.01;
/// Where the figure draws a momentum drift of exactly zero.
const DRIFT_FLOOR: f64 = 1e-18;

/// The start: trunk at the origin, level, already drifting at 0.1 m/s along x and turning at
/// 0.3 rad/s about a tilted axis (in the trunk's frame); the legs straight and at rest.
fn initial_state() -> ManifoldState<NQ, NV> {
    let mut q = [0.0; NQ];
    q[6] = 1.0; // the unit quaternion (x, y, z, w) of no rotation
    let mut v = [0.0; NV];
    v[..6].copy_from_slice(&[0.1, 0.0, 0.0, 0.1, -0.2, 0.2]);
    ManifoldState::new(q, v)
}

/// The legs' motors: PD tracking of sinusoids of different frequencies and phases, joint by
/// joint (stiffness 20 N·m/rad, damping 1 N·m·s/rad); no force or moment on the trunk (the
/// first six entries of u are zero), so every torque acts between two bodies of the robot.
fn leg_drive(t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NV] {
    let mut u = [0.0; NV];
    for j in 0..NV - 6 {
        let k = j as f64;
        let reference = 0.6 * ((1.0 + 0.35 * k) * t + 0.8 * k).sin();
        u[6 + j] = 20.0 * (reference - q[7 + j]) - 1.0 * v[6 + j];
    }
    u
}

/// The samples of the run.
struct Samples {
    t: Vec<f64>,
    /// Trunk position (m).
    position: Vec<[f64; 3]>,
    /// Trunk rotation from the start (rad): 2 acos |w|.
    turn: Vec<f64>,
    /// Joint angles (rad).
    joints: Vec<[f64; NV - 6]>,
    /// Total momentum about the world origin, world axes.
    momentum: Vec<Momentum>,
}

/// The quadruped swinging its legs in zero gravity, with its momentum beside the motion.
/// A second of simulation takes a few milliseconds: no progress bar.
pub(crate) fn quadruped_in_space_scenario(name: &str) -> Result<Outcome, ScenarioError> {
    let x0 = initial_state();
    let times = output_times(0.0, DURATION, SAMPLE);
    let mut samples = Samples {
        t: Vec::with_capacity(times.len()),
        position: Vec::with_capacity(times.len()),
        turn: Vec::with_capacity(times.len()),
        joints: Vec::with_capacity(times.len()),
        momentum: Vec::with_capacity(times.len()),
    };
    let mut momentum_error = None;
    let stats = LieVariational::new(STEP)
        .integrate(&Model, &leg_drive, &x0, &times, |t, x| {
            match world_momentum(&Model, &x.q, &x.v) {
                Ok(h) => samples.momentum.push(h),
                Err(e) => momentum_error = Some(e),
            }
            samples.t.push(t);
            samples.position.push([x.q[0], x.q[1], x.q[2]]);
            samples.turn.push(2.0 * x.q[6].abs().min(1.0).acos());
            samples.joints.push(std::array::from_fn(|j| x.q[7 + j]));
        })
        .and_then(|stats| momentum_error.map_or(Ok(stats), Err))
        .map_err(SimError::in_run("quadruped in zero gravity"))?;
    Ok(outcome(name, &samples, &stats))
}

/// Findings, CSV and figure of a run.
fn outcome(name: &str, s: &Samples, stats: &Stats) -> Outcome {
    let h0 = s.momentum[0];
    let drift: Vec<f64> = s.momentum.iter().map(|h| h.max_difference(&h0)).collect();
    let findings = findings(s, stats, &drift);
    Outcome {
        scenario: name.to_owned(),
        tables: vec![Table {
            file: format!("{name}.csv"),
            csv: csv(s),
        }],
        figures: vec![Figure {
            file: name.to_owned(),
            title:
                "The quadruped swinging its legs in zero gravity (Lie-group variational, h = 1 ms)"
                    .into(),
            panels: panels(s, &drift),
        }],
        findings,
    }
}

/// The findings of a run: the momentum's largest drift `drift` from h(0) and h(0) itself, how
/// far the trunk travels and turns, the largest joint angle, and the integrator's work.
fn findings(s: &Samples, stats: &Stats, drift: &[f64]) -> Vec<Finding> {
    let h0 = s.momentum[0];
    let largest_drift = drift.iter().copied().fold(0.0, f64::max);
    let travel = s
        .position
        .iter()
        .map(|p| p.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let turn = s.turn.iter().copied().fold(0.0, f64::max);
    let excursion = s
        .joints
        .iter()
        .flat_map(|q| q.iter().map(|x| x.abs()))
        .fold(0.0, f64::max);
    vec![
        Finding::new(
            "max over t ≤ 10 s of |h(t) − h(0)|, every component of the linear (kg·m/s) and \
             angular (kg·m²/s) momentum about the world origin",
            format!("{largest_drift:.1e}"),
            "—",
        ),
        Finding::new(
            "momentum at t = 0: linear, angular",
            format!("{:.3?}, {:.3?}", h0.linear, h0.angular),
            "—",
        ),
        Finding::new(
            "trunk: largest distance from the start, largest rotation from the start",
            format!("{travel:.3} m, {turn:.3} rad"),
            "—",
        ),
        Finding::new("largest joint angle", format!("{excursion:.2} rad"), "—"),
        Finding::new(
            "integrator: steps, fixed-point iterations",
            format!("{}, {}", stats.steps, stats.iterations),
            "—",
        ),
    ]
}

/// The figure's panels: the trunk's position and rotation, the joint angles, and the
/// momentum's drift `drift` on a logarithmic axis.
fn panels(s: &Samples, drift: &[f64]) -> Vec<Panel> {
    let positions = ["x", "y", "z"].iter().enumerate().map(|(i, axis)| {
        Curve::new(
            format!("trunk {axis}"),
            &s.t,
            s.position.iter().map(|p| p[i]),
        )
    });
    let trunk = Panel::new(
        "trunk (m, rad)",
        positions
            .chain([Curve::new("trunk rotation", &s.t, s.turn.iter().copied())])
            .collect(),
    );
    let legs = Panel::new(
        "q (rad)",
        JOINTS
            .iter()
            .enumerate()
            .map(|(j, joint)| Curve::new(*joint, &s.t, s.joints.iter().map(|q| q[j])))
            .collect(),
    );
    // An exact zero (t = 0, and steps that round back onto h(0)) is drawn at DRIFT_FLOOR, two
    // decades below a rounding error of momenta of order one, so that the logarithmic axis
    // spans the drift's decades and not the 300 down to the smallest double.
    let conservation = Panel::log(
        "|h − h(0)|",
        vec![Curve::new(
            "max component of |h(t) − h(0)|",
            &s.t,
            drift.iter().map(|d| d.max(DRIFT_FLOOR)),
        )],
    );
    vec![trunk, legs, conservation]
}

/// `t, x, y, z, turn, q1 … q8` (the joints in the order of `JOINTS`)`, px, py, pz, Lx, Ly, Lz`
/// per sample.
fn csv(s: &Samples) -> String {
    let mut out = String::from("t,x,y,z,turn");
    for j in 1..=JOINTS.len() {
        out.push_str(&format!(",q{j}"));
    }
    out.push_str(",px,py,pz,Lx,Ly,Lz\n");
    for k in 0..s.t.len() {
        let row = [s.t[k]]
            .into_iter()
            .chain(s.position[k])
            .chain([s.turn[k]])
            .chain(s.joints[k])
            .chain(s.momentum[k].linear)
            .chain(s.momentum[k].angular);
        let cells: Vec<String> = row.map(|x| x.to_string()).collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

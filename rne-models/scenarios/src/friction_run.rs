//! The damped double pendulum with friction in the model (issue 14): the thesis's figure 6.10
//! run again with its damping u = −Kd q̇, Kd = (1.5, 1.5), (6.30), moved from the controller
//! into the joints' viscous friction of the spec (`friction: include`), and compared with the
//! controller run sample by sample. Both integrate the same equation (6.31), so they differ
//! only by rounding and by the adaptive step sizes it perturbs.

use super::catalogue::{run_with, seconds, RunOptions};
use super::error::ScenarioError;
use super::experiments::{damped, damped_by_friction};
use super::figures::{energies, joint_angles};
use super::measures::{separation, time_within};
use super::outcome::{Finding, Outcome, Table};
use super::parameters::{thesis_solver, DAMPED_END, HANGING_DOWN, SAMPLE};
use rne_figures::time_series::{Curve, Figure, Panel};
use rne_sim::output_times;

/// Figure 6.10 with the damping as joint friction, against the controller run.
pub(crate) fn damped_by_friction_scenario(
    name: &str,
    options: &RunOptions,
) -> Result<Outcome, ScenarioError> {
    let times = output_times(0.0, DAMPED_END, SAMPLE);
    let solver = thesis_solver();
    let friction = run_with(options, "viscous friction in the model", &solver, |i| {
        damped_by_friction(i, &times)
    })?;
    let controller = run_with(options, "damping controller Kd = 1.5", &solver, |i| {
        damped(i, &times)
    })?;
    let apart = separation(&friction, &controller);
    let largest = apart.iter().copied().fold(0.0, f64::max);
    let findings = vec![
        Finding::new(
            "max over t ≤ 40 s of |q_friction(t) − q_controller(t)|",
            format!("{largest:.1e} rad"),
            "the same motion: (6.31) either way",
        ),
        Finding::new(
            "time from which max |q − (−π/2, 0)| ≤ 0.01 rad (friction run)",
            seconds(
                time_within(&friction, &HANGING_DOWN, 1e-2),
                "not within 40 s",
            ),
            "converges in about 25 s",
        ),
    ];
    let difference = Panel::log(
        "|Δq| (rad)",
        vec![Curve::new(
            "max_i |q_i friction − q_i controller|",
            &friction.t,
            apart.iter().map(|d| d.max(f64::MIN_POSITIVE)),
        )],
    );
    Ok(Outcome {
        scenario: name.to_owned(),
        tables: vec![Table::of(format!("{name}.csv"), &friction)],
        figures: vec![Figure {
            file: format!("fig6.10-{name}"),
            title: "Figure 6.10 with viscous joint friction fv = 1.5 instead of the controller"
                .into(),
            panels: vec![
                joint_angles(&friction, Some(&HANGING_DOWN)),
                energies(&friction),
                difference,
            ],
        }],
        findings,
    })
}

//! Case 2: link lengths from 10⁻⁴ to 10² m.
//!
//! The four-joint [`Chain::arm`] with every length (DH a and d, centres of mass) of link k
//! multiplied by s_k and its inertia by s_k², masses kept: the whole arm at one scale, and arms
//! mixing links of very different lengths.

use rne_codegen::Kernel;

use super::{chain_model, driven_states, largest, sweep_row, sweep_table};
use crate::chain::Chain;
use crate::error::StressError;
use crate::measure::EPSILON;
use crate::probe::{Engine, Probe};
use crate::report::CaseReport;
use crate::states::generator;
use crate::sweep::{sweep, Sweep};
use crate::Settings;
use rne_figures::sci;

/// The case's name.
pub const SLUG: &str = "link-length";

/// The per-link length scales measured: the whole arm at 10⁻⁴ … 10² m, then two mixtures.
pub const SCALES: [[f64; 4]; 9] = [
    [1e-4; 4],
    [1e-3; 4],
    [1e-2; 4],
    [1e-1; 4],
    [1.0; 4],
    [1e1; 4],
    [1e2; 4],
    [1e2, 1e-2, 1.0, 1e-4],
    [1e-4, 1e2, 1e-4, 1e2],
];

/// The ratio l₁/l₄ of the length scales of the first and last link in the first mixture.
const LEVER: f64 = SCALES[7][0] / SCALES[7][3];

/// The kernels measured.
pub const KERNELS: [Kernel; 6] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::GravityTorques,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
    Kernel::KineticEnergy,
];

/// Bounds of the states: |q| ≤ π, |q̇| ≤ 2 rad/s, |q̈| ≤ 2 rad/s².
const STATE: (f64, f64, f64) = (std::f64::consts::PI, 2.0, 2.0);

/// Seed of the states.
const SEED: u64 = 0x5eed_0002;

/// The arm with link k's lengths multiplied by `scales[k]`.
pub fn robot(scales: &[f64; 4]) -> Chain {
    let arm = Chain::arm();
    Chain {
        name: "arm-link-lengths".into(),
        links: arm
            .links
            .iter()
            .zip(scales)
            .map(|(l, &s)| l.scaled_lengths(s))
            .collect(),
        ..arm
    }
}

/// The errors of [`KERNELS`] for the length scales `scales` over `samples` seeded states.
pub fn measure(engine: Engine, scales: &[f64; 4], samples: usize) -> Result<Sweep, StressError> {
    let probe = Probe::new(
        &chain_model(&robot(scales))?,
        &KERNELS,
        engine,
        &robot(scales).name,
    )?;
    let states = driven_states(&probe, &mut generator(SEED), samples, STATE);
    Ok(sweep(&probe, &KERNELS, &states))
}

/// The report section.
pub fn report(settings: Settings) -> Result<CaseReport, StressError> {
    let Settings { effort, engine } = settings;
    let samples = effort.pick(1000, 10);
    let mut table = sweep_table(
        format!("Length scale of links 1–4, {samples} states per row."),
        "scales (m/m)",
        &KERNELS,
    );
    let mut uniform = Vec::new();
    let mut mixed = Vec::new();
    for scales in &SCALES {
        let sweep = measure(engine, scales, samples)?;
        let same = scales.iter().all(|&s| s == scales[0]);
        let label = if same {
            sci(scales[0])
        } else {
            scales.map(sci).join(", ")
        };
        table.push(sweep_row(label, &sweep, &KERNELS));
        if same {
            uniform.push(sweep);
        } else {
            mixed.push(sweep);
        }
    }
    let worst = |sweeps: &[Sweep], k: Kernel| largest(sweeps.iter().map(|s| s.errors.max(k)));
    let smallest = uniform.first();
    let tip = mixed.first();
    let findings = format!(
        "**Length scale costs τ, M, g and T nothing; it costs forward dynamics through \
         gravity.** With the whole arm scaled from 1e-4 to 1e2 m the largest errors are {tau} \
         for τ, {m} for M, {g} for g and {t} for T: every term of the recursion scales by a \
         power of s, so the rounding is that of a unit arm. Forward dynamics loses digits as \
         the arm shrinks, to {fd_small} at s = 1e-4 m: the gravity torques scale as m g s and \
         the inertial ones as m s² q̈, so at ordinary accelerations τ − g is a difference \
         smaller than τ by κ ≈ g/(s q̈) (median {kappa} at 1e-4 m), and q̈ inherits the \
         absolute error ε‖g‖ of that subtraction: the error stays within {ratio:.1} × ε κ κₛ \
         in rows 1–7 and 9. A 0.1 mm arm in gravity has natural accelerations of g/s ~ 1e5 \
         rad/s²; asking it for 2 rad/s² asks for five digits of cancellation.\n\n\
         Row 8 ends the arm with a 1e-4 m link behind a 1e2 m one. Its joint's acceleration is \
         q̈₄ = (r₄ − M₄₁ q̈₁ − …)/M₄₄ with M₄₁/M₄₄ ~ l₁/l₄ = {ratio_tip}: forward dynamics \
         cancels log₁₀(l₁/l₄) digits of the lever arm, and its error reaches {fd_tip} ≈ {lever:.1} ε·l₁/l₄ \
         (cond(M) ≈ {cond_tip}, error ≈ ε √cond(M)), beyond the κ κₛ estimate. τ, M and g \
         of the same arm stay at {tau_mixed}, {m_mixed} and {g_mixed}. Row 9, where the \
         short links carry long ones, loses nothing.",
        tau = sci(worst(&uniform, Kernel::InverseDynamics)),
        m = sci(worst(&uniform, Kernel::MassMatrix)),
        g = sci(worst(&uniform, Kernel::GravityTorques)),
        t = sci(worst(&uniform, Kernel::KineticEnergy)),
        fd_small = sci(smallest.map_or(f64::NAN, |s| s.errors.max(Kernel::ForwardDynamics))),
        kappa = sci(smallest.map_or(f64::NAN, |s| s.cancellation.median)),
        ratio = largest(
                uniform
                    .iter()
                    .chain(mixed.get(1))
                    .map(|s| s.fd_over_estimate.max)
            ),
        fd_tip = sci(tip.map_or(f64::NAN, |s| s.errors.max(Kernel::ForwardDynamics))),
        lever = tip.map_or(f64::NAN, |s| s.errors.max(Kernel::ForwardDynamics) / (EPSILON * LEVER)),
        ratio_tip = sci(LEVER),
        cond_tip = sci(tip.map_or(f64::NAN, |s| s.condition.median)),
        tau_mixed = sci(worst(&mixed, Kernel::InverseDynamics)),
        m_mixed = sci(worst(&mixed, Kernel::MassMatrix)),
        g_mixed = sci(worst(&mixed, Kernel::GravityTorques)),
    );
    Ok(CaseReport {
        slug: SLUG,
        title: "2. Link lengths from 1e-4 to 1e2 m".into(),
        setup: "The arm of case 1 (equal masses) with link k's DH lengths a, d and centre of \
                mass multiplied by s_k and its inertia about the centre of mass by s_k²: the \
                whole arm at one scale (rows 1–7) and two mixtures of 1e-4 m and 1e2 m links \
                (rows 8–9). States as in case 1."
            .into(),
        tables: vec![table],
        plots: Vec::new(),
        findings,
    })
}

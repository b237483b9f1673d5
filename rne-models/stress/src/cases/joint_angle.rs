//! Case 3: joint angles up to |q| = 10⁶ rad (and 10⁸ beyond the fast argument reduction).
//!
//! The kernels take sin q and cos q with `rne_symbolic::trig::sin_cos`: Cody–Waite reduction
//! by π/2 in three parts, exact for |q| < 2²⁰·π/2 ≈ 1.6·10⁶, the standard library beyond.
//! The double-double reference reduces with π/2 to about 165 bits and is accurate to 10⁻³¹
//! for |q| ≤ 2⁵², so it measures the reduction exactly. Separately, the case measures what
//! the *input* can mean: an `f64` of size 10⁶ is only known to ulp(10⁶)/2 ≈ 5.8·10⁻¹¹ rad.

use rand_chacha::ChaCha8Rng;
use rne_codegen::Kernel;
use rne_symbolic::DoubleDouble;

use super::{builtin_model, kernel_cells, kernel_table, largest, sweep_cells, SWEEP_HEADINGS};
use crate::error::StressError;
use crate::measure::Spread;
use crate::probe::{Engine, Probe};
use crate::report::CaseReport;
use crate::states::{generator, magnitudes, uniform};
use crate::sweep::{sweep, torque_for, Sweep};
use crate::Settings;
use rne_figures::sci;
use rne_figures::{ulp, Deviation, Format};
use rne_interpreted::JointState;

/// The case's name.
pub const SLUG: &str = "joint-angle";

/// The robot: the PUMA 560, six revolute joints.
pub const ROBOT: &str = "puma560";

/// The angle magnitudes measured: |q| ≤ π, then |q| ∈ [Q/2, Q] for each larger Q.
pub const MAGNITUDES: [f64; 6] = [std::f64::consts::PI, 1e2, 1e4, 1e5, 1e6, 1e8];

/// The kernels measured.
pub const KERNELS: [Kernel; 5] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::GravityTorques,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
];

/// Seed of the states.
const SEED: u64 = 0x5eed_0003;

/// The measurements at one angle magnitude.
#[derive(Clone, Debug, PartialEq)]
pub struct AngleRow {
    /// The magnitude Q.
    pub magnitude: f64,
    /// The kernels' rounding errors.
    pub sweep: Sweep,
    /// ‖τ(q⁺) − τ(q)‖∞ / ‖τ(q)‖∞ in double-double, q⁺ = q moved one ulp away from zero in
    /// every joint: how much of τ the `f64` input angle itself leaves undetermined.
    pub input_ulp_effect: Spread,
}

/// `n` angles for magnitude `magnitude`: uniform in [−π, π] for the first, of size
/// [Q/2, Q] otherwise.
fn angles(rng: &mut ChaCha8Rng, n: usize, magnitude: f64) -> Vec<f64> {
    if magnitude <= std::f64::consts::PI {
        uniform(rng, n, magnitude)
    } else {
        magnitudes(rng, n, magnitude / 2.0, magnitude)
    }
}

/// The errors of [`KERNELS`] on the PUMA 560 at `samples` states with angles of size
/// `magnitude`, |q̇| ≤ 2, |q̈| ≤ 2, τ from inverse dynamics.
pub fn measure(engine: Engine, magnitude: f64, samples: usize) -> Result<AngleRow, StressError> {
    let probe = Probe::new(&builtin_model(ROBOT)?, &KERNELS, engine, ROBOT)?;
    let n = probe.dof();
    let mut rng = generator(SEED);
    let states: Vec<JointState> = (0..samples)
        .map(|_| {
            let mut s = JointState {
                q: angles(&mut rng, n, magnitude),
                qd: uniform(&mut rng, n, 2.0),
                qdd: uniform(&mut rng, n, 2.0),
                tau: Vec::new(),
            };
            s.tau = torque_for(&probe, &s).unwrap_or_default();
            s
        })
        .collect();
    let input_ulp_effect = Spread::of(states.iter().map(|s| {
        let moved = JointState {
            q: s.q.iter().map(|&q| q + q.signum() * ulp(q)).collect(),
            ..s.clone()
        };
        let at = |state: &JointState| {
            probe
                .exact(Kernel::InverseDynamics, state.as_ref())
                .unwrap_or_default()
        };
        let moved: Vec<f64> = at(&moved).into_iter().map(DoubleDouble::to_f64).collect();
        Deviation::between(&moved, &at(s), Format::F64).relative
    }));
    Ok(AngleRow {
        magnitude,
        sweep: sweep(&probe, &KERNELS, &states),
        input_ulp_effect,
    })
}

/// The report section.
pub fn report(settings: Settings) -> Result<CaseReport, StressError> {
    let Settings { effort, engine } = settings;
    let samples = effort.pick(1000, 10);
    let mut headings = vec![
        "Q (rad)",
        "ulp(Q)/2 (rad)",
        "τ change from 1 ulp of q (median)",
    ];
    headings.extend(SWEEP_HEADINGS);
    let mut table = kernel_table(
        format!(
            "PUMA 560, angles of size Q (|q| ≤ π in the first row, |q| ∈ [Q/2, Q] after), \
             {samples} states per row."
        ),
        &headings,
        &KERNELS,
    );
    let mut rows = Vec::new();
    for magnitude in MAGNITUDES {
        let row = measure(engine, magnitude, samples)?;
        let mut cells = vec![
            sci(magnitude),
            sci(ulp(magnitude) / 2.0),
            sci(row.input_ulp_effect.median),
        ];
        cells.extend(sweep_cells(&row.sweep));
        cells.extend(kernel_cells(&row.sweep.errors, &KERNELS));
        table.push(cells);
        rows.push(row);
    }
    let worst = |k: Kernel| largest(rows.iter().map(|r| r.sweep.errors.max(k)));
    let at_million = rows
        .iter()
        .find(|r| r.magnitude == 1e6)
        .map_or(f64::NAN, |r| r.input_ulp_effect.median);
    let findings = format!(
        "**The kernels lose nothing to large angles; the angle itself does.** For every \
         magnitude up to 1e8 rad the kernels' error against the double-double evaluation of \
         the same `f64` angles stays at {tau} for τ, {m} for M, {g} for g and {fd} for \
         forward dynamics: `sin_cos` reduces the argument exactly (Cody–Waite with π/2 in \
         three parts up to 1.6e6, the standard library's exact reduction beyond), so \
         sin(1e6) of the double 1e6 is correct to an ulp.\n\n\
         But a double near 1e6 is spaced ulp = 1.2e-10 apart: as a physical angle it is known \
         only to ±5.8e-11 rad, and moving every q by one ulp changes τ by {million} \
         (median) at |q| ~ 1e6 — about 1e-10 relative, against 1e-16 at |q| ≤ π. This loss \
         is the input's, not the kernel's: it grows as |q|·ε and no evaluation of an `f64` \
         angle can undo it. Keep joint angles reduced (e.g. to [−π, π] for continuous \
         joints) when they are integrated over long times, or carry them as a whole number \
         of turns plus a remainder.",
        tau = sci(worst(Kernel::InverseDynamics)),
        m = sci(worst(Kernel::MassMatrix)),
        g = sci(worst(Kernel::GravityTorques)),
        fd = sci(worst(Kernel::ForwardDynamics)),
        million = sci(at_million),
    );
    Ok(CaseReport {
        slug: SLUG,
        title: "3. Joint angles up to |q| = 1e6 rad (argument reduction)".into(),
        setup: "The built-in PUMA 560 (six revolute joints). Angles of magnitude Q in every \
                joint, |q̇| ≤ 2 rad/s, |q̈| ≤ 2 rad/s², τ from inverse dynamics. The reference \
                is the double-double evaluation at the same `f64` angles, whose sin/cos \
                reduce by π/2 held to 165 bits (accurate to 1e-31 up to 2^52). The column \
                \"τ change from 1 ulp of q\" is the double-double τ at q moved by one ulp in \
                every joint, relative to τ(q): what the `f64` input leaves undetermined."
            .into(),
        tables: vec![table],
        plots: Vec::new(),
        findings,
    })
}

//! The stress cases of `rne stress`, each with a stated bound on the rounding error of the
//! `f64` kernels against the double-double evaluation of the same expression graph (docs/
//! stress.md explains each bound). Small samples keep the suite fast in debug builds; the
//! report runs the same measurements on thousands of states.

use rne_codegen::Kernel;
use rne_stress::cases::{
    chaos, conditioning, joint_angle, joint_count, link_length, mass_ratio, velocity,
};
use rne_stress::measure::EPSILON;
use rne_stress::{Engine, Sweep};

/// Asserts `sweep`'s largest error of each of `kernels` is at most `bound`.
fn assert_within(case: &str, sweep: &Sweep, kernels: &[Kernel], bound: f64) {
    for &k in kernels {
        let e = sweep.errors.max(k);
        assert!(e <= bound, "{case}: {} error {e:e} > {bound:e}", k.name());
    }
}

/// Case 1, bound 1e-13 for τ, M, g, bias and T and 1e-12 for q̈ at mass ratios 1e-6 and 1e6
/// (measured over 1000 states per ratio, r = 1e-6 … 1e6: at most 9.0e-15 and 5.6e-14):
/// scaling masses rounds nothing new, and the LᵀDL factorisation ignores the grading of M.
#[test]
fn mass_ratio_extremes_keep_full_accuracy() {
    for r in [1e-6, 1e6] {
        let sweep = mass_ratio::measure(Engine::Interpreted, r, 8).unwrap();
        let case = format!("mass ratio {r:e}");
        assert_within(
            &case,
            &sweep,
            &[
                Kernel::InverseDynamics,
                Kernel::MassMatrix,
                Kernel::GravityTorques,
                Kernel::BiasTorques,
                Kernel::KineticEnergy,
            ],
            1e-13,
        );
        assert_within(&case, &sweep, &[Kernel::ForwardDynamics], 1e-12);
        if r < 1.0 {
            assert!(
                sweep.condition.max > 1e6,
                "M is badly scaled: {:?}",
                sweep.condition
            );
        }
    }
}

/// Case 2, uniform scales 1e-4 and 1e2 m: bound 1e-13 for τ, M, g, bias and T; q̈ within
/// 100 ε κ κₛ (measured at most 5.6), κ the cancellation of gravity in τ − g (≈ 1e5 at
/// 1e-4 m). Mixed scales ending in a 1e-4 m link behind a 1e2 m one: τ, M, g still 1e-13, q̈
/// within 10 ε l₁/l₄ = 2.2e-9 (measured 5.0e-10), the lever arm it must cancel.
#[test]
fn link_lengths_cost_only_forward_dynamics_through_cancellation() {
    let exact = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::GravityTorques,
        Kernel::BiasTorques,
        Kernel::KineticEnergy,
    ];
    for s in [1e-4, 1e2] {
        let sweep = link_length::measure(Engine::Interpreted, &[s; 4], 8).unwrap();
        let case = format!("length scale {s:e}");
        assert_within(&case, &sweep, &exact, 1e-13);
        assert!(
            sweep.fd_over_estimate.max <= 100.0,
            "{case}: q̈ error {:?} × ε κ κₛ",
            sweep.fd_over_estimate
        );
    }
    let tip = link_length::measure(Engine::Interpreted, &link_length::SCALES[7], 8).unwrap();
    assert_within("mixed lengths", &tip, &exact[..3], 1e-13);
    assert_within(
        "mixed lengths",
        &tip,
        &[Kernel::ForwardDynamics],
        10.0 * EPSILON * 1e6,
    );
}

/// Case 3, PUMA 560 at |q| ~ 1e6 and 1e8 rad: bound 1e-13 for τ, M, g against the
/// double-double evaluation (whose argument reduction is exact to 2⁵²), 1e-12 for q̈
/// (measured at most 1.5e-15 and 2.0e-14): the reduction of `sin_cos` is exact. The input
/// itself is what limits: one ulp of every q moves τ by 1e-11 … 1e-9 at |q| ~ 1e6 (measured
/// median 1.3e-10).
#[test]
fn huge_joint_angles_are_reduced_exactly() {
    for magnitude in [1e6, 1e8] {
        let row = joint_angle::measure(Engine::Interpreted, magnitude, 4).unwrap();
        let case = format!("|q| ~ {magnitude:e}");
        assert_within(
            &case,
            &row.sweep,
            &[
                Kernel::InverseDynamics,
                Kernel::MassMatrix,
                Kernel::GravityTorques,
            ],
            1e-13,
        );
        assert_within(&case, &row.sweep, &[Kernel::ForwardDynamics], 1e-12);
        if magnitude == 1e6 {
            let effect = row.input_ulp_effect.median;
            assert!(
                (1e-11..=1e-9).contains(&effect),
                "one ulp of q moves τ by {effect:e}"
            );
        }
    }
}

/// Case 4, PUMA 560 at |q̇| ~ 1e3 rad/s: bound 1e-13 for τ, C, bias, T and M; q̈ within
/// 300 ε κ κₛ (measured at most 78 over 5000 states), κ ~ 5e4 the cancellation of C q̇ + g
/// against τ when |q̈| ≤ 10 rad/s².
#[test]
fn high_velocities_cost_only_forward_dynamics_through_cancellation() {
    let sweep = velocity::measure(Engine::Interpreted, 1e3, 6).unwrap();
    assert_within(
        "|q̇| ~ 1e3",
        &sweep,
        &[
            Kernel::InverseDynamics,
            Kernel::CoriolisMatrix,
            Kernel::BiasTorques,
            Kernel::KineticEnergy,
            Kernel::MassMatrix,
        ],
        1e-13,
    );
    assert!(sweep.cancellation.median > 1e3, "{:?}", sweep.cancellation);
    assert!(
        sweep.fd_over_estimate.max <= 300.0,
        "q̈ error {:?} × ε κ κₛ",
        sweep.fd_over_estimate
    );
}

/// Case 5: with near-dependent joints (a short middle link), cond(M) from 1e2 to 1e12 and
/// q̈'s error at most 1e-16 · cond(M) · C with C = 10 (measured C ≤ 2.0 over 2600 states);
/// with a graded M (a 1e-12 kg tip link, cond(M) ~ 1e13) the error stays below 1e-14
/// (measured 2.3e-16).
#[test]
fn forward_dynamics_error_follows_the_condition_number() {
    let family = conditioning::Family::ShortLink;
    let mut largest_condition = 0.0f64;
    for delta in [0.5, 5e-4, 1.6e-6] {
        for p in conditioning::measure(Engine::Interpreted, family, delta, 4).unwrap() {
            largest_condition = largest_condition.max(p.condition);
            let bound = 1e-16 * p.condition * 10.0;
            assert!(
                p.error <= bound,
                "δ = {delta:e}: error {:e} > {bound:e} ({p:?})",
                p.error
            );
        }
    }
    assert!(
        largest_condition > 1e11,
        "cond(M) reached only {largest_condition:e}"
    );
    for p in conditioning::measure(
        Engine::Interpreted,
        conditioning::Family::LightTip,
        1e-12,
        4,
    )
    .unwrap()
    {
        assert!(p.condition > 1e12 && p.error <= 1e-14, "light tip: {p:?}");
    }
}

/// Case 6, 10 s of the chaotic double pendulum released from q = 0: Gauss–Legendre (h = 2e-3
/// s) keeps the energy to 1e-6 of the energy scale (measured 1.8e-7; 5.5e-8 over 1000 s with
/// h = 1e-3) and halving h divides the error by at least 8 (measured 17: order 4),
/// Dormand–Prince at rtol 1e-10 to 1e-7 (measured 1.9e-9); runs at two tolerances part by
/// more than 1e-6 rad within the 10 s (measured at 4.3 s): the motion is chaotic.
#[test]
fn chaotic_release_keeps_energy() {
    let runs = chaos::simulate_releases(10.0, 2e-3).unwrap();
    let relative = |r: &chaos::Run| r.energy_drift() / r.energy_scale();
    assert!(runs.gauss.energy_scale() > 10.0, "the arm swings");
    assert!(
        relative(&runs.gauss) <= 1e-6,
        "GL {:e}",
        relative(&runs.gauss)
    );
    assert!(
        relative(&runs.gauss_fine) <= relative(&runs.gauss) / 8.0,
        "GL is order 4"
    );
    assert!(
        relative(&runs.dopri_loose) <= 1e-7,
        "DP {:e}",
        relative(&runs.dopri_loose)
    );
    assert!(relative(&runs.dopri_tight) <= relative(&runs.dopri_loose));
    let d = chaos::divergence(&runs.dopri_loose, &runs.dopri_tight);
    let parted = chaos::first_time_above(&runs.gauss.record.t, &d, 1e-6);
    assert!(
        parted.is_some_and(|t| t < 10.0),
        "runs parted at {parted:?}"
    );
}

/// Case 7, random robots of 1, 6 and 12 joints (mixed revolute and prismatic): bound 1e-12
/// for τ, M and g (measured at most 4.3e-14 over 9600 states, where τ nearly vanishes: 2.0e-15
/// of the size of its terms; bound 1e-14 on that), q̈ within 100 ε κ κₛ (measured at most
/// 24).
#[test]
fn random_robots_up_to_twelve_joints() {
    for n in [1, 6, joint_count::MAX_JOINTS] {
        let row = joint_count::measure(Engine::Interpreted, n, 1, 3).unwrap();
        let case = format!("{n} joints");
        assert_within(
            &case,
            &row.sweep,
            &[
                Kernel::InverseDynamics,
                Kernel::MassMatrix,
                Kernel::GravityTorques,
            ],
            1e-12,
        );
        assert!(
            row.sweep.fd_over_estimate.max <= 100.0,
            "{case}: q̈ error {:?} × ε κ κₛ",
            row.sweep.fd_over_estimate
        );
        assert!(
            row.tau_against_terms.max <= 1e-14,
            "{case}: τ error {:?} of its terms",
            row.tau_against_terms
        );
    }
}

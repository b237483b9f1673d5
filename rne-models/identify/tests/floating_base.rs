//! Identification on a floating base: rne-models' quadruped (a trunk and four two-joint legs,
//! NV = 6 + 8) on a free-flyer. Its base parameters number the stacked
//! regressor's rank and reproduce the generalised forces, and an optimised excitation of base
//! and legs with 1 % force noise gives them back.

mod common;

use common::numeric_rank;
use nalgebra::{DMatrix, DVector};
use rne_identify::{
    design, fit, identify, predict, simulate, BaseSet, Design, Limits, Measurements, Simulation,
    BASE_COORDINATES,
};
use rne_models::QUADRUPED;
use rne_reference::Reference;
use rne_symbolic::model::Base;
use rne_symbolic::spec::LoadOptions;

fn quadruped() -> Reference {
    let mut model = QUADRUPED
        .load(&LoadOptions::default())
        .expect("the quadruped loads");
    model.set_base(Base::Floating);
    Reference::new(&model.to_numeric())
}

/// Seeded states with a unit quaternion, distinct from the ones `BaseSet::find` uses.
fn states(count: usize) -> Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let mut x: u64 = 0x5eed;
    let mut next = move || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|_| {
            let mut q: Vec<f64> = (0..3).map(|_| next()).collect();
            let quaternion: Vec<f64> = (0..4).map(|_| next()).collect();
            let norm = quaternion.iter().map(|v| v * v).sum::<f64>().sqrt();
            q.extend(quaternion.iter().map(|v| v / norm));
            q.extend((0..8).map(|_| 3.0 * next()));
            let v = (0..14).map(|_| 2.0 * next()).collect();
            let a = (0..14).map(|_| 4.0 * next()).collect();
            (q, v, a)
        })
        .collect()
}

#[test]
fn the_floating_quadrupeds_base_parameters_are_the_rank_and_reproduce_the_forces() {
    let mut reference = quadruped();
    assert_eq!((reference.nq(), reference.nv()), (15, 14));
    let base = BaseSet::find(&mut reference).expect("base parameters");
    let p = reference.parameter_count();
    let states = states(60);
    let mut w = DMatrix::zeros(states.len() * 14, p);
    for (s, (q, v, a)) in states.iter().enumerate() {
        let y = reference.regressor(q, v, a).expect("sizes");
        w.view_mut((s * 14, 0), (14, p)).copy_from(&y);
    }
    assert_eq!(base.len(), numeric_rank(&w));
    let pi_b = DVector::from_vec(base.model_values());
    for (q, v, a) in &states {
        let tau = reference.inverse_dynamics(q, v, a).expect("sizes");
        let predicted = base.base_regressor(&mut reference, q, v, a).expect("sizes") * &pi_b;
        let error = (&predicted - &tau).amax() / tau.amax();
        assert!(error < 1e-12, "Y_b π_b vs τ: relative {error:e}");
    }
}

/// 10 s at 100 Hz of an optimised excitation (base within ±0.3 m and ±0.8 rad, legs within
/// ±1.2 rad, rates within 2 per second), 1 % noise on each generalised force: every base
/// parameter to 2 % or three standard deviations, and a fresh trajectory's forces predicted
/// to 2 % RMS.
#[test]
fn a_floating_base_is_identified_from_a_noisy_excitation() {
    let mut reference = quadruped();
    let base = BaseSet::find(&mut reference).expect("base parameters");
    let mut position = vec![0.3, 0.3, 0.3, 0.8, 0.8, 0.8];
    position.extend([1.2; 8]);
    assert_eq!(position.len(), BASE_COORDINATES + 8);
    let limits = Limits {
        position,
        velocity: vec![2.0; 14],
        acceleration: vec![f64::INFINITY; 14],
    };
    let mut measured = |seed: u64, iterations: usize| -> Measurements {
        let excitation = design(
            &mut reference,
            &base,
            &Design {
                period: 10.0,
                harmonics: 5,
                limits: limits.clone(),
                iterations,
                criterion_states: 40,
                seed,
            },
        )
        .expect("a design");
        let simulation = Simulation {
            duration: 10.0,
            rate: 100.0,
            noise: 0.01,
            seed,
        };
        simulate(&mut reference, &excitation.trajectory, &simulation).expect("simulated")
    };
    let (data, fresh) = (measured(1, 30), measured(2, 0));
    assert_eq!((data.positions, data.joints), (15, 14));
    let estimate = identify(&mut reference, &base, &data, true).expect("identified");
    let truth = base.model_values();
    for (b, &expected) in truth.iter().enumerate() {
        let (value, sigma) = (estimate.values[b], estimate.deviations[b]);
        let error = (value - expected).abs();
        assert!(
            error <= 0.02 * expected.abs() || error <= 3.0 * sigma,
            "b{} = {}: {value:e} vs {expected:e} (σ {sigma:e})",
            b + 1,
            base.combination(b)
        );
    }
    let predicted = predict(&mut reference, &base, &estimate.values, &fresh).expect("predicted");
    let fit = fit(&predicted, &fresh);
    println!(
        "quadruped (floating): {} base of {} standard parameters, condition number {:.1}, \
         prediction RMS error {:.3} %",
        base.len(),
        base.standard_len(),
        estimate.condition,
        100.0 * fit.overall
    );
    assert!(
        fit.overall <= 0.02,
        "RMS error {:.3} %",
        100.0 * fit.overall
    );
}

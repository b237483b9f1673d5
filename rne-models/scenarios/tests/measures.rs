//! The measurements of runs (settling time, time within a band, link flips, separation,
//! turning points, Lyapunov growth) follow their definitions on hand-made records.

use rne_scenarios::measures::{
    first_flip, largest_lyapunov_increase, separation, settling_time, time_within, turning_points,
};
use rne_sim::{Record, Stats};

/// A record with q₁(t) given at t = 0, 1, 2, … (only t and q are filled).
fn record(q1: &[f64]) -> Record<1> {
    Record {
        t: (0..q1.len()).map(|k| k as f64).collect(),
        q: q1.iter().map(|&q| [q]).collect(),
        qd: Vec::new(),
        u: Vec::new(),
        kinetic: Vec::new(),
        potential: Vec::new(),
        total: Vec::new(),
        lyapunov: None,
        stats: Stats::default(),
    }
}

/// The measurements follow their definitions on hand-made samples.
#[test]
fn measurements_follow_their_definitions() {
    let r = record(&[0.0, 1.5, 0.9, 1.015, 0.99, 1.0]);
    assert_eq!(settling_time(&r, &[1.0]), Some(3.0));
    assert_eq!(time_within(&r, &[1.0], 0.1), Some(2.0));
    assert_eq!(time_within(&r, &[5.0], 0.1), None);
    assert_eq!(first_flip(&record(&[0.0, 2.0, 3.5]), 0), Some(2.0));
    assert_eq!(first_flip(&r, 0), None);
    let other = record(&[0.0, 1.5, 1.0, 1.0, 1.0, 1.0]);
    let gap = separation(&r, &other);
    assert_eq!((gap[1], gap[2]), (0.0, (0.9_f64 - 1.0).abs()));
    // q = −(t − 2.3)² sampled at integers: the vertex is recovered exactly.
    let parabola: Vec<f64> = (0..5).map(|k| -(f64::from(k) - 2.3).powi(2)).collect();
    let peaks = turning_points(&record(&parabola), 0, true);
    assert_eq!(peaks.len(), 1);
    assert!(peaks[0].abs() < 1e-12, "{peaks:?}");
    let valleys = turning_points(
        &record(&parabola.iter().map(|q| -q).collect::<Vec<_>>()),
        0,
        false,
    );
    assert!(valleys[0].abs() < 1e-12);
    assert_eq!(largest_lyapunov_increase(&r), None);
}

//! A generated floating-base robot (a trunk with a three-joint arm, `tests/robots/floating-arm.toml`)
//! simulated with the Lie-group variational integrator: the momentum it reports is the robot's
//! (checked body by body against the independent reference), total momentum is conserved over
//! 10 s of joint motion in zero gravity while the base moves and turns, and the robot falls
//! freely at g in any orientation.
//!
//! Run with `cargo test -p rne-sim --test floating_momentum -- --nocapture` to see the measured
//! figures.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_reference::Reference;
use rne_runtime::Dynamics;
use rne_sim::{
    integrate, output_times, world_momentum, LieVariational, ManifoldState, Momentum, Stats,
};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::NumericModel;
use rne_symbolic::{read_robot, Description};

rne_codegen::derive_dynamics! {
    /// The arm in zero gravity.
    mod space {
        robot: "tests/robots/floating-arm.toml",
        outputs: [mass_matrix, coriolis_matrix, gravity_torques, forward_dynamics,
                  kinetic_energy, potential_energy],
        gravity: [0.0, 0.0, 0.0],
    }
}

rne_codegen::derive_dynamics! {
    /// The arm under the spec's gravity, (0, 0, −9.81).
    mod earth {
        robot: "tests/robots/floating-arm.toml",
        outputs: [mass_matrix, coriolis_matrix, gravity_torques, forward_dynamics,
                  kinetic_energy, potential_energy],
    }
}

const NQ: usize = space::NQ;
const NV: usize = space::NV;
const G: [f64; 3] = [0.0, 0.0, -9.81];

fn numeric_model() -> NumericModel {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/robots/floating-arm.toml");
    read_robot(Description::file(&path), &LoadOptions::default())
        .expect("the spec loads")
        .to_numeric()
}

/// A seeded random state: base anywhere within 1 m in any orientation, joints within ±π,
/// velocities within ±2.
fn random_state(rng: &mut ChaCha8Rng) -> ([f64; NQ], [f64; NV]) {
    let mut q: [f64; NQ] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
    q[3..7].iter_mut().for_each(|x| *x /= norm);
    for x in &mut q[7..] {
        *x *= std::f64::consts::PI;
    }
    (q, std::array::from_fn(|_| rng.gen_range(-2.0..2.0)))
}

/// The robot's momentum summed body by body from the reference's kinematics alone:
/// for each link, its frame's placement (R, o) and twist (v_o, ω) = J v, the centre of mass
/// c = o + R c_local moving at v_o + ω × (c − o), and
/// h = Σ (m v_c; c × m v_c + R I_c Rᵀ ω), in world axes about the world origin.
fn reference_momentum(
    model: &NumericModel,
    reference: &mut Reference,
    q: &[f64],
    v: &[f64],
) -> Momentum {
    let placements = reference.frame_placements(q).unwrap();
    let jacobians = reference.frame_jacobians(q).unwrap();
    assert_eq!(placements.len(), model.links.len());
    let v = nalgebra::DVector::from_column_slice(v);
    let (mut linear, mut angular) = (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros());
    for ((link, (r, o)), jacobian) in model.links.iter().zip(&placements).zip(&jacobians) {
        let twist = jacobian * &v;
        let (v_o, w) = (
            twist.fixed_rows::<3>(0).into_owned(),
            twist.fixed_rows::<3>(3).into_owned(),
        );
        let offset = r * nalgebra::Vector3::from(link.com);
        let c = o + offset;
        let momentum = (v_o + w.cross(&offset)) * link.mass;
        let inertia = nalgebra::Matrix3::from_fn(|i, j| link.inertia[i][j]);
        linear += momentum;
        angular += c.cross(&momentum) + r * inertia * r.transpose() * w;
    }
    Momentum {
        linear: linear.into(),
        angular: angular.into(),
    }
}

fn largest(h: &Momentum) -> f64 {
    h.linear
        .iter()
        .chain(&h.angular)
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Property: the first six rows of M(q) v, rotated and shifted to the world
/// ([`world_momentum`]), are the robot's momentum as the reference sums it body by body from
/// placements and Jacobians (no mass matrix involved); and `integrate` is the reference's
/// q ⊕ v (Pinocchio's convention).
#[test]
fn the_base_rows_of_m_v_are_the_momentum_the_reference_sums_body_by_body() {
    let model = numeric_model();
    let mut reference = Reference::new(&model);
    let mut rng = ChaCha8Rng::seed_from_u64(0x6d6f_6d65);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let (q, v) = random_state(&mut rng);
        let ours = world_momentum(&earth::Model, &q, &v).unwrap();
        let theirs = reference_momentum(&model, &mut reference, &q, &v);
        worst = worst.max(ours.max_difference(&theirs) / largest(&theirs).max(1.0));
        let moved = integrate(&earth::Model, &q, &v).unwrap();
        let expected = reference.integrate(&q, &v).unwrap();
        for (a, b) in moved.iter().zip(expected.iter()) {
            assert!((a - b).abs() < 1e-14, "q ⊕ v: {moved:?} vs {expected}");
        }
    }
    println!("momentum from M v against the body-by-body sum: max relative difference {worst:e}");
    assert!(worst < 1e-13, "{worst:e}");
}

/// The contract the integrator relies on: the joint rows of C(q, v)ᵀ v are ∂(½ vᵀ M v)/∂θ, by
/// central differences of the generated M along each joint.
#[test]
fn the_joint_rows_of_c_transpose_v_are_the_kinetic_energy_gradient() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x6374_7621);
    for _ in 0..20 {
        let (q, v) = random_state(&mut rng);
        let c = space::coriolis_matrix(&q, &v);
        let kinetic = |q: &[f64; NQ]| {
            let m = space::mass_matrix(q);
            0.5 * (0..NV)
                .map(|i| (0..NV).map(|j| v[i] * m[i][j] * v[j]).sum::<f64>())
                .sum::<f64>()
        };
        for k in 6..NV {
            let ctv: f64 = (0..NV).map(|i| c[i][k] * v[i]).sum();
            let e = 1e-6;
            let (mut a, mut b) = (q, q);
            a[k + 1] += e;
            b[k + 1] -= e;
            let gradient = (kinetic(&a) - kinetic(&b)) / (2.0 * e);
            assert!(
                (ctv - gradient).abs() < 1e-7 * (1.0 + gradient.abs()),
                "{ctv} vs {gradient}"
            );
        }
    }
}

/// Internal joint torques: PD tracking of sinusoids of different frequencies. No force or
/// moment on the base (the first six entries are zero).
fn joint_drive(t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NV] {
    let reference = [
        1.2 * (1.3 * t).sin(),
        0.8 * (2.1 * t).sin() - 0.4,
        1.5 * (0.7 * t).cos(),
    ];
    let mut u = [0.0; NV];
    for j in 0..3 {
        u[6 + j] = 4.0 * (reference[j] - q[7 + j]) - 0.5 * v[6 + j];
    }
    u
}

/// What one 10 s run measured.
struct Run {
    /// The initial momentum.
    h0: Momentum,
    /// The largest component difference of the momentum to `h0` at the outputs.
    drift: f64,
    /// The base's largest distance from its start (m).
    travel: f64,
    /// The base's largest rotation from its start (rad).
    turn: f64,
    /// The largest | |quaternion| − 1 |.
    norm_error: f64,
    /// The largest joint excursion from the start (rad).
    excursion: f64,
    /// The integrator's work.
    stats: Stats,
}

/// One 10 s run of the zero-gravity arm under [`joint_drive`], h = 1 ms, outputs every 10 ms.
fn ten_seconds(x0: &ManifoldState<NQ, NV>) -> Run {
    let h0 = world_momentum(&space::Model, &x0.q, &x0.v).unwrap();
    let (mut drift, mut travel, mut turn, mut norm_error, mut excursion) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let start = x0.q;
    let stats = LieVariational::new(1e-3)
        .integrate(
            &space::Model,
            &joint_drive,
            x0,
            &output_times(0.0, 10.0, 0.01),
            |_, x| {
                let h = world_momentum(&space::Model, &x.q, &x.v).unwrap();
                drift = drift.max(h.max_difference(&h0));
                travel = travel.max(
                    (0..3)
                        .map(|i| (x.q[i] - start[i]).powi(2))
                        .sum::<f64>()
                        .sqrt(),
                );
                // The angle between two unit quaternions: 2 acos |⟨a, b⟩|.
                let dot: f64 = (3..7).map(|i| x.q[i] * start[i]).sum();
                turn = turn.max(2.0 * dot.abs().min(1.0).acos());
                let norm: f64 = x.q[3..7].iter().map(|c| c * c).sum();
                norm_error = norm_error.max((norm.sqrt() - 1.0).abs());
                excursion = excursion.max(
                    (7..NQ)
                        .map(|i| (x.q[i] - start[i]).abs())
                        .fold(0.0, f64::max),
                );
            },
        )
        .unwrap();
    Run {
        h0,
        drift,
        travel,
        turn,
        norm_error,
        excursion,
        stats,
    }
}

/// Property (issue 11): total momentum is conserved in a zero-gravity simulation of a floating
/// robot moving its joints, over 10 s with the symplectic integrator; the base really moves and
/// turns (from rest, only through the joints' reaction), and the quaternion stays unit.
#[test]
fn total_momentum_is_conserved_over_ten_seconds_of_joint_motion_in_zero_gravity() {
    let q0 = [0.2, -0.1, 0.5, 0.0, 0.0, 0.0, 1.0, 0.3, -0.5, 0.8];
    // From rest: the momentum is zero and must stay so, while the arm swings the trunk about.
    let run = ten_seconds(&ManifoldState::at_rest(q0));
    println!(
        "from rest: momentum drift {:e} kg·m/s (·m), base travel {:.3} m, base turn {:.3} rad, \
         joint excursion {:.2} rad, quaternion norm error {:e}, {:?}",
        run.drift, run.travel, run.turn, run.excursion, run.norm_error, run.stats
    );
    assert!(
        run.excursion > 1.0,
        "the joints hardly moved: {}",
        run.excursion
    );
    assert!(
        run.travel > 0.01 && run.turn > 0.2,
        "the base did not move: {} m, {} rad",
        run.travel,
        run.turn
    );
    assert!(run.drift < 1e-13, "momentum drift {:e}", run.drift);
    assert!(
        run.norm_error < 1e-14,
        "quaternion norm error {:e}",
        run.norm_error
    );

    // With a tumbling, drifting base: the (non-zero) momentum stays what it was.
    let x0 = ManifoldState::new(q0, [0.3, -0.2, 0.1, 0.4, -0.7, 0.9, 0.5, -1.0, 2.0]);
    let run = ten_seconds(&x0);
    let relative = run.drift / largest(&run.h0);
    println!(
        "moving: momentum {:?}, relative drift {relative:e}, base travel {:.3} m, base turn {:.3} rad, \
         quaternion norm error {:e}, {:?}",
        run.h0, run.travel, run.turn, run.norm_error, run.stats
    );
    assert!(
        run.travel > 0.5 && run.turn > 1.0,
        "{} m, {} rad",
        run.travel,
        run.turn
    );
    // Rounding only: an O(h²) method that did not conserve momentum would show ~1e-6 here.
    assert!(relative < 1e-12, "relative momentum drift {relative:e}");
    assert!(
        run.norm_error < 1e-14,
        "quaternion norm error {:e}",
        run.norm_error
    );
}

/// Property (symplectic, order 2): without input the energy error of the tumbling, swinging
/// robot stays bounded over 10 s, and halving the step divides it by about 4.
#[test]
fn the_energy_error_is_bounded_and_of_second_order() {
    let x0 = ManifoldState::new(
        [0.2, -0.1, 0.5, 0.0, 0.0, 0.0, 1.0, 0.3, -0.5, 0.8],
        [0.3, -0.2, 0.1, 0.4, -0.7, 0.9, 0.5, -1.0, 2.0],
    );
    let e0 = space::kinetic_energy(&x0.q, &x0.v);
    let no_input = |_: f64, _: &[f64; NQ], _: &[f64; NV]| [0.0; NV];
    let energy_error = |h: f64| {
        let (mut early, mut late) = (0.0f64, 0.0f64);
        LieVariational::new(h)
            .integrate(
                &space::Model,
                &no_input,
                &x0,
                &output_times(0.0, 10.0, 0.01),
                |t, x| {
                    let e = ((space::kinetic_energy(&x.q, &x.v) - e0) / e0).abs();
                    if t <= 2.0 {
                        early = early.max(e);
                    } else {
                        late = late.max(e);
                    }
                },
            )
            .unwrap();
        (early, late)
    };
    let (coarse, fine) = (energy_error(2e-3), energy_error(1e-3));
    println!(
        "relative energy error (first 2 s, rest of 10 s): h = 2 ms {coarse:?}, h = 1 ms {fine:?}"
    );
    // Bounded: the last 8 s stay within what the first 2 s reached, up to the fluctuation.
    assert!(
        coarse.1 < 3.0 * coarse.0 && fine.1 < 3.0 * fine.0,
        "{coarse:?} {fine:?}"
    );
    let ratio = coarse.0.max(coarse.1) / fine.0.max(fine.1);
    assert!((3.5..4.5).contains(&ratio), "order: ratio {ratio}");
    assert!(fine.0.max(fine.1) < 1e-4, "{fine:?}");
}

/// Property (issue 11): a floating robot released at rest under gravity falls freely: after
/// 1 s its base has moved by ½ g t² and has the velocity g t (v_base = Rᵀ g t in the base
/// frame), without turning and with its joints still, in every orientation tried. The
/// trapezoidal potential of the variational integrator makes this exact to rounding.
#[test]
fn a_floating_robot_falls_at_g_in_every_orientation() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let orientations = [
        [0.0, 0.0, 0.0, 1.0],
        [s, 0.0, 0.0, s],
        [0.0, 1.0, 0.0, 0.0],
        [0.5, -0.5, 0.5, 0.5],
        [0.1, 0.7, -0.3, 0.640_312_423_743_284_9],
    ];
    let no_input = |_: f64, _: &[f64; NQ], _: &[f64; NV]| [0.0; NV];
    let mut worst = 0.0f64;
    for quaternion in orientations {
        let mut q0 = [1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.4, -0.9, 1.3];
        q0[3..7].copy_from_slice(&quaternion);
        let mut last = ManifoldState::at_rest(q0);
        let t = 1.0;
        LieVariational::new(1e-2)
            .integrate(
                &earth::Model,
                &no_input,
                &ManifoldState::at_rest(q0),
                &[0.0, t],
                |_, x| last = *x,
            )
            .unwrap();
        let r = rotation(&quaternion);
        let mut expected = q0;
        let mut expected_v = [0.0; NV];
        for i in 0..3 {
            expected[i] += 0.5 * G[i] * t * t;
            expected_v[i] = (0..3).map(|k| r[(k, i)] * G[k] * t).sum();
        }
        // Position ½ g t², body velocity Rᵀ g t; orientation, joints, ω and joint rates unchanged.
        let error = last
            .q
            .iter()
            .zip(&expected)
            .chain(last.v.iter().zip(&expected_v))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(error < 1e-11, "{quaternion:?}: {last:?}");
        worst = worst.max(error);
    }
    println!("free fall over 1 s at h = 10 ms: largest error in q and v {worst:e}");
    // The forward-dynamics kernel agrees: the body acceleration at rest is Rᵀ g.
    let q = [0.0, 0.0, 0.0, 0.5, -0.5, 0.5, 0.5, 0.4, -0.9, 1.3];
    let a = earth::Model
        .forward_dynamics(&q, &[0.0; NV], &[0.0; NV])
        .unwrap();
    let r = rotation(&[0.5, -0.5, 0.5, 0.5]);
    for i in 0..3 {
        let expected: f64 = (0..3).map(|k| r[(k, i)] * G[k]).sum();
        assert!((a[i] - expected).abs() < 1e-12, "{a:?}");
    }
}

/// The rotation matrix of a unit quaternion [x, y, z, w], through nalgebra.
fn rotation(q: &[f64; 4]) -> nalgebra::Matrix3<f64> {
    nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[3], q[0], q[1], q[2]))
        .to_rotation_matrix()
        .into_inner()
}

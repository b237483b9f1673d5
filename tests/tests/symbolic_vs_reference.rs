//! The symbolic dynamics of floating-base, mimic and geared models — and their derivatives,
//! frame kinematics and regressor — against the independent numeric reference
//! (`rne-reference`: spatial algorithms and dual numbers), evaluated from the expression graphs
//! in f64 at seeded random states. The two share no recursion code.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_models::{RobotSource, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::expr::Id;
use rne_symbolic::model::{Base, Mimic};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

const STATES: usize = 30;

/// A trunk with two legs of a revolute and a prismatic joint each, and a sensor frame behind
/// a fixed joint; the second leg's knee follows the first's (`q = 0.5 q_knee1 − 0.01`) and
/// both hips are geared.
const QUADRUPED_HALF: &str = r#"
name = "biped"
gravity = [0.2, -0.1, -9.81]
[[link]]
name = "trunk"
joint = "fixed"
origin = { xyz = [0, 0, 0] }
mass = 8.0
com = [0.02, -0.01, 0.03]
inertia = { xx = 0.2, yy = 0.3, zz = 0.25, xy = 0.01, xz = -0.02, yz = 0.005 }
[[link]]
name = "hip1"
q = "hip1"
joint = "revolute"
origin = { xyz = [0.2, 0.1, -0.05], rpy = [0.2, 0, 0.3] }
axis = [0, 1, 0]
mass = 1.0
com = [0, 0.01, -0.1]
inertia = { xx = 0.01, yy = 0.012, zz = 0.003 }
[[link]]
name = "knee1"
q = "knee1"
joint = "prismatic"
origin = { xyz = [0, 0, -0.2] }
axis = [0.3, 0, -1]
mass = 0.5
com = [0, 0.01, -0.1]
inertia = { xx = 0.005, yy = 0.005, zz = 0.001 }
[[link]]
name = "hip2"
parent = "trunk"
q = "hip2"
joint = "revolute"
origin = { xyz = [-0.2, 0.1, -0.05] }
axis = [0.6, 0.8, 0]
mass = 1.1
com = [0.01, 0, -0.1]
inertia = { xx = 0.011, yy = 0.01, zz = 0.003 }
[[link]]
name = "knee2"
parent = "hip2"
q = "knee2"
joint = "prismatic"
origin = { xyz = [0, 0, -0.2] }
axis = [0, 0, -1]
mass = 0.4
com = [0, 0, -0.1]
inertia = { xx = 0.004, yy = 0.004, zz = 0.001 }
[[link]]
name = "camera"
parent = "trunk"
joint = "fixed"
origin = { xyz = [0.3, 0, 0.1], rpy = [0, 0.5, 0] }
mass = 0.2
com = [0.01, 0, 0]
inertia = { xx = 0.0001, yy = 0.0001, zz = 0.0001 }
"#;

fn biped(floating: bool) -> RobotModel {
    let mut model = read_robot(
        Description::toml(QUADRUPED_HALF, "biped.toml"),
        &LoadOptions::default(),
    )
    .expect("valid spec");
    let g = &mut model.graph;
    model.links[4].mimic = Some(Mimic {
        leader: "knee1".into(),
        multiplier: g.constant(0.5),
        offset: g.constant(-0.01),
    });
    model.links[1].armature = Some(g.constant(0.02));
    model.links[3].armature = Some(g.constant(0.03));
    model.constrain_mimic_joints().expect("no loop");
    if floating {
        model.set_base(Base::Floating);
    }
    model
}

/// A random state: q with a unit quaternion on a floating base, v, q̈ and u.
struct State {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    u: Vec<f64>,
}

fn random_state(rng: &mut ChaCha8Rng, floating: bool, ndof: usize) -> State {
    let mut q = Vec::new();
    if floating {
        q.extend((0..3).map(|_| rng.gen_range(-1.0..1.0)));
        let quaternion: Vec<f64> = (0..4).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let norm = quaternion.iter().map(|x: &f64| x * x).sum::<f64>().sqrt();
        q.extend(quaternion.iter().map(|x| x / norm));
    }
    q.extend((0..ndof).map(|_| rng.gen_range(-3.0..3.0) * 0.1));
    let nv = ndof + if floating { 6 } else { 0 };
    let mut draw = |scale: f64| (0..nv).map(|_| rng.gen_range(-scale..scale)).collect();
    State {
        v: draw(2.0),
        a: draw(3.0),
        u: draw(10.0),
        q,
    }
}

fn eval(d: &SymbolicDynamics, ids: &[Id], s: &State) -> Vec<f64> {
    d.model.graph.eval::<f64>(ids, |sym| match sym {
        Symbol::Position(k) => s.q[k as usize],
        Symbol::Velocity(k) => s.v[k as usize],
        Symbol::Acceleration(k) => s.a[k as usize],
        Symbol::Force(k) => s.u[k as usize],
        Symbol::Parameter(_) => d.model.parameter_value(sym).unwrap_or(f64::NAN),
        Symbol::Lane(_) => f64::NAN,
    })
}

/// Relative to the largest magnitude of either.
fn assert_agree(what: &str, symbolic: &[f64], reference: &[f64], tolerance: f64) {
    assert_eq!(symbolic.len(), reference.len(), "{what}: sizes");
    let scale = symbolic
        .iter()
        .chain(reference)
        .fold(1e-300f64, |m, x| m.max(x.abs()));
    for (i, (a, b)) in symbolic.iter().zip(reference).enumerate() {
        assert!(
            (a - b).abs() <= tolerance * scale,
            "{what}[{i}]: symbolic {a} vs reference {b} (scale {scale})"
        );
    }
}

fn row_major(m: &nalgebra::DMatrix<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect()
}

fn check_dynamics(name: &str, model: &RobotModel) {
    let mut d = SymbolicDynamics::new(model);
    let layout = d.layout();
    let mut reference = Reference::new(&model.to_numeric());
    assert_eq!((reference.nq(), reference.nv()), (layout.nq(), layout.nv()));
    let tau = d.inverse_dynamics();
    let m = d.mass_matrix().concat();
    let g = d.gravity_torques();
    let bias = d.bias_torques();
    let fd = d.forward_dynamics();
    let (kinetic, potential) = (d.kinetic_energy(), d.potential_energy());
    let (dtau_dq, dtau_dv) = d.inverse_dynamics_derivatives();
    let (dqdd_dq, dqdd_dv, minv) = d.forward_dynamics_derivatives();
    let (dtau_dq, dtau_dv) = (dtau_dq.concat(), dtau_dv.concat());
    let (dqdd_dq, dqdd_dv, minv) = (dqdd_dq.concat(), dqdd_dv.concat(), minv.concat());
    let frames: Vec<usize> = (0..d.frames().len()).collect();
    let placements: Vec<Id> = d
        .frame_placements(&frames)
        .into_iter()
        .flat_map(|(r, p)| r.into_iter().flatten().chain(p))
        .collect();
    let jacobians: Vec<Id> = d.frame_jacobians(&frames).concat().concat();
    let jdot: Vec<Id> = d.frame_jacobian_dot_qd(&frames).concat();
    let y = d.regressor();
    let pi = d.standard_parameters();
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed_0f10);
    for k in 0..STATES {
        let s = random_state(&mut rng, layout.floating, layout.ndof);
        let at = |what: &str| format!("{name} state {k}: {what}");
        let r_tau = reference.inverse_dynamics(&s.q, &s.v, &s.a).unwrap();
        assert_agree(&at("τ"), &eval(&d, &tau, &s), r_tau.as_slice(), 1e-12);
        let r_m = reference.mass_matrix(&s.q).unwrap();
        assert_agree(&at("M"), &eval(&d, &m, &s), &row_major(&r_m), 1e-12);
        let r_g = reference.gravity_torques(&s.q).unwrap();
        assert_agree(&at("g"), &eval(&d, &g, &s), r_g.as_slice(), 1e-12);
        let r_bias = reference.bias_torques(&s.q, &s.v).unwrap();
        assert_agree(&at("bias"), &eval(&d, &bias, &s), r_bias.as_slice(), 1e-12);
        let r_fd = reference.forward_dynamics(&s.q, &s.v, &s.u).unwrap();
        assert_agree(&at("FD"), &eval(&d, &fd, &s), r_fd.as_slice(), 1e-10);
        let r_kinetic = reference.kinetic_energy(&s.q, &s.v).unwrap();
        assert_agree(&at("T"), &eval(&d, &[kinetic], &s), &[r_kinetic], 1e-12);
        let r_potential = reference.potential_energy(&s.q).unwrap();
        assert_agree(&at("V"), &eval(&d, &[potential], &s), &[r_potential], 1e-12);

        let (r_dq, r_dv) = reference
            .inverse_dynamics_derivatives(&s.q, &s.v, &s.a)
            .unwrap();
        assert_agree(
            &at("∂τ/∂q"),
            &eval(&d, &dtau_dq, &s),
            &row_major(&r_dq),
            1e-11,
        );
        assert_agree(
            &at("∂τ/∂q̇"),
            &eval(&d, &dtau_dv, &s),
            &row_major(&r_dv),
            1e-11,
        );
        let r_fdd = reference
            .forward_dynamics_derivatives(&s.q, &s.v, &s.u)
            .unwrap();
        let r_minv = reference.mass_matrix_inverse(&s.q).unwrap();
        assert_agree(&at("M⁻¹"), &eval(&d, &minv, &s), &row_major(&r_minv), 1e-10);
        assert_agree(
            &at("∂q̈/∂q"),
            &eval(&d, &dqdd_dq, &s),
            &row_major(&r_fdd.dqdd_dq),
            1e-9,
        );
        assert_agree(
            &at("∂q̈/∂q̇"),
            &eval(&d, &dqdd_dv, &s),
            &row_major(&r_fdd.dqdd_dqd),
            1e-9,
        );

        let r_placements: Vec<f64> = reference
            .frame_placements(&s.q)
            .unwrap()
            .iter()
            .flat_map(|(r, p)| {
                (0..3)
                    .flat_map(move |i| (0..3).map(move |j| r[(i, j)]))
                    .chain(p.iter().copied())
            })
            .collect();
        assert_agree(
            &at("placements"),
            &eval(&d, &placements, &s),
            &r_placements,
            1e-13,
        );
        let r_jacobians: Vec<f64> = reference
            .frame_jacobians(&s.q)
            .unwrap()
            .iter()
            .flat_map(row_major)
            .collect();
        assert_agree(&at("J"), &eval(&d, &jacobians, &s), &r_jacobians, 1e-13);
        let r_jdot: Vec<f64> = reference
            .frame_jacobian_dot_qd(&s.q, &s.v)
            .unwrap()
            .iter()
            .flat_map(|x| x.iter().copied().collect::<Vec<_>>())
            .collect();
        assert_agree(&at("J̇q̇"), &eval(&d, &jdot, &s), &r_jdot, 1e-12);

        // Y π = τ with the model's own standard parameters, on both sides.
        let (yy, p) = (eval(&d, &y.concat(), &s), eval(&d, &pi, &s));
        let y_pi: Vec<f64> = (0..layout.nv())
            .map(|i| (0..p.len()).map(|c| yy[i * p.len() + c] * p[c]).sum())
            .collect();
        assert_agree(&at("Y π"), &y_pi, r_tau.as_slice(), 1e-12);
        let r_y = reference.regressor(&s.q, &s.v, &s.a).unwrap();
        let bodies = 10 * d.model.links.len();
        let symbolic_bodies: Vec<f64> = (0..layout.nv())
            .flat_map(|i| (0..bodies).map(move |c| (i, c)))
            .map(|(i, c)| yy[i * p.len() + c])
            .collect();
        let reference_bodies: Vec<f64> = (0..layout.nv())
            .flat_map(|i| (0..bodies).map(move |c| (i, c)))
            .map(|(i, c)| r_y[(i, c)])
            .collect();
        assert_agree(
            &at("Y (bodies)"),
            &symbolic_bodies,
            &reference_bodies,
            1e-12,
        );
    }
}

#[test]
fn a_floating_biped_with_a_mimic_knee_and_geared_hips_agrees_with_the_reference() {
    check_dynamics("floating biped", &biped(true));
}

#[test]
fn the_same_biped_bolted_to_the_ground_agrees_with_the_reference() {
    check_dynamics("fixed biped", &biped(false));
}

/// Every built-in robot as bolted down, and on a floating base those whose root body has mass
/// (a massless free-flyer — the thesis's specs put their first joint on the base, UR5's
/// `base_link` has no inertial — makes M singular).
#[test]
fn every_builtin_robot_agrees_with_the_reference_fixed_and_floating() {
    for robot in BUILTIN_ROBOTS {
        let mut model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .expect("built-in robots load");
        check_dynamics(robot.name, &model);
        model.set_base(Base::Floating);
        let merged = SymbolicDynamics::new(&model).model;
        if merged
            .graph
            .as_const(merged.links[0].mass)
            .is_some_and(|m| m > 0.0)
        {
            check_dynamics(&format!("{} (floating)", robot.name), &model);
        }
    }
}

//! The floating base (a free-flyer root) against what mechanics says of a free body, and the
//! floating model's kernels against each other.

use super::SymbolicDynamics;
use crate::expr::{Id, Symbol};
use crate::model::{Base, RobotModel};
use crate::spec::{parse_str, LoadOptions};

/// A trunk with a two-joint leg; the trunk is fixed to the world in the spec.
pub(super) fn legged() -> RobotModel {
    let text = r#"
name = "hopper"
gravity = [0.3, -0.2, -9.81]
[[link]]
name = "trunk"
joint = "fixed"
origin = { xyz = [0, 0, 0] }
mass = 5.0
com = [0.02, -0.01, 0.03]
inertia = { xx = 0.1, yy = 0.2, zz = 0.15, xy = 0.01, xz = -0.02, yz = 0.005 }
[[link]]
name = "hip"
joint = "revolute"
origin = { xyz = [0.1, 0.05, -0.1], rpy = [0.2, 0, 0.3] }
axis = [0, 1, 0]
mass = 1.0
com = [0, 0, -0.1]
inertia = { xx = 0.01, yy = 0.01, zz = 0.002 }
[[link]]
name = "knee"
joint = "prismatic"
origin = { xyz = [0, 0, -0.2] }
axis = [0.3, 0, -1]
mass = 0.5
com = [0, 0.01, -0.1]
inertia = { xx = 0.005, yy = 0.005, zz = 0.001 }
[[link]]
name = "foot"
joint = "fixed"
origin = { xyz = [0.02, -0.03, -0.15], rpy = [0.1, -0.4, 0.7] }
mass = 0
inertia = { xx = 0, yy = 0, zz = 0 }
"#;
    let mut model = parse_str(text, "hopper.toml", &LoadOptions::default()).expect("valid spec");
    model.set_base(Base::Floating);
    model
}

/// A state of the floating model: q (NQ = 9, unit quaternion), v, a, u (NV = 8).
pub(super) struct State {
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) a: Vec<f64>,
    pub(super) u: Vec<f64>,
}

pub(super) fn state(k: usize) -> State {
    let f = |a: f64| ((k as f64 + 1.0) * a).fract() * 2.0 - 1.0;
    let quaternion = [f(0.31), f(0.57), f(0.77), f(0.13)];
    let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut q = vec![f(0.11), f(0.23), f(0.37)];
    q.extend(quaternion.map(|x| x / norm));
    q.extend([2.0 * f(0.41), 0.2 * f(0.53)]);
    let v = (0..8).map(|i| 2.0 * f(0.17 + 0.1 * i as f64)).collect();
    let a = (0..8).map(|i| 3.0 * f(0.29 + 0.07 * i as f64)).collect();
    let u = (0..8).map(|i| 10.0 * f(0.61 + 0.03 * i as f64)).collect();
    State { q, v, a, u }
}

pub(super) fn eval(d: &SymbolicDynamics, ids: &[Id], s: &State) -> Vec<f64> {
    d.model.graph.eval::<f64>(ids, |sym| match sym {
        Symbol::Position(k) => s.q[k as usize],
        Symbol::Velocity(k) => s.v[k as usize],
        Symbol::Acceleration(k) => s.a[k as usize],
        Symbol::Force(k) => s.u[k as usize],
        Symbol::Parameter(_) | Symbol::Lane(_) => f64::NAN,
    })
}

/// The base orientation of a state, row-major.
pub(super) fn rotation(s: &State) -> [[f64; 3]; 3] {
    let [x, y, z, w] = [s.q[3], s.q[4], s.q[5], s.q[6]];
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A single free body with no applied force falls with gravity's acceleration whatever its
/// orientation and spin: the classical acceleration of its origin, R (v̇ + ω × v), is g when
/// its centre of mass is at the origin.
#[test]
fn a_free_body_falls_at_g_in_every_orientation() {
    let text = r#"
name = "brick"
gravity = [0.5, 1.0, -9.81]
[[link]]
name = "brick"
joint = "fixed"
origin = { xyz = [0, 0, 0] }
mass = 3.0
inertia = { xx = 0.25, yy = 0.2, zz = 0.1, xy = 0.02 }
"#;
    let mut model = parse_str(text, "brick.toml", &LoadOptions::default()).expect("valid spec");
    model.set_base(Base::Floating);
    let mut d = SymbolicDynamics::new(&model);
    assert_eq!(d.layout().nv(), 6);
    let fd = d.forward_dynamics();
    for k in 0..50 {
        let mut s = state(k);
        s.q.truncate(7);
        s.v.truncate(6);
        s.u = vec![0.0; 6];
        let a = eval(&d, &fd, &s);
        let r = rotation(&s);
        let lin = [a[0], a[1], a[2]];
        let omega = [s.v[3], s.v[4], s.v[5]];
        let transport = cross(omega, [s.v[0], s.v[1], s.v[2]]);
        let body: Vec<f64> = (0..3).map(|i| lin[i] + transport[i]).collect();
        let world: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| r[i][j] * body[j]).sum())
            .collect();
        for (i, expected) in [0.5, 1.0, -9.81].into_iter().enumerate() {
            assert!(
                (world[i] - expected).abs() < 1e-12,
                "state {k}: acceleration {world:?}"
            );
        }
    }
}

/// Inverse dynamics of the floating model is M a + bias, forward dynamics inverts it, the
/// kinetic energy is ½ vᵀ M v, and M is symmetric and positive definite (its LᵀDL pivots are
/// positive): the kernels of a floating base agree with each other.
#[test]
fn floating_kernels_are_consistent() {
    let mut d = SymbolicDynamics::new(&legged());
    let (nq, nv) = (d.layout().nq(), d.layout().nv());
    assert_eq!((nq, nv), (9, 8));
    let tau = d.inverse_dynamics();
    let m = d.mass_matrix();
    let bias = d.bias_torques();
    let fd = d.forward_dynamics();
    let kinetic = d.kinetic_energy();
    let m_flat: Vec<Id> = m.concat();
    for k in 0..40 {
        let mut s = state(k);
        let t = eval(&d, &tau, &s);
        let mm = eval(&d, &m_flat, &s);
        let b = eval(&d, &bias, &s);
        let scale = t.iter().fold(1.0f64, |x, y| x.max(y.abs()));
        for i in 0..nv {
            let ma: f64 = (0..nv).map(|j| mm[i * nv + j] * s.a[j]).sum();
            assert!(
                (t[i] - ma - b[i]).abs() < 1e-12 * scale,
                "state {k} row {i}"
            );
            for j in 0..nv {
                assert_eq!(mm[i * nv + j], mm[j * nv + i]);
            }
        }
        let energy = eval(&d, &[kinetic], &s)[0];
        let quadratic: f64 = (0..nv)
            .flat_map(|i| (0..nv).map(move |j| (i, j)))
            .map(|(i, j)| 0.5 * s.v[i] * mm[i * nv + j] * s.v[j])
            .sum();
        assert!((energy - quadratic).abs() < 1e-12 * quadratic.max(1.0));
        // Forward dynamics at u = τ(a) gives back a.
        s.u = t;
        let a = eval(&d, &fd, &s);
        for i in 0..nv {
            assert!(
                (a[i] - s.a[i]).abs() < 1e-9,
                "state {k}: {a:?} vs {:?}",
                s.a
            );
        }
    }
}

/// The floating model's mass matrix does not depend on where the base is or how it is turned
/// (base-frame velocities), and its base block is the whole robot's rigid-body inertia: total
/// mass on the linear diagonal.
#[test]
fn the_mass_matrix_ignores_the_base_pose() {
    let mut d = SymbolicDynamics::new(&legged());
    let m = d.mass_matrix();
    let flat: Vec<Id> = m.concat();
    let first = eval(&d, &flat, &state(0));
    let mut moved = state(0);
    moved.q[..7].copy_from_slice(&state(7).q[..7]);
    assert_eq!(eval(&d, &flat, &moved), first);
    for a in 0..3 {
        assert!((first[a * 8 + a] - 6.5).abs() < 1e-14, "total mass");
    }
}

/// The Christoffel C of a floating base, completed by the momentum transport of the base's
/// Euler–Poincaré equation, gives C v + g = bias, and Ṁ − 2C is skew-symmetric. Ṁ is
/// computed here by central differences of M along the motion (only the joint angles move M).
#[test]
fn the_floating_coriolis_matrix_gives_the_bias_and_a_skew_mdot_minus_2c() {
    let mut d = SymbolicDynamics::new(&legged());
    let nv = 8;
    let c = d.coriolis_matrix().concat();
    let m = d.mass_matrix().concat();
    let (g, bias) = (d.gravity_torques(), d.bias_torques());
    for k in 0..20 {
        let s = state(k);
        let cc = eval(&d, &c, &s);
        let (gg, b) = (eval(&d, &g, &s), eval(&d, &bias, &s));
        for i in 0..nv {
            let cv: f64 = (0..nv).map(|j| cc[i * nv + j] * s.v[j]).sum();
            assert!((cv + gg[i] - b[i]).abs() < 1e-11, "state {k} row {i}");
        }
        let h = 1e-6;
        let at = |sign: f64| {
            let mut moved = state(k);
            for j in 0..2 {
                moved.q[7 + j] += sign * h * s.v[6 + j];
            }
            eval(&d, &m, &moved)
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        for i in 0..nv {
            for j in 0..nv {
                let mdot = |a: usize, b: usize| (plus[a * nv + b] - minus[a * nv + b]) / (2.0 * h);
                let n_ij = mdot(i, j) - 2.0 * cc[i * nv + j];
                let n_ji = mdot(j, i) - 2.0 * cc[j * nv + i];
                assert!((n_ij + n_ji).abs() < 1e-7, "state {k}: ({i}, {j})");
            }
        }
    }
}

/// Y π reproduces inverse dynamics on a floating base (the base body's ten parameters first).
#[test]
fn the_floating_regressor_times_the_standard_parameters_is_the_torque() {
    let mut d = SymbolicDynamics::new(&legged());
    let tau = d.inverse_dynamics();
    let y: Vec<Id> = d.regressor().concat();
    let pi = d.standard_parameters();
    assert_eq!(pi.len(), 30);
    for k in 0..20 {
        let s = state(k);
        let (t, yy, p) = (eval(&d, &tau, &s), eval(&d, &y, &s), eval(&d, &pi, &s));
        for i in 0..8 {
            let y_pi: f64 = (0..30).map(|c| yy[i * 30 + c] * p[c]).sum();
            assert!((y_pi - t[i]).abs() < 1e-11 * t[i].abs().max(1.0), "row {i}");
        }
    }
}

//! The recursive Coriolis matrix (`coriolis.rs`) against its definition from the Christoffel
//! symbols of M on fixed bases, and against the geometry of body-frame velocities on a
//! floating base.

use super::floating_tests::legged;
use super::mimic_tests::gripper;
use super::tests::planar_elbow;
use super::SymbolicDynamics;
use crate::expr::{Id, Symbol};
use crate::model::RobotModel;
use crate::spec::{parse_str, LoadOptions};

/// A branched tree: a revolute trunk carrying a prismatic arm and a two-joint arm, with
/// oblique axes and rotated joint frames, so that no entry of C is structurally simple.
fn branched() -> RobotModel {
    let text = r#"
name = "branched"
[[link]]
name = "trunk"
joint = "revolute"
origin = { xyz = [0, 0, 0.2], rpy = [0.1, 0.2, 0.3] }
axis = [0, 0, 1]
mass = 3.0
com = [0.02, 0.01, 0.1]
inertia = { xx = 0.05, yy = 0.06, zz = 0.04, xy = 0.002, xz = -0.003, yz = 0.001 }
[[link]]
name = "slider"
parent = "trunk"
joint = "prismatic"
origin = { xyz = [0.1, 0, 0.3], rpy = [0, 0.5, 0] }
axis = [0.6, 0, 0.8]
mass = 0.8
com = [0, 0.03, 0.05]
inertia = { xx = 0.004, yy = 0.005, zz = 0.003 }
[[link]]
name = "upper"
parent = "trunk"
joint = "revolute"
origin = { xyz = [-0.1, 0.05, 0.3], rpy = [0.4, 0, -0.2] }
axis = [0, 0.8, 0.6]
mass = 1.5
com = [0, 0, -0.15]
inertia = { xx = 0.02, yy = 0.02, zz = 0.004, xz = 0.001 }
[[link]]
name = "fore"
parent = "upper"
joint = "revolute"
origin = { xyz = [0, 0.02, -0.3], rpy = [0, 0.3, 0.7] }
axis = [1, 0, 0]
mass = 0.9
com = [0.01, 0, -0.12]
inertia = { xx = 0.01, yy = 0.011, zz = 0.002, yz = -0.0005 }
"#;
    parse_str(text, "branched.toml", &LoadOptions::default()).expect("valid spec")
}

/// A seeded state: q, q̇ and a second velocity w, with joint-sized vectors of length `nv`.
fn state(k: usize, nv: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let f = |a: f64| ((k as f64 + 1.0) * a).fract() * 2.0 - 1.0;
    let q = (0..nv).map(|i| 3.0 * f(0.754 + 0.113 * i as f64)).collect();
    let v = (0..nv).map(|i| 4.0 * f(0.431 + 0.071 * i as f64)).collect();
    let w = (0..nv).map(|i| 4.0 * f(0.137 + 0.059 * i as f64)).collect();
    (q, v, w)
}

fn eval(d: &SymbolicDynamics, ids: &[Id], q: &[f64], v: &[f64]) -> Vec<f64> {
    d.model.graph.eval::<f64>(ids, |sym| match sym {
        Symbol::Position(k) => q[k as usize],
        Symbol::Velocity(k) => v[k as usize],
        Symbol::Parameter(_) => d.model.parameter_value(sym).unwrap_or(f64::NAN),
        _ => f64::NAN,
    })
}

/// On joint coordinates the recursion's C is the Christoffel C, entry by entry: on the
/// thesis's planar elbow, a branched tree with prismatic and oblique joints, and a gripper
/// whose finger follows another (constrained mimic) or moves freely.
#[test]
fn the_recursive_coriolis_matrix_is_the_christoffel_one() {
    for (name, model) in [
        ("planar elbow", planar_elbow()),
        ("branched", branched()),
        ("gripper, mimic constrained", gripper(true)),
        ("gripper, mimic free", gripper(false)),
    ] {
        let mut d = SymbolicDynamics::new(&model);
        let nv = d.layout().nv();
        let recursive = d.recursive_coriolis_matrix().concat();
        let christoffel = d.christoffel_coriolis_matrix().concat();
        for k in 0..25 {
            let (q, v, _) = state(k, nv);
            let (a, b) = (eval(&d, &recursive, &q, &v), eval(&d, &christoffel, &q, &v));
            let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                assert!(
                    (x - y).abs() <= 1e-13 * scale,
                    "{name}, state {k}: C[{}][{}] = {x}, Christoffel {y}",
                    i / nv,
                    i % nv
                );
            }
        }
    }
}

/// On a floating base the base velocities are body-frame twists, whose vector fields do not
/// commute: the torsion-free (Christoffel) C then satisfies C(v) w − C(w) v = M [v_b × w_b; 0]
/// with the spatial cross product of the base twists ([lin; ang] order), instead of the
/// symmetry C(v) w = C(w) v of coordinates. The old construction (Christoffel symbols of the
/// joint angles plus the base's momentum transport) did not.
#[test]
fn on_a_floating_base_the_coriolis_matrix_is_torsion_free_in_the_body_frame() {
    let mut d = SymbolicDynamics::new(&legged());
    let nv = 8;
    let c = d.coriolis_matrix().concat();
    let m = d.mass_matrix().concat();
    let cross = |a: &[f64], b: &[f64]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    for k in 0..20 {
        let (mut q, v, w) = state(k, 9);
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let (v, w) = (&v[..nv], &w[..nv]);
        let (cv, cw) = (eval(&d, &c, &q, v), eval(&d, &c, &q, w));
        let mm = eval(&d, &m, &q, v);
        // [v₁; ω₁] × [v₂; ω₂] = [ω₁ × v₂ + v₁ × ω₂; ω₁ × ω₂].
        let (a, b) = (cross(&v[3..6], &w[0..3]), cross(&v[0..3], &w[3..6]));
        let mut bracket = vec![0.0; nv];
        bracket[0..3].copy_from_slice(&[a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        bracket[3..6].copy_from_slice(&cross(&v[3..6], &w[3..6]));
        for i in 0..nv {
            let torsion: f64 = (0..nv)
                .map(|j| cv[i * nv + j] * w[j] - cw[i * nv + j] * v[j])
                .sum();
            let expected: f64 = (0..nv).map(|j| mm[i * nv + j] * bracket[j]).sum();
            assert!(
                (torsion - expected).abs() < 1e-11 * expected.abs().max(1.0),
                "state {k}, row {i}: {torsion} vs {expected}"
            );
        }
    }
}

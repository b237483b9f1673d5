//! The joint reactions f_i, τ_i of the recursion ((3.21), (3.24)) — the loads the joints must
//! resist, section 5.4 — checked against statics: at rest, the base carries the whole weight,
//! and the moment about joint 1 is the moment of every link's weight about it.

use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{Symbol, SymbolicDynamics};

fn irb140() -> SymbolicDynamics {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/robots/irb140-3dof.toml"
    );
    SymbolicDynamics::new(
        &read_robot(Description::file(path.as_ref()), &LoadOptions::default()).unwrap(),
    )
}

#[test]
fn at_rest_the_first_joint_carries_the_whole_weight_and_its_moment() {
    let mut d = irb140();
    let reactions = d.joint_reactions();
    let numeric = d.model.to_numeric();
    let total_mass: f64 = numeric.links.iter().map(|l| l.mass).sum();
    let g0 = numeric.gravity;
    let ids: Vec<_> = reactions[0]
        .force
        .iter()
        .chain(&reactions[0].torque)
        .copied()
        .collect();
    for q in [[0.0, 0.0, 0.0], [0.7, -0.3, 1.1], [-2.0, 1.4, -0.5]] {
        let values = d.model.graph.eval::<f64>(&ids, |s| match s {
            Symbol::Position(k) => q[k as usize],
            _ => 0.0,
        });
        // Body frame 1 is the base frame turned by R_1^0(q1) = E_1 Rot(u_1, q1): rotate the
        // reaction back into the base frame.
        let e = numeric.links[0].rotation;
        let u = numeric.links[0].axis;
        let rot = axis_rotation(u, q[0]);
        let r = mat_mul(e, rot);
        let force = mat_vec(r, [values[0], values[1], values[2]]);
        let torque = mat_vec(r, [values[3], values[4], values[5]]);
        for k in 0..3 {
            assert!(
                (force[k] + total_mass * g0[k]).abs() < 1e-10,
                "f_1 = -m g: {force:?}"
            );
        }
        // Σ p_ci × m_i g about the base origin (on joint 1's axis): the base must apply the
        // opposite moment.
        let weight_moment = weight_moment_about_origin(&d, &q);
        for k in 0..3 {
            assert!(
                (torque[k] + weight_moment[k]).abs() < 1e-10,
                "tau_1 = -sum p x m g: {torque:?} vs {weight_moment:?}"
            );
        }
    }
}

/// Σ_i p_ci × m_i g_0 from the potential energy's gradient would hide an error of the same
/// kind, so the COM positions are computed here directly from the numeric placements.
fn weight_moment_about_origin(d: &SymbolicDynamics, q: &[f64; 3]) -> [f64; 3] {
    let numeric = d.model.to_numeric();
    let mut poses: Vec<([[f64; 3]; 3], [f64; 3])> = Vec::new();
    let mut moment = [0.0; 3];
    for link in &numeric.links {
        let k = link.joint.expect("no fixed links");
        let rot = mat_mul(link.rotation, axis_rotation(link.axis, q[k]));
        let (parent_r, parent_p) = link.parent.map_or((identity(), [0.0; 3]), |p| poses[p]);
        let r = mat_mul(parent_r, rot);
        let p = add(parent_p, mat_vec(parent_r, link.translation));
        let com = add(p, mat_vec(r, link.com));
        let weight = numeric.gravity.map(|g| g * link.mass);
        moment = add(moment, cross(com, weight));
        poses.push((r, p));
    }
    moment
}

fn identity() -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
}

/// Rodrigues' rotation by `angle` about the unit vector `u`.
fn axis_rotation(u: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let mut r = [[0.0; 3]; 3];
    let skew = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (1.0 - c) * u[i] * u[j] + s * skew[i][j] + if i == j { c } else { 0.0 };
        }
    }
    r
}

fn mat_mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

fn mat_vec(a: [[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

//! A first use of rne: UR5's dynamics, generated at compile time from the built-in robot's
//! URDF file. `cargo run -p rne-examples --example first_steps`
rne_codegen::derive_dynamics! {
    /// Universal Robots' UR5 (`rne-models/robots/ur5.urdf`).
    pub mod ur5 {
        robot: "../rne-models/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, gravity_torques],
    }
}

fn main() {
    let q = [0.0, -1.2, 1.5, -0.3, 1.57, 0.0];
    let (qd, qdd, zero) = ([0.2; ur5::NV], [1.0; ur5::NV], [0.0; ur5::NV]);
    // τ = M(q) q̈ + C(q, q̇) q̇ + g(q): the joint torques that give the arm acceleration q̈.
    let tau = ur5::inverse_dynamics(&q, &qd, &qdd);
    let (m, g) = (ur5::mass_matrix(&q), ur5::gravity_torques(&q));
    println!(
        "joints {:?}\nτ    = {tau:.4?} N·m\ng(q) = {g:.4?} N·m",
        ur5::JOINTS
    );
    for (i, row) in m.iter().enumerate() {
        println!("M[{i}] = {row:.4?}");
    }
    // At rest (q̇ = q̈ = 0) the torques are gravity's alone; M is symmetric.
    let still = ur5::inverse_dynamics(&q, &zero, &zero);
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    assert!((0..ur5::NV).all(|i| near(still[i], g[i])));
    assert!((0..ur5::NV).all(|i| (0..ur5::NV).all(|j| m[i][j] == m[j][i])));
}

//! A robot chosen while the program runs: the URDF named on the command line is read,
//! its kernels are generated and compiled in memory (rne-jit, no Rust build), and its inverse
//! dynamics, mass matrix and forward dynamics are evaluated at one state.
//!
//! ```sh
//! cargo run --release -p rne-examples --example robot_at_run_time -- rne-models/robots/ur5.urdf
//! ```

use std::path::PathBuf;

use rne_codegen::{GenerationOptions, Kernel, Scene};
use rne_jit::{JitModel, State};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .ok_or("usage: robot_at_run_time ROBOT.urdf|ROBOT.toml")?;
    let options = GenerationOptions {
        outputs: vec![
            Kernel::InverseDynamics,
            Kernel::MassMatrix,
            Kernel::ForwardDynamics,
        ],
        ..GenerationOptions::default()
    };
    let model = JitModel::load(&path, &Scene::default(), &options)?;
    let t = model.timings();
    println!(
        "{}: {} joints, kernels in {:.1} ms (generation {:.1} ms, JIT {:.1} ms)",
        model.robot(),
        model.nv(),
        (t.generation + t.compilation).as_secs_f64() * 1e3,
        t.generation.as_secs_f64() * 1e3,
        t.compilation.as_secs_f64() * 1e3
    );
    let n = model.nv();
    let q: Vec<f64> = (0..n).map(|i| 0.1 * (i + 1) as f64).collect();
    let qd = vec![0.5; n];
    let qdd = vec![0.0; n];
    let state = State {
        q: &q,
        qd: &qd,
        qdd: &qdd,
        tau: &[],
    };
    let tau = model.evaluate_vec(Kernel::InverseDynamics, state)?;
    println!("tau = {tau:?}");
    let m = model.evaluate_vec(Kernel::MassMatrix, state)?;
    println!("M[0][0..{n}] = {:?}", &m[..n]);
    // Forward dynamics at the torques just computed gives back q̈ = 0.
    let qdd_back = model.evaluate_vec(Kernel::ForwardDynamics, State { tau: &tau, ..state })?;
    println!("qdd from those torques = {qdd_back:?}");
    Ok(())
}

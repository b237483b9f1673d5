//! `forward_dynamics` by the articulated-body algorithm or by M + LᵀDL: the default takes the
//! one with fewer operations, either can be forced, and both compute the same accelerations.

use std::path::PathBuf;

use rne_codegen_core::{
    build_kernel_with, generate, read_robot, ForwardDynamicsMethod, GenerationOptions, Kernel,
    KernelSetup, Scene,
};
use rne_symbolic::{Symbol, SymbolicDynamics};

fn robot(file: &str, options: &GenerationOptions) -> rne_symbolic::RobotModel {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/robots")
        .join(file);
    Scene::default()
        .apply(&read_robot(&path, file, &Scene::default(), options).unwrap())
        .unwrap()
}

#[test]
fn the_default_takes_the_cheaper_algorithm_and_either_can_be_forced() {
    for file in ["planar-elbow.toml", "puma560.toml"] {
        let mut options = GenerationOptions {
            outputs: vec![Kernel::ForwardDynamics],
            ..GenerationOptions::default()
        };
        let model = robot(file, &options);
        let auto = generate(&model, &Scene::default(), &options, file).unwrap();
        let choice = auto.forward_dynamics_choice.clone().expect("both apply");
        let cheaper = if choice.aba.cost() < choice.ldlt.cost() {
            ForwardDynamicsMethod::Aba
        } else {
            ForwardDynamicsMethod::Ldlt
        };
        assert_eq!(choice.chosen, cheaper, "{file}");
        let emitted = auto.kernels[0].ops;
        let expected = match cheaper {
            ForwardDynamicsMethod::Aba => choice.aba,
            _ => choice.ldlt,
        };
        assert_eq!(
            emitted, expected,
            "{file}: the emitted kernel is the chosen one"
        );
        for forced in [ForwardDynamicsMethod::Aba, ForwardDynamicsMethod::Ldlt] {
            options.forward_dynamics = forced;
            let module = generate(&model, &Scene::default(), &options, file).unwrap();
            assert_eq!(module.forward_dynamics_choice.unwrap().chosen, forced);
        }
    }
}

#[test]
fn both_algorithms_compute_the_same_accelerations() {
    let model = robot("puma560.toml", &GenerationOptions::default());
    let dynamics = SymbolicDynamics::new(&model);
    let setup = KernelSetup::new(&dynamics, &[Kernel::ForwardDynamics]);
    let program = |articulated| {
        let setup = KernelSetup {
            articulated,
            ..setup.clone()
        };
        build_kernel_with(&dynamics, Kernel::ForwardDynamics, &setup).program
    };
    let (aba, ldlt) = (program(true), program(false));
    assert_ne!(aba, ldlt, "two different programs");
    for k in 0..100 {
        let x = k as f64 * 0.37;
        let value = |s: Symbol| match s {
            Symbol::Position(i) => (x + i as f64).sin() * 3.0,
            Symbol::Velocity(i) => (0.5 * x - i as f64).cos() * 2.0,
            Symbol::Force(i) => (x * i as f64).sin() * 20.0,
            _ => f64::NAN,
        };
        let (a, b) = (aba.eval(value), ldlt.eval(value));
        let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let error = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
            / scale;
        assert!(error < 1e-10, "ABA and LDLT differ by {error:e}");
    }
}

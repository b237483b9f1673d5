//! Generation has a bound on size: a kernel whose expression graph would pass the generation options' node
//! limit is an error naming the kernel and the limit, returned quickly, and a limit the robot
//! stays under changes nothing.

use std::path::PathBuf;
use std::time::Instant;

use rne_codegen_core::{generate, read_robot, CodegenError, GenerationOptions, Kernel, Scene};

fn puma(options: &GenerationOptions) -> rne_symbolic::RobotModel {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/robots/puma560.toml");
    read_robot(&path, "puma560.toml", &Scene::default(), options).unwrap()
}

#[test]
fn a_kernel_past_the_node_limit_is_an_error_naming_it() {
    let options = GenerationOptions {
        outputs: vec![Kernel::InverseDynamics, Kernel::ForwardDynamicsDerivatives],
        node_limit: 3_000,
        ..GenerationOptions::default()
    };
    let start = Instant::now();
    let error = generate(&puma(&options), &Scene::default(), &options, "puma560.toml").unwrap_err();
    assert!(start.elapsed().as_secs() < 10, "the error comes quickly");
    match &error {
        CodegenError::TooLarge { kernel, limit } => {
            assert_eq!(*kernel, Kernel::ForwardDynamicsDerivatives);
            assert_eq!(*limit, 3_000);
        }
        other => panic!("{other:?}"),
    }
    let message = error.to_string();
    assert!(
        message.contains("forward_dynamics_derivatives") && message.contains("3000 nodes"),
        "{message}"
    );
}

#[test]
fn a_limit_the_kernels_stay_under_changes_nothing() {
    let generous = GenerationOptions {
        outputs: vec![Kernel::InverseDynamics, Kernel::MassMatrix],
        node_limit: 100_000,
        ..GenerationOptions::default()
    };
    let default = GenerationOptions {
        node_limit: GenerationOptions::default().node_limit,
        ..generous.clone()
    };
    let model = puma(&default);
    assert_eq!(
        generate(&model, &Scene::default(), &generous, "puma560.toml")
            .unwrap()
            .source,
        generate(&model, &Scene::default(), &default, "puma560.toml")
            .unwrap()
            .source
    );
}

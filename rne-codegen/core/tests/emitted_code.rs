//! The emitted code of two robots, pinned: every change of the optimiser or the emitter
//! shows up as a reviewed snapshot diff (`cargo insta review`).

use std::path::PathBuf;

use rne_codegen_core::{generate, read_robot, GenerationOptions, Kernel, ParameterMode, Scene};
use rne_symbolic::dynamics::derivatives::Sweep;
use rne_symbolic::SymbolicDynamics;

/// The formatted module generated for `robots/<file>` with `outputs`.
fn emitted(file: &str, outputs: &[Kernel]) -> String {
    emitted_with(file, outputs, ParameterMode::Constant)
}

/// The same with `parameters`.
fn emitted_with(file: &str, outputs: &[Kernel], parameters: ParameterMode) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/robots")
        .join(file);
    let options = GenerationOptions {
        outputs: outputs.to_vec(),
        parameters,
        ..GenerationOptions::default()
    };
    let model = read_robot(&path, file, &Scene::default(), &options).expect("the robot loads");
    generate(&model, &Scene::default(), &options, file)
        .expect("the module generates")
        .to_pretty_string()
}

#[test]
fn planar_elbow_every_kernel() {
    insta::assert_snapshot!(emitted("planar-elbow.toml", &Kernel::DYNAMICS));
}

#[test]
fn planar_elbow_control_and_identification_kernels() {
    let control: Vec<Kernel> = Kernel::ALL
        .into_iter()
        .filter(|k| !Kernel::DYNAMICS.contains(k))
        .collect();
    insta::assert_snapshot!(emitted("planar-elbow.toml", &control));
}

/// `parameters: base`: the `Params` of the six base parameters (the thesis's groups of
/// (4.45)–(4.47), `from_standard` regrouping m2 with l1 = 0.3 and l1² = 0.09) and the
/// dynamics as functions of them alone.
#[test]
fn planar_elbow_base_parameters() {
    insta::assert_snapshot!(emitted_with(
        "planar-elbow.toml",
        &Kernel::DYNAMICS,
        ParameterMode::Base
    ));
}

/// Base parameters are found at numeric geometry: a model read with symbolic parameters is
/// an error naming the robot, not a panic.
#[test]
fn base_parameters_of_a_model_with_symbolic_parameters_are_an_error() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/robots/planar-elbow.toml");
    let symbolic = GenerationOptions {
        parameters: ParameterMode::Runtime,
        ..GenerationOptions::default()
    };
    let model = read_robot(&path, "planar-elbow.toml", &Scene::default(), &symbolic)
        .expect("the robot loads");
    let base = GenerationOptions {
        parameters: ParameterMode::Base,
        ..GenerationOptions::default()
    };
    let error = generate(&model, &Scene::default(), &base, "planar-elbow.toml")
        .expect_err("symbolic geometry");
    assert!(
        error
            .to_string()
            .starts_with("planar-elbow.toml: `parameters: base` needs"),
        "{error}"
    );
}

#[test]
fn puma560_inverse_and_forward_dynamics() {
    insta::assert_snapshot!(emitted(
        "puma560.toml",
        &[Kernel::InverseDynamics, Kernel::ForwardDynamics]
    ));
}

#[test]
fn the_module_is_byte_identical_from_one_generation_to_the_next() {
    assert_eq!(
        emitted("puma560.toml", &Kernel::ALL),
        emitted("puma560.toml", &Kernel::ALL)
    );
}

#[test]
fn every_kernel_of_the_runtime_has_a_construction() {
    // `build_outputs` panics for a kernel it cannot build; the module lists each in KERNELS.
    let module = emitted("planar-elbow.toml", &Kernel::ALL);
    for kernel in Kernel::ALL {
        assert!(
            module.contains(&format!("pub fn {}(", kernel.name())),
            "{kernel}"
        );
    }
}

/// The text of `pub fn name` in `module`, to its closing brace.
fn function<'m>(module: &'m str, name: &str) -> &'m str {
    let start = module
        .find(&format!("pub fn {name}("))
        .unwrap_or_else(|| panic!("the module has `{name}`"));
    let end = start + module[start..].find("\n}\n").expect("a function ends");
    &module[start..end]
}

/// The threads take the shared kernels costliest first, not in the order asked for; the
/// module still lists its functions in the order asked for, whichever order that is.
#[test]
fn the_functions_come_in_the_order_asked_for() {
    let mut outputs = Kernel::ALL.to_vec();
    for _ in 0..2 {
        let module = emitted("puma560.toml", &outputs);
        let places: Vec<usize> = outputs
            .iter()
            .map(|k| {
                module
                    .find(&format!("pub fn {}(", k.name()))
                    .unwrap_or_else(|| panic!("the module has {k}"))
            })
            .collect();
        assert!(places.windows(2).all(|w| w[0] < w[1]), "{outputs:?}");
        outputs.reverse();
    }
}

/// The module's threads share out the kernels according to which are asked for (in scalars,
/// when ∂FD comes with ∂ID, the graph of ∂ID is built by forward sweeps on one thread and by
/// reverse sweeps on the other, the cheaper kept, and ∂FD takes the sweep chosen; in lanes
/// both are built on one): a kernel's code is the same whichever kernels come with it,
/// derivatives in scalars or in lanes, for a robot whose torque derivatives are cheaper by
/// forward sweeps (PUMA 560) and one whose are cheaper by reverse sweeps (the Panda arm).
#[test]
fn a_kernel_is_the_same_whichever_kernels_come_with_it() {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let robots = [
        (manifest.join("tests/robots/puma560.toml"), Sweep::Forward),
        (
            manifest.join("../../rne-models/robots/panda-arm.urdf"),
            Sweep::Reverse,
        ),
    ];
    for (path, sweep) in robots {
        let name = path
            .file_name()
            .expect("a file")
            .to_string_lossy()
            .into_owned();
        let mut dynamics = SymbolicDynamics::new(
            &read_robot(
                &path,
                &name,
                &Scene::default(),
                &GenerationOptions::default(),
            )
            .expect("loads"),
        );
        dynamics.inverse_dynamics_derivatives();
        assert_eq!(dynamics.derivative_sweep(), Some(sweep), "{name}");
        let derivatives = [
            Kernel::InverseDynamicsDerivatives,
            Kernel::ForwardDynamicsDerivatives,
        ];
        // Every kernel with PUMA 560; the derivatives with the Panda arm (the debug build's
        // symbolic engine is slow on its other kernels).
        let every: &[Kernel] = match sweep {
            Sweep::Forward => &Kernel::ALL,
            Sweep::Reverse => &derivatives,
        };
        let compared: &[Kernel] = match sweep {
            Sweep::Forward => &[
                Kernel::InverseDynamicsDerivatives,
                Kernel::ForwardDynamicsDerivatives,
                Kernel::ForwardDynamics,
                Kernel::MassMatrix,
                Kernel::BaseRegressor,
            ],
            Sweep::Reverse => &derivatives,
        };
        for derivative_lanes in [false, true] {
            let module = |outputs: &[Kernel]| {
                let options = GenerationOptions {
                    outputs: outputs.to_vec(),
                    derivative_lanes,
                    ..GenerationOptions::default()
                };
                let model =
                    read_robot(&path, &name, &Scene::default(), &options).expect("the robot loads");
                generate(&model, &Scene::default(), &options, &name)
                    .expect("the module generates")
                    .to_pretty_string()
            };
            let with_others = module(every);
            for &kernel in compared {
                let alone = module(&[kernel]);
                assert_eq!(
                    function(&alone, kernel.name()),
                    function(&with_others, kernel.name()),
                    "{name}: {kernel}, derivatives in lanes: {derivative_lanes}"
                );
            }
        }
    }
}

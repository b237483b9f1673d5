//! The C emitter's inputs and errors: `generate_programs` builds the programs `generate` emits,
//! and what C cannot be written is an error naming it, never a panic. (The C's values are
//! tested against the Rust kernels in `tests/tests/c_kernels.rs`.)

use std::path::PathBuf;

use rne_codegen_core::{
    emit_c, generate, generate_c, generate_programs, read_robot, CodegenError, GenerationOptions,
    Instr, Kernel, Operand, ParameterMode, ScalarType, Scene,
};
use rne_symbolic::model::Parameter;
use rne_symbolic::Symbol;

fn robot(file: &str, options: &GenerationOptions) -> rne_symbolic::RobotModel {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/robots")
        .join(file);
    read_robot(&path, file, &Scene::default(), options).unwrap()
}

/// Every kernel, with and without fused multiply-adds: the programs have the operations of
/// the functions `generate` emits (the forward dynamics' algorithm and the derivatives'
/// sweeps chosen alike).
#[test]
fn the_programs_are_those_generate_emits() {
    for fma in [false, true] {
        let options = GenerationOptions {
            outputs: Kernel::ALL.to_vec(),
            fma,
            ..GenerationOptions::default()
        };
        let model = robot("puma560.toml", &options);
        let module = generate(&model, &Scene::default(), &options, "puma560").unwrap();
        let programs = generate_programs(&model, &Scene::default(), &options, "puma560").unwrap();
        assert_eq!(programs.kernels.len(), module.kernels.len());
        for (kp, report) in programs.kernels.iter().zip(&module.kernels) {
            let (kernel, program) = (&kp.kernel, &kp.program);
            assert_eq!(*kernel, report.kernel);
            assert_eq!(program.op_count(), report.ops, "{kernel}, fma {fma}");
            assert_eq!(
                program.critical_path(),
                report.critical_path,
                "{kernel}, fma {fma}"
            );
        }
        assert_eq!(
            programs.forward_dynamics_choice,
            module.forward_dynamics_choice
        );
    }
}

fn message(error: CodegenError) -> String {
    error.to_string()
}

#[test]
fn a_scalar_other_than_double_is_an_error() {
    let options = GenerationOptions {
        scalar: ScalarType::F32,
        ..GenerationOptions::default()
    };
    let error = generate_c(
        &robot("planar-elbow.toml", &options),
        &Scene::default(),
        &options,
        "elbow",
    )
    .unwrap_err();
    assert!(message(error).contains("double"));
}

/// A program reading vector lanes, or with the wrong number of outputs, is refused with the
/// kernel's name.
#[test]
fn a_kernel_c_cannot_write_is_an_error_naming_it() {
    let options = GenerationOptions {
        outputs: vec![Kernel::InverseDynamics, Kernel::MassMatrix],
        ..GenerationOptions::default()
    };
    let model = robot("planar-elbow.toml", &options);
    let programs = generate_programs(&model, &Scene::default(), &options, "elbow").unwrap();
    assert!(emit_c(&programs, "elbow").is_ok());

    let mut lanes = programs.clone();
    let program = std::sync::Arc::make_mut(&mut lanes.kernels[1].program);
    program.instrs.push(Instr::Mul(
        Operand::Input(Symbol::Lane(0)),
        Operand::Input(Symbol::Position(0)),
    ));
    program.outputs[0] = Operand::Temp(program.instrs.len() as u32 - 1);
    let error = message(emit_c(&lanes, "elbow").unwrap_err());
    assert!(
        error.contains("`mass_matrix`") && error.contains("lanes"),
        "{error}"
    );

    let mut short = programs.clone();
    std::sync::Arc::make_mut(&mut short.kernels[0].program)
        .outputs
        .pop();
    let error = message(emit_c(&short, "elbow").unwrap_err());
    assert!(error.contains("`inverse_dynamics`"), "{error}");
}

/// Kinematics of no frame would return an empty array, which C does not have.
#[test]
fn an_empty_result_is_an_error() {
    let options = GenerationOptions {
        outputs: vec![Kernel::FramePlacements],
        frames: Some(Vec::new()),
        ..GenerationOptions::default()
    };
    let error = generate_c(
        &robot("planar-elbow.toml", &options),
        &Scene::default(),
        &options,
        "elbow",
    )
    .unwrap_err();
    let error = message(error);
    assert!(
        error.contains("`frame_placements`") && error.contains("empty"),
        "{error}"
    );
}

/// A runtime parameter must be a field name in both C and C++.
#[test]
fn a_parameter_that_cannot_be_a_c_field_is_an_error() {
    let options = GenerationOptions {
        outputs: vec![Kernel::InverseDynamics],
        parameters: ParameterMode::Runtime,
        ..GenerationOptions::default()
    };
    let model = robot("planar-elbow.toml", &options);
    let mut programs = generate_programs(&model, &Scene::default(), &options, "elbow").unwrap();
    assert!(emit_c(&programs, "elbow").is_ok());
    programs.runtime_parameters.push(Parameter {
        name: "class".to_owned(),
        value: 1.0,
    });
    let error = emit_c(&programs, "elbow").unwrap_err();
    assert!(matches!(&error, CodegenError::CParameterName(name) if name == "class"));
}

//! The build-script `Builder` and the determinism of generated code.

use std::path::PathBuf;

use rne_codegen::{
    generate_from_path, Builder, GenerationOptions, Kernel, Scene, KEEP_GENERATED_ENV,
};

fn robot_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/robots")
        .join(name)
}

fn robot() -> PathBuf {
    robot_file("irb140-3dof.toml")
}

#[test]
fn two_generations_of_the_same_spec_are_byte_identical() {
    let options = GenerationOptions::default();
    let first = generate_from_path(&robot(), &Scene::default(), &options).unwrap();
    let second = generate_from_path(&robot(), &Scene::default(), &options).unwrap();
    assert_eq!(first.source, second.source);
    assert_eq!(first.to_pretty_string(), second.to_pretty_string());
}

/// The source of the function `name` in `module`'s formatted source.
fn function_source(module: &str, name: &str) -> String {
    let start = module
        .find(&format!("pub fn {name}("))
        .expect("the function is generated");
    let end = start + module[start..].find("\n}\n").expect("the function ends");
    module[start..end].to_owned()
}

#[test]
fn a_kernel_is_the_same_code_whichever_other_kernels_are_generated() {
    // Kernels that shared one expression graph had the terms of their sums ordered by node
    // ids that depended on the kernels built before them, so adding an output changed the
    // last bits of another. Each is now built on its own.
    for robot in ["puma560.toml", "panda-arm.urdf"] {
        let path = robot_file(robot);
        let everything =
            generate_from_path(&path, &Scene::default(), &GenerationOptions::default())
                .unwrap()
                .to_pretty_string();
        for kernel in Kernel::DYNAMICS {
            let options = GenerationOptions {
                outputs: vec![kernel],
                ..GenerationOptions::default()
            };
            let alone = generate_from_path(&path, &Scene::default(), &options)
                .unwrap()
                .to_pretty_string();
            assert_eq!(
                function_source(&alone, kernel.name()),
                function_source(&everything, kernel.name()),
                "{robot}: {kernel} generated alone differs from {kernel} among all kernels"
            );
        }
    }
}

#[test]
fn a_kernel_listed_twice_is_generated_once() {
    let options = GenerationOptions {
        outputs: vec![
            Kernel::MassMatrix,
            Kernel::InverseDynamics,
            Kernel::MassMatrix,
        ],
        ..GenerationOptions::default()
    };
    let module = generate_from_path(&robot(), &Scene::default(), &options).unwrap();
    let kernels: Vec<Kernel> = module.kernels.iter().map(|r| r.kernel).collect();
    assert_eq!(kernels, [Kernel::MassMatrix, Kernel::InverseDynamics]);
    assert_eq!(
        module
            .to_pretty_string()
            .matches("pub fn mass_matrix(")
            .count(),
        1
    );
}

#[test]
fn builder_writes_the_module_to_out_dir_and_a_readable_copy_on_request() {
    let root = std::env::temp_dir().join(format!("rne-builder-test-{}", std::process::id()));
    let out_dir = root.join("out");
    let keep = root.join("keep");
    std::fs::create_dir_all(&out_dir).unwrap();
    std::env::set_var("OUT_DIR", &out_dir);
    std::env::set_var(KEEP_GENERATED_ENV, &keep);
    let builder = Builder::new(robot())
        .outputs(&[Kernel::InverseDynamics, Kernel::MassMatrix])
        .lock("q1", 0.0);
    let written = builder.write("irb140.rs").unwrap();
    assert_eq!(written, out_dir.join("irb140.rs"));
    let source = std::fs::read_to_string(&written).unwrap();
    let expected = generate_from_path(&robot(), builder.scene(), builder.options())
        .unwrap()
        .to_pretty_string();
    assert_eq!(
        source, expected,
        "the file holds the same module as the macro"
    );
    assert!(source.contains("pub const NDOF: usize = 2;"));
    assert!(source.contains("pub fn inverse_dynamics(") && source.contains("pub fn mass_matrix("));
    assert!(
        !source.contains("pub fn forward_dynamics("),
        "only the requested kernels"
    );
    assert_eq!(
        std::fs::read_to_string(keep.join("irb140.rs")).unwrap(),
        source
    );
    std::fs::remove_dir_all(&root).unwrap();
}

/// `Builder::at_rest(true)` is the macro's `at_rest: true`: the same module as the scene at
/// rest, whose functions never read q̇ (the Coriolis and centrifugal terms are gone), while the
/// default scene's inverse dynamics does read it.
#[test]
fn builder_at_rest_generates_the_static_scene_whose_functions_ignore_qd() {
    let builder = Builder::new(robot()).at_rest(true);
    assert!(builder.scene().at_rest);
    let at_rest = builder.generate().unwrap().to_pretty_string();
    let scene = Scene {
        at_rest: true,
        ..Scene::default()
    };
    let expected = generate_from_path(&robot(), &scene, &GenerationOptions::default()).unwrap();
    assert_eq!(at_rest, expected.to_pretty_string());
    for kernel in [Kernel::InverseDynamics, Kernel::CoriolisMatrix] {
        let function = function_source(&at_rest, kernel.name());
        assert!(
            !function.contains("qd["),
            "{kernel} reads qd at rest: {function}"
        );
    }
    let moving = Builder::new(robot()).generate().unwrap().to_pretty_string();
    assert!(function_source(&moving, "inverse_dynamics").contains("qd["));
}

#[test]
fn builder_reports_a_missing_robot_file_by_name() {
    let error = Builder::new("/nonexistent/arm.toml")
        .generate()
        .unwrap_err();
    assert!(
        error.to_string().contains("/nonexistent/arm.toml"),
        "{error}"
    );
}

#[test]
fn builder_code_reaches_the_runtime_through_the_crate_path_it_is_given() {
    let default = Builder::new(robot()).generate().unwrap().to_pretty_string();
    assert!(
        default.contains("::rne_codegen::__private::Real"),
        "{default}"
    );
    let renamed = Builder::new(robot())
        .crate_path("::my_reexport::rne_codegen")
        .generate()
        .unwrap()
        .to_pretty_string();
    assert!(renamed.contains("::my_reexport::rne_codegen::__private::Real"));
    assert!(
        renamed.contains("impl ::my_reexport::rne_codegen::__private::Dynamics<NQ, NV> for Model")
    );
    assert!(!renamed.contains(":: rne_codegen") && !renamed.contains(" ::rne_codegen"));
}

#[test]
fn builder_refuses_a_crate_path_that_is_not_a_path() {
    let error = Builder::new(robot())
        .crate_path("not a path")
        .generate()
        .unwrap_err();
    assert!(
        error.to_string().contains("`not a path` is not a path"),
        "{error}"
    );
}

/// A robot file with a warning: the Builder generates and reports it (printed as
/// `cargo:warning=` by `write`); `strict(true)` refuses the file naming the same place.
#[test]
fn builder_reports_warnings_and_strict_validation_makes_them_errors() {
    let path = std::env::temp_dir().join(format!("rne-builder-warn-{}.toml", std::process::id()));
    std::fs::write(
        &path,
        "name = \"t\"\n[[link]]\nname = \"upper\"\njoint = \"revolute\"\n\
         origin = { xyz = [0, 0, 0] }\naxis = [0, 0, 1]\nmass = 2\n\
         inertia = { xx = 0.01, yy = 0.01, zz = 0.05 }\n",
    )
    .unwrap();
    let (module, warnings) = Builder::new(&path).generate_with_warnings().unwrap();
    assert_eq!(module.ndof, 1);
    assert_eq!(warnings.len(), 1);
    let warning = warnings[0].to_string();
    assert!(
        warning.contains("link 'upper'") && warning.contains("triangle inequality"),
        "{warning}"
    );
    let error = Builder::new(&path).strict(true).generate().unwrap_err();
    assert_eq!(
        error.to_string(),
        format!("{warning} (an error under strict validation)")
    );
    std::fs::remove_file(&path).unwrap();
}

//! Which sines and cosines a kernel computes, and how they are batched.

use std::path::PathBuf;

use rne_codegen::{generate_from_path, GenerationOptions, Kernel, ScalarType, Scene};

fn puma560() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/robots/puma560.toml")
}

/// The angles passed to `sin_cos_array` in the emitted source of `kernel`.
fn batched_angles(kernel: Kernel, scalar: ScalarType, gravity: [f64; 3]) -> Vec<String> {
    let options = GenerationOptions {
        outputs: vec![kernel],
        scalar,
        ..GenerationOptions::default()
    };
    let scene = Scene {
        gravity: Some(gravity),
        ..Scene::default()
    };
    let source = generate_from_path(&puma560(), &scene, &options)
        .unwrap()
        .source
        .replace(' ', "");
    let start =
        source.find("sin_cos_array(&[").expect("a batched sin_cos") + "sin_cos_array(&[".len();
    let end = start + source[start..].find("])").unwrap();
    source[start..end].split(',').map(str::to_owned).collect()
}

#[test]
fn kernels_take_no_sine_of_a_joint_they_do_not_depend_on() {
    // Turning the whole arm about the first axis changes no inertia seen along the later
    // axes, so M(q) does not depend on q1; neither does the inverse dynamics while gravity
    // is along that axis (the PUMA's base z).
    let vertical = [0.0, 0.0, -9.81];
    let tail = ["q[1]", "q[2]", "q[3]", "q[4]", "q[5]"];
    assert_eq!(
        batched_angles(Kernel::MassMatrix, ScalarType::Generic, vertical),
        tail
    );
    assert_eq!(
        batched_angles(Kernel::InverseDynamics, ScalarType::Generic, vertical),
        tail
    );
    let sideways = [9.81, 0.0, 0.0];
    let all = ["q[0]", "q[1]", "q[2]", "q[3]", "q[4]", "q[5]"];
    assert_eq!(
        batched_angles(Kernel::InverseDynamics, ScalarType::Generic, sideways),
        all
    );
}

#[test]
fn f64_and_f32_kernels_batch_an_even_number_of_angles() {
    // Five angles in two-lane vectors leave one lane alone; the kernel repeats the last.
    let vertical = [0.0, 0.0, -9.81];
    for scalar in [ScalarType::F64, ScalarType::F32] {
        let angles = batched_angles(Kernel::MassMatrix, scalar, vertical);
        assert_eq!(angles, ["q[1]", "q[2]", "q[3]", "q[4]", "q[5]", "q[5]"]);
    }
    let sideways = [9.81, 0.0, 0.0];
    let angles = batched_angles(Kernel::InverseDynamics, ScalarType::F64, sideways);
    assert_eq!(angles, ["q[0]", "q[1]", "q[2]", "q[3]", "q[4]", "q[5]"]);
}

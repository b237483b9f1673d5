//! `rne emit --lang c`: the files it writes, what it prints without `--out`, the same bytes
//! from every process, and the C++ example of `examples/c` built on them (as its README
//! says) printing the Rust kernel's torques. The compilers are `$CC` (else `cc`) and `$CXX`
//! (else `c++`); without them the tests that need them say so and pass.

mod common;
use common::rne;

use std::path::{Path, PathBuf};
use std::process::Command;

/// `$var`, else `default`, if it runs.
fn compiler(var: &str, default: &str) -> Option<String> {
    let program = std::env::var(var).unwrap_or_else(|_| default.to_owned());
    let runs = Command::new(&program)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !runs {
        eprintln!("skipped: no compiler `{program}` (set {var} to one)");
    }
    runs.then_some(program)
}

/// Runs `command`, panicking with its output if it fails; returns its standard output.
fn checked(command: &mut Command) -> String {
    let output = command.output().expect("the command starts");
    assert!(
        output.status.success(),
        "{command:?} failed:\n{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("utf-8 output")
}

/// A fresh directory under the target directory; `sub` below it does not exist yet.
fn scratch(label: &str, sub: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(label);
    let _ = std::fs::remove_dir_all(&dir);
    dir.join(sub)
}

/// `-mfma` exactly when the Rust build fuses its multiply-adds (the header's rule).
fn fma_flag() -> Option<&'static str> {
    cfg!(all(target_arch = "x86_64", target_feature = "fma")).then_some("-mfma")
}

/// The example of `examples/c`, built as its README says on the files `rne emit --lang c ur5
/// --out DIR` writes (into a directory it creates), prints the torques of rne-models' UR5
/// kernel bit for bit.
#[test]
fn the_cpp_example_prints_the_rust_kernels_torques() {
    let (Some(cc), Some(cxx)) = (compiler("CC", "cc"), compiler("CXX", "c++")) else {
        return;
    };
    let dir = scratch("cli_emit_c_example", "nested/c");
    // rne-models' URDF kernels have fused multiply-adds with its feature `fma`.
    let fma = rne_models::generated::FUSED_MULTIPLY_ADD.then_some("--fma");
    let dir_text = dir.to_str().expect("a UTF-8 path");
    let mut args = vec!["emit", "--lang", "c", "ur5", "--out", dir_text];
    args.extend(fma);
    let printed = rne(&args).unwrap();
    for file in ["ur5.h", "ur5.c"] {
        assert!(dir.join(file).is_file(), "{file} not written");
        assert!(printed.contains(file), "{printed}");
    }
    let warnings = ["-Wall", "-Wextra", "-pedantic", "-Werror"];
    checked(
        Command::new(&cc)
            .args(["-std=c99", "-O2"])
            .args(warnings)
            .args(fma_flag())
            .arg("-c")
            .arg(dir.join("ur5.c"))
            .arg("-o")
            .arg(dir.join("ur5.o")),
    );
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/c/ur5_tau.cpp");
    let exe = dir.join("ur5_tau");
    checked(
        Command::new(&cxx)
            .args(["-std=c++11", "-O2"])
            .args(warnings)
            .arg("-I")
            .arg(&dir)
            .arg(&example)
            .arg(dir.join("ur5.o"))
            .arg("-o")
            .arg(&exe),
    );
    let output = checked(&mut Command::new(&exe));
    let tau: Vec<f64> = output
        .lines()
        .map(|line| line.split_whitespace().nth(1).unwrap().parse().unwrap())
        .collect();
    let (q, qd, qdd) = (
        [0.1, -1.2, 1.5, -0.4, 0.8, 0.3],
        [0.5, -0.3, 0.2, 1.0, -0.7, 0.4],
        [1.0, 0.5, -2.0, 0.3, 0.0, -1.5],
    );
    let expected = rne_models::generated::ur5::inverse_dynamics(&q, &qd, &qdd);
    assert_eq!(tau.len(), 6, "{output}");
    for (c, rust) in tau.iter().zip(expected) {
        assert_eq!(c.to_bits(), rust.to_bits(), "{output}");
    }
    assert!(output.starts_with("shoulder_pan_joint"), "{output}");
}

/// Without `--out`, the header and then the source are printed.
#[test]
fn without_out_the_header_then_the_source_is_printed() {
    let text = rne(&["emit", "--lang", "c", "panda-arm"]).unwrap();
    let guard = text.find("#ifndef PANDA_ARM_H").expect("the header");
    let include = text.find("#include \"panda_arm.h\"").expect("the source");
    assert!(guard < include);
    assert!(text.contains("void panda_arm_mass_matrix(const double q[7], double out[49]);"));
    assert!(text.contains("double panda_arm_kinetic_energy(const double q[7], const double qd[7])"));
    let runtime = rne(&[
        "emit",
        "--lang",
        "c",
        "irb140-3dof",
        "--parameters",
        "runtime",
    ])
    .unwrap();
    assert!(runtime.contains("struct irb140_3dof_params {"), "{runtime}");
    assert!(runtime.contains(
        "void irb140_3dof_inverse_dynamics(const struct irb140_3dof_params *p, const double q[3]"
    ));
}

/// Two processes write the same bytes.
#[test]
fn the_c_is_byte_identical_across_processes() {
    let emit = || {
        let output = Command::new(env!("CARGO_BIN_EXE_rne"))
            .args([
                "emit",
                "--lang",
                "c",
                "panda",
                "--outputs",
                "inverse_dynamics,forward_dynamics_derivatives",
            ])
            .output()
            .expect("rne runs");
        assert!(output.status.success());
        output.stdout
    };
    let first = emit();
    assert!(first.len() > 100_000, "the Panda's derivatives are long");
    assert_eq!(first, emit(), "two processes emitted different C");
}

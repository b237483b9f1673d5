//! `rne verify` lists every kernel the generator emits for every built-in robot, each with its
//! error and its own tolerance, and its bad arguments are one-line errors.

use std::process::Command;

use rne_codegen::Kernel;
use rne_models::BUILTIN_ROBOTS;

#[test]
fn verify_lists_all_18_kernels_of_every_builtin_robot_with_error_and_tolerance() {
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["verify", "--samples", "20"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}{stdout}",
        String::from_utf8_lossy(&output.stderr)
    );
    let lines: Vec<&str> = stdout.lines().collect();
    for robot in BUILTIN_ROBOTS {
        let start = lines
            .iter()
            .position(|l| l.starts_with(&format!("{} (", robot.name)))
            .unwrap_or_else(|| panic!("{}: no section in\n{stdout}", robot.name));
        let section = &lines[start..];
        assert!(section[0].contains("18 kernels"), "{}", section[0]);
        for kernel in Kernel::ALL {
            let row = section
                .iter()
                .take(Kernel::ALL.len() + 3)
                .find(|l| l.split_whitespace().next() == Some(kernel.name()))
                .unwrap_or_else(|| panic!("{} {kernel}: no row", robot.name));
            let fields: Vec<&str> = row.split_whitespace().collect();
            // kernel, operations, compiled (or -), jit, tolerance, verdict.
            assert_eq!(fields.len(), 6, "{row}");
            let jit: f64 = fields[3].parse().unwrap();
            let tolerance: f64 = fields[4].parse().unwrap();
            assert!(jit <= tolerance, "{row}");
            assert_eq!(fields[5], "ok", "{row}");
            let compiled = Kernel::DYNAMICS.contains(&kernel);
            assert_eq!(
                fields[2] != "-",
                compiled,
                "compiled module's kernels: {row}"
            );
        }
    }
    assert!(
        stdout.contains("all 18 kernels of 7 robots agree"),
        "{stdout}"
    );
}

#[test]
fn verify_refuses_bad_arguments_in_one_line() {
    for (args, expected) in [
        (&["verify", "pandaa"][..], "not a built-in robot"),
        (&["verify", "--tolerance=-1"], "--tolerance"),
        (&["verify", "--tolerance", "inf"], "--tolerance"),
        (&["verify", "--samples", "0"], "--samples"),
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_rne"))
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

#[test]
fn a_tolerance_below_the_errors_fails_the_run_naming_the_kernels() {
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args([
            "verify",
            "planar-elbow",
            "--samples",
            "20",
            "--tolerance",
            "1e-30",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stdout.contains("FAIL"),
        "the report is printed first: {stdout}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("kernels disagree"), "{stderr}");
    assert!(stderr.contains("planar-elbow inverse_dynamics"), "{stderr}");
}

//! What fuzzing the readers found (`tools/fuzz`, docs/fuzzing.md), each kept as a test: the
//! input, or a generator of it, and the clear error or the load it must give.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rne_symbolic::spec::{LoadOptions, SpecErrorKind};
use rne_symbolic::RobotFormat;
use rne_symbolic::{read_robot, Description};

fn regression(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_regressions")
        .join(file)
}

/// A chain of `n` revolute joints after a root link, each joint from the second on mimicking
/// the one before it (fuzz: "a chain of 3000 joints mimicking each other").
fn mimic_chain_urdf(n: usize, closing_loop: bool) -> String {
    let inertial = "<inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" \
                    iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>";
    let mut text = String::from("<robot name=\"chain\">\n<link name=\"l0\"/>\n");
    for k in 1..=n {
        let leader = match k {
            1 if closing_loop => format!("<mimic joint=\"j{n}\"/>"),
            1 => String::new(),
            _ => format!("<mimic joint=\"j{}\" multiplier=\"0.5\"/>", k - 1),
        };
        text.push_str(&format!(
            "<link name=\"l{k}\">{inertial}</link>\n<joint name=\"j{k}\" type=\"revolute\">\
             <parent link=\"l{}\"/><child link=\"l{k}\"/><axis xyz=\"0 0 1\"/>{leader}</joint>\n",
            k - 1
        ));
    }
    text + "</robot>\n"
}

/// Found by the urdf target: a chain of 3000 mimic joints took minutes to load (each
/// follower walked its chain of leaders, looking each one up by a linear search: cubic in
/// the chain's length), a hang to the user. The check is linear now: it loads at once, and a
/// loop closed over the whole chain is still found and named from its first joint.
#[test]
fn a_long_chain_of_mimic_joints_loads_at_once() {
    let start = Instant::now();
    let model = read_robot(
        Description::urdf(&mimic_chain_urdf(3000, false), "chain.urdf"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.dof(), 3000);
    let error = read_robot(
        Description::urdf(&mimic_chain_urdf(3000, true), "loop.urdf"),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Tree);
    assert_eq!(error.joint(), Some("j1"));
    assert!(
        error
            .message()
            .starts_with("the mimic joints 'j1' → 'j3000' → 'j2999'")
            && error
                .message()
                .ends_with("'j2' follow each other in a loop: one of them must be free"),
        "{}",
        &error.message()[..200]
    );
    // Tens of milliseconds; minutes before the fix.
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
}

/// Found by the urdf target: a stray byte that is not UTF-8 gave "cannot read the robot
/// file: stream did not contain valid UTF-8", naming the file but not where. The error now
/// names the line and column of the byte.
#[test]
fn a_stray_byte_names_its_line_and_column() {
    let path = regression("stray_byte.urdf");
    let error = read_robot(Description::file(&path), &LoadOptions::default()).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Io);
    assert_eq!(error.line(), Some(3));
    assert_eq!(
        error.to_string(),
        format!(
            "{}:3: the file is not UTF-8 text: byte 0xff at column 6 is not valid UTF-8 (robot \
             files are UTF-8)",
            path.display()
        )
    );
}

/// Found by the toml target: a spec truncated inside a UTF-8 character, located when read
/// from its file and when read from the bytes a caller read (`Description::bytes`).
#[test]
fn a_file_truncated_inside_a_character_names_its_line_and_column() {
    let path = regression("truncated_character.toml");
    let (bytes, origin) = (std::fs::read(&path).unwrap(), path.display().to_string());
    for error in [
        read_robot(Description::file(&path), &LoadOptions::default()).unwrap_err(),
        read_robot(
            Description::bytes(&bytes, RobotFormat::Toml, &origin),
            &LoadOptions::default(),
        )
        .unwrap_err(),
    ] {
        assert_eq!(
            error.to_string(),
            format!(
                "{}:1: the file is not UTF-8 text: it ends inside a UTF-8 character at column 21 \
                 (robot files are UTF-8)",
                path.display()
            )
        );
    }
}

/// A spec of `n` links in a chain whose principal moments (0.01, 0.01, 0.05) break the
/// triangle inequality: one warning each (fuzz: "3000 copies of link 'upper' in a chain" of
/// tests/ui/specs/triangle.toml).
fn triangle_chain_toml(n: usize) -> String {
    let mut text = String::from("name = \"chain\"\n");
    for k in 0..n {
        text.push_str(&format!(
            "\n[[link]]\nname = \"l{k}\"\njoint = \"revolute\"\nq = \"q{k}\"\n\
             origin = {{ xyz = [0, 0, 0.3] }}\naxis = [0, 0, 1]\nmass = 2\n\
             inertia = {{ xx = 0.01, yy = 0.01, zz = 0.05 }}\n"
        ));
    }
    text
}

/// Found by the toml target: 3000 links that each break the triangle inequality took over
/// 10 s to load, a hang to the user: each warning looked its link's table up by a linear
/// search and counted the newlines before it (quadratic in the file's length). Warnings are
/// now placed through an index of the tables and of the lines: at once, and on the line of
/// their field.
#[test]
fn thousands_of_warnings_are_located_at_once() {
    let start = Instant::now();
    let text = triangle_chain_toml(3000);
    let model = read_robot(
        Description::toml(&text, "chain.toml"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.warnings.len(), 3000);
    for (k, warning) in model.warnings.iter().enumerate().step_by(499) {
        // Link k's table starts on line 2 + 9k; its inertia is the table's 8th line.
        assert_eq!(warning.line(), Some(10 + 9 * k), "{warning}");
        assert_eq!(warning.link(), Some(format!("l{k}").as_str()));
        assert_eq!(warning.field(), Some("inertia"));
    }
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
}

/// The URDF reader's warnings likewise: 3000 joints of a chain, each link breaking the
/// triangle inequality, each warning on its `<link>` element's line.
#[test]
fn thousands_of_urdf_warnings_are_located_at_once() {
    let start = Instant::now();
    let mut text = String::from("<robot name=\"chain\">\n<link name=\"l0\"/>\n");
    for k in 1..=3000 {
        text.push_str(&format!(
            "<link name=\"l{k}\"><inertial><mass value=\"2\"/><inertia ixx=\"0.01\" ixy=\"0\" \
             ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.05\"/></inertial></link>\n\
             <joint name=\"j{k}\" type=\"revolute\"><parent link=\"l{}\"/>\
             <child link=\"l{k}\"/><axis xyz=\"0 0 1\"/></joint>\n",
            k - 1
        ));
    }
    text.push_str("</robot>\n");
    let model = read_robot(
        Description::urdf(&text, "chain.urdf"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.warnings.len(), 3000);
    for warning in model.warnings.iter().step_by(499) {
        let k: usize = warning.link().unwrap()[1..].parse().unwrap();
        assert_eq!(warning.line(), Some(1 + 2 * k), "{warning}");
    }
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
}

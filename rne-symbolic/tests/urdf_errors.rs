//! Every URDF the reader refuses, one test each, with the exact message: the file, the line of
//! the element, the joint or link, the field, then what is wrong (DESIGN §2: "a clear error
//! naming the joint, never a silent approximation").

use std::path::Path;

use rne_symbolic::spec::{self, LoadOptions, RobotFormat, SpecError, SpecErrorKind};

/// A valid robot: a base, two revolute joints and a fixed tool; each test breaks one thing.
const VALID: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="upper">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 0"/>
      <mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>
    </inertial>
  </link>
  <joint name="elbow" type="revolute">
    <parent link="upper"/>
    <child link="fore"/>
    <origin xyz="0.3 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
  </joint>
  <link name="fore">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <joint name="tool_joint" type="fixed">
    <parent link="fore"/>
    <child link="tool"/>
  </joint>
  <link name="tool"/>
</robot>
"#;

const FILE: &str = "robots/arm.urdf";

fn read(text: &str) -> Result<(), SpecError> {
    spec::parse_robot(text, FILE, RobotFormat::Urdf, &LoadOptions::default()).map(|_| ())
}

/// The error of `VALID` with `from` replaced by `to` (which must occur in it).
fn broken(from: &str, to: &str) -> SpecError {
    assert!(VALID.contains(from), "{from}");
    read(&VALID.replacen(from, to, 1)).expect_err("the URDF should be rejected")
}

fn check(error: SpecError, kind: SpecErrorKind, message: &str) {
    assert_eq!(error.to_string(), message);
    assert_eq!(error.kind(), kind, "{message}");
    assert_eq!(error.file(), FILE);
}

#[test]
fn the_valid_urdf_is_valid() {
    read(VALID).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn floating_joint() {
    check(
        broken(
            r#""shoulder" type="revolute""#,
            r#""shoulder" type="floating""#,
        ),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:4: joint 'shoulder', field 'type': floating joints are not supported: \
         every joint must be revolute, continuous, prismatic or fixed",
    );
}

#[test]
fn planar_joint() {
    check(
        broken(r#""elbow" type="revolute""#, r#""elbow" type="planar""#),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:17: joint 'elbow', field 'type': planar joints are not supported: \
         every joint must be revolute, continuous, prismatic or fixed",
    );
}

#[test]
fn unknown_joint_type() {
    check(
        broken(r#""elbow" type="revolute""#, r#""elbow" type="ball""#),
        SpecErrorKind::Urdf,
        "robots/arm.urdf: cannot read the URDF: unknown variant `ball`, expected one of \
         `revolute`, `continuous`, `prismatic`, `fixed`, `floating`, `planar`, `spherical`",
    );
}

#[test]
fn mimic_joint() {
    check(
        broken(
            r#"<axis xyz="0 1 0"/>"#,
            r#"<axis xyz="0 1 0"/><mimic joint="shoulder" multiplier="2"/>"#,
        ),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:17: joint 'elbow', field 'mimic': mimic joints are not supported: this \
         joint follows 'shoulder', but every moving joint must have a free variable of its own",
    );
}

#[test]
fn closed_loop_a_link_with_two_parents() {
    check(
        broken(
            "  <link name=\"tool\"/>",
            "  <link name=\"tool\"/>\n  <joint name=\"strut\" type=\"revolute\">\n    \
             <parent link=\"base\"/>\n    <child link=\"fore\"/>\n  </joint>",
        ),
        SpecErrorKind::Tree,
        "robots/arm.urdf:34: joint 'strut', field 'child': link 'fore' is already the child of \
         joint 'elbow': a link with two parents closes a loop, which a tree cannot model",
    );
}

#[test]
fn cycle_of_joints() {
    // upper -> fore -> upper, cut off from the base.
    let text = VALID.replacen(
        "<parent link=\"base\"/>\n    <child link=\"upper\"/>",
        "<parent link=\"fore\"/>\n    <child link=\"upper\"/>",
        1,
    );
    check(
        read(&text).unwrap_err(),
        SpecErrorKind::Tree,
        "robots/arm.urdf:10: link 'upper': the link is its own ancestor through the joints \
         'shoulder', 'elbow': closed loops are not supported",
    );
}

#[test]
fn joint_naming_a_missing_parent_link() {
    check(
        broken(r#"<parent link="upper"/>"#, r#"<parent link="uper"/>"#),
        SpecErrorKind::Tree,
        "robots/arm.urdf:17: joint 'elbow', field 'parent': the parent link 'uper' does not exist",
    );
}

#[test]
fn joint_naming_a_missing_child_link() {
    check(
        broken(r#"<child link="tool"/>"#, r#"<child link="gripper"/>"#),
        SpecErrorKind::Tree,
        "robots/arm.urdf:29: joint 'tool_joint', field 'child': the child link 'gripper' does \
         not exist",
    );
}

#[test]
fn several_roots() {
    check(
        broken(
            "  <link name=\"tool\"/>",
            "  <link name=\"tool\"/>\n  <link name=\"stray\"/>",
        ),
        SpecErrorKind::Tree,
        "robots/arm.urdf:34: link 'stray': several root links ('base', 'stray'): every link but \
         one must be the child of a joint",
    );
}

#[test]
fn duplicate_link_names() {
    check(
        broken(
            "  <link name=\"tool\"/>",
            "  <link name=\"tool\"/>\n  <link name=\"upper\"/>",
        ),
        SpecErrorKind::Tree,
        "robots/arm.urdf:10: link 'upper', field 'name': duplicate link name 'upper'",
    );
}

#[test]
fn duplicate_joint_names() {
    check(
        broken(r#"<joint name="tool_joint""#, r#"<joint name="elbow""#),
        SpecErrorKind::Tree,
        "robots/arm.urdf:17: joint 'elbow', field 'name': duplicate joint name 'elbow'",
    );
}

#[test]
fn no_links() {
    check(
        read("<robot name=\"empty\"></robot>").unwrap_err(),
        SpecErrorKind::Tree,
        "robots/arm.urdf: the URDF has no <link>",
    );
}

#[test]
fn nothing_moves() {
    let text = VALID.replace(r#"type="revolute""#, r#"type="fixed""#);
    check(
        read(&text).unwrap_err(),
        SpecErrorKind::Tree,
        "robots/arm.urdf: the URDF has no revolute, continuous or prismatic joint: nothing moves",
    );
}

#[test]
fn zero_axis() {
    check(
        broken(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 0 0"/>"#),
        SpecErrorKind::Kinematics,
        "robots/arm.urdf:17: joint 'elbow', field 'axis': axis must not be zero",
    );
}

#[test]
fn non_finite_origin() {
    check(
        broken(
            r#"xyz="0.3 0 0" rpy="0 0 0""#,
            r#"xyz="0.3 0 0" rpy="0 nan 0""#,
        ),
        SpecErrorKind::Physics,
        "robots/arm.urdf:17: joint 'elbow', field 'origin.rpy': origin.rpy is not finite (NaN)",
    );
}

#[test]
fn negative_mass() {
    check(
        broken(r#"<mass value="1.0"/>"#, r#"<mass value="-1.0"/>"#),
        SpecErrorKind::Physics,
        "robots/arm.urdf:23: link 'fore', field 'inertial.mass': mass must be >= 0, got -1",
    );
}

#[test]
fn inertia_not_positive_semi_definite() {
    check(
        broken(
            r#"iyy="0.02" iyz="0" izz="0.02""#,
            r#"iyy="-0.02" iyz="0" izz="0.02""#,
        ),
        SpecErrorKind::Physics,
        "robots/arm.urdf:10: link 'upper', field 'inertial.inertia': inertia is not positive \
         semi-definite: principal moments -0.02, 0.01, 0.02",
    );
}

#[test]
fn triangle_inequality_broken() {
    check(
        broken(
            r#"iyy="0.02" iyz="0" izz="0.02""#,
            r#"iyy="0.02" iyz="0" izz="0.04""#,
        ),
        SpecErrorKind::Physics,
        "robots/arm.urdf:10: link 'upper', field 'inertial.inertia': inertia breaks the triangle \
         inequality: principal moments 0.01 + 0.02 < 0.04 (a spec may set triangle_inequality = \
         false for published data that does, saying why in a comment)",
    );
}

#[test]
fn joint_name_that_is_not_a_variable_name() {
    check(
        broken(r#"<joint name="elbow""#, r#"<joint name="elbow-joint""#),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:17: joint 'elbow-joint', field 'name': joint variable 'elbow-joint' is \
         not a name (letters, digits and _, not pi, sqrt, sin, cos, Rx, Ry, Rz)",
    );
}

#[test]
fn joint_names_printed_alike() {
    check(
        broken(r#"<joint name="elbow""#, r#"<joint name="Dshoulder""#),
        SpecErrorKind::Tree,
        "robots/arm.urdf:4: joint 'shoulder', field 'name': joint variable 'shoulder' clashes \
         with the joint variable 'Dshoulder': its velocity is printed 'Dshoulder'",
    );
}

#[test]
fn malformed_xml() {
    check(
        read("<robot name=\"arm\"><link name=\"base\"></robot>").unwrap_err(),
        SpecErrorKind::Urdf,
        "robots/arm.urdf: cannot read the URDF: Elements not properly nested",
    );
}

#[test]
fn missing_element() {
    check(
        broken(r#"<mass value="1.0"/>"#, ""),
        SpecErrorKind::Urdf,
        "robots/arm.urdf: cannot read the URDF: missing field `mass`",
    );
}

#[test]
fn unknown_file_extension() {
    let error = spec::load_robot(Path::new("robots/arm.xml"), &LoadOptions::default()).unwrap_err();
    check_file(
        error,
        SpecErrorKind::UnknownFormat,
        "robots/arm.xml: cannot tell the robot format from the file name: expected a .toml or \
         .urdf extension",
    );
}

#[test]
fn missing_file() {
    let error =
        spec::load_robot(Path::new("robots/missing.urdf"), &LoadOptions::default()).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Io);
    assert!(
        error
            .to_string()
            .starts_with("robots/missing.urdf: cannot read the robot file: "),
        "{error}"
    );
}

fn check_file(error: SpecError, kind: SpecErrorKind, message: &str) {
    assert_eq!(error.to_string(), message);
    assert_eq!(error.kind(), kind);
}

/// Truncations and byte flips of a valid URDF are rejected or read, never a panic.
#[test]
fn damaged_urdfs_never_panic() {
    let bytes = VALID.as_bytes();
    for end in (0..bytes.len()).step_by(7) {
        if let Ok(text) = std::str::from_utf8(&bytes[..end]) {
            let _ = read(text);
        }
    }
    for at in (0..bytes.len()).step_by(5) {
        for replacement in [b'<', b'>', b'"', b' ', b'-', b'0', b'x'] {
            let mut damaged = bytes.to_vec();
            damaged[at] = replacement;
            if let Ok(text) = String::from_utf8(damaged) {
                let _ = read(&text);
            }
        }
    }
}

//! Every URDF the reader refuses, one test each, with the exact message: the file, the line of
//! the element, the joint or link, the field, then what is wrong (docs/design.md §2.3: "What
//! rne cannot model exactly is an error, never a silent approximation").

use std::path::Path;

use rne_symbolic::spec::{LoadOptions, SpecError, SpecErrorKind};
use rne_symbolic::{read_robot, Description};

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
    read_robot(Description::urdf(text, FILE), &LoadOptions::default()).map(|_| ())
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
        "robots/arm.urdf:17: joint 'elbow', field 'type': unknown joint type 'ball' (expected \
         revolute, continuous, prismatic, fixed, floating, planar or spherical)",
    );
}

#[test]
fn mimic_of_a_missing_joint() {
    check(
        broken(
            r#"<axis xyz="0 1 0"/>"#,
            r#"<axis xyz="0 1 0"/><mimic joint="wrist" multiplier="2"/>"#,
        ),
        SpecErrorKind::Tree,
        "robots/arm.urdf:17: joint 'elbow', field 'mimic.joint': the mimic joint follows 'wrist', \
         which is not a moving joint of the robot",
    );
}

#[test]
fn mimic_of_a_fixed_joint() {
    check(
        broken(
            r#"<axis xyz="0 1 0"/>"#,
            r#"<axis xyz="0 1 0"/><mimic joint="tool_joint"/>"#,
        ),
        SpecErrorKind::Tree,
        "robots/arm.urdf:17: joint 'elbow', field 'mimic.joint': the mimic joint follows \
         'tool_joint', which is not a moving joint of the robot",
    );
}

/// Not an error: a fixed joint has no coordinate, so its `<mimic>` is ignored, as urdfdom and
/// Pinocchio ignore it (Talos's reduced models carry such elements on their grippers).
#[test]
fn mimic_on_a_fixed_joint_is_ignored() {
    let text = VALID.replace(
        r#"<child link="tool"/>"#,
        r#"<child link="tool"/><mimic joint="elbow"/>"#,
    );
    let model = read_robot(Description::urdf(&text, FILE), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(model.links.iter().all(|l| l.mimic.is_none()));
    assert_eq!(model.joint_names(), ["shoulder", "elbow"]);
    assert!(model.warnings.is_empty());
}

#[test]
fn mimic_joints_in_a_loop() {
    let text = VALID
        .replacen(
            r#"<axis xyz="0 0 1"/>"#,
            r#"<axis xyz="0 0 1"/><mimic joint="elbow"/>"#,
            1,
        )
        .replacen(
            r#"<axis xyz="0 1 0"/>"#,
            r#"<axis xyz="0 1 0"/><mimic joint="shoulder" multiplier="-1"/>"#,
            1,
        );
    check(
        read(&text).unwrap_err(),
        SpecErrorKind::Tree,
        "robots/arm.urdf:4: joint 'shoulder', field 'mimic.joint': the mimic joints 'shoulder' → \
         'elbow' follow each other in a loop: one of them must be free",
    );
    let itself = broken(
        r#"<axis xyz="0 1 0"/>"#,
        r#"<axis xyz="0 1 0"/><mimic joint="elbow"/>"#,
    );
    assert_eq!(itself.kind(), SpecErrorKind::Tree);
    assert!(itself.message().contains("in a loop"), "{itself}");
}

#[test]
fn negative_damping() {
    check(
        broken(
            r#"<axis xyz="0 1 0"/>"#,
            r#"<axis xyz="0 1 0"/><dynamics damping="-0.5" friction="0.1"/>"#,
        ),
        SpecErrorKind::Physics,
        "robots/arm.urdf:17: joint 'elbow', field 'dynamics.damping': dynamics.damping must be \
         >= 0, got -0.5",
    );
}

#[test]
fn malformed_number() {
    check(
        broken(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 1 ${z}"/>"#),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:17: joint 'elbow', field 'axis': expected 3 numbers separated by \
         spaces, got '0 1 ${z}'",
    );
    check(
        broken(r#"<mass value="1.0"/>"#, r#"<mass value="1.0kg"/>"#),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:23: link 'fore', field 'inertial.mass': expected a number, got '1.0kg'",
    );
}

#[test]
fn non_finite_mass() {
    check(
        broken(r#"<mass value="1.0"/>"#, r#"<mass value="inf"/>"#),
        SpecErrorKind::Physics,
        "robots/arm.urdf:23: link 'fore', field 'inertial.mass': inertial.mass is not finite (inf)",
    );
}

#[test]
fn missing_parent_element() {
    check(
        broken(r#"<parent link="upper"/>"#, ""),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:17: joint 'elbow', field 'parent': the joint has no <parent link=\"..\"/>",
    );
}

#[test]
fn missing_name_attribute() {
    check(
        broken(r#"<link name="fore">"#, "<link>"),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:23: field 'name': <link> has no 'name' attribute",
    );
}

#[test]
fn root_element_that_is_not_robot() {
    check(
        read("<?xml version=\"1.0\"?>\n<sdf version=\"1.6\"/>").unwrap_err(),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:2: cannot read the URDF: the root element is <sdf>, not <robot>",
    );
}

#[test]
fn truncated_file() {
    let end = VALID.find("  <link name=\"fore\">").unwrap();
    check(
        read(&VALID[..end]).unwrap_err(),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:2: cannot read the URDF: the file ends inside an element opened here",
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

/// A URDF in which no joint moves reads; with a fixed base nothing moves (an error once the base
/// is known), with a floating base it is a 6-DOF rigid body.
#[test]
fn nothing_moves_on_a_fixed_base() {
    let text = VALID.replace(r#"type="revolute""#, r#"type="fixed""#);
    let mut model = read_robot(Description::urdf(&text, FILE), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.dof(), 0);
    assert_eq!(
        model.check_moves().unwrap_err().to_string(),
        "`arm` has no revolute, continuous or prismatic joint and a fixed base: nothing moves \
         (with a floating base it is a 6-DOF rigid body)"
    );
    model.set_base(rne_symbolic::model::Base::Floating);
    assert_eq!(model.check_moves(), Ok(()));
    assert_eq!(model.state_layout().nv(), 6);
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
fn triangle_inequality_broken_under_strict_validation() {
    let text = VALID.replacen(
        r#"iyy="0.02" iyz="0" izz="0.02""#,
        r#"iyy="0.02" iyz="0" izz="0.04""#,
        1,
    );
    let strict = LoadOptions {
        strict: true,
        ..LoadOptions::default()
    };
    check(
        read_robot(Description::urdf(&text, FILE), &strict).unwrap_err(),
        SpecErrorKind::Strict,
        "robots/arm.urdf:10: link 'upper', field 'inertial.inertia': inertia breaks the triangle \
         inequality: principal moments 0.01 + 0.02 < 0.04 (a TOML spec may set \
         triangle_inequality = false for published data that does, saying why in a comment) (an \
         error under strict validation)",
    );
}

#[test]
fn malformed_xml() {
    check(
        read("<robot name=\"arm\">\n<link name=\"base\">\n</robot>").unwrap_err(),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:3: cannot read the URDF: malformed XML: ill-formed document: expected \
         `</link>`, but `</robot>` was found",
    );
}

#[test]
fn missing_element() {
    check(
        broken(r#"<mass value="1.0"/>"#, ""),
        SpecErrorKind::Urdf,
        "robots/arm.urdf:23: link 'fore', field 'inertial.mass': the <inertial> has no <mass \
         value=\"..\"/>",
    );
}

#[test]
fn unknown_file_extension() {
    let error = read_robot(
        Description::file(Path::new("robots/arm.obj")),
        &LoadOptions::default(),
    )
    .unwrap_err();
    check_file(
        error,
        SpecErrorKind::UnknownFormat,
        "robots/arm.obj: cannot tell the robot format from the file name: expected a .toml or \
         .urdf extension",
    );
}

/// A MuJoCo model is named as such, by its extension or its root element.
#[test]
fn mjcf_is_not_supported_yet() {
    let error = read_robot(
        Description::file(Path::new("robots/arm.xml")),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::UnknownFormat);
    assert!(error.to_string().contains("MJCF"), "{error}");
    let error = read("<mujoco model=\"arm\"><worldbody/></mujoco>").unwrap_err();
    assert!(
        error
            .to_string()
            .contains("MJCF (a MuJoCo <mujoco> model) is not supported yet"),
        "{error}"
    );
}

#[test]
fn missing_file() {
    let error = read_robot(
        Description::file(Path::new("robots/missing.urdf")),
        &LoadOptions::default(),
    )
    .unwrap_err();
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

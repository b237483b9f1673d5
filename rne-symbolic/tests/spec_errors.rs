//! Every malformed-spec case of docs/design.md §2.3, and the reader's own, with the exact message:
//! the file, the line, the link and the field, then what is wrong.

use std::path::Path;

use rne_symbolic::spec::{LoadOptions, SpecError, SpecErrorKind};
use rne_symbolic::{read_robot, Description};

/// A valid two-link spec; each test breaks one thing in it.
const VALID: &str = r#"name = "arm"
[parameters]
m1 = 2.0
l1 = 0.5
[[link]]
name = "link1"
joint = "revolute"
rotation = "Rz(q1)"
position = ["l1", 0, 0]
mass = "m1"
com = [0, 0, 0]
inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }
[[link]]
name = "link2"
joint = "revolute"
dh = { a = 0.3, alpha = 0 }
mass = 1
inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }
"#;

fn read(text: &str) -> Result<(), SpecError> {
    read_robot(
        Description::toml(text, "robots/arm.toml"),
        &LoadOptions::default(),
    )
    .map(|_| ())
}

/// The error of `VALID` with `from` replaced by `to` (which must occur in it).
fn broken(from: &str, to: &str) -> SpecError {
    assert!(VALID.contains(from), "{from}");
    read(&VALID.replacen(from, to, 1)).expect_err("the spec should be rejected")
}

/// The error of `VALID` with the last occurrence of `from` replaced by `to`.
fn broken_last(from: &str, to: &str) -> SpecError {
    let at = VALID.rfind(from).expect(from);
    read(&format!(
        "{}{to}{}",
        &VALID[..at],
        &VALID[at + from.len()..]
    ))
    .expect_err("the spec should be rejected")
}

fn check(error: SpecError, kind: SpecErrorKind, message: &str) {
    assert_eq!(error.to_string(), message);
    assert_eq!(error.kind(), kind, "{message}");
    assert_eq!(error.file(), "robots/arm.toml");
}

#[test]
fn the_valid_spec_is_valid() {
    read(VALID).unwrap_or_else(|e| panic!("{e}"));
    for symbolic_parameters in [false, true] {
        read_robot(
            Description::toml(VALID, "robots/arm.toml"),
            &LoadOptions {
                symbolic_parameters,
                ..LoadOptions::default()
            },
        )
        .unwrap();
    }
}

#[test]
fn unknown_top_level_key() {
    check(
        broken("[parameters]", "colour = \"red\"\n[parameters]"),
        SpecErrorKind::Format,
        "robots/arm.toml:2: field 'colour': unknown key 'colour' (expected one of: name, gravity, base, \
         parameters, link)",
    );
}

#[test]
fn unknown_link_key() {
    check(
        broken("mass = 1\n", "mass = 1\ncolour = 3\n"),
        SpecErrorKind::Format,
        "robots/arm.toml:18: link 'link2', field 'colour': unknown key 'colour' (expected one of: name, parent, \
         joint, q, rotation, position, dh, mdh, origin, axis, mass, com, com_from_prev, inertia, \
         triangle_inequality, mimic, friction, armature)",
    );
}

#[test]
fn unknown_inertia_key() {
    check(
        broken("inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }\n[[link]]", "inertia = { xx = 0.1, yy = 0.1, zz = 0.1, xw = 0 }\n[[link]]"),
        SpecErrorKind::Format,
        "robots/arm.toml:12: link 'link1', field 'inertia.xw': unknown key 'xw' in 'inertia' (expected one of: xx, \
         yy, zz, xy, xz, yz)",
    );
}

#[test]
fn unknown_dh_key() {
    check(
        broken("alpha = 0", "beta = 0"),
        SpecErrorKind::Format,
        "robots/arm.toml:16: link 'link2', field 'dh.beta': unknown key 'beta' in 'dh' (expected one of: a, alpha, \
         d, theta)",
    );
}

#[test]
fn missing_mass() {
    check(
        broken("mass = 1\n", ""),
        SpecErrorKind::Format,
        "robots/arm.toml:13: link 'link2', field 'mass': missing required key 'mass'",
    );
}

#[test]
fn negative_mass() {
    check(
        broken("mass = 1", "mass = -3"),
        SpecErrorKind::Physics,
        "robots/arm.toml:17: link 'link2', field 'mass': mass must be >= 0, got -3",
    );
}

#[test]
fn inertia_not_symmetric() {
    check(
        broken_last("inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }", "inertia = [[1, 0.1, 0], [0.2, 1, 0], [0, 0, 1]]"),
        SpecErrorKind::Physics,
        "robots/arm.toml:18: link 'link2', field 'inertia': inertia is not symmetric: [0][1] = 0.1 but [1][0] = 0.2",
    );
}

#[test]
fn inertia_not_positive_semi_definite() {
    check(
        broken_last("{ xx = 0.1, yy = 0.1, zz = 0.1 }", "{ xx = 1, yy = 1, zz = 1, xy = 2 }"),
        SpecErrorKind::Physics,
        "robots/arm.toml:18: link 'link2', field 'inertia': inertia is not positive semi-definite: principal \
         moments -1, 1, 3",
    );
}

#[test]
fn triangle_inequality_broken_under_strict_validation() {
    let text = VALID.replace(
        "mass = 1\ninertia = { xx = 0.1, yy = 0.1, zz = 0.1 }",
        "mass = 1\ninertia = { xx = 0.066, yy = 0.086, zz = 0.0125 }",
    );
    assert_ne!(text, VALID);
    let strict = LoadOptions {
        strict: true,
        ..LoadOptions::default()
    };
    check(
        read_robot(Description::toml(&text, "robots/arm.toml"), &strict).unwrap_err(),
        SpecErrorKind::Strict,
        "robots/arm.toml:18: link 'link2', field 'inertia': inertia breaks the triangle inequality: principal \
         moments 0.0125 + 0.066 < 0.086 (a TOML spec may set triangle_inequality = false for published data \
         that does, saying why in a comment) (an error under strict validation)",
    );
}

#[test]
fn unknown_symbol() {
    check(
        broken("mass = 1", "mass = \"m2\""),
        SpecErrorKind::Expression,
        "robots/arm.toml:17: link 'link2', field 'mass': unknown symbol 'm2' in \"m2\"",
    );
}

#[test]
fn cycle_of_links() {
    check(
        broken("name = \"link1\"\n", "name = \"link1\"\nparent = \"link2\"\n"),
        SpecErrorKind::Tree,
        "robots/arm.toml:7: link 'link1', field 'parent': link 'link1' is its own ancestor: link1 -> link2 -> link1",
    );
}

#[test]
fn link_that_is_its_own_parent() {
    check(
        broken("name = \"link2\"\n", "name = \"link2\"\nparent = \"link2\"\n"),
        SpecErrorKind::Tree,
        "robots/arm.toml:15: link 'link2', field 'parent': link 'link2' is its own ancestor: link2 -> link2",
    );
}

#[test]
fn duplicate_link_names() {
    check(
        broken("name = \"link2\"", "name = \"link1\""),
        SpecErrorKind::Tree,
        "robots/arm.toml:14: link 'link1', field 'name': duplicate link name 'link1'",
    );
}

#[test]
fn errors_in_a_link_that_repeats_a_name_point_at_that_link() {
    let text = VALID
        .replacen("name = \"link2\"", "name = \"link1\"", 1)
        .replacen("mass = 1\n", "", 1);
    check(
        read(&text).unwrap_err(),
        SpecErrorKind::Format,
        "robots/arm.toml:13: link 'link1', field 'mass': missing required key 'mass'",
    );
}

#[test]
fn duplicate_joint_names() {
    check(
        broken("name = \"link2\"\n", "name = \"link2\"\nq = \"q1\"\n"),
        SpecErrorKind::Tree,
        "robots/arm.toml:15: link 'link2', field 'q': duplicate joint variable 'q1': already joint variable 'q1' of \
         link 'link1'",
    );
}

#[test]
fn joint_variable_missing_from_revolute_rotation() {
    check(
        broken("rotation = \"Rz(q1)\"", "rotation = \"Rz(pi/2)\""),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:8: link 'link1', field 'rotation': joint variable 'q1' missing from rotation: a revolute \
         joint needs one factor Rx, Ry or Rz of ±q1 + c",
    );
}

#[test]
fn revolute_rotation_omitted() {
    check(
        broken("rotation = \"Rz(q1)\"\n", ""),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:5: link 'link1', field 'rotation': joint variable 'q1' missing from rotation: a revolute \
         joint needs one factor Rx, Ry or Rz of ±q1 + c",
    );
}

#[test]
fn joint_variable_not_of_the_form_plus_minus_q_plus_c() {
    check(
        broken("rotation = \"Rz(q1)\"", "rotation = \"Rz(2*q1)\""),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:8: link 'link1', field 'rotation': joint variable 'q1' must enter as ±q1 + c with c free of \
         q1, found (* 2 q1)",
    );
}

#[test]
fn long_joint_angles_are_reported_without_printing_them() {
    let angle = format!("2*q1{}", " + m1".repeat(20_000));
    check(
        broken("rotation = \"Rz(q1)\"", &format!("rotation = \"Rz({angle})\"")),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:8: link 'link1', field 'rotation': joint variable 'q1' must enter as ±q1 + c with c free of \
         q1",
    );
}

#[test]
fn two_frame_conventions() {
    check(
        broken("dh = {", "rotation = \"Rz(q2)\"\ndh = {"),
        SpecErrorKind::Format,
        "robots/arm.toml:13: link 'link2': two frame conventions, rotation/position and dh: give exactly one of \
         rotation/position, dh, mdh or origin/axis",
    );
}

#[test]
fn no_frame_convention() {
    check(
        broken("dh = { a = 0.3, alpha = 0 }\n", ""),
        SpecErrorKind::Format,
        "robots/arm.toml:13: link 'link2': no frame convention: give one of rotation/position, dh, mdh or \
         origin/axis",
    );
}

#[test]
fn unknown_joint_kind() {
    check(
        broken("joint = \"revolute\"\ndh", "joint = \"rotary\"\ndh"),
        SpecErrorKind::Format,
        "robots/arm.toml:15: link 'link2', field 'joint': unknown joint kind 'rotary' (expected revolute, prismatic \
         or fixed)",
    );
}

#[test]
fn malformed_expression() {
    check(
        broken("mass = \"m1\"", "mass = \"m1 +\""),
        SpecErrorKind::Expression,
        "robots/arm.toml:10: link 'link1', field 'mass': malformed expression \"m1 +\": expected a number, a name or \
         '(' at the end",
    );
}

#[test]
fn non_integer_power() {
    check(
        broken("mass = \"m1\"", "mass = \"m1^1.5\""),
        SpecErrorKind::Expression,
        "robots/arm.toml:10: link 'link1', field 'mass': non-integer power in \"m1^1.5\": an exponent must be an \
         integer or 0.5, got 1.5",
    );
}

#[test]
fn parameter_cycle() {
    check(
        broken("m1 = 2.0\nl1 = 0.5", "m1 = \"2 * l1\"\nl1 = \"m1 / 4\""),
        SpecErrorKind::Expression,
        "robots/arm.toml:3: field 'parameters.m1': parameter cycle: m1 -> l1 -> m1",
    );
}

#[test]
fn invalid_toml_syntax() {
    let error = broken("name = \"arm\"", "name = \"arm");
    assert_eq!(error.kind(), SpecErrorKind::Syntax);
    let message = error.to_string();
    assert!(
        message.starts_with("robots/arm.toml:1: invalid TOML: "),
        "{message}"
    );
    let error = broken("m1 = 2.0", "m1 = 2.0\nm1 = 3.0");
    assert!(
        error
            .to_string()
            .starts_with("robots/arm.toml:4: invalid TOML: "),
        "{error}"
    );
}

#[test]
fn another_links_joint_variable() {
    check(
        broken("alpha = 0 }", "alpha = 0, theta = \"q1\" }"),
        SpecErrorKind::Expression,
        "robots/arm.toml:16: link 'link2', field 'dh.theta': joint variable 'q1' of link 'link1' may not appear here \
         in \"q1\"",
    );
}

#[test]
fn own_joint_variable_outside_the_frame_convention() {
    check(
        broken("mass = 1", "mass = \"1 + q2\""),
        SpecErrorKind::Expression,
        "robots/arm.toml:17: link 'link2', field 'mass': joint variable 'q2' may not appear here in \"1 + q2\"",
    );
}

#[test]
fn joint_variable_in_the_wrong_dh_entry() {
    check(
        broken("a = 0.3", "a = \"0.3 + q2\""),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:16: link 'link2', field 'dh.a': joint variable 'q2' may appear only in dh.theta",
    );
}

#[test]
fn unknown_parent() {
    check(
        broken(
            "name = \"link2\"\n",
            "name = \"link2\"\nparent = \"link7\"\n",
        ),
        SpecErrorKind::Tree,
        "robots/arm.toml:15: link 'link2', field 'parent': unknown parent 'link7'",
    );
}

#[test]
fn no_links() {
    let error = read("name = \"arm\"\n").unwrap_err();
    check(
        error,
        SpecErrorKind::Tree,
        "robots/arm.toml: field 'link': the spec has no [[link]]",
    );
}

#[test]
fn missing_name() {
    check(
        broken("name = \"arm\"\n", ""),
        SpecErrorKind::Format,
        "robots/arm.toml: field 'name': missing required key 'name'",
    );
}

#[test]
fn value_of_the_wrong_type() {
    check(
        broken("mass = 1", "mass = true"),
        SpecErrorKind::Format,
        "robots/arm.toml:17: link 'link2', field 'mass': expected a number or an expression string, found a boolean",
    );
    check(
        broken("com = [0, 0, 0]", "com = [0, 0]"),
        SpecErrorKind::Format,
        "robots/arm.toml:11: link 'link1', field 'com': expected an array of 3 elements, found 2",
    );
}

#[test]
fn links_as_a_single_table() {
    let text = "name = \"arm\"\n[link]\nname = \"a\"\n";
    check(
        read(text).unwrap_err(),
        SpecErrorKind::Format,
        "robots/arm.toml:2: field 'link': expected an array of tables [[link]], found a table",
    );
}

#[test]
fn base_is_not_a_link() {
    check(
        broken("name = \"link1\"", "name = \"base\""),
        SpecErrorKind::Tree,
        "robots/arm.toml:6: link 'base', field 'name': 'base' names the fixed base; choose another link name",
    );
}

#[test]
fn fixed_joints_have_no_variable() {
    check(
        broken(
            "joint = \"revolute\"\ndh",
            "joint = \"fixed\"\nq = \"q2\"\ndh",
        ),
        SpecErrorKind::Format,
        "robots/arm.toml:16: link 'link2', field 'q': a fixed joint has no joint variable",
    );
}

#[test]
fn joint_variable_clashes_with_a_parameter() {
    check(
        broken("name = \"link2\"\n", "name = \"link2\"\nq = \"m1\"\n"),
        SpecErrorKind::Tree,
        "robots/arm.toml:15: link 'link2', field 'q': joint variable 'm1' clashes with the parameter 'm1'",
    );
    check(
        broken("l1 = 0.5", "l1 = 0.5\nDq2 = 1"),
        SpecErrorKind::Tree,
        "robots/arm.toml:14: link 'link2', field 'q': joint variable 'q2' clashes with the parameter 'Dq2': its \
         velocity is printed 'Dq2'",
    );
}

#[test]
fn names_must_be_identifiers_and_not_reserved() {
    check(
        broken("l1 = 0.5", "\"l 1\" = 0.5"),
        SpecErrorKind::Format,
        "robots/arm.toml:4: field 'parameters.l 1': parameter name 'l 1' is not a name (letters, digits and _, \
         not pi, sqrt, sin, cos, Rx, Ry, Rz)",
    );
    check(
        broken("name = \"link2\"\n", "name = \"link2\"\nq = \"pi\"\n"),
        SpecErrorKind::Format,
        "robots/arm.toml:15: link 'link2', field 'q': joint variable 'pi' is not a name (letters, digits and _, \
         not pi, sqrt, sin, cos, Rx, Ry, Rz)",
    );
}

#[test]
fn com_given_twice_or_in_the_wrong_convention() {
    check(
        broken("com = [0, 0, 0]", "com = [0, 0, 0]\ncom_from_prev = [0, 0, 0]"),
        SpecErrorKind::Format,
        "robots/arm.toml:12: link 'link1', field 'com_from_prev': give either com or com_from_prev, not both",
    );
    check(
        broken("mass = 1", "mass = 1\ncom_from_prev = [0, 0, 0]"),
        SpecErrorKind::Format,
        "robots/arm.toml:18: link 'link2', field 'com_from_prev': com_from_prev belongs to the rotation/position \
         convention; use com",
    );
}

#[test]
fn numbers_must_be_finite() {
    check(
        broken("mass = 1", "mass = \"1 / 0\""),
        SpecErrorKind::Physics,
        "robots/arm.toml:17: link 'link2', field 'mass': mass is not finite (inf)",
    );
    check(
        broken("mass = 1", "mass = nan"),
        SpecErrorKind::Physics,
        "robots/arm.toml:17: link 'link2', field 'mass': NaN is not a finite number",
    );
    check(
        broken("l1 = 0.5", "l1 = \"sqrt(-1)\""),
        SpecErrorKind::Physics,
        "robots/arm.toml:4: field 'parameters.l1': parameter 'l1' is not finite: NaN",
    );
}

#[test]
fn prismatic_axis_must_be_unit() {
    check(
        broken("joint = \"revolute\"\nrotation = \"Rz(q1)\"\nposition = [\"l1\", 0, 0]", "joint = \"prismatic\"\nposition = [\"l1\", 0, \"2 * q1\"]"),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:8: link 'link1', field 'position': the joint axis must be a unit vector, got length 2",
    );
}

#[test]
fn urdf_axis_must_not_be_zero() {
    check(
        broken("dh = { a = 0.3, alpha = 0 }", "axis = [0, 0, 0]"),
        SpecErrorKind::Kinematics,
        "robots/arm.toml:16: link 'link2', field 'axis': axis must not be zero",
    );
}

#[test]
fn unreadable_file() {
    let error = read_robot(
        Description::file(Path::new("/nonexistent/robot.toml")),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Io);
    assert!(
        error
            .to_string()
            .starts_with("/nonexistent/robot.toml: cannot read the robot file: "),
        "{error}"
    );
}

#[test]
fn errors_expose_their_parts() {
    let error = broken("mass = 1", "mass = -3");
    assert_eq!(error.line(), Some(17));
    assert_eq!(error.link(), Some("link2"));
    assert_eq!(error.field(), Some("mass"));
    assert_eq!(error.message(), "mass must be >= 0, got -3");
}

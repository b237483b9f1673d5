//! Graded validation (docs/design.md §2.4), for both readers: what published data often gets
//! slightly wrong is a warning with the location of an error — a broken triangle inequality, a
//! negative principal moment negligible against the robot's inertia scale, a moving joint that
//! carries no mass — and strict validation makes each of them an error; a clearly negative
//! principal moment stays an error.

use rne_symbolic::input::NEGLIGIBLE_INERTIA;
use rne_symbolic::spec::{self, LoadOptions, SpecErrorKind, SpecWarningKind};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

const STRICT: LoadOptions = LoadOptions {
    symbolic_parameters: false,
    strict: true,
    free_mimic: false,
    exact_right_angles: true,
};

/// Two revolute links; `{upper}` and `{fore}` are the `<inertia>` attributes of each.
fn urdf(upper: &str, fore: &str) -> String {
    format!(
        r#"<robot name="arm">
  <link name="base"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
  </joint>
  <link name="upper">
    <inertial>
      <mass value="2.0"/>
      <inertia {upper}/>
    </inertial>
  </link>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
  </joint>
  <link name="fore">
    <inertial>
      <mass value="1.0"/>
      <inertia {fore}/>
    </inertial>
  </link>
</robot>
"#
    )
}

const GOOD: &str = r#"ixx="0.5" ixy="0" ixz="0" iyy="0.5" iyz="0" izz="0.5""#;

fn read_urdf(text: &str, options: &LoadOptions) -> Result<RobotModel, spec::SpecError> {
    read_robot(Description::urdf(text, "robots/arm.urdf"), options)
}

fn warnings(model: &RobotModel) -> Vec<(SpecWarningKind, String)> {
    model
        .warnings
        .iter()
        .map(|w| (w.kind(), w.to_string()))
        .collect()
}

#[test]
fn a_valid_robot_has_no_warnings() {
    let model = read_urdf(&urdf(GOOD, GOOD), &STRICT).unwrap();
    assert!(model.warnings.is_empty());
}

#[test]
fn triangle_inequality_is_a_warning_in_a_urdf() {
    let text = urdf(
        GOOD,
        r#"ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.04""#,
    );
    let model = read_urdf(&text, &LoadOptions::default()).unwrap();
    assert_eq!(
        warnings(&model),
        [(
            SpecWarningKind::TriangleInequality,
            "robots/arm.urdf:15: link 'fore', field 'inertial.inertia': inertia breaks the \
             triangle inequality: principal moments 0.01 + 0.02 < 0.04 (a TOML spec may set \
             triangle_inequality = false for published data that does, saying why in a comment)"
                .to_owned()
        )]
    );
    let error = read_urdf(&text, &STRICT).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Strict);
    assert_eq!(error.line(), Some(15));
}

#[test]
fn a_negligible_negative_principal_moment_is_a_warning() {
    // Tiago's antenna: -1e-8 against a robot whose largest moment is 0.5.
    let text = urdf(
        GOOD,
        r#"ixx="-1e-8" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="2e-5""#,
    );
    let model = read_urdf(&text, &LoadOptions::default()).unwrap();
    let found = warnings(&model);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, SpecWarningKind::NegligibleNegativeInertia);
    assert_eq!(
        found[0].1,
        "robots/arm.urdf:15: link 'fore', field 'inertial.inertia': inertia has a negative \
         principal moment, negligible against the robot's largest principal moment 0.5 (at most \
         1e-6 of it): principal moments -0.00000001, 0.00002, 0.00002"
    );
    assert_eq!(
        read_urdf(&text, &STRICT).unwrap_err().kind(),
        SpecErrorKind::Strict
    );
}

#[test]
fn a_negative_principal_moment_beyond_the_tolerance_is_an_error() {
    let moment = -2.0 * NEGLIGIBLE_INERTIA * 0.5;
    let text = urdf(
        GOOD,
        &format!(r#"ixx="{moment}" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1""#),
    );
    let error = read_urdf(&text, &LoadOptions::default()).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Physics);
    assert_eq!(
        error.to_string(),
        "robots/arm.urdf:15: link 'fore', field 'inertial.inertia': inertia is not positive \
         semi-definite: principal moments -0.000001, 0.1, 0.1"
    );
}

#[test]
fn a_joint_that_moves_no_mass_is_a_warning() {
    let text = urdf(GOOD, GOOD).replace(
        "<inertial>\n      <mass value=\"1.0\"/>",
        "<inertial>\n      <mass value=\"0\"/>",
    );
    let text = text.replace(
        &format!("<mass value=\"0\"/>\n      <inertia {GOOD}/>"),
        "<mass value=\"0\"/>\n      <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/>",
    );
    let model = read_urdf(&text, &LoadOptions::default()).unwrap();
    assert_eq!(
        warnings(&model),
        [(
            SpecWarningKind::MasslessSubtree,
            "robots/arm.urdf:12: joint 'elbow': the joint moves no mass: link 'fore' and every \
             link beyond it have zero mass and inertia, so M(q) is singular and forward dynamics \
             is undefined (the joint is kept for kinematics)"
                .to_owned()
        )]
    );
    assert_eq!(model.dof(), 2);
    assert_eq!(
        read_urdf(&text, &STRICT).unwrap_err().kind(),
        SpecErrorKind::Strict
    );
}

const TOML: &str = r#"name = "arm"
[[link]]
name = "l1"
joint = "revolute"
rotation = "Rz(q1)"
mass = 1
inertia = { xx = 0.066, yy = 0.086, zz = 0.0125 }
[[link]]
name = "l2"
joint = "revolute"
rotation = "Rz(q2)"
position = [0.3, 0, 0]
mass = 1
inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }
"#;

#[test]
fn triangle_inequality_is_a_warning_in_a_toml_spec_unless_turned_off() {
    let model = read_robot(
        Description::toml(TOML, "robots/arm.toml"),
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(
        warnings(&model),
        [(
            SpecWarningKind::TriangleInequality,
            "robots/arm.toml:7: link 'l1', field 'inertia': inertia breaks the triangle \
             inequality: principal moments 0.0125 + 0.066 < 0.086 (a TOML spec may set \
             triangle_inequality = false for published data that does, saying why in a comment)"
                .to_owned()
        )]
    );
    let off = TOML.replace(
        "mass = 1\ninertia = { xx = 0.066",
        "mass = 1\ntriangle_inequality = false\ninertia = { xx = 0.066",
    );
    let model = read_robot(Description::toml(&off, "robots/arm.toml"), &STRICT).unwrap();
    assert!(model.warnings.is_empty());
    let error = read_robot(Description::toml(TOML, "robots/arm.toml"), &STRICT).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Strict);
}

#[test]
fn a_massless_moving_link_is_a_warning_in_a_toml_spec() {
    let text = TOML.replace(
        "mass = 1\ninertia = { xx = 0.1, yy = 0.1, zz = 0.1 }",
        "mass = 0\ninertia = { xx = 0, yy = 0, zz = 0 }",
    );
    let text = text.replace(
        "mass = 1\ninertia = { xx = 0.066",
        "mass = 1\ntriangle_inequality = false\ninertia = { xx = 0.066",
    );
    let model = read_robot(
        Description::toml(&text, "robots/arm.toml"),
        &LoadOptions::default(),
    )
    .unwrap();
    let found = warnings(&model);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, SpecWarningKind::MasslessSubtree);
    assert!(
        found[0]
            .1
            .starts_with("robots/arm.toml:9: link 'l2': the joint moves no mass"),
        "{}",
        found[0].1
    );
}

/// A follower whose `<mimic>` names a joint the robot does not have (as
/// `alex_psyonic_hands.urdf` of example-robot-data does): an error with mimic joints
/// constrained; with mimic joints free the tag is dropped with a warning naming the joint and
/// the follower is a joint of its own; strict validation makes that warning an error.
#[test]
fn a_mimic_of_a_missing_joint_is_dropped_with_a_warning_when_mimic_joints_are_free() {
    let text = r#"<robot name="hand">
  <link name="palm"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="finger"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="finger_q2" type="revolute">
    <parent link="palm"/><child link="finger"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="finger_q1" multiplier="1"/>
  </joint>
</robot>"#;
    let read = |options: LoadOptions| read_robot(Description::urdf(text, "hand.urdf"), &options);
    let refused = read(LoadOptions::default()).unwrap_err();
    assert!(
        refused.to_string().contains("follows 'finger_q1'"),
        "{refused}"
    );

    let free = LoadOptions {
        free_mimic: true,
        ..LoadOptions::default()
    };
    let model = read(free).expect("loads with mimic joints free");
    assert_eq!(model.dof(), 1, "the follower is a joint of its own");
    let [warning] = &model.warnings[..] else {
        panic!("one warning expected: {:?}", model.warnings);
    };
    assert_eq!(warning.kind(), SpecWarningKind::MimicLeaderMissing);
    let message = warning.to_string();
    assert!(
        message.contains("hand.urdf:")
            && message.contains("finger_q2")
            && message.contains("finger_q1"),
        "{message}"
    );

    let strict = read(LoadOptions {
        strict: true,
        ..free
    })
    .unwrap_err();
    assert_eq!(strict.kind(), SpecErrorKind::Strict, "{strict}");
}

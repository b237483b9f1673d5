//! The TOML keys for what real robots need (docs/design.md §2.1): `base`, and per link `mimic`,
//! `friction` and `armature` — read into the model as expressions over the parameters, checked
//! finite, friction coefficients and armature non-negative, mimic leaders existing and free of
//! loops.

use rne_symbolic::model::Base;
use rne_symbolic::spec::{self, LoadOptions, SpecErrorKind};
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{Id, RobotModel, Symbol};

const ARM: &str = r#"name = "arm"
[parameters]
k = 2.0
fv = 0.3
[[link]]
name = "l1"
joint = "revolute"
rotation = "Rz(q1)"
mass = 1
inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }
[[link]]
name = "l2"
joint = "revolute"
rotation = "Rz(q2)"
position = [0.3, 0, 0]
mass = 1
inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }
"#;

fn read(text: &str, symbolic: bool) -> Result<RobotModel, spec::SpecError> {
    let options = LoadOptions {
        symbolic_parameters: symbolic,
        ..LoadOptions::default()
    };
    read_robot(Description::toml(text, "robots/arm.toml"), &options)
}

/// `ARM` with `line` added to link l2.
fn with_l2(line: &str) -> String {
    format!("{ARM}{line}\n")
}

fn value(model: &RobotModel, id: Id) -> f64 {
    let values = model.graph.eval::<f64>(&[id], |s| match s {
        Symbol::Parameter(k) => model.parameters[k as usize].value,
        _ => f64::NAN,
    });
    values[0]
}

#[test]
fn base_defaults_to_fixed_and_reads_floating() {
    assert_eq!(read(ARM, false).unwrap().base, Base::Fixed);
    let floating = format!("base = \"floating\"\n{ARM}");
    assert_eq!(read(&floating, false).unwrap().base, Base::Floating);
    let error = read(&format!("base = \"flying\"\n{ARM}"), false).unwrap_err();
    assert_eq!(
        error.to_string(),
        "robots/arm.toml:1: field 'base': unknown base 'flying' (expected fixed or floating)"
    );
}

#[test]
fn mimic_is_read_with_expressions_and_defaults() {
    for symbolic in [false, true] {
        let model = read(
            &with_l2(r#"mimic = { joint = "q1", multiplier = "-k", offset = "pi/4" }"#),
            symbolic,
        )
        .unwrap();
        let mimic = model.links[1].mimic.clone().unwrap();
        assert_eq!(mimic.leader, "q1");
        assert_eq!(value(&model, mimic.multiplier), -2.0);
        assert_eq!(value(&model, mimic.offset), std::f64::consts::FRAC_PI_4);
        // The follower keeps its own variable until mimic joints are constrained.
        assert_eq!(model.dof(), 2);
        assert!(model.links[1].coupling.is_none());
    }
    let model = read(&with_l2(r#"mimic = { joint = "q1" }"#), false).unwrap();
    let mimic = model.links[1].mimic.clone().unwrap();
    assert_eq!(model.graph.as_const(mimic.multiplier), Some(1.0));
    assert_eq!(model.graph.as_const(mimic.offset), Some(0.0));
    assert!(model.links[0].mimic.is_none());
}

#[test]
fn mimic_errors() {
    let check = |line: &str, kind: SpecErrorKind, message: &str| {
        let error = read(&with_l2(line), false).unwrap_err();
        assert_eq!(error.to_string(), message);
        assert_eq!(error.kind(), kind, "{message}");
    };
    check(
        r#"mimic = { joint = "q7" }"#,
        SpecErrorKind::Tree,
        "robots/arm.toml:18: link 'l2', field 'mimic.joint': the mimic joint follows 'q7', which \
         is not a moving joint of the robot",
    );
    check(
        r#"mimic = { joint = "q2" }"#,
        SpecErrorKind::Tree,
        "robots/arm.toml:18: link 'l2', field 'mimic.joint': the mimic joints 'q2' follow each \
         other in a loop: one of them must be free",
    );
    check(
        r#"mimic = { joint = "q1", gain = 2 }"#,
        SpecErrorKind::Format,
        "robots/arm.toml:18: link 'l2', field 'mimic.gain': unknown key 'gain' in 'mimic' (expected one of: \
         joint, multiplier, offset)",
    );
    check(
        r#"mimic = { joint = "q1", multiplier = "1/0" }"#,
        SpecErrorKind::Physics,
        "robots/arm.toml:18: link 'l2', field 'mimic.multiplier': mimic.multiplier is not finite \
         (inf)",
    );
    let looped = ARM
        .replace(
            "rotation = \"Rz(q1)\"",
            "rotation = \"Rz(q1)\"\nmimic = { joint = \"q2\" }",
        )
        .replace(
            "rotation = \"Rz(q2)\"",
            "rotation = \"Rz(q2)\"\nmimic = { joint = \"q1\" }",
        );
    let error = read(&looped, false).unwrap_err();
    assert_eq!(
        error.message(),
        "the mimic joints 'q1' → 'q2' follow each other in a loop: one of them must be free"
    );
    let fixed = format!(
        "{ARM}[[link]]\nname = \"tool\"\njoint = \"fixed\"\nposition = [0.1, 0, 0]\nmass = 0\n\
         inertia = {{ xx = 0, yy = 0, zz = 0 }}\nmimic = {{ joint = \"q1\" }}\n"
    );
    let error = read(&fixed, false).unwrap_err();
    assert_eq!(error.kind(), SpecErrorKind::Kinematics);
    assert_eq!(
        error.message(),
        "a fixed joint cannot mimic another joint: it has no coordinate"
    );
}

#[test]
fn friction_and_armature_are_read_with_defaults() {
    let model = read(
        &with_l2("friction = { viscous = \"fv\", coulomb = 0.5 }\narmature = \"k / 10\""),
        true,
    )
    .unwrap();
    let friction = model.links[1].friction.unwrap();
    assert_eq!(value(&model, friction.viscous), 0.3);
    assert_eq!(value(&model, friction.coulomb), 0.5);
    assert_eq!(value(&model, friction.offset), 0.0);
    assert_eq!(value(&model, model.links[1].armature.unwrap()), 0.2);
    assert!(model.links[0].friction.is_none() && model.links[0].armature.is_none());
    let model = read(&with_l2("friction = { offset = -0.1 }"), false).unwrap();
    let friction = model.links[1].friction.unwrap();
    assert_eq!(model.graph.as_const(friction.offset), Some(-0.1));
    assert_eq!(model.graph.as_const(friction.viscous), Some(0.0));
}

#[test]
fn negative_or_non_finite_friction_and_armature_are_errors() {
    let check = |line: &str, message: &str| {
        let error = read(&with_l2(line), false).unwrap_err();
        assert_eq!(error.kind(), SpecErrorKind::Physics, "{error}");
        assert_eq!(error.to_string(), message);
    };
    check(
        "friction = { viscous = -0.3 }",
        "robots/arm.toml:18: link 'l2', field 'friction.viscous': friction.viscous must be >= 0, \
         got -0.3",
    );
    check(
        "friction = { coulomb = \"-fv\" }",
        "robots/arm.toml:18: link 'l2', field 'friction.coulomb': friction.coulomb must be >= 0, \
         got -0.3",
    );
    check(
        "armature = -1",
        "robots/arm.toml:18: link 'l2', field 'armature': armature must be >= 0, got -1",
    );
    check(
        "armature = \"sqrt(-1)\"",
        "robots/arm.toml:18: link 'l2', field 'armature': armature is not finite (NaN)",
    );
}

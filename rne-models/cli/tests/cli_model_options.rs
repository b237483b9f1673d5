//! The model options every command taking a MODEL has (docs/design.md §5): `--mimic free` and
//! `--floating-base`, on `check`, `eval`, `emit`, `stats` and `show`, and a robot without moving joints.

mod common;
use common::rne;

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&rne(args).unwrap_or_else(|e| panic!("{args:?}: {e}"))).unwrap()
}

/// Writes `text` to a file of the tests' scratch directory and returns its path.
fn scratch(name: &str, text: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// The built-in Panda with its second finger a `<mimic>` of the first, as franka_description
/// publishes it, in a file of its own for each test (tests run in parallel).
fn panda_with_mimic_fingers(test: &str) -> String {
    let text = rne_models::builtin("panda").unwrap().source;
    let joint = r#"<joint name="panda_finger_joint2" type="prismatic">"#;
    assert!(text.contains(joint));
    let text = text.replace(
        joint,
        &format!(r#"{joint}<mimic joint="panda_finger_joint1"/>"#),
    );
    scratch(&format!("panda_mimic_{test}.urdf"), &text)
}

fn flat(value: &serde_json::Value) -> Vec<f64> {
    match value {
        serde_json::Value::Array(items) => items.iter().flat_map(flat).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

fn assert_close(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= 1e-11 * scale, "{what}: {x} vs {y}");
    }
}

#[test]
fn panda_fingers_are_8_variables_constrained_9_free_and_6_more_floating() {
    let path = panda_with_mimic_fingers("check");
    let constrained = json(&["check", &path, "--json"]);
    assert_eq!(constrained["dof"], 8);
    assert_eq!(
        constrained["mimic"],
        serde_json::json!(["panda_finger_joint2"])
    );
    let free = json(&["check", &path, "--mimic", "free", "--json"]);
    assert_eq!(free["dof"], 9);
    assert_eq!(free["joints"][8], "panda_finger_joint2");
    let floating = json(&["check", &path, "--floating-base", "--json"]);
    assert_eq!(floating["base"], "floating");
    assert_eq!(
        (&floating["dof"], &floating["nq"], &floating["nv"]),
        (
            &serde_json::json!(8),
            &serde_json::json!(15),
            &serde_json::json!(14)
        )
    );
}

#[test]
fn emit_and_stats_follow_the_mimic_option() {
    let path = panda_with_mimic_fingers("emit");
    let outputs = ["--outputs", "gravity_torques"];
    let constrained = rne(&[&["emit", &path][..], &outputs].concat()).unwrap();
    assert!(constrained.contains("pub const NDOF: usize = 8;"));
    let free = rne(&[&["emit", &path, "--mimic", "free"][..], &outputs].concat()).unwrap();
    assert!(free.contains("pub const NDOF: usize = 9;"));
    let floating = rne(&[&["emit", &path, "--floating-base"][..], &outputs].concat()).unwrap();
    assert!(floating.contains("pub const NQ: usize = 15;"));
    assert!(floating.contains("pub const NV: usize = 14;"));
    assert_eq!(
        json(&["stats", &path, "--mimic", "free", "--json"])["dof"],
        9
    );
}

/// On a floating base the symbolic engine and the numeric reference agree at a state of NQ
/// positions and NV rates, for a file and for a built-in robot (whose compiled kernels are
/// fixed-base: the expression graph stands in for them).
#[test]
fn eval_on_a_floating_base_takes_nq_positions_and_engines_agree() {
    let path = panda_with_mimic_fingers("eval");
    let q = "0.1,-0.2,0.3,0.1,0.2,-0.3,0.927361849549570,0.1,-0.4,0.2,-1.8,0.3,1.5,0.6,0.02";
    let v = "0.3,-0.1,0.2,0.5,-0.4,0.1,1,-0.5,0.3,0.2,-0.7,0.4,0.1,0.05";
    let tau = "1,2,3,0.5,-0.5,0.2,1,-2,3,-4,1,0.5,0.2,1";
    for (model, mimic) in [(path.as_str(), "constrained"), ("panda", "free")] {
        let (q, v, tau) = if mimic == "free" {
            (
                format!("{q},0.02"),
                format!("{v},-0.05"),
                format!("{tau},2"),
            )
        } else {
            (q.to_owned(), v.to_owned(), tau.to_owned())
        };
        let args = [
            "eval",
            model,
            "--floating-base",
            "--mimic",
            mimic,
            "--q",
            &q,
            "--qd",
            &v,
            "--qdd",
            &v,
            "--tau",
            &tau,
            "--what",
            "tau,M,g,bias,fd,energy",
            "--json",
        ];
        let symbolic = json(&args);
        let numeric = json(&[&args[..], &["--engine", "numeric"]].concat());
        let nv = v.split(',').count();
        assert_eq!(flat(&symbolic["tau"]).len(), nv, "{model}");
        for key in ["tau", "M", "g", "bias", "qdd", "kinetic", "potential"] {
            assert_close(
                &flat(&symbolic[key]),
                &flat(&numeric[key]),
                &format!("{model} {key}"),
            );
        }
    }
}

const BRICK: &str = r#"<robot name="brick">
  <link name="body">
    <inertial>
      <origin xyz="0.1 0 0"/>
      <mass value="2.0"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.25"/>
    </inertial>
  </link>
  <joint name="lid_hinge" type="fixed">
    <parent link="body"/>
    <child link="lid"/>
    <origin xyz="0 0 0.2"/>
  </joint>
  <link name="lid">
    <inertial><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>
"#;

/// A URDF without moving joints: an error on a fixed base (nothing moves), a 6-DOF rigid body
/// on a floating one, which falls at g: with the body upright, the base force that holds it is
/// m·g straight up and no torque is needed about its centre of mass.
#[test]
fn a_body_without_joints_is_an_error_fixed_and_a_rigid_body_floating() {
    let path = scratch("brick.urdf", BRICK);
    let error = rne(&["check", &path]).unwrap_err();
    assert!(error.contains("nothing moves"), "{error}");
    let report = json(&["check", &path, "--floating-base", "--json"]);
    assert_eq!(
        (&report["dof"], &report["nv"]),
        (&serde_json::json!(0), &serde_json::json!(6))
    );
    let state = ["--q", "0,0,1,0,0,0,1", "--what", "g,fd", "--json"];
    let result = json(&[&["eval", &path, "--floating-base"][..], &state].concat());
    let mass = 2.5;
    let com_x = (2.0 * 0.1) / mass;
    let g = flat(&result["g"]);
    // g(q) is the generalised force gravity asks for: [f; τ] = −[m g; c × m g] in body axes.
    assert_close(
        &g,
        &[0.0, 0.0, mass * 9.81, 0.0, -com_x * mass * 9.81, 0.0],
        "g",
    );
    let qdd = flat(&result["qdd"]);
    assert_close(
        &qdd[..3],
        &[0.0, 0.0, -9.81],
        "free fall of the body origin",
    );
    assert_close(&qdd[3..], &[0.0; 3], "no angular acceleration");
}

/// On a floating base `rne show` names the base's coordinates (x … qw in q, vx … wz in v, their
/// rates, fx … nz in τ) and numbers the joints after them from 1, in the expanded equations
/// and in the compact program; before, the quaternion printed as q4 … q7 and the first joint
/// as q8.
#[test]
fn show_names_a_floating_bases_coordinates_and_numbers_the_joints_from_one() {
    let show = |what: &[&str]| {
        let args = [
            &["show", "planar-elbow", "--floating-base", "--what"][..],
            what,
        ]
        .concat();
        rne(&args).unwrap()
    };
    let g = show(&["g"]);
    assert!(
        g.starts_with("# planar-elbow (8 degrees of freedom: a floating base and 2 joints: q1, q2)\n# floating base: position x y z, orientation quaternion qx qy qz qw"),
        "{g}"
    );
    assert!(g.contains("g2 = 294.3 - 588.6 qx^2 - 588.6 qz^2\n"), "{g}");
    assert!(g.contains("(132.435 s1 + 44.145 s12)"), "{g}");
    for wrong in ["q4", "q7", "q8", "s8", "s89"] {
        assert!(!g.contains(wrong), "{wrong} in\n{g}");
    }
    let tau = show(&["tau"]);
    for named in ["Dvx", "Dwz", "DDq1", "vx wz", "Dq1 Dq2"] {
        assert!(tau.contains(named), "{named} in\n{tau}");
    }
    let latex = show(&["tau", "--format", "latex"]);
    for named in ["\\dot{v}_{x}", "\\omega_{z}", "q_{w}", "\\ddot{q}_{1}"] {
        assert!(latex.contains(named), "{named} in\n{latex}");
    }
    let compact = show(&["M", "--compact"]);
    assert!(compact.contains("\ns1 = sin(q1)\n"), "{compact}");
    assert!(!compact.contains("q8"), "{compact}");
}

//! User scenario files: unknown, missing and out-of-range keys are errors that name the key and
//! the file; vectors are checked against the model when it is known.

use std::path::Path;

use rne_scenarios::{RunOptions, UserScenario};

fn parse(text: &str) -> Result<UserScenario, String> {
    UserScenario::parse(text, Path::new("test.toml")).map_err(|e| e.to_string())
}

/// Unknown keys, missing keys and out-of-range values are errors that name the key.
#[test]
fn bad_files_are_errors_naming_the_key() {
    let base = "model = \"planar-elbow\"\nduration = 1.0\nq0 = [0, 0]\n";
    assert!(parse(base).is_ok(), "{:?}", parse(base).err());
    let unknown = parse(&format!("{base}speed = 3\n")).unwrap_err();
    assert!(
        unknown.contains("speed") && unknown.contains("test.toml"),
        "{unknown}"
    );
    let nested = parse(&format!("{base}[controller]\nkq = [1, 2]\n")).unwrap_err();
    assert!(nested.contains("kq"), "{nested}");
    let method = parse(&format!("{base}[integrator]\nmethod = \"euler\"\n")).unwrap_err();
    assert!(method.contains("euler"), "{method}");
    let stray = parse(&format!(
        "{base}[integrator]\nmethod = \"rk4\"\nstep = 0.01\nrtol = 1e-3\n"
    ))
    .unwrap_err();
    assert!(stray.contains("rtol"), "{stray}");
    let missing = parse("model = \"planar-elbow\"\nq0 = [0, 0]\n").unwrap_err();
    assert!(missing.contains("duration"), "{missing}");
    let negative = parse("model = \"planar-elbow\"\nduration = -1\nq0 = [0, 0]\n").unwrap_err();
    assert!(negative.contains("`duration`"), "{negative}");
    let kp = parse(&format!("{base}[controller]\nkp = [1, 1]\n")).unwrap_err();
    assert!(kp.contains("q_ref"), "{kp}");
    let sat = parse(&format!("{base}[controller]\nsaturation = [0, 1]\n")).unwrap_err();
    assert!(sat.contains("saturation"), "{sat}");
    let gravity = parse(&format!("{base}[controller]\ngravity = \"up\"\n")).unwrap_err();
    assert!(gravity.contains("up"), "{gravity}");
}

/// A step so small that the run would never end is refused before it starts; a step
/// within the cap is accepted.
#[test]
fn fixed_steps_beyond_the_cap_are_errors() {
    let base = "model = \"planar-elbow\"\nduration = 1.0\nq0 = [0, 0]\n";
    for method in ["rk4", "gauss-legendre", "implicit-midpoint"] {
        let tiny = format!("{base}[integrator]\nmethod = \"{method}\"\nstep = 1e-300\n");
        let e = parse(&tiny).unwrap_err();
        assert!(e.contains("integrator.step") && e.contains("1e8"), "{e}");
        let fine = format!("{base}[integrator]\nmethod = \"{method}\"\nstep = 1e-8\n");
        assert!(parse(&fine).is_ok(), "{method}: {:?}", parse(&fine).err());
    }
}

/// Vectors must have one entry per joint of the model, checked when the model is known;
/// the error names the key and the joints.
#[test]
fn vectors_must_match_the_model() {
    let s = parse("model = \"planar-elbow\"\nduration = 0.1\nq0 = [0, 0, 0]\n").unwrap();
    let e = s.run(&RunOptions::default()).unwrap_err().to_string();
    assert!(
        e.contains("`q0` has 3 values") && e.contains("q1, q2"),
        "{e}"
    );
    let s = parse("model = \"no-such-robot.toml\"\nduration = 0.1\nq0 = [0]\n").unwrap();
    let e = s.run(&RunOptions::default()).unwrap_err().to_string();
    assert!(e.contains("no-such-robot.toml"), "{e}");
}

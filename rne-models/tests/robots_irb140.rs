//! The six-joint IRB 140: its first three links are those of the thesis's three-joint model,
//! and its wrist sits where ABB's dimension drawing puts it.

mod robots_common;

use rne_symbolic::{Id, RobotModel};
use robots_common::{load, robot_file};

fn values(model: &RobotModel, ids: impl IntoIterator<Item = Id>) -> Vec<f64> {
    ids.into_iter()
        .map(|id| model.graph.as_const(id).expect("a constant"))
        .collect()
}

/// Every number of link `i`: placement, axis, mass, COM, inertia.
fn link_numbers(model: &RobotModel, i: usize) -> Vec<f64> {
    let link = &model.links[i];
    let mut ids: Vec<Id> = link.rotation.iter().flatten().copied().collect();
    ids.extend(link.translation);
    ids.extend(link.axis);
    ids.push(link.mass);
    ids.extend(link.com);
    ids.extend(link.inertia.iter().flatten());
    values(model, ids)
}

#[test]
fn the_first_three_links_are_the_thesis_model() {
    let six = load(&robot_file("irb140.toml"));
    let three = load(&robot_file("irb140-3dof.toml"));
    assert_eq!(six.joint_names(), ["q1", "q2", "q3", "q4", "q5", "q6"]);
    for i in 0..3 {
        assert_eq!(six.links[i].name, three.links[i].name);
        assert_eq!(six.links[i].parent, three.links[i].parent);
        assert_eq!(
            link_numbers(&six, i),
            link_numbers(&three, i),
            "link {}",
            i + 1
        );
    }
    assert_eq!(
        six.gravity.map(|g| six.graph.as_const(g)),
        three.gravity.map(|g| three.graph.as_const(g))
    );
}

/// Body origin, COM and joint axis of each link in the base frame at q = 0.
fn at_rest(model: &RobotModel) -> Vec<([f64; 3], [f64; 3], [f64; 3])> {
    let numeric = model.to_numeric();
    let mut frames: Vec<([[f64; 3]; 3], [f64; 3])> = Vec::new();
    let mut out = Vec::new();
    for link in &numeric.links {
        let (r_p, p_p) = match link.parent {
            Some(p) => frames[p],
            None => (
                [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                [0.0; 3],
            ),
        };
        let apply = |r: &[[f64; 3]; 3], v: [f64; 3]| {
            [0, 1, 2].map(|i| (0..3).map(|k| r[i][k] * v[k]).sum::<f64>())
        };
        let r = [0, 1, 2].map(|i| {
            [0, 1, 2].map(|j| (0..3).map(|k| r_p[i][k] * link.rotation[k][j]).sum::<f64>())
        });
        let moved = apply(&r_p, link.translation);
        let p = [0, 1, 2].map(|k| p_p[k] + moved[k]);
        let c = apply(&r, link.com);
        out.push((p, [0, 1, 2].map(|k| p[k] + c[k]), apply(&r, link.axis)));
        frames.push((r, p));
    }
    out
}

fn assert_near(a: [f64; 3], b: [f64; 3], what: &str) {
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() < 1e-12, "{what}: {a:?} != {b:?}");
    }
}

#[test]
fn the_wrist_follows_abbs_geometry() {
    let model = load(&robot_file("irb140.toml"));
    let rest = at_rest(&model);
    // Axis 1 to axis 2: 70 mm forward, 352 mm up; upper arm 360 mm; forearm 380 mm to the
    // wrist centre, where axes 4, 5 and 6 meet (body origins of links 4, 5 and 6 in the
    // thesis's convention sit on the previous frame's origin, the wrist centre).
    let wrist_centre = [0.070 + 0.380, 0.0, 0.352 + 0.360];
    for body in &rest[3..6] {
        assert_near(body.0, wrist_centre, "wrist centre");
    }
    // The flange 65 mm beyond the wrist centre along axis 6; link 6's COM 5 mm behind it.
    assert_near(rest[5].1, [0.515 - 0.005, 0.0, 0.712], "link 6 COM");
    // Axes 4 and 6 along the forearm (x of the base at rest), axis 5 horizontal across it,
    // parallel to axes 2 and 3.
    assert_near(rest[3].2, [1.0, 0.0, 0.0], "axis 4");
    assert_near(rest[4].2, rest[1].2, "axis 5");
    assert_near(rest[4].2, [0.0, -1.0, 0.0], "axis 5");
    assert_near(rest[5].2, [1.0, 0.0, 0.0], "axis 6");
    let numeric = model.to_numeric();
    // The estimated wrist: 3 kg on top of table 6.2's 70 kg.
    let masses: Vec<f64> = numeric.links.iter().map(|l| l.mass).collect();
    assert_eq!(masses, [23.0, 25.0, 22.0, 2.0, 0.8, 0.2]);
}

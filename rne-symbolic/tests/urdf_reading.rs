//! What the URDF reader takes from a file as robots publish it: joints, `<mimic>`,
//! `<dynamics>` and inertials; any joint and link name URDF allows, kept verbatim; and
//! everything else — visual, collision, materials, gazebo, transmissions, sensors, unknown
//! elements and attributes, xacro leftovers — ignored, never a reason to fail.

use rne_symbolic::canonical::{format_polynomial, Polynomial, PrintFormat};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{JointKind, RobotModel, SymbolicDynamics};

fn read(text: &str) -> RobotModel {
    read_robot(
        Description::urdf(text, "robots/odd.urdf"),
        &LoadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

const INERTIAL: &str = r#"<inertial><origin xyz="0.1 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"#;

/// A chain of revolute joints with these names, each moving a link with mass.
fn chain(names: &[&str]) -> String {
    let mut text = String::from("<robot name=\"odd\">\n  <link name=\"root\"/>\n");
    let mut parent = "root".to_owned();
    for (k, name) in names.iter().enumerate() {
        let child = format!("link {k} ⟨{name}⟩");
        text.push_str(&format!(
            "  <joint name=\"{name}\" type=\"continuous\">\n    <parent link=\"{parent}\"/>\n    \
             <child link=\"{child}\"/>\n    <origin xyz=\"0 0 0.2\"/>\n    <axis xyz=\"0 1 0\"/>\n  \
             </joint>\n  <link name=\"{child}\">{INERTIAL}</link>\n"
        ));
        parent = child;
    }
    text.push_str("</robot>\n");
    text
}

#[test]
fn any_joint_and_link_name_is_kept_verbatim() {
    let names = [
        "8",
        "FL-hip",
        "joint.1",
        "ünïcödé",
        "sin",
        "a b",
        "Dx",
        "x",
        "tau_x",
    ];
    let model = read(&chain(&names));
    assert_eq!(model.joint_names(), names);
    assert_eq!(model.links[3].name, "link 2 ⟨joint.1⟩");
    // The symbolic dynamics and its printing work on such names, unambiguously.
    let mut dynamics = SymbolicDynamics::new(&model);
    let tau = dynamics.inverse_dynamics();
    let graph = &dynamics.model.graph;
    let polynomial = Polynomial::from_expr(graph, tau[0]).unwrap();
    let printed = format_polynomial(&polynomial, graph.symbols(), PrintFormat::Text);
    assert!(printed.contains("`8`"), "{printed}");
    assert!(printed.contains("DD`FL-hip`"), "{printed}");
}

#[test]
fn mimic_and_dynamics_are_read() {
    let text = chain(&["a", "b"]).replacen(
        "<axis xyz=\"0 1 0\"/>\n  </joint>\n  <link name=\"link 1",
        "<axis xyz=\"0 1 0\"/>\n    <mimic joint=\"a\" multiplier=\"-0.5\" offset=\"0.1\"/>\n    \
             <dynamics damping=\"0.7\" friction=\"0.2\"/>\n  </joint>\n  <link name=\"link 1",
        1,
    );
    let model = read(&text);
    let g = &model.graph;
    let follower = &model.links[2];
    let mimic = follower.mimic.clone().expect("a mimic joint");
    assert_eq!(mimic.leader, "a");
    assert_eq!(g.as_const(mimic.multiplier), Some(-0.5));
    assert_eq!(g.as_const(mimic.offset), Some(0.1));
    let friction = follower.friction.expect("friction");
    assert_eq!(g.as_const(friction.viscous), Some(0.7));
    assert_eq!(g.as_const(friction.coulomb), Some(0.2));
    assert_eq!(g.as_const(friction.offset), Some(0.0));
    assert!(model.links[1].mimic.is_none() && model.links[1].friction.is_none());
    assert!(follower.armature.is_none());
    // The follower keeps its own variable until the model's mimic joints are constrained.
    assert_eq!(model.dof(), 2);
}

#[test]
fn the_root_and_fixed_links_are_model_links() {
    let text = chain(&["a"]).replace(
        "</robot>",
        "  <joint name=\"flange\" type=\"fixed\"><parent link=\"link 0 ⟨a⟩\"/>\
         <child link=\"tool0\"/><origin xyz=\"0 0 0.1\"/></joint>\n  <link name=\"tool0\"/>\n</robot>",
    );
    let model = read(&text);
    let names: Vec<&str> = model.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["root", "link 0 ⟨a⟩", "tool0"]);
    let kinds: Vec<JointKind> = model.links.iter().map(|l| l.kind).collect();
    assert_eq!(
        kinds,
        [JointKind::Fixed, JointKind::Revolute, JointKind::Fixed]
    );
    assert_eq!(model.links[0].parent, None);
    assert_eq!(model.links[2].parent, Some(1));
    // The dynamics drop the root and merge the flange.
    assert_eq!(model.merge_fixed_links().links.len(), 1);
}

#[test]
fn what_the_dynamics_does_not_need_is_ignored() {
    let plain = read(&chain(&["a", "b"]));
    let decorated = chain(&["a", "b"])
        .replace(
            "<robot name=\"odd\">",
            "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!DOCTYPE robot>\n<!-- generated -->\n\
             <robot name=\"odd\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\" version=\"${v}\">\n  \
             <xacro:macro name=\"m\" params=\"x\"><link name=\"${x}\"/></xacro:macro>\n  \
             <material name=\"grey\"><color rgba=\"0.5 0.5 0.5 1\"/><texture filename=\"t.png\"/></material>\n  \
             <gazebo reference=\"root\"><sensor type=\"camera\" name=\"c\"><camera/></sensor></gazebo>\n  \
             <transmission name=\"t\"><type>SimpleTransmission</type><joint name=\"a\"/></transmission>",
        )
        .replace(
            "<axis xyz=\"0 1 0\"/>",
            "<axis xyz=\"0 1 0\" xacro:if=\"${x}\"/>\n    <limit lower=\"${-pi}\" upper=\"bad\" effort=\"\"/>\n    \
             <safety_controller k_velocity=\"x\"/>\n    <calibration rising=\"?\"/>\n    <unknown><deeper/></unknown>",
        )
        .replace(
            "<inertial>",
            "<visual><geometry><mesh filename=\"package://m.dae\" scale=\"${s}\"/></geometry>\
             <material name=\"${m}\"/></visual><collision><geometry><box size=\"1 2\"/></geometry>\
             </collision><inertial colour=\"blue\">",
        );
    let model = read(&decorated);
    assert_eq!(model.joint_names(), plain.joint_names());
    assert_eq!(model.links.len(), plain.links.len());
    let mut a = SymbolicDynamics::new(&plain);
    let mut b = SymbolicDynamics::new(&model);
    assert_eq!(a.mass_matrix(), b.mass_matrix());
}

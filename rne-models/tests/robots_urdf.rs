//! The URDF edge cases of issue 4 (`tests/fixtures/urdf/`, copies of rne-symbolic's) through the symbolic
//! dynamics and the independent numeric reference, which keeps fixed links as bodies of their
//! own (the symbolic path merges them): rpy on every joint, negative axes, a fixed link with
//! mass and rotated inertia, a branch, a massless intermediate link, prismatic joints. And the
//! handwritten robot's URDF and TOML give the same generated code, token for token.

mod robots_common;

use rne_codegen_core::{generate, GenerationOptions, Scene};
use rne_reference::Reference;
use robots_common::{assert_close, fixture, load, reference, rng, state, uniform, Symbolic};

fn agrees_with_the_reference(file: &str) {
    let model = load(&fixture(file));
    let symbolic = Symbolic::new(&model);
    let mut numeric = Reference::new(&model.to_numeric());
    let mut rng = rng(0x0b07_5003);
    let n = model.dof();
    for _ in 0..200 {
        let (q, qd, qdd) = state(&mut rng, n);
        let tau = uniform(&mut rng, n, 10.0);
        let expected = reference(&mut numeric, &q, &qd, &qdd, &tau);
        let errors = symbolic.eval(&q, &qd, &qdd, &tau).errors(&expected);
        assert_close(file, "symbolic vs reference", errors, 1e-12, &q);
    }
}

#[test]
fn rpy_on_every_joint() {
    agrees_with_the_reference("rpy_every_joint.urdf");
}

#[test]
fn negative_axes() {
    agrees_with_the_reference("negative_axes.urdf");
}

#[test]
fn fixed_link_with_mass_and_rotated_inertia() {
    agrees_with_the_reference("fixed_link.urdf");
}

#[test]
fn branch() {
    agrees_with_the_reference("branch.urdf");
}

#[test]
fn massless_intermediate_link() {
    agrees_with_the_reference("massless_link.urdf");
}

#[test]
fn prismatic_joints() {
    agrees_with_the_reference("prismatic.urdf");
}

#[test]
fn handwritten_urdf_and_toml_generate_the_same_code() {
    agrees_with_the_reference("handwritten.urdf");
    let urdf = load(&fixture("handwritten.urdf"));
    let toml = load(&fixture("handwritten.toml"));
    let (scene, options) = (Scene::default(), GenerationOptions::default());
    let a = generate(&urdf, &scene, &options, "handwritten").unwrap();
    let b = generate(&toml, &scene, &options, "handwritten").unwrap();
    assert_eq!(a.joints, b.joints);
    assert_eq!(a.source, b.source);
}

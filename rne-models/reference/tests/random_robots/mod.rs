//! Random robots for the proptest identities: chains and trees of revolute, prismatic and fixed
//! links with random geometry and inertias that satisfy the triangle inequality.

#![allow(dead_code)]

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use rne_symbolic::model::{Base, NumericLink};
use rne_symbolic::{JointKind, NumericModel};

/// A unit vector from spherical angles (polar, azimuth).
pub fn direction([polar, azimuth]: [f64; 2]) -> Vector3<f64> {
    Vector3::new(
        polar.sin() * azimuth.cos(),
        polar.sin() * azimuth.sin(),
        polar.cos(),
    )
}

/// A rotation from an axis (spherical angles) and an angle.
pub fn rotation(axis: [f64; 2], angle: f64) -> Matrix3<f64> {
    Rotation3::from_axis_angle(&Unit::new_unchecked(direction(axis)), angle).into_inner()
}

pub fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[(r, c)]))
}

/// The raw numbers of one random link.
#[derive(Clone, Debug)]
pub struct LinkSpec {
    /// Below 0.7: the previous link (a chain); above: any earlier link or the base.
    pub parent_choice: f64,
    /// 0, 1: revolute; 2: prismatic; 3: fixed with mass; 4: fixed, massless.
    pub kind: u8,
    pub rotation_axis: [f64; 2],
    pub rotation_angle: f64,
    pub translation: [f64; 3],
    pub joint_axis: [f64; 2],
    pub mass: f64,
    pub com: [f64; 3],
    /// Second moments of mass along the principal axes, per kg: `I = m diag(b+c, a+c, a+b)`
    /// satisfies the triangle inequality.
    pub moments: [f64; 3],
    pub principal_axis: [f64; 2],
    pub principal_angle: f64,
}

pub fn angles() -> impl Strategy<Value = [f64; 2]> {
    [0.0..std::f64::consts::PI, -3.2..3.2]
}

pub fn link_spec() -> impl Strategy<Value = LinkSpec> {
    (
        (
            0.0..1.0,
            0u8..5,
            angles(),
            -3.2..3.2,
            [-0.6..0.6, -0.6..0.6, -0.6..0.6],
            angles(),
        ),
        (
            0.1..5.0,
            [-0.3..0.3, -0.3..0.3, -0.3..0.3],
            [0.001..0.05, 0.001..0.05, 0.001..0.05],
        ),
        (angles(), -3.2..3.2),
    )
        .prop_map(|(geometry, inertia, principal)| {
            let (parent_choice, kind, rotation_axis, rotation_angle, translation, joint_axis) =
                geometry;
            let (mass, com, moments) = inertia;
            let (principal_axis, principal_angle) = principal;
            LinkSpec {
                parent_choice,
                kind,
                rotation_axis,
                rotation_angle,
                translation,
                joint_axis,
                mass,
                com,
                moments,
                principal_axis,
                principal_angle,
            }
        })
}

/// A robot from link specs; joint indices are assigned in link order, shifted cyclically by
/// `shift` so that the reference cannot rely on any particular numbering.
pub fn robot(specs: &[LinkSpec], shift: usize, gravity: [f64; 3]) -> NumericModel {
    let dof = specs.iter().filter(|s| s.kind < 3).count();
    let mut next_joint = 0;
    let links = specs
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let parent = if s.parent_choice < 0.7 {
                i.checked_sub(1)
            } else {
                let pick = ((s.parent_choice - 0.7) / 0.3 * (i + 1) as f64) as usize;
                pick.min(i).checked_sub(1)
            };
            let (kind, joint) = match s.kind {
                0 | 1 => (JointKind::Revolute, Some((next_joint + shift) % dof)),
                2 => (JointKind::Prismatic, Some((next_joint + shift) % dof)),
                _ => (JointKind::Fixed, None),
            };
            next_joint += usize::from(joint.is_some());
            let mass = if s.kind == 4 { 0.0 } else { s.mass };
            let [a, b, c] = s.moments;
            let principal = rotation(s.principal_axis, s.principal_angle);
            let inertia = principal
                * Matrix3::from_diagonal(&Vector3::new(b + c, a + c, a + b))
                * principal.transpose()
                * mass;
            NumericLink {
                name: format!("link{i}"),
                parent,
                kind,
                joint,
                rotation: rows(&rotation(s.rotation_axis, s.rotation_angle)),
                translation: s.translation,
                axis: direction(s.joint_axis).into(),
                mass,
                com: s.com,
                inertia: rows(&inertia),
                coupling: None,
                friction: None,
                armature: None,
            }
        })
        .collect();
    NumericModel {
        name: "random".into(),
        gravity,
        base: Base::Fixed,
        links,
        joint_names: (0..dof).map(|k| format!("q{k}")).collect(),
    }
}

/// A random robot with 1–8 joints and up to 10 links, and a state for it.
pub fn robot_and_state() -> impl Strategy<Value = (NumericModel, State)> {
    (
        prop::collection::vec(link_spec(), 1..=10).prop_filter("1 to 8 joints", |specs| {
            (1..=8).contains(&specs.iter().filter(|s| s.kind < 3).count())
        }),
        0usize..8,
        [-10.0..10.0, -10.0..10.0, -10.0..10.0],
        prop::array::uniform8(-3.2..3.2),
        prop::array::uniform8(-2.0..2.0),
        prop::array::uniform8(-5.0..5.0),
    )
        .prop_map(|(specs, shift, gravity, q, qd, qdd)| {
            let model = robot(&specs, shift, gravity);
            let n = model.dof();
            let state = State {
                q: q[..n].to_vec(),
                qd: qd[..n].to_vec(),
                qdd: qdd[..n].to_vec(),
            };
            (model, state)
        })
}

/// One sample of [`robot_and_state`] for the deterministic tests.
pub fn sample_robot_and_state(min_dof: usize) -> (NumericModel, State) {
    let mut runner = TestRunner::deterministic();
    let strategy = robot_and_state().prop_filter("enough joints", move |(m, _)| m.dof() >= min_dof);
    strategy.new_tree(&mut runner).unwrap().current()
}

/// `count` link specs drawn deterministically, for tests that then fix kinds and parents.
pub fn sample_link_specs(count: usize) -> Vec<LinkSpec> {
    let mut runner = TestRunner::deterministic();
    let strategy = prop::collection::vec(link_spec(), count);
    strategy.new_tree(&mut runner).unwrap().current()
}

#[derive(Clone, Debug)]
pub struct State {
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
}

pub fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

pub fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

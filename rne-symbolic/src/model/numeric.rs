//! The model with every expression evaluated: plain `f64` data for numeric algorithms.

use super::{JointKind, RobotModel};
use crate::expr::{Id, Symbol};

/// One link of a [`NumericModel`]; fields as in [`Link`](super::Link).
#[derive(Clone, Debug, PartialEq)]
pub struct NumericLink {
    /// The link's name.
    pub name: String,
    /// Index of the parent link; `None` for a link on the base.
    pub parent: Option<usize>,
    /// Revolute, prismatic or fixed.
    pub kind: JointKind,
    /// Index of the joint variable (`None` for fixed joints).
    pub joint: Option<usize>,
    /// `E_i`, row-major.
    pub rotation: [[f64; 3]; 3],
    /// `t_i`.
    pub translation: [f64; 3],
    /// `u_i` (unit).
    pub axis: [f64; 3],
    /// Mass.
    pub mass: f64,
    /// Centre of mass in the body frame.
    pub com: [f64; 3],
    /// Inertia about the centre of mass, body axes, row-major.
    pub inertia: [[f64; 3]; 3],
}

/// A robot with numeric geometry and inertia, for algorithms that do not work on expressions
/// (the independent numeric reference, simulations). Fixed joints are kept as they are.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericModel {
    /// The robot's name.
    pub name: String,
    /// Gravity in the base frame.
    pub gravity: [f64; 3],
    /// Links, parents first.
    pub links: Vec<NumericLink>,
    /// Joint variable names in joint order.
    pub joint_names: Vec<String>,
}

impl NumericModel {
    /// Number of joint variables.
    pub fn dof(&self) -> usize {
        self.joint_names.len()
    }
}

impl RobotModel {
    /// Evaluates every expression of the model at the parameters' values.
    pub fn to_numeric(&self) -> NumericModel {
        let mut outputs: Vec<Id> = self.gravity.to_vec();
        for link in &self.links {
            outputs.extend(link.rotation.iter().flatten());
            outputs.extend(link.translation);
            outputs.extend(link.axis);
            outputs.push(link.mass);
            outputs.extend(link.com);
            outputs.extend(link.inertia.iter().flatten());
        }
        let values = self.graph.eval::<f64>(&outputs, |s: Symbol| {
            self.parameter_value(s).unwrap_or(f64::NAN)
        });
        let mut reader = Reader {
            values: &values,
            next: 0,
        };
        let gravity = reader.vec3();
        let links = self
            .links
            .iter()
            .map(|link| NumericLink {
                name: link.name.clone(),
                parent: link.parent,
                kind: link.kind,
                joint: link.joint,
                rotation: reader.mat3(),
                translation: reader.vec3(),
                axis: reader.vec3(),
                mass: reader.scalar(),
                com: reader.vec3(),
                inertia: reader.mat3(),
            })
            .collect();
        NumericModel {
            name: self.name.clone(),
            gravity,
            links,
            joint_names: self.joint_names(),
        }
    }
}

struct Reader<'a> {
    values: &'a [f64],
    next: usize,
}

impl Reader<'_> {
    fn scalar(&mut self) -> f64 {
        self.next += 1;
        self.values[self.next - 1]
    }

    fn vec3(&mut self) -> [f64; 3] {
        [self.scalar(), self.scalar(), self.scalar()]
    }

    fn mat3(&mut self) -> [[f64; 3]; 3] {
        [self.vec3(), self.vec3(), self.vec3()]
    }
}

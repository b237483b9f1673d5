//! The model with every expression evaluated: plain `f64` data for numeric algorithms.

use super::{Base, JointKind, RobotModel};
use crate::expr::{Id, Symbol};

/// Joint friction with numeric coefficients: `τ_f = viscous · q̇ + coulomb · sign(q̇) + offset`
/// (see [`Friction`](super::Friction)).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct NumericFriction {
    /// Viscous coefficient f_v.
    pub viscous: f64,
    /// Coulomb coefficient f_c.
    pub coulomb: f64,
    /// Constant offset.
    pub offset: f64,
}

/// One link of a [`NumericModel`]; fields as in [`Link`](super::Link).
#[derive(Clone, Debug, PartialEq)]
pub struct NumericLink {
    /// The link's name.
    pub name: String,
    /// Index of the parent link; `None` for a link on the base.
    pub parent: Option<usize>,
    /// Revolute, prismatic, fixed, or the free-flyer root of a floating base.
    pub kind: JointKind,
    /// Index of the joint variable (`None` for fixed joints and the free-flyer); for a coupled
    /// (mimic) link, the index of the variable it follows.
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
    /// `(multiplier, offset)` of a constrained mimic follower: its coordinate is
    /// `multiplier · q[joint] + offset` (see [`Coupling`](super::Coupling)); `None` when the
    /// link's coordinate is its variable.
    pub coupling: Option<(f64, f64)>,
    /// Joint friction, if the model has it.
    pub friction: Option<NumericFriction>,
    /// Armature (reflected rotor inertia) of the joint, if the model has it.
    pub armature: Option<f64>,
}

/// A robot with numeric geometry and inertia, for algorithms that do not work on expressions
/// (the independent numeric reference, simulations). Fixed joints are kept as they are.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericModel {
    /// The robot's name.
    pub name: String,
    /// Gravity in the base frame (the world frame of a floating base).
    pub gravity: [f64; 3],
    /// Fixed to the world, or floating (then link 0 is the [`JointKind::FreeFlyer`] root).
    pub base: Base,
    /// Links, parents first.
    pub links: Vec<NumericLink>,
    /// Joint variable names in joint order.
    pub joint_names: Vec<String>,
}

impl NumericModel {
    /// Number of joint variables (the free-flyer not counted).
    pub fn dof(&self) -> usize {
        self.joint_names.len()
    }

    /// Size of the configuration vector: `dof`, plus 7 (position, unit quaternion) with a
    /// floating base.
    pub fn nq(&self) -> usize {
        match self.base {
            Base::Fixed => self.dof(),
            Base::Floating => 7 + self.dof(),
        }
    }

    /// Size of the velocity vector: `dof`, plus 6 (linear and angular velocity) with a
    /// floating base.
    pub fn nv(&self) -> usize {
        match self.base {
            Base::Fixed => self.dof(),
            Base::Floating => 6 + self.dof(),
        }
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
            if let Some(coupling) = link.coupling {
                outputs.extend([coupling.multiplier, coupling.offset]);
            }
            if let Some(friction) = link.friction {
                outputs.extend([friction.viscous, friction.coulomb, friction.offset]);
            }
            outputs.extend(link.armature);
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
                coupling: link.coupling.map(|_| (reader.scalar(), reader.scalar())),
                friction: link.friction.map(|_| NumericFriction {
                    viscous: reader.scalar(),
                    coulomb: reader.scalar(),
                    offset: reader.scalar(),
                }),
                armature: link.armature.map(|_| reader.scalar()),
            })
            .collect();
        NumericModel {
            name: self.name.clone(),
            gravity,
            base: self.base,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Coupling, Friction};
    use crate::spec::{parse_str, LoadOptions};

    const TWO_LINKS: &str = r#"
name = "two"
[[link]]
name = "upper"
joint = "revolute"
q = "q1"
rotation = "Rz(q1)"
mass = 1.0
inertia = { xx = 0.01, yy = 0.01, zz = 0.01 }
[[link]]
name = "lower"
joint = "revolute"
q = "q2"
rotation = "Rz(q2)"
position = [0.2, 0.0, 0.0]
mass = 0.5
inertia = { xx = 0.02, yy = 0.02, zz = 0.02 }
"#;

    #[test]
    fn to_numeric_carries_base_coupling_friction_and_armature() {
        let mut model = parse_str(TWO_LINKS, "two.toml", &LoadOptions::default()).unwrap();
        let g = &mut model.graph;
        let (m, o, fv, fc, f0, ia) = (
            g.constant(-2.0),
            g.constant(0.3),
            g.constant(0.1),
            g.constant(0.2),
            g.constant(-0.05),
            g.constant(0.04),
        );
        model.links[1].coupling = Some(Coupling {
            multiplier: m,
            offset: o,
        });
        model.links[1].friction = Some(Friction {
            viscous: fv,
            coulomb: fc,
            offset: f0,
        });
        model.links[0].armature = Some(ia);
        model.base = Base::Floating;
        let numeric = model.to_numeric();
        assert_eq!(numeric.base, Base::Floating);
        assert_eq!((numeric.nq(), numeric.nv()), (9, 8));
        assert_eq!(numeric.links[1].coupling, Some((-2.0, 0.3)));
        assert_eq!(
            numeric.links[1].friction,
            Some(NumericFriction {
                viscous: 0.1,
                coulomb: 0.2,
                offset: -0.05
            })
        );
        assert_eq!(numeric.links[0].armature, Some(0.04));
        assert_eq!(
            (numeric.links[0].coupling, numeric.links[0].friction),
            (None, None)
        );
        assert_eq!(numeric.links[1].armature, None);
        assert_eq!(numeric.links[1].mass, 0.5);
    }
}

//! The floating base: a free-flyer joint between the world and the model's root body, and the
//! layout of the configuration and velocity vectors it implies (docs/design.md §4.5, Pinocchio's
//! free-flyer conventions).
//!
//! With a fixed base, q, q̇, q̈ and the generalised forces all have one entry per joint
//! variable (NQ = NV = NDOF). With a floating base the root body's six degrees of freedom come
//! first: q = [x, y, z, qx, qy, qz, qw, joints] (the base origin in the world and the unit
//! quaternion of its orientation), v = [v, ω, joint rates] (the velocity of the base origin and
//! the angular velocity, both in base-frame axes), generalised forces = [force, torque about the
//! base origin, in base-frame axes; joint torques]; NQ = NV + 1.

use super::{Base, JointKind, Link, RobotModel};

/// Entries of the configuration taken by a free-flyer: position and unit quaternion.
pub const FREE_FLYER_NQ: usize = 7;
/// Entries of the velocity taken by a free-flyer: linear and angular velocity.
pub const FREE_FLYER_NV: usize = 6;

/// Where each joint variable sits in the configuration and velocity vectors.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct StateLayout {
    /// Whether the first entries belong to a free-flyer.
    pub floating: bool,
    /// Number of joint variables (NDOF).
    pub ndof: usize,
}

impl StateLayout {
    /// NQ: the length of q.
    pub fn nq(self) -> usize {
        self.q_offset() + self.ndof
    }

    /// NV: the length of q̇, q̈ and of the generalised forces.
    pub fn nv(self) -> usize {
        self.v_offset() + self.ndof
    }

    /// Index in q of the first joint variable.
    pub fn q_offset(self) -> usize {
        if self.floating {
            FREE_FLYER_NQ
        } else {
            0
        }
    }

    /// Index in v of the first joint variable.
    pub fn v_offset(self) -> usize {
        if self.floating {
            FREE_FLYER_NV
        } else {
            0
        }
    }
}

/// A model with a fixed base and no joint variable: nothing in it can move. On a floating base
/// the same model is a 6-DOF rigid body (a quadrotor, a box).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{robot}` has no revolute, continuous or prismatic joint and a fixed base: nothing moves \
     (with a floating base it is a 6-DOF rigid body)"
)]
pub struct NothingMoves {
    /// The robot's name.
    pub robot: String,
}

impl RobotModel {
    /// Whether something moves: a floating base or at least one joint variable. Checked once
    /// the base is decided (a robot file, then the scene or the command line, may set it).
    pub fn check_moves(&self) -> Result<(), NothingMoves> {
        if self.is_floating() || self.dof() > 0 {
            Ok(())
        } else {
            Err(NothingMoves {
                robot: self.name.clone(),
            })
        }
    }

    /// Whether the root is a free-flyer.
    pub fn is_floating(&self) -> bool {
        self.links
            .first()
            .is_some_and(|l| l.kind == JointKind::FreeFlyer)
    }

    /// The layout of q and v.
    pub fn state_layout(&self) -> StateLayout {
        StateLayout {
            floating: self.is_floating(),
            ndof: self.dof(),
        }
    }

    /// Attaches the model to the world as `base` says; idempotent.
    ///
    /// Floating: when the model has a single root body fixed to the world (a URDF root link,
    /// a TOML link on `base` with a fixed joint), that body becomes the free-flyer; otherwise a
    /// massless free-flyer body named `base` is put under every root, carrying them (a robot
    /// whose first joint sits on the base then moves that joint relative to a weightless
    /// floating base, and M is singular unless the base carries mass). Fixed: the free-flyer,
    /// if any, becomes a fixed joint at the identity. Joint variables keep their numbering.
    pub fn set_base(&mut self, base: Base) {
        self.attach(base);
        let floating = self.is_floating();
        self.graph.symbols_mut().set_floating_base(floating);
    }

    /// The free-flyer root that `base` asks for, made or removed.
    fn attach(&mut self, base: Base) {
        self.base = base;
        match base {
            Base::Fixed => {
                if let Some(root) = self.links.first_mut() {
                    if root.kind == JointKind::FreeFlyer {
                        root.kind = JointKind::Fixed;
                    }
                }
            }
            Base::Floating if self.is_floating() => {}
            Base::Floating => {
                let roots: Vec<usize> = self.children(None);
                if let [root] = roots[..] {
                    if self.links[root].kind == JointKind::Fixed && self.is_identity_placement(root)
                    {
                        // The root comes first: parents precede their children.
                        debug_assert_eq!(root, 0);
                        self.links[root].kind = JointKind::FreeFlyer;
                        return;
                    }
                }
                self.insert_massless_root("base");
            }
        }
    }

    fn is_identity_placement(&self, link: usize) -> bool {
        let g = &self.graph;
        let link = &self.links[link];
        (0..3).all(|i| {
            g.is_zero(link.translation[i])
                && (0..3).all(|j| {
                    if i == j {
                        g.is_one(link.rotation[i][j])
                    } else {
                        g.is_zero(link.rotation[i][j])
                    }
                })
        })
    }

    /// Puts a massless free-flyer body named `name` at index 0, parent of every root.
    fn insert_massless_root(&mut self, name: &str) {
        let g = &mut self.graph;
        let zero = g.zero();
        let zeros = g.zero_vec();
        let flyer = Link {
            name: name.to_owned(),
            parent: None,
            kind: JointKind::FreeFlyer,
            joint: None,
            rotation: g.identity(),
            translation: zeros,
            axis: zeros,
            mass: zero,
            com: zeros,
            inertia: [zeros; 3],
            mimic: None,
            coupling: None,
            friction: None,
            armature: None,
        };
        for link in &mut self.links {
            link.parent = Some(link.parent.map_or(0, |p| p + 1));
        }
        self.links.insert(0, flyer);
        for joint in &mut self.joints {
            joint.link += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{parse_str, LoadOptions};

    fn arm(first_joint: &str) -> RobotModel {
        let text = format!(
            r#"
name = "arm"
[[link]]
name = "trunk"
joint = "{first_joint}"
{axis}
origin = {{ xyz = [0, 0, 0] }}
mass = 2.0
inertia = {{ xx = 0.1, yy = 0.1, zz = 0.1 }}
[[link]]
name = "upper"
joint = "revolute"
origin = {{ xyz = [0.2, 0, 0] }}
axis = [0, 0, 1]
mass = 1.0
inertia = {{ xx = 0.01, yy = 0.01, zz = 0.01 }}
"#,
            axis = if first_joint == "fixed" {
                ""
            } else {
                "axis = [0, 0, 1]"
            },
        );
        parse_str(&text, "arm.toml", &LoadOptions::default()).expect("valid spec")
    }

    #[test]
    fn a_root_body_fixed_to_the_world_becomes_the_free_flyer() {
        let mut model = arm("fixed");
        let links = model.links.len();
        model.set_base(Base::Floating);
        assert_eq!(model.links.len(), links, "no body is added");
        assert_eq!(model.links[0].kind, JointKind::FreeFlyer);
        assert_eq!(model.links[0].name, "trunk");
        let layout = model.state_layout();
        assert_eq!((layout.nq(), layout.nv()), (8, 7));
        model.set_base(Base::Floating);
        assert_eq!(model.links.len(), links, "idempotent");
        model.set_base(Base::Fixed);
        assert_eq!(model.links[0].kind, JointKind::Fixed);
        assert_eq!(model.state_layout().nv(), 1);
    }

    #[test]
    fn a_body_without_joints_moves_only_on_a_floating_base() {
        let text = "name = \"brick\"\n[[link]]\nname = \"body\"\njoint = \"fixed\"\n\
                    origin = { xyz = [0, 0, 0] }\nmass = 1.0\n\
                    inertia = { xx = 0.1, yy = 0.2, zz = 0.3 }\n";
        let mut model = parse_str(text, "brick.toml", &LoadOptions::default()).expect("valid");
        assert_eq!(
            model.check_moves().unwrap_err().to_string(),
            "`brick` has no revolute, continuous or prismatic joint and a fixed base: nothing \
             moves (with a floating base it is a 6-DOF rigid body)"
        );
        model.set_base(Base::Floating);
        assert_eq!(model.check_moves(), Ok(()));
        let layout = model.state_layout();
        assert_eq!((layout.nq(), layout.nv()), (7, 6));
    }

    #[test]
    fn a_joint_on_the_world_gets_a_massless_free_flyer_beneath_it() {
        let mut model = arm("revolute");
        model.set_base(Base::Floating);
        assert_eq!(model.links.len(), 3);
        assert_eq!(model.links[0].kind, JointKind::FreeFlyer);
        assert_eq!(model.links[0].name, "base");
        assert_eq!(model.links[1].parent, Some(0));
        assert_eq!(model.links[2].parent, Some(1));
        assert_eq!(
            model.joints[0].link, 1,
            "joint variables follow their links"
        );
        assert_eq!(model.state_layout().nv(), 6 + 2);
    }
}

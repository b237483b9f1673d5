//! Locking joints at constant values (the macro's `lock:` scene setting).

use super::{axis_angle_rotation, JointKind, RobotModel};

/// Why a joint could not be locked.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LockError {
    /// No joint variable has this name.
    #[error("no joint named `{name}` to lock (joints: {known})")]
    UnknownJoint {
        /// The name asked for.
        name: String,
        /// The model's joint names, comma-separated.
        known: String,
    },
    /// The position is NaN or infinite.
    #[error("joint `{name}` cannot be locked at {value}: not a finite number")]
    NotFinite {
        /// The joint.
        name: String,
        /// The position asked for, as given.
        value: String,
    },
}

impl RobotModel {
    /// Turns joint `name` into a fixed joint at position `value` (rad or m): its rotation or
    /// translation is folded into the link's placement and the joint leaves the state; later
    /// joints are renumbered. The mimic followers it drives are fixed with it, each at
    /// `multiplier · value + offset`.
    pub fn lock_joint(&mut self, name: &str, value: f64) -> Result<(), LockError> {
        if !value.is_finite() {
            return Err(LockError::NotFinite {
                name: name.to_owned(),
                value: value.to_string(),
            });
        }
        let k = self
            .joints
            .iter()
            .position(|j| j.name == name)
            .ok_or_else(|| LockError::UnknownJoint {
                name: name.to_owned(),
                known: self.joint_names().join(", "),
            })?;
        // The variable's own link and every mimic follower it drives.
        let driven: Vec<usize> = (0..self.links.len())
            .filter(|&i| self.links[i].joint == Some(k))
            .collect();
        let g = &mut self.graph;
        let value = g.constant(value);
        for i in driven {
            let link = &mut self.links[i];
            let position = match link.coupling.take() {
                Some(c) => {
                    let scaled = g.mul(c.multiplier, value);
                    g.add(scaled, c.offset)
                }
                None => value,
            };
            match link.kind {
                JointKind::Revolute => {
                    let (c, s) = (g.cos(position), g.sin(position));
                    let motion = axis_angle_rotation(g, link.axis, c, s);
                    link.rotation = g.mat_mul(&link.rotation, &motion);
                }
                JointKind::Prismatic => {
                    let offset = g.vscale(position, link.axis);
                    let moved = g.mat_vec(&link.rotation, offset);
                    link.translation = g.vadd(link.translation, moved);
                }
                JointKind::Fixed | JointKind::FreeFlyer => {
                    unreachable!("fixed joints and the free-flyer have no joint variable")
                }
            }
            link.kind = JointKind::Fixed;
            link.joint = None;
        }
        self.joints.remove(k);
        for link in &mut self.links {
            if let Some(j) = link.joint.as_mut() {
                if *j > k {
                    *j -= 1;
                }
            }
        }
        let names = self.joint_names();
        self.graph.symbols_mut().set_joints(names);
        Ok(())
    }
}

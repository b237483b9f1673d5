//! Joints that move no mass, the one way a well-formed model makes M(q) singular at every q.

use super::{NumericModel, RobotModel};

/// A joint whose link and every link beyond it have zero mass and zero inertia: its row and
/// column of M(q) vanish, so M is singular at every q and forward dynamics is undefined
/// (thesis (6.2) needs M⁻¹). A URDF link without `<inertial>` is massless, so a moving joint
/// that ends a chain of such links is the usual cause. (Mass lying exactly on a revolute
/// axis with no inertia beyond is singular too; that rarer case is not detected.)
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "joint `{joint}` moves no mass: link `{link}` and every link beyond it have zero mass and \
     inertia, so M(q) is singular and forward dynamics is undefined"
)]
pub struct MasslessJoint {
    /// The joint variable.
    pub joint: String,
    /// The link it moves.
    pub link: String,
}

impl NumericModel {
    /// The first joint, in joint order, that moves no mass or inertia at all.
    pub fn massless_joint(&self) -> Option<MasslessJoint> {
        // Children come after their parents: one backward pass gives what each link carries.
        let mut carries: Vec<bool> = self
            .links
            .iter()
            .map(|link| link.mass != 0.0 || link.inertia.iter().flatten().any(|&i| i != 0.0))
            .collect();
        for i in (0..self.links.len()).rev() {
            if let Some(parent) = self.links[i].parent {
                carries[parent] |= carries[i];
            }
        }
        // A variable moves mass if any of its links does (a mimic follower may be massless
        // while its leader is not); the link named is the first of the variable's links.
        let mut variables: Vec<Option<(usize, bool)>> = vec![None; self.dof()];
        for (i, link) in self.links.iter().enumerate() {
            if let Some(k) = link.joint {
                let (_, moves_mass) = variables[k].get_or_insert((i, false));
                *moves_mass |= carries[i];
            }
        }
        variables.iter().enumerate().find_map(|(k, v)| match *v {
            Some((i, false)) => Some(MasslessJoint {
                joint: self.joint_names[k].clone(),
                link: self.links[i].name.clone(),
            }),
            _ => None,
        })
    }
}

impl RobotModel {
    /// `Err` naming the first joint that moves no mass ([`MasslessJoint`]), at the parameters'
    /// values: the check to make before anything inverts M(q).
    pub fn check_mass_matrix_invertible(&self) -> Result<(), MasslessJoint> {
        match self.to_numeric().massless_joint() {
            Some(joint) => Err(joint),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::spec::{parse_str, LoadOptions};

    const ARM: &str = r#"
name = "two"
[[link]]
name = "upper"
joint = "revolute"
q = "q1"
rotation = "Rz(q1)"
mass = 1.0
com_from_prev = [0.1, 0.0, 0.0]
inertia = { xx = 0.01, yy = 0.01, zz = 0.01 }
[[link]]
name = "tool"
joint = "revolute"
q = "q2"
rotation = "Rz(q2)"
position = [0.2, 0.0, 0.0]
mass = MASS
com_from_prev = [0.2, 0.0, 0.0]
inertia = { xx = INERTIA, yy = INERTIA, zz = INERTIA }
"#;

    fn arm(mass: &str, inertia: &str) -> crate::RobotModel {
        let text = ARM.replace("MASS", mass).replace("INERTIA", inertia);
        parse_str(&text, "two.toml", &LoadOptions::default()).unwrap()
    }

    #[test]
    fn a_massless_last_link_is_named() {
        let error = arm("0.0", "0.0")
            .check_mass_matrix_invertible()
            .unwrap_err();
        assert_eq!((error.joint.as_str(), error.link.as_str()), ("q2", "tool"));
        assert!(error.to_string().contains("M(q) is singular"), "{error}");
    }

    #[test]
    fn a_massless_mimic_follower_of_a_massive_leader_is_not_massless() {
        let mut model = arm("0.0", "0.0").to_numeric();
        // The massless tool now follows q1, which moves the upper link's mass.
        model.links[1].joint = Some(0);
        model.links[1].coupling = Some((1.0, 0.0));
        model.joint_names.pop();
        assert_eq!(model.massless_joint(), None);
        model.links[0].mass = 0.0;
        model.links[0].inertia = [[0.0; 3]; 3];
        let error = model.massless_joint().unwrap();
        assert_eq!((error.joint.as_str(), error.link.as_str()), ("q1", "upper"));
    }

    #[test]
    fn mass_or_inertia_alone_is_enough() {
        assert!(arm("0.5", "0.0").check_mass_matrix_invertible().is_ok());
        assert!(arm("0.0", "0.001").check_mass_matrix_invertible().is_ok());
    }
}

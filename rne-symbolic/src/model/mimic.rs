//! Mimic joints constrained to their leaders (URDF semantics, docs/design.md §2.1–§2.2): a
//! follower's coordinate is `q_f = multiplier · q_leader + offset`, so it has no variable of its
//! own; its motion enters every kernel through the chain rule.

use super::{Coupling, RobotModel};
use crate::expr::Id;

/// Why mimic joints could not be constrained.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MimicError {
    /// A follower names a joint variable the model does not have.
    #[error("joint `{follower}` mimics `{leader}`, which is no joint of the model")]
    UnknownLeader {
        /// The follower's joint variable.
        follower: String,
        /// The name it follows.
        leader: String,
    },
    /// Following the leaders from a follower comes back to it.
    #[error("mimic joints follow each other in a loop: {}", cycle.join(" -> "))]
    Loop {
        /// The joint variables of the loop, in following order, the first repeated at the end.
        cycle: Vec<String>,
    },
}

impl RobotModel {
    /// Removes the variable of every mimic follower ([`super::Link::mimic`]): its link is driven
    /// by the root leader's variable through a [`Coupling`]. A follower of a follower follows
    /// the root leader with the composed multiplier and offset,
    /// `q = m₂ (m₁ q_l + o₁) + o₂`. Later variables are renumbered; followers whose coupling is
    /// already set are left as they are.
    pub fn constrain_mimic_joints(&mut self) -> Result<(), MimicError> {
        let names = self.joint_names();
        let variable = |name: &str| names.iter().position(|n| n == name);
        // The leader of each variable's link, for variables whose link mimics another.
        let mut leader: Vec<Option<(usize, Id, Id)>> = vec![None; names.len()];
        for (k, joint) in self.joints.iter().enumerate() {
            let link = &self.links[joint.link];
            if let (Some(mimic), None) = (&link.mimic, link.coupling) {
                let l = variable(&mimic.leader).ok_or_else(|| MimicError::UnknownLeader {
                    follower: joint.name.clone(),
                    leader: mimic.leader.clone(),
                })?;
                leader[k] = Some((l, mimic.multiplier, mimic.offset));
            }
        }
        // Each follower's root leader and composed coupling.
        let mut resolved: Vec<Option<(usize, Coupling)>> = vec![None; names.len()];
        for k in 0..names.len() {
            let Some(mut step) = leader[k] else { continue };
            let mut path = vec![k];
            let g = &mut self.graph;
            let mut coupling = Coupling {
                multiplier: step.1,
                offset: step.2,
            };
            while let Some(next) = leader[step.0] {
                if let Some(start) = path.iter().position(|&p| p == step.0) {
                    let mut cycle: Vec<String> =
                        path[start..].iter().map(|&p| names[p].clone()).collect();
                    cycle.push(names[step.0].clone());
                    return Err(MimicError::Loop { cycle });
                }
                path.push(step.0);
                // q = m (m' q_l + o') + o = (m m') q_l + (m o' + o).
                let offset = g.mul(coupling.multiplier, next.2);
                coupling = Coupling {
                    multiplier: g.mul(coupling.multiplier, next.1),
                    offset: g.add(offset, coupling.offset),
                };
                step = next;
            }
            resolved[k] = Some((step.0, coupling));
        }
        // Drive each follower's link by its root leader, then drop the followers' variables.
        for (k, entry) in resolved.iter().enumerate() {
            if let Some((root, coupling)) = *entry {
                let link = self.joints[k].link;
                self.links[link].joint = Some(root);
                self.links[link].coupling = Some(coupling);
            }
        }
        let kept: Vec<usize> = (0..names.len())
            .filter(|&k| resolved[k].is_none())
            .collect();
        let renumber: Vec<Option<usize>> = (0..names.len())
            .map(|k| kept.iter().position(|&j| j == k))
            .collect();
        for link in &mut self.links {
            link.joint = link
                .joint
                .map(|k| renumber[k].expect("root leaders are kept"));
        }
        self.joints = kept.iter().map(|&k| self.joints[k].clone()).collect();
        let names = self.joint_names();
        self.graph.symbols_mut().set_joints(names);
        Ok(())
    }

    /// Whether some link follows another joint's variable.
    pub fn has_couplings(&self) -> bool {
        self.links.iter().any(|l| l.coupling.is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mimic;
    use crate::spec::{parse_str, LoadOptions};

    /// A hand with a palm joint and three fingers, finger `k` following joint `follows[k]`.
    fn hand(follows: [Option<(&str, f64, f64)>; 3]) -> RobotModel {
        let mut text = String::from(
            "name = \"hand\"\n[[link]]\nname = \"palm\"\nq = \"palm\"\njoint = \"revolute\"\n\
             origin = { xyz = [0, 0, 0] }\naxis = [0, 0, 1]\nmass = 1\n\
             inertia = { xx = 0.1, yy = 0.1, zz = 0.1 }\n",
        );
        for k in 0..3 {
            text.push_str(&format!(
                "[[link]]\nname = \"finger{k}\"\nparent = \"palm\"\nq = \"f{k}\"\n\
                 joint = \"prismatic\"\norigin = {{ xyz = [0.1, 0, 0] }}\naxis = [0, 1, 0]\n\
                 mass = 0.1\ninertia = {{ xx = 0.001, yy = 0.001, zz = 0.001 }}\n"
            ));
        }
        let mut model = parse_str(&text, "hand.toml", &LoadOptions::default()).expect("valid");
        for (k, follow) in follows.iter().enumerate() {
            if let Some((leader, m, o)) = *follow {
                let g = &mut model.graph;
                model.links[k + 1].mimic = Some(Mimic {
                    leader: leader.to_owned(),
                    multiplier: g.constant(m),
                    offset: g.constant(o),
                });
            }
        }
        model
    }

    #[test]
    fn followers_lose_their_variables_and_follow_the_root_leader() {
        let mut model = hand([None, Some(("f0", 2.0, 0.1)), Some(("f1", -1.0, 0.5))]);
        model.constrain_mimic_joints().expect("no loop");
        assert_eq!(model.joint_names(), ["palm", "f0"]);
        let g = &model.graph;
        let c1 = model.links[2].coupling.expect("finger1 follows");
        assert_eq!(model.links[2].joint, Some(1));
        assert_eq!(
            (g.as_const(c1.multiplier), g.as_const(c1.offset)),
            (Some(2.0), Some(0.1))
        );
        // finger2 = −(2 f0 + 0.1) + 0.5 = −2 f0 + 0.4.
        let c2 = model.links[3]
            .coupling
            .expect("finger2 follows through finger1");
        assert_eq!(model.links[3].joint, Some(1));
        assert_eq!(g.as_const(c2.multiplier), Some(-2.0));
        assert!((g.as_const(c2.offset).unwrap() - 0.4).abs() < 1e-15);
        assert_eq!(model.links[1].coupling, None);
        assert_eq!(model.joints[1].link, 1);
    }

    #[test]
    fn a_loop_of_followers_is_an_error_naming_it() {
        let mut model = hand([Some(("f1", 1.0, 0.0)), Some(("f0", 1.0, 0.0)), None]);
        let error = model.constrain_mimic_joints().unwrap_err();
        assert_eq!(
            error.to_string(),
            "mimic joints follow each other in a loop: f0 -> f1 -> f0"
        );
    }

    #[test]
    fn following_a_missing_joint_is_an_error() {
        let mut model = hand([Some(("thumb", 1.0, 0.0)), None, None]);
        assert_eq!(
            model.constrain_mimic_joints().unwrap_err(),
            MimicError::UnknownLeader {
                follower: "f0".into(),
                leader: "thumb".into()
            }
        );
    }
}

//! Checks of the mimic joints as read (URDF `<mimic>`, TOML `mimic = {..}`): a follower moves
//! (a fixed joint has no coordinate to follow with), its leader is a joint variable of the
//! model, and following leaders from follower to leader never comes back to where it started.
//! A leader of another joint type than its follower is fine (URDF allows a prismatic joint to
//! follow a revolute one: `multiplier` then carries the units).

use super::{InputLink, Place};
use crate::model::{JointKind, JointVariable};
use crate::spec::{SpecError, SpecErrorKind, SpecWarning, SpecWarningKind};

/// Checks every mimic link of `links`, whose joint variables are `joints`.
pub(crate) fn check(links: &[InputLink], joints: &[JointVariable]) -> Result<(), SpecError> {
    for (i, input) in links.iter().enumerate() {
        let Some(mimic) = &input.link.mimic else {
            continue;
        };
        let field = input.fields.mimic;
        let error = |kind, message: String| {
            input.place(Place::Joint, SpecError::new(kind, message).at_field(field))
        };
        if input.link.kind == JointKind::Fixed {
            return Err(error(
                SpecErrorKind::Kinematics,
                "a fixed joint cannot mimic another joint: it has no coordinate".to_owned(),
            ));
        }
        if leader_link(links, joints, &mimic.leader).is_none() {
            return Err(error(
                SpecErrorKind::Tree,
                format!(
                    "the mimic joint follows '{}', which is not a moving joint of the robot",
                    mimic.leader
                ),
            ));
        }
        let mut chain = vec![i];
        let mut at = i;
        while let Some(next) = links[at]
            .link
            .mimic
            .as_ref()
            .and_then(|m| leader_link(links, joints, &m.leader))
        {
            if next == i {
                let names: Vec<String> = chain
                    .iter()
                    .map(|&l| format!("'{}'", variable_name(links, joints, l)))
                    .collect();
                return Err(error(
                    SpecErrorKind::Tree,
                    format!(
                        "the mimic joints {} follow each other in a loop: one of them must be free",
                        names.join(" → ")
                    ),
                ));
            }
            if chain.contains(&next) || chain.len() > links.len() {
                break;
            }
            chain.push(next);
            at = next;
        }
    }
    Ok(())
}

/// With mimic joints free: removes every mimic whose leader is not a moving joint of the
/// robot (which [`check`] refuses), returning the link index and a warning for each.
pub(crate) fn drop_missing_leaders(
    links: &mut [InputLink],
    joints: &[JointVariable],
) -> Vec<(usize, SpecWarning)> {
    let missing: Vec<(usize, String)> = links
        .iter()
        .enumerate()
        .filter_map(|(i, input)| {
            let mimic = input.link.mimic.as_ref()?;
            leader_link(links, joints, &mimic.leader)
                .is_none()
                .then(|| (i, mimic.leader.clone()))
        })
        .collect();
    missing
        .into_iter()
        .map(|(i, leader)| {
            links[i].link.mimic = None;
            let warning = SpecWarning::new(
                SpecWarningKind::MimicLeaderMissing,
                format!(
                    "the mimic joint follows '{leader}', which is not a moving joint of the \
                     robot; with mimic joints free it is a joint of its own"
                ),
            )
            .at_field(links[i].fields.mimic);
            (i, warning)
        })
        .collect()
}

/// The link moved by the joint variable `name`.
fn leader_link(links: &[InputLink], joints: &[JointVariable], name: &str) -> Option<usize> {
    joints
        .iter()
        .find(|j| j.name == name)
        .map(|j| j.link)
        .filter(|&l| l < links.len())
}

/// The joint variable name of link `l`.
fn variable_name<'a>(links: &'a [InputLink], joints: &'a [JointVariable], l: usize) -> &'a str {
    links[l]
        .link
        .joint
        .and_then(|k| joints.get(k))
        .map_or(links[l].link.name.as_str(), |j| j.name.as_str())
}

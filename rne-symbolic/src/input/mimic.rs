//! Checks of the mimic joints as read (URDF `<mimic>`, TOML `mimic = {..}`): a follower moves
//! (a fixed joint has no coordinate to follow with), its leader is a joint variable of the
//! model, and following leaders from follower to leader never comes back to where it started.
//! A leader of another joint type than its follower is fine (URDF allows a prismatic joint to
//! follow a revolute one: `multiplier` then carries the units).

use super::{InputLink, Place};
use crate::model::{JointKind, JointVariable};
use crate::spec::{SpecError, SpecErrorKind, SpecWarning, SpecWarningKind};

/// Checks every mimic link of `links`, whose joint variables are `joints`, in link order: the
/// first follower that is fixed, follows a missing leader or lies on a loop of followers is
/// the error. Linear in the number of links: leaders are looked up by name once, and the loops
/// found by one walk over the graph of followers (each link has at most one leader).
pub(crate) fn check(links: &[InputLink], joints: &[JointVariable]) -> Result<(), SpecError> {
    let leaders = Leaders::new(links, joints);
    let on_loop = on_loops(&leaders.of);
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
        if leaders.of[i].is_none() {
            return Err(error(
                SpecErrorKind::Tree,
                format!(
                    "the mimic joint follows '{}', which is not a moving joint of the robot",
                    mimic.leader
                ),
            ));
        }
        if on_loop[i] {
            let names: Vec<String> = loop_from(&leaders.of, i)
                .into_iter()
                .map(|l| format!("'{}'", variable_name(links, joints, l)))
                .collect();
            return Err(error(
                SpecErrorKind::Tree,
                format!(
                    "the mimic joints {} follow each other in a loop: one of them must be free",
                    names.join(" → ")
                ),
            ));
        }
    }
    Ok(())
}

/// The leader link of every link: the link moved by the joint variable its mimic names, if
/// it is a link of the model (`None` for a link that mimics nothing or a missing joint).
struct Leaders {
    of: Vec<Option<usize>>,
}

impl Leaders {
    fn new(links: &[InputLink], joints: &[JointVariable]) -> Leaders {
        let by_name = joint_links(links, joints);
        let of = links
            .iter()
            .map(|input| {
                let mimic = input.link.mimic.as_ref()?;
                by_name.get(mimic.leader.as_str()).copied()
            })
            .collect();
        Leaders { of }
    }
}

/// The link of each joint variable, by name (the first variable of a name, as a search in
/// joint order finds it), for the links of the model.
fn joint_links<'a>(
    links: &[InputLink],
    joints: &'a [JointVariable],
) -> std::collections::HashMap<&'a str, usize> {
    let mut by_name = std::collections::HashMap::with_capacity(joints.len());
    for joint in joints.iter().filter(|j| j.link < links.len()) {
        by_name.entry(joint.name.as_str()).or_insert(joint.link);
    }
    by_name
}

/// Which links lie on a loop of the functional graph `leader` (each link pointing at its
/// leader, if any): one walk from every link not yet reached, marking the links of the walk as
/// in progress, and the loop where it meets one of them again.
fn on_loops(leader: &[Option<usize>]) -> Vec<bool> {
    #[derive(Copy, Clone, PartialEq)]
    enum Seen {
        Not,
        InWalk,
        Done,
    }
    let mut seen = vec![Seen::Not; leader.len()];
    let mut on_loop = vec![false; leader.len()];
    for start in 0..leader.len() {
        let mut walk = Vec::new();
        let mut at = Some(start);
        while let Some(l) = at.filter(|&l| seen[l] == Seen::Not) {
            seen[l] = Seen::InWalk;
            walk.push(l);
            at = leader[l];
        }
        if let Some(met) = at.filter(|&l| seen[l] == Seen::InWalk) {
            let first = walk.iter().position(|&l| l == met).unwrap_or(walk.len());
            for &l in &walk[first..] {
                on_loop[l] = true;
            }
        }
        for &l in &walk {
            seen[l] = Seen::Done;
        }
    }
    on_loop
}

/// The links of the loop through `start`, from `start` following leaders.
fn loop_from(leader: &[Option<usize>], start: usize) -> Vec<usize> {
    let mut chain = vec![start];
    let mut at = leader[start];
    while let Some(next) = at.filter(|&l| l != start && chain.len() <= leader.len()) {
        chain.push(next);
        at = leader[next];
    }
    chain
}

/// With mimic joints free: removes every mimic whose leader is not a moving joint of the
/// robot (which [`check`] refuses), returning the link index and a warning for each.
pub(crate) fn drop_missing_leaders(
    links: &mut [InputLink],
    joints: &[JointVariable],
) -> Vec<(usize, SpecWarning)> {
    let by_name = joint_links(links, joints);
    let missing: Vec<(usize, String)> = links
        .iter()
        .enumerate()
        .filter_map(|(i, input)| {
            let mimic = input.link.mimic.as_ref()?;
            (!by_name.contains_key(mimic.leader.as_str())).then(|| (i, mimic.leader.clone()))
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

/// The joint variable name of link `l`.
fn variable_name<'a>(links: &'a [InputLink], joints: &'a [JointVariable], l: usize) -> &'a str {
    links[l]
        .link
        .joint
        .and_then(|k| joints.get(k))
        .map_or(links[l].link.name.as_str(), |j| j.name.as_str())
}

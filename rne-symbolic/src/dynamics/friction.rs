//! Joint friction τ_f = f_v q̇ + f_c sign(q̇) + offset (docs/design.md §2.1), per joint that has
//! it, on its own rate: a constrained mimic follower moves at `multiplier · q̇_leader`, and its
//! friction reaches the leader's variable times the multiplier, like every other generalised
//! force of the follower.
//!
//! `sign(0) = 0`: at rest the Coulomb term vanishes (the model has no stiction; a simulator
//! that needs sticking must add it), so the torque is a function of q̇ alone, as identification
//! needs, and its derivative with respect to q̇ is f_v (the sign's is zero away from 0).

use crate::expr::{ExprGraph, Id};
use crate::model::{Link, RobotModel};

/// The friction coefficients' names, in the regressor's column order.
pub const FRICTION_PARAMETER_NAMES: [&str; 3] = ["fv", "fc", "f0"];

/// A joint with friction: the index in v of the variable it acts on, the multiplier d q_link /
/// d q_variable (`None` for 1) and the link's rate.
pub(super) struct FrictionJoint {
    /// Index of the variable in v.
    pub index: usize,
    /// The coupling's multiplier, if the link is a mimic follower.
    pub multiplier: Option<Id>,
    /// q̇ of the link's own coordinate.
    pub rate: Id,
}

/// The joint of `link` with its rate taken from `qd` (the velocity vector, whose joint rates
/// start at `v_offset`), or `None` for a link without a joint variable.
pub(super) fn friction_joint(
    g: &mut ExprGraph,
    link: &Link,
    qd: &[Id],
    v_offset: usize,
) -> Option<FrictionJoint> {
    let index = v_offset + link.joint?;
    let multiplier = link.coupling.map(|c| c.multiplier);
    let rate = match multiplier {
        Some(m) => g.mul(m, qd[index]),
        None => qd[index],
    };
    Some(FrictionJoint {
        index,
        multiplier,
        rate,
    })
}

/// τ_f of every entry of v (zero for the free-flyer and for joints without friction).
pub fn friction_torques(model: &mut RobotModel, qd: &[Id]) -> Vec<Id> {
    let mut tau: Vec<Vec<Id>> = vec![Vec::new(); qd.len()];
    let v_offset = model.state_layout().v_offset();
    let g = &mut model.graph;
    for link in &model.links {
        let Some(friction) = link.friction else {
            continue;
        };
        let Some(joint) = friction_joint(g, link, qd, v_offset) else {
            continue;
        };
        let viscous = g.mul(friction.viscous, joint.rate);
        let sign = g.sign(joint.rate);
        let coulomb = g.mul(friction.coulomb, sign);
        let mut torque = g.sum([viscous, coulomb, friction.offset]);
        if let Some(m) = joint.multiplier {
            torque = g.mul(m, torque);
        }
        tau[joint.index].push(torque);
    }
    tau.into_iter().map(|terms| g.sum(terms)).collect()
}

//! Frames for kinematics: every link of the model as read, placed on the moving body it is
//! rigidly attached to once fixed joints are merged (tool flanges and sensors live behind
//! fixed joints).

use super::{JointKind, RobotModel};
use crate::expr::{Mat3, Vec3};

/// A link's frame, relative to the body that carries it after [`RobotModel::merge_fixed_links`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// The link's name.
    pub name: String,
    /// The index of the carrying body in the merged model; `None` for a frame fixed to the
    /// world.
    pub body: Option<usize>,
    /// Orientation of the frame in the body frame.
    pub rotation: Mat3,
    /// Origin of the frame in the body frame.
    pub translation: Vec3,
}

impl RobotModel {
    /// The frame of every link, in link order: a moving link's is its body frame; a fixed
    /// link's is its placement composed up to its nearest moving ancestor (or the world).
    pub fn frames(&mut self) -> Vec<Frame> {
        // Index of each moving link in the merged model: fixed links are removed, order kept.
        let mut merged_index = vec![None; self.links.len()];
        let mut next = 0;
        for (i, link) in self.links.iter().enumerate() {
            if link.kind != JointKind::Fixed {
                merged_index[i] = Some(next);
                next += 1;
            }
        }
        let g = &mut self.graph;
        let identity = g.identity();
        let zero = g.zero_vec();
        (0..self.links.len())
            .map(|i| {
                let link = &self.links[i];
                if link.kind != JointKind::Fixed {
                    return Frame {
                        name: link.name.clone(),
                        body: merged_index[i],
                        rotation: identity,
                        translation: zero,
                    };
                }
                let (mut rotation, mut translation) = (link.rotation, link.translation);
                let mut parent = link.parent;
                while let Some(p) = parent {
                    let above = &self.links[p];
                    if above.kind != JointKind::Fixed {
                        break;
                    }
                    let moved = g.mat_vec(&above.rotation, translation);
                    translation = g.vadd(above.translation, moved);
                    rotation = g.mat_mul(&above.rotation, &rotation);
                    parent = above.parent;
                }
                Frame {
                    name: link.name.clone(),
                    body: parent.and_then(|p| merged_index[p]),
                    rotation,
                    translation,
                }
            })
            .collect()
    }
}

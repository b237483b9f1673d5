//! Merging links behind fixed joints into their moving parent.

use super::{JointKind, Link, RobotModel};
use crate::expr::{ExprGraph, Id, Mat3, Vec3};

impl RobotModel {
    /// The same robot with every fixed joint removed: a fixed link's mass, centre of mass and
    /// inertia are combined exactly with its parent's (parallel-axis theorem), its children
    /// are re-attached to the parent with composed placements, and links fixed to the base
    /// (which never move) are dropped. Joint numbering is unchanged.
    pub fn merge_fixed_links(&self) -> RobotModel {
        let mut model = self.clone();
        while let Some(f) = model.links.iter().position(|l| l.kind == JointKind::Fixed) {
            model.remove_fixed_link(f);
        }
        model
    }

    fn remove_fixed_link(&mut self, f: usize) {
        let fixed = self.links[f].clone();
        let g = &mut self.graph;
        if let Some(p) = fixed.parent {
            let parent = &self.links[p];
            let (mass, com, inertia) = combine_inertia(g, parent, &fixed);
            let parent = &mut self.links[p];
            parent.mass = mass;
            parent.com = com;
            parent.inertia = inertia;
        }
        for child in self.links.iter_mut().filter(|l| l.parent == Some(f)) {
            child.rotation = g.mat_mul(&fixed.rotation, &child.rotation);
            let moved = g.mat_vec(&fixed.rotation, child.translation);
            child.translation = g.vadd(fixed.translation, moved);
            child.parent = fixed.parent;
        }
        self.links.remove(f);
        for link in &mut self.links {
            link.parent = link.parent.map(|p| if p > f { p - 1 } else { p });
        }
        for joint in &mut self.joints {
            if joint.link > f {
                joint.link -= 1;
            }
        }
    }
}

/// Mass, COM and inertia about the COM (in the parent's body frame) of the rigid union of
/// `parent` and `fixed`, whose body frame sits at `fixed.translation` with orientation
/// `fixed.rotation` in the parent's body frame.
fn combine_inertia(g: &mut ExprGraph, parent: &Link, fixed: &Link) -> (Id, Vec3, Mat3) {
    let fixed_com = {
        let rotated = g.mat_vec(&fixed.rotation, fixed.com);
        g.vadd(rotated, fixed.translation)
    };
    let fixed_inertia = g.similarity(&fixed.rotation, &fixed.inertia);
    let mass = g.add(parent.mass, fixed.mass);
    if g.is_zero(fixed.mass) {
        let inertia = matrix_sum(g, &parent.inertia, &fixed_inertia);
        return (parent.mass, parent.com, inertia);
    }
    if g.is_zero(parent.mass) {
        let inertia = matrix_sum(g, &parent.inertia, &fixed_inertia);
        return (fixed.mass, fixed_com, inertia);
    }
    let weighted = {
        let a = g.vscale(parent.mass, parent.com);
        let b = g.vscale(fixed.mass, fixed_com);
        g.vadd(a, b)
    };
    let com = weighted.map(|w| g.div(w, mass));
    let shifted_parent = parallel_axis(g, &parent.inertia, parent.mass, parent.com, com);
    let shifted_fixed = parallel_axis(g, &fixed_inertia, fixed.mass, fixed_com, com);
    (mass, com, matrix_sum(g, &shifted_parent, &shifted_fixed))
}

/// Inertia about `point` of a body with inertia `inertia` about its COM `com`:
/// `I + m (|d|² 1 − d dᵀ)`, `d = com − point`.
fn parallel_axis(g: &mut ExprGraph, inertia: &Mat3, mass: Id, com: Vec3, point: Vec3) -> Mat3 {
    let d = g.vsub(com, point);
    let d2 = g.dot(d, d);
    let mut out = *inertia;
    for i in 0..3 {
        for j in 0..3 {
            let dd = g.mul(d[i], d[j]);
            let geometric = if i == j { g.sub(d2, dd) } else { g.neg(dd) };
            let term = g.mul(mass, geometric);
            out[i][j] = g.add(inertia[i][j], term);
        }
    }
    out
}

fn matrix_sum(g: &mut ExprGraph, a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| g.add(a[i][j], b[i][j])))
}

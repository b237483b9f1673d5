//! The state the recursions run on: joint variables, the free-flyer's motion, and what each
//! link's joint does with them (its coordinate and its placement in the parent).
//!
//! A link's coordinate is its joint variable, or `multiplier · variable + offset` for a mimic
//! follower ([`Coupling`](crate::model::Coupling)); the free-flyer of a floating base has
//! six. Newton–Euler, the composite-rigid-body algorithm and the energies all place links and
//! project forces through this module, so the three agree on the conventions of
//! [`crate::model`].

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{axis_angle_rotation, JointKind, Link};

/// The motion of a free-flyer root (Pinocchio's conventions, docs/design.md §4.5).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct BaseMotion {
    /// Orientation of the base frame in the world.
    pub rotation: Mat3,
    /// Position of the base origin in the world.
    pub position: Vec3,
    /// `[v, ω]`: velocity of the base origin and angular velocity, in base-frame axes.
    pub velocity: [Id; 6],
    /// The time derivatives of `velocity`'s components.
    pub acceleration: [Id; 6],
}

/// q, q̇ and q̈ of every joint variable as expressions (symbols, constants, or zeros for the
/// special cases M, g and the bias), and the free-flyer's motion for a floating base.
#[derive(Clone, Debug)]
pub struct JointMotion {
    /// Joint positions q, in joint order.
    pub q: Vec<Id>,
    /// Joint velocities q̇.
    pub qd: Vec<Id>,
    /// Joint accelerations q̈.
    pub qdd: Vec<Id>,
    /// The free-flyer's motion (`None` on a fixed base).
    pub base: Option<BaseMotion>,
}

/// The coordinate of one link's one-variable joint and its rates.
#[derive(Copy, Clone, Debug)]
pub struct LinkCoordinate {
    /// The joint variable it follows.
    pub variable: usize,
    /// ∂coordinate/∂variable (`None` when the coordinate is the variable itself).
    pub multiplier: Option<Id>,
    /// The coordinate.
    pub q: Id,
    /// Its rate.
    pub qd: Id,
    /// Its acceleration.
    pub qdd: Id,
}

impl LinkCoordinate {
    /// The coordinate of `link`'s revolute or prismatic joint, `None` for fixed joints and
    /// the free-flyer.
    pub fn of(g: &mut ExprGraph, link: &Link, motion: &JointMotion) -> Option<LinkCoordinate> {
        let k = link.joint?;
        if !matches!(link.kind, JointKind::Revolute | JointKind::Prismatic) {
            return None;
        }
        Some(match link.coupling {
            None => LinkCoordinate {
                variable: k,
                multiplier: None,
                q: motion.q[k],
                qd: motion.qd[k],
                qdd: motion.qdd[k],
            },
            Some(c) => {
                let scaled = g.mul(c.multiplier, motion.q[k]);
                LinkCoordinate {
                    variable: k,
                    multiplier: Some(c.multiplier),
                    q: g.add(scaled, c.offset),
                    qd: g.mul(c.multiplier, motion.qd[k]),
                    qdd: g.mul(c.multiplier, motion.qdd[k]),
                }
            }
        })
    }

    /// `x` carried onto the variable: `multiplier · x` (the chain rule).
    pub fn project(&self, g: &mut ExprGraph, x: Id) -> Id {
        match self.multiplier {
            Some(m) => g.mul(m, x),
            None => x,
        }
    }
}

/// Where a link sits in its parent: `R_i^p = E_i · Rot(u_i, q_i)` applied as two factors
/// (never multiplied out), and the attachment point of its body origin in the parent's body
/// frame (`t_i`, moved along `E_i u_i` by a prismatic coordinate). A free-flyer's joint
/// rotation is the base orientation in the world.
#[derive(Copy, Clone, Debug)]
pub struct LinkPlacement {
    /// `E_i`.
    pub fixed: Mat3,
    /// `Rot(u_i, q_i)`, or the base orientation; `None` for a constant placement.
    pub joint: Option<Mat3>,
    /// The origin of B_i in B_p.
    pub attachment: Vec3,
}

impl LinkPlacement {
    /// The placement of every link at the motion's coordinates.
    pub fn all(g: &mut ExprGraph, links: &[Link], motion: &JointMotion) -> Vec<LinkPlacement> {
        links
            .iter()
            .map(|link| {
                let coordinate = LinkCoordinate::of(g, link, motion);
                let (joint, attachment) = match (link.kind, coordinate, motion.base) {
                    (JointKind::Revolute, Some(c), _) => {
                        let (cos, sin) = (g.cos(c.q), g.sin(c.q));
                        (
                            Some(axis_angle_rotation(g, link.axis, cos, sin)),
                            link.translation,
                        )
                    }
                    (JointKind::Prismatic, Some(c), _) => {
                        let slide = g.vscale(c.q, link.axis);
                        let moved = g.mat_vec(&link.rotation, slide);
                        (None, g.vadd(link.translation, moved))
                    }
                    (JointKind::FreeFlyer, _, Some(base)) => {
                        let moved = g.mat_vec(&link.rotation, base.position);
                        (Some(base.rotation), g.vadd(link.translation, moved))
                    }
                    _ => (None, link.translation),
                };
                LinkPlacement {
                    fixed: link.rotation,
                    joint,
                    attachment,
                }
            })
            .collect()
    }

    /// `R_i^p v`: a vector of B_i in B_p's axes.
    pub fn to_parent(&self, g: &mut ExprGraph, v: Vec3) -> Vec3 {
        let v = match &self.joint {
            Some(r) => g.mat_vec(r, v),
            None => v,
        };
        g.mat_vec(&self.fixed, v)
    }

    /// `(R_i^p)ᵀ v`: a vector of B_p in B_i's axes.
    pub fn to_child(&self, g: &mut ExprGraph, v: Vec3) -> Vec3 {
        let v = g.mat_t_vec(&self.fixed, v);
        match &self.joint {
            Some(r) => g.mat_t_vec(r, v),
            None => v,
        }
    }

    /// `R_i^p` multiplied out.
    pub fn rotation(&self, g: &mut ExprGraph) -> Mat3 {
        match &self.joint {
            Some(r) => g.mat_mul(&self.fixed, r),
            None => self.fixed,
        }
    }
}

/// The rotation matrix of the unit quaternion `[x, y, z, w]` (the standard formula, as
/// Pinocchio and Eigen evaluate it; the quaternion is assumed normalised).
pub fn quaternion_rotation(g: &mut ExprGraph, quaternion: [Id; 4]) -> Mat3 {
    let [x, y, z, w] = quaternion;
    let two = g.constant(2.0);
    let (tx, ty, tz) = (g.mul(two, x), g.mul(two, y), g.mul(two, z));
    let (twx, twy, twz) = (g.mul(tx, w), g.mul(ty, w), g.mul(tz, w));
    let (txx, txy, txz) = (g.mul(tx, x), g.mul(ty, x), g.mul(tz, x));
    let (tyy, tyz, tzz) = (g.mul(ty, y), g.mul(tz, y), g.mul(tz, z));
    let one = g.one();
    let diagonal = |g: &mut ExprGraph, a: Id, b: Id| {
        let s = g.add(a, b);
        g.sub(one, s)
    };
    [
        [diagonal(g, tyy, tzz), g.sub(txy, twz), g.add(txz, twy)],
        [g.add(txy, twz), diagonal(g, txx, tzz), g.sub(tyz, twx)],
        [g.sub(txz, twy), g.add(tyz, twx), diagonal(g, txx, tyy)],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{Symbol, SymbolTable};

    /// The quaternion of a rotation by θ about a unit axis gives Rodrigues' rotation.
    #[test]
    fn quaternion_rotation_is_the_axis_angle_rotation() {
        let mut g = ExprGraph::new(SymbolTable::default());
        let q: [Id; 4] = std::array::from_fn(|k| g.symbol(Symbol::Position(k as u16)));
        let r = quaternion_rotation(&mut g, q);
        let axis = [2.0f64, -1.0, 0.5];
        let norm = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
        let u = axis.map(|a| a / norm);
        let angle = 0.7f64;
        let (s, c) = (angle / 2.0).sin_cos();
        let values = [u[0] * s, u[1] * s, u[2] * s, c];
        let flat: Vec<Id> = r.iter().flatten().copied().collect();
        let got = g.eval::<f64>(&flat, |sym| match sym {
            Symbol::Position(k) => values[k as usize],
            _ => f64::NAN,
        });
        let mut h = ExprGraph::new(SymbolTable::default());
        let axis_ids = h.const_vec(u);
        let (ci, si) = (h.constant(angle.cos()), h.constant(angle.sin()));
        let expected = axis_angle_rotation(&mut h, axis_ids, ci, si);
        for i in 0..3 {
            for j in 0..3 {
                let e = h.as_const(expected[i][j]).expect("constant");
                assert!((got[3 * i + j] - e).abs() < 1e-15, "R[{i}][{j}]");
            }
        }
    }
}

//! Rotation matrices as expressions: elementary rotations, rotation about an arbitrary axis,
//! roll-pitch-yaw, and rigid transforms.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};

/// A coordinate axis of an elementary rotation.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

impl Axis {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// The axis with this index.
    pub fn from_index(i: usize) -> Axis {
        [Axis::X, Axis::Y, Axis::Z][i]
    }
}

/// The elementary rotation about `axis` whose angle has cosine `c` and sine `s`
/// (for Z: `[[c, −s, 0], [s, c, 0], [0, 0, 1]]`, as (4.7)).
pub fn elementary_rotation(g: &mut ExprGraph, axis: Axis, c: Id, s: Id) -> Mat3 {
    let (z, o) = (g.zero(), g.one());
    let ns = g.neg(s);
    match axis {
        Axis::X => [[o, z, z], [z, c, ns], [z, s, c]],
        Axis::Y => [[c, z, s], [z, o, z], [ns, z, c]],
        Axis::Z => [[c, ns, z], [s, c, z], [z, z, o]],
    }
}

/// The elementary rotation by `angle` about `axis`; `sin` and `cos` of constant multiples of
/// π/2 are exact.
pub fn rotation_about(g: &mut ExprGraph, axis: Axis, angle: Id) -> Mat3 {
    let c = g.cos(angle);
    let s = g.sin(angle);
    elementary_rotation(g, axis, c, s)
}

/// If `axis` is exactly ± a coordinate axis, that axis and the sign.
pub fn as_coordinate_axis(g: &ExprGraph, axis: Vec3) -> Option<(Axis, f64)> {
    let values: Vec<f64> = axis.iter().map(|&a| g.as_const(a)).collect::<Option<_>>()?;
    let nonzero: Vec<usize> = (0..3).filter(|&i| values[i] != 0.0).collect();
    match nonzero.as_slice() {
        [i] if values[*i].abs() == 1.0 => Some((Axis::from_index(*i), values[*i])),
        _ => None,
    }
}

/// The rotation by the angle with cosine `c` and sine `s` about the unit vector `axis`:
/// elementary when `axis` is ± a coordinate axis, Rodrigues' formula
/// `c I + (1 − c) u uᵀ + s [u]×` otherwise.
pub fn axis_angle_rotation(g: &mut ExprGraph, axis: Vec3, c: Id, s: Id) -> Mat3 {
    if let Some((k, sign)) = as_coordinate_axis(g, axis) {
        let s = if sign < 0.0 { g.neg(s) } else { s };
        return elementary_rotation(g, k, c, s);
    }
    let one = g.one();
    let versine = g.sub(one, c);
    let u = axis;
    let su = g.vscale(s, u);
    let skew = [
        [None, Some((2, -1.0)), Some((1, 1.0))],
        [Some((2, 1.0)), None, Some((0, -1.0))],
        [Some((1, -1.0)), Some((0, 1.0)), None],
    ];
    let mut r = g.identity();
    for i in 0..3 {
        for j in 0..3 {
            let uu = g.mul(u[i], u[j]);
            let outer = g.mul(versine, uu);
            let diagonal = if i == j { c } else { g.zero() };
            let mut entry = g.add(diagonal, outer);
            if let Some((k, sign)) = skew[i][j] {
                let term = if sign < 0.0 { g.neg(su[k]) } else { su[k] };
                entry = g.add(entry, term);
            }
            r[i][j] = entry;
        }
    }
    r
}

/// URDF roll-pitch-yaw: `Rz(yaw) Ry(pitch) Rx(roll)`.
pub fn rpy_rotation(g: &mut ExprGraph, rpy: Vec3) -> Mat3 {
    let rx = rotation_about(g, Axis::X, rpy[0]);
    let ry = rotation_about(g, Axis::Y, rpy[1]);
    let rz = rotation_about(g, Axis::Z, rpy[2]);
    let zy = g.mat_mul(&rz, &ry);
    g.mat_mul(&zy, &rx)
}

/// A rigid transform: a point `p` of the child frame is `rotation p + translation` in the
/// parent frame.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Transform {
    /// Orientation of the child frame in the parent frame.
    pub rotation: Mat3,
    /// Origin of the child frame in the parent frame.
    pub translation: Vec3,
}

impl Transform {
    /// The identity transform.
    pub fn identity(g: &mut ExprGraph) -> Transform {
        Transform {
            rotation: g.identity(),
            translation: g.zero_vec(),
        }
    }

    /// A pure rotation.
    pub fn rotation(g: &mut ExprGraph, rotation: Mat3) -> Transform {
        Transform {
            rotation,
            translation: g.zero_vec(),
        }
    }

    /// A pure translation.
    pub fn translation(g: &mut ExprGraph, translation: Vec3) -> Transform {
        Transform {
            rotation: g.identity(),
            translation,
        }
    }

    /// `self ∘ other`: first `other` (child of `self`), then `self`.
    pub fn then(&self, g: &mut ExprGraph, other: &Transform) -> Transform {
        let rotation = g.mat_mul(&self.rotation, &other.rotation);
        let moved = g.mat_vec(&self.rotation, other.translation);
        let translation = g.vadd(self.translation, moved);
        Transform {
            rotation,
            translation,
        }
    }

    /// Maps a point of the child frame into the parent frame.
    pub fn apply(&self, g: &mut ExprGraph, p: Vec3) -> Vec3 {
        let rotated = g.mat_vec(&self.rotation, p);
        g.vadd(rotated, self.translation)
    }
}

//! The four frame conventions of docs/design.md §2.1, each mapped onto one form: frame i of a link,
//! relative to its parent's frame (the base frame for a link on the base), is
//!
//! ```text
//! frame i = pre ∘ motion(q) ∘ post        body frame B_i = pre ∘ motion(q)
//! ```
//!
//! with constant transforms `pre` and `post` and a motion that rotates about, or translates
//! along, a constant unit axis u expressed in B_i. The placement of the body frame in the
//! parent's body frame is then `parent.post ∘ pre` (see [`crate::model`]).
//!
//! | convention | pre | motion axis | post |
//! |---|---|---|---|
//! | (a) thesis `rotation` = P·Ra(±q + c)·Q, `position` r_{i−1,i} | rotation P·Ra(c)·Q | Qᵀ(±e_a) | Trans(r_{i−1,i}) |
//! | (a) thesis, prismatic: `position` = p₀ + u q | rotation | u | Trans(p₀) |
//! | (b) `dh` | Rz(θ₀)·Tz(d₀) | ±e_z | Tx(a)·Rx(α) |
//! | (c) `mdh` | Rx(α)·Tx(a)·Rz(θ₀)·Tz(d₀) | ±e_z | identity |
//! | (d) `origin`/`axis` | Trans(xyz)·Rz(y)Ry(p)Rx(r) | axis / ‖axis‖ | identity |
//!
//! In (a), R_i^{i−1}(q) = P·Ra(c)·Q · Qᵀ·Ra(±q)·Q = E·Rot(Qᵀ(±e_a), q), so u is b_i of (3.27);
//! for the IRB 140, R_1^0 = Rz(q1)Rx(π/2)Rz(π/2) gives u = [1, 0, 0] as (5.17).

use super::transplant::{mentions, substitute};
use crate::expr::{ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::model::{rotation_about, rpy_rotation, Axis, Transform};
use crate::spec::{SpecError, SpecErrorKind};

/// The motion of a joint and its variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Motion {
    /// Rotation by q about the axis.
    Revolute(Symbol),
    /// Translation by q along the axis.
    Prismatic(Symbol),
    /// None.
    Fixed,
}

impl Motion {
    fn variable(self) -> Option<Symbol> {
        match self {
            Motion::Revolute(q) | Motion::Prismatic(q) => Some(q),
            Motion::Fixed => None,
        }
    }
}

/// A link's convention mapped onto `pre ∘ motion(q) ∘ post`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct JointFrames {
    /// From the parent's frame to the joint frame.
    pub(crate) pre: Transform,
    /// The unit motion axis in the body frame (zero for a fixed joint).
    pub(crate) axis: Vec3,
    /// From the body frame to frame i, in which the link's inertials are given.
    pub(crate) post: Transform,
}

/// The entries of a `dh` or `mdh` table (zero when omitted).
#[derive(Copy, Clone, Debug)]
pub(crate) struct DhParameters {
    pub(crate) a: Id,
    pub(crate) alpha: Id,
    pub(crate) d: Id,
    pub(crate) theta: Id,
}

/// Convention (a): `rotation` (its elementary factors in order) and `position`.
pub(crate) fn thesis(
    g: &mut ExprGraph,
    motion: Motion,
    rotation: &[(Axis, Id)],
    position: Vec3,
) -> Result<JointFrames, SpecError> {
    match motion {
        Motion::Revolute(q) => thesis_revolute(g, q, rotation, position),
        Motion::Prismatic(q) => thesis_prismatic(g, q, rotation, position),
        Motion::Fixed => {
            let e = product(g, rotation);
            let axis = g.zero_vec();
            Ok(JointFrames {
                pre: Transform::rotation(g, e),
                axis,
                post: Transform::translation(g, position),
            })
        }
    }
}

/// Convention (a) for a revolute joint: `rotation` = P·Ra(±q + c)·Q gives pre = P·Ra(c)·Q and
/// the axis Qᵀ(±e_a), `position` (constant) the post translation.
fn thesis_revolute(
    g: &mut ExprGraph,
    q: Symbol,
    rotation: &[(Axis, Id)],
    position: Vec3,
) -> Result<JointFrames, SpecError> {
    let k = variable_factor(g, rotation, q)?;
    let (before, rest) = rotation.split_at(k);
    let Some(((axis, angle), after)) = rest.split_first() else {
        return Err(kinematics("rotation has no factors").at_field("rotation"));
    };
    let (sign, offset) = affine(g, *angle, q).map_err(|e| e.at_field("rotation"))?;
    reject_variable(
        g,
        &position,
        q,
        "position",
        "a revolute joint's r_{i-1,i} is constant in frame i",
    )?;
    let p = product(g, before);
    let c = rotation_about(g, *axis, offset);
    let q_factors = product(g, after);
    let pc = g.mat_mul(&p, &c);
    let e = g.mat_mul(&pc, &q_factors);
    let unit = signed_unit(g, *axis, sign);
    let axis = g.mat_t_vec(&q_factors, unit);
    Ok(JointFrames {
        pre: Transform::rotation(g, e),
        axis,
        post: Transform::translation(g, position),
    })
}

/// The one factor of `rotation` that contains the joint variable `q`.
fn variable_factor(g: &ExprGraph, rotation: &[(Axis, Id)], q: Symbol) -> Result<usize, SpecError> {
    let with_q: Vec<usize> = (0..rotation.len())
        .filter(|&k| mentions_factor(g, rotation, k, q))
        .collect();
    match with_q.as_slice() {
        [k] => Ok(*k),
        [] => Err(kinematics(format!(
            "joint variable '{}' missing from rotation: a revolute joint needs one factor \
                 Rx, Ry or Rz of ±{0} + c",
            name(g, q)
        ))
        .at_field("rotation")),
        more => Err(kinematics(format!(
            "joint variable '{}' appears in {} factors of rotation; exactly one may contain it",
            name(g, q),
            more.len()
        ))
        .at_field("rotation")),
    }
}

/// Convention (a) for a prismatic joint: `position` = p₀ + u q gives the axis u and the post
/// translation p₀; `rotation` (constant) is pre.
fn thesis_prismatic(
    g: &mut ExprGraph,
    q: Symbol,
    rotation: &[(Axis, Id)],
    position: Vec3,
) -> Result<JointFrames, SpecError> {
    if (0..rotation.len()).any(|k| mentions_factor(g, rotation, k, q)) {
        return Err(kinematics(format!(
            "joint variable '{}' of a prismatic joint may not appear in rotation",
            name(g, q)
        ))
        .at_field("rotation"));
    }
    let e = product(g, rotation);
    let axis = position.map(|p| g.derivative(p, q));
    if axis.iter().any(|&u| mentions(g, u, q)) {
        return Err(kinematics(format!(
            "joint variable '{}' must enter position linearly, as p0 + u {0}",
            name(g, q)
        ))
        .at_field("position"));
    }
    if axis.iter().all(|&u| g.is_zero(u)) {
        return Err(kinematics(format!(
            "joint variable '{}' missing from position: a prismatic joint moves frame i along u in \
             position = p0 + u {0}",
            name(g, q)
        ))
        .at_field("position"));
    }
    let zero = g.zero();
    let rest = position.map(|p| substitute(g, p, q, zero));
    Ok(JointFrames {
        pre: Transform::rotation(g, e),
        axis,
        post: Transform::translation(g, rest),
    })
}

/// Convention (b), standard DH: frame i = Rz(θ)·Tz(d)·Tx(a)·Rx(α), with q added to θ
/// (revolute) or d (prismatic) unless the table writes it there as ±q + c.
pub(crate) fn dh(
    g: &mut ExprGraph,
    motion: Motion,
    p: DhParameters,
) -> Result<JointFrames, SpecError> {
    let (theta, d, axis) = dh_joint(g, motion, p, "dh")?;
    let rz = rotation_about(g, Axis::Z, theta);
    let rotate = Transform::rotation(g, rz);
    let z = g.zero();
    let lift = Transform::translation(g, [z, z, d]);
    let pre = rotate.then(g, &lift);
    let slide = Transform::translation(g, [p.a, z, z]);
    let rx = rotation_about(g, Axis::X, p.alpha);
    let twist = Transform::rotation(g, rx);
    let post = slide.then(g, &twist);
    Ok(JointFrames { pre, axis, post })
}

/// Convention (c), modified DH (Craig): frame i = Rx(α)·Tx(a)·Rz(θ)·Tz(d), q as in [`dh`].
pub(crate) fn mdh(
    g: &mut ExprGraph,
    motion: Motion,
    p: DhParameters,
) -> Result<JointFrames, SpecError> {
    let (theta, d, axis) = dh_joint(g, motion, p, "mdh")?;
    let z = g.zero();
    let rx = rotation_about(g, Axis::X, p.alpha);
    let twist = Transform::rotation(g, rx);
    let slide = Transform::translation(g, [p.a, z, z]);
    let rz = rotation_about(g, Axis::Z, theta);
    let rotate = Transform::rotation(g, rz);
    let lift = Transform::translation(g, [z, z, d]);
    let pre = twist.then(g, &slide).then(g, &rotate).then(g, &lift);
    let post = Transform::identity(g);
    Ok(JointFrames { pre, axis, post })
}

/// Convention (d), URDF: the joint frame is Trans(xyz)·Rz(yaw)Ry(pitch)Rx(roll) and the joint
/// moves about or along the normalised axis.
pub(crate) fn urdf(
    g: &mut ExprGraph,
    motion: Motion,
    xyz: Vec3,
    rpy: Vec3,
    axis: Vec3,
) -> Result<JointFrames, SpecError> {
    let place = Transform::translation(g, xyz);
    let rotation = rpy_rotation(g, rpy);
    let orient = Transform::rotation(g, rotation);
    let pre = place.then(g, &orient);
    let axis = match motion {
        Motion::Fixed => g.zero_vec(),
        Motion::Revolute(_) | Motion::Prismatic(_) => normalise(g, axis)?,
    };
    let post = Transform::identity(g);
    Ok(JointFrames { pre, axis, post })
}

/// θ₀ + motion and d₀ + motion of a DH table, and the joint axis ±e_z.
fn dh_joint(
    g: &mut ExprGraph,
    motion: Motion,
    p: DhParameters,
    table: &str,
) -> Result<(Id, Id, Vec3), SpecError> {
    let z = g.zero();
    let Some(q) = motion.variable() else {
        return Ok((p.theta, p.d, [z, z, z]));
    };
    let (moving, moving_name) = match motion {
        Motion::Prismatic(_) => (p.d, "d"),
        _ => (p.theta, "theta"),
    };
    for (entry, entry_name) in [
        (p.a, "a"),
        (p.alpha, "alpha"),
        (p.d, "d"),
        (p.theta, "theta"),
    ] {
        if entry_name != moving_name && mentions(g, entry, q) {
            return Err(kinematics(format!(
                "joint variable '{}' may appear only in {table}.{moving_name}",
                name(g, q)
            ))
            .at_field(format!("{table}.{entry_name}")));
        }
    }
    let (sign, offset) = if mentions(g, moving, q) {
        affine(g, moving, q).map_err(|e| e.at_field(format!("{table}.{moving_name}")))?
    } else {
        (1.0, moving)
    };
    let axis = signed_unit(g, Axis::Z, sign);
    Ok(match motion {
        Motion::Prismatic(_) => (p.theta, offset, axis),
        _ => (offset, p.d, axis),
    })
}

/// `(±1, c)` such that `expr = ±q + c` with `c` free of q, or an error.
fn affine(g: &mut ExprGraph, expr: Id, q: Symbol) -> Result<(f64, Id), SpecError> {
    let slope = g.derivative(expr, q);
    let sign = match g.as_const(slope) {
        Some(s) if s == 1.0 || s == -1.0 => s,
        _ => {
            return Err(kinematics(format!(
                "joint variable '{}' must enter as ±{0} + c with c free of {0}{}",
                name(g, q),
                found(g, expr)
            )))
        }
    };
    let zero = g.zero();
    Ok((sign, substitute(g, expr, q, zero)))
}

/// The axis divided by its length: numerically when it is constant (an exact unit axis stays
/// exact), symbolically otherwise. A constant zero axis is an error.
fn normalise(g: &mut ExprGraph, axis: Vec3) -> Result<Vec3, SpecError> {
    if let [Some(x), Some(y), Some(z)] = axis.map(|a| g.as_const(a)) {
        let unit = unit_vector([x, y, z])
            .ok_or_else(|| kinematics("axis must not be zero").at_field("axis"))?;
        if unit == [x, y, z] {
            return Ok(axis);
        }
        return Ok(unit.map(|c| g.constant(c)));
    }
    let squared = g.dot(axis, axis);
    let length = g.sqrt(squared);
    Ok(axis.map(|a| g.div(a, length)))
}

/// `v / ‖v‖`, `None` for a zero vector. When ‖v‖² would overflow or lose digits to underflow
/// (components beyond about 1e154 or all below about 1e-154), `v` is first divided by its
/// largest component, after which the squares can do neither.
fn unit_vector(v: [f64; 3]) -> Option<[f64; 3]> {
    let squared: f64 = v.iter().map(|c| c * c).sum();
    if squared.is_finite() && squared >= f64::MIN_POSITIVE {
        let length = squared.sqrt();
        return Some(if length == 1.0 {
            v
        } else {
            v.map(|c| c / length)
        });
    }
    let largest = v.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return None;
    }
    let scaled = v.map(|c| c / largest);
    let length = scaled.iter().map(|c| c * c).sum::<f64>().sqrt();
    Some(scaled.map(|c| c / length))
}

/// The product of elementary rotations, the identity for none.
fn product(g: &mut ExprGraph, factors: &[(Axis, Id)]) -> Mat3 {
    let mut total = g.identity();
    for &(axis, angle) in factors {
        let r = rotation_about(g, axis, angle);
        total = g.mat_mul(&total, &r);
    }
    total
}

/// `sign · e_axis`.
fn signed_unit(g: &mut ExprGraph, axis: Axis, sign: f64) -> Vec3 {
    let mut unit = [0.0; 3];
    if let Some(slot) = unit.get_mut(axis.index()) {
        *slot = sign;
    }
    g.const_vec(unit)
}

fn mentions_factor(g: &ExprGraph, rotation: &[(Axis, Id)], k: usize, q: Symbol) -> bool {
    rotation
        .get(k)
        .is_some_and(|&(_, angle)| mentions(g, angle, q))
}

fn reject_variable(
    g: &ExprGraph,
    v: &Vec3,
    q: Symbol,
    field: &str,
    why: &str,
) -> Result<(), SpecError> {
    if v.iter().any(|&x| mentions(g, x, q)) {
        return Err(kinematics(format!(
            "joint variable '{}' may not appear in {field}: {why}",
            name(g, q)
        ))
        .at_field(field));
    }
    Ok(())
}

/// `, found <s-expression>` for a small expression (printing recurses through it), else nothing.
fn found(g: &ExprGraph, expr: Id) -> String {
    if g.reachable(&[expr]).len() <= 32 {
        format!(", found {}", g.to_sexpr(expr))
    } else {
        String::new()
    }
}

fn name(g: &ExprGraph, q: Symbol) -> String {
    g.symbols().name(q)
}

fn kinematics(message: impl Into<String>) -> SpecError {
    SpecError::new(SpecErrorKind::Kinematics, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::SymbolTable;
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

    fn graph() -> (ExprGraph, Symbol, Id) {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["q1"]));
        let q = Symbol::Position(0);
        let qi = g.symbol(q);
        (g, q, qi)
    }

    fn constants(g: &ExprGraph, v: &[Id]) -> Vec<f64> {
        v.iter()
            .map(|&x| g.as_const(x).expect("constant"))
            .collect()
    }

    #[test]
    fn irb140_first_joint_axis_is_x() {
        let (mut g, q, qi) = graph();
        let half_pi = g.constant(FRAC_PI_2);
        let zero = g.zero();
        let f = thesis(
            &mut g,
            Motion::Revolute(q),
            &[(Axis::Z, qi), (Axis::X, half_pi), (Axis::Z, half_pi)],
            [zero, zero, zero],
        )
        .unwrap();
        assert_eq!(constants(&g, &f.axis), [1.0, 0.0, 0.0]);
        let e: Vec<f64> = constants(&g, &f.pre.rotation.concat());
        assert_eq!(e, [0.0, -1.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0]);
    }

    #[test]
    fn angle_offsets_go_into_the_constant_rotation() {
        let (mut g, q, qi) = graph();
        let half_pi = g.constant(FRAC_PI_2);
        let angle = g.sub(qi, half_pi);
        let zero = g.zero();
        let f = thesis(&mut g, Motion::Revolute(q), &[(Axis::Z, angle)], [zero; 3]).unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, 0.0, 1.0]);
        assert_eq!(
            constants(&g, &f.pre.rotation.concat()),
            [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
        );
        let negative = g.neg(qi);
        let f = thesis(
            &mut g,
            Motion::Revolute(q),
            &[(Axis::Y, negative)],
            [zero; 3],
        )
        .unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, -1.0, 0.0]);
    }

    #[test]
    fn nonlinear_joint_angles_are_errors() {
        let (mut g, q, qi) = graph();
        let two = g.constant(2.0);
        let double = g.mul(two, qi);
        let zero = g.zero();
        let error =
            thesis(&mut g, Motion::Revolute(q), &[(Axis::Z, double)], [zero; 3]).unwrap_err();
        assert_eq!(
            error.message(),
            "joint variable 'q1' must enter as ±q1 + c with c free of q1, found (* q1 2)"
        );
        let error = thesis(
            &mut g,
            Motion::Revolute(q),
            &[(Axis::Z, qi), (Axis::X, qi)],
            [zero; 3],
        )
        .unwrap_err();
        assert!(
            error.message().contains("appears in 2 factors"),
            "{}",
            error.message()
        );
    }

    #[test]
    fn prismatic_position_is_linear() {
        let (mut g, q, qi) = graph();
        let d = g.constant(0.5);
        let z = g.add(d, qi);
        let zero = g.zero();
        let f = thesis(&mut g, Motion::Prismatic(q), &[], [zero, zero, z]).unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, 0.0, 1.0]);
        assert_eq!(constants(&g, &f.post.translation), [0.0, 0.0, 0.5]);
        let squared = g.mul(qi, qi);
        let error = thesis(&mut g, Motion::Prismatic(q), &[], [zero, zero, squared]).unwrap_err();
        assert!(error.message().contains("linearly"));
    }

    #[test]
    fn dh_adds_the_joint_variable_or_reads_it() {
        let (mut g, q, qi) = graph();
        let zero = g.zero();
        let a = g.constant(0.4318);
        let alpha = g.constant(FRAC_PI_2);
        let p = DhParameters {
            a,
            alpha,
            d: zero,
            theta: zero,
        };
        let f = dh(&mut g, Motion::Revolute(q), p).unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, 0.0, 1.0]);
        assert_eq!(constants(&g, &f.post.translation), [0.4318, 0.0, 0.0]);
        assert_eq!(
            constants(&g, &f.post.rotation.concat()),
            [1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0]
        );
        let theta = g.neg(qi);
        let f = dh(&mut g, Motion::Revolute(q), DhParameters { theta, ..p }).unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, 0.0, -1.0]);
        let error = dh(&mut g, Motion::Revolute(q), DhParameters { d: qi, ..p }).unwrap_err();
        assert_eq!(error.field(), Some("dh.d"));
    }

    #[test]
    fn urdf_axes_are_normalised() {
        let (mut g, q, _) = graph();
        let zero = g.zero_vec();
        let axis = g.const_vec([0.0, 0.0, 2.0]);
        let f = urdf(&mut g, Motion::Revolute(q), zero, zero, axis).unwrap();
        assert_eq!(constants(&g, &f.axis), [0.0, 0.0, 1.0]);
        let error = urdf(&mut g, Motion::Revolute(q), zero, zero, zero).unwrap_err();
        assert_eq!(error.message(), "axis must not be zero");
    }

    #[test]
    fn axes_whose_squared_length_overflows_or_underflows_are_normalised_exactly() {
        let (mut g, q, _) = graph();
        let zero = g.zero_vec();
        // As [1, 1, 0] normalises: 1 / fl(√2), one ulp below FRAC_1_SQRT_2.
        let half = 1.0 / 2f64.sqrt();
        assert!((half - FRAC_1_SQRT_2).abs() <= f64::EPSILON);
        for (given, unit) in [
            ([1e308, 1e308, 0.0], [half, half, 0.0]),
            ([f64::MAX, 0.0, 0.0], [1.0, 0.0, 0.0]),
            ([0.0, 1e-160, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -f64::MIN_POSITIVE / 4.0], [0.0, 0.0, -1.0]),
        ] {
            let axis = g.const_vec(given);
            let f = urdf(&mut g, Motion::Revolute(q), zero, zero, axis).unwrap();
            assert_eq!(constants(&g, &f.axis), unit, "axis {given:?}");
        }
    }
}

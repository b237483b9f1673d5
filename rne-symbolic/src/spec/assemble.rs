//! One link of a spec built into the reader's graph as an [`InputLink`]: its frame convention
//! mapped onto `pre ∘ motion ∘ post`, its placement `parent.post ∘ pre`, its inertials
//! converted into the body frame, and its mimic, friction and armature read.

use super::error::{SpecError, SpecErrorKind};
use super::expression::parse_rotation;
use super::schema::{ComSpec, DhSpec, FrameSpec, InertiaSpec, LinkSpec};
use super::scope::{Namespace, Scope};
use crate::expr::{ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::input::frames::{self, DhParameters, JointFrames, Motion};
use crate::input::inertia::{box_inertia, from_components, to_body, upper_symmetric};
use crate::input::{Fields, InputLink};
use crate::model::{Friction, JointKind, Link, Mimic, Transform};

/// Where each part of a link's placement comes from, for messages.
#[derive(Copy, Clone, Debug)]
struct FrameFields {
    rotation: &'static str,
    translation: &'static str,
    axis: &'static str,
}

/// Builds `spec` (whose joint variable is joint `joint`) attached to a parent whose frame is
/// `parent_post` of its body frame (identity for the base).
pub(crate) fn link(
    g: &mut ExprGraph,
    spec: &LinkSpec<'_>,
    parent: Option<usize>,
    joint: Option<usize>,
    parent_post: &Transform,
    space: &Namespace,
) -> Result<InputLink, SpecError> {
    let q = joint.map(|k| Symbol::Position(k as u16));
    let motion = match (spec.kind, q) {
        (JointKind::Revolute, Some(q)) => Motion::Revolute(q),
        (JointKind::Prismatic, Some(q)) => Motion::Prismatic(q),
        _ => Motion::Fixed,
    };
    let geometry = space.scope(q, true);
    let inertials = space.scope(q, false);
    let (frames, frame_fields) = joint_frames(g, &spec.frame, motion, &geometry)?;
    let mass = inertials.number(g, &spec.mass)?;
    let (com, com_field) = match &spec.com {
        ComSpec::Origin => (g.zero_vec(), "com"),
        ComSpec::Frame(v) => (inertials.vector(g, v)?, "com"),
        ComSpec::FromPrevious(v) => (inertials.vector(g, v)?, "com_from_prev"),
    };
    let (inertia, declared_inertia, box_edges) = inertia(g, &spec.inertia, mass, &inertials)?;
    let (body_com, inertia) = to_body(g, &frames.post, com, &inertia);
    let com = match spec.com {
        ComSpec::FromPrevious(_) => com,
        _ => body_com,
    };
    let placement = parent_post.then(g, &frames.pre);
    let mimic = mimic(g, spec, &inertials)?;
    let friction = friction(g, spec, &inertials)?;
    let armature = spec
        .armature
        .as_ref()
        .map(|a| inertials.number(g, a))
        .transpose()?;
    let link = Link {
        name: spec.name.name.clone(),
        parent,
        kind: spec.kind,
        joint,
        rotation: placement.rotation,
        translation: placement.translation,
        axis: frames.axis,
        mass,
        com,
        inertia,
        mimic,
        coupling: None,
        friction,
        armature,
    };
    Ok(InputLink {
        link,
        joint_element: None,
        frames,
        fields: fields(frame_fields, com_field),
        declared_inertia,
        box_edges,
        triangle_inequality: spec.triangle_inequality,
    })
}

/// The rotational inertia `spec` declares (about the COM, in the link's frame), with the rows
/// as declared when given as a matrix and the box's edges when given as a box of mass `mass`.
type DeclaredInertia = (Mat3, Option<Mat3>, Option<Vec3>);

/// The inertia of [`DeclaredInertia`], read from `spec` in the inertials' scope.
fn inertia(
    g: &mut ExprGraph,
    spec: &InertiaSpec<'_>,
    mass: Id,
    inertials: &Scope<'_>,
) -> Result<DeclaredInertia, SpecError> {
    Ok(match spec {
        InertiaSpec::Components { diagonal, products } => {
            let diagonal = inertials.vector(g, diagonal)?;
            let [xy, xz, yz] = products;
            let products = [
                inertials.number_or_zero(g, xy.as_ref())?,
                inertials.number_or_zero(g, xz.as_ref())?,
                inertials.number_or_zero(g, yz.as_ref())?,
            ];
            (from_components(diagonal, products), None, None)
        }
        InertiaSpec::Matrix(rows) => {
            let [r0, r1, r2] = rows;
            let declared = [
                inertials.vector(g, r0)?,
                inertials.vector(g, r1)?,
                inertials.vector(g, r2)?,
            ];
            (upper_symmetric(&declared), Some(declared), None)
        }
        InertiaSpec::Box(edges) => {
            let edges = inertials.vector(g, edges)?;
            (box_inertia(g, mass, edges), None, Some(edges))
        }
    })
}

/// The link's mimic coupling (multiplier 1 and offset 0 unless given).
fn mimic(
    g: &mut ExprGraph,
    spec: &LinkSpec<'_>,
    inertials: &Scope<'_>,
) -> Result<Option<Mimic>, SpecError> {
    Ok(match &spec.mimic {
        None => None,
        Some(m) => Some(Mimic {
            leader: m.joint.name.clone(),
            multiplier: match &m.multiplier {
                Some(n) => inertials.number(g, n)?,
                None => g.one(),
            },
            offset: inertials.number_or_zero(g, m.offset.as_ref())?,
        }),
    })
}

/// The joint's friction (each coefficient 0 unless given).
fn friction(
    g: &mut ExprGraph,
    spec: &LinkSpec<'_>,
    inertials: &Scope<'_>,
) -> Result<Option<Friction>, SpecError> {
    Ok(match &spec.friction {
        None => None,
        Some(f) => Some(Friction {
            viscous: inertials.number_or_zero(g, f.viscous.as_ref())?,
            coulomb: inertials.number_or_zero(g, f.coulomb.as_ref())?,
            offset: inertials.number_or_zero(g, f.offset.as_ref())?,
        }),
    })
}

/// The spec fields each part of a link comes from, for messages.
fn fields(frame_fields: FrameFields, com_field: &'static str) -> Fields {
    Fields {
        rotation: frame_fields.rotation,
        translation: frame_fields.translation,
        axis: frame_fields.axis,
        mass: "mass",
        com: com_field,
        inertia: "inertia",
        mimic: "mimic.joint",
        mimic_multiplier: "mimic.multiplier",
        mimic_offset: "mimic.offset",
        viscous: "friction.viscous",
        coulomb: "friction.coulomb",
        friction_offset: "friction.offset",
    }
}

fn joint_frames(
    g: &mut ExprGraph,
    frame: &FrameSpec<'_>,
    motion: Motion,
    scope: &Scope<'_>,
) -> Result<(JointFrames, FrameFields), SpecError> {
    match frame {
        FrameSpec::Thesis { rotation, position } => {
            let factors = match rotation {
                None => Vec::new(),
                Some(text) => parse_rotation(g, &text.name, scope).map_err(|message| {
                    SpecError::new(SpecErrorKind::Expression, message)
                        .at_field("rotation")
                        .at_span(text.span.clone())
                })?,
            };
            let position = match position {
                None => g.zero_vec(),
                Some(p) => scope.vector(g, p)?,
            };
            let axis = if matches!(motion, Motion::Prismatic(_)) {
                "position"
            } else {
                "rotation"
            };
            let fields = FrameFields {
                rotation: "rotation",
                translation: "position",
                axis,
            };
            Ok((frames::thesis(g, motion, &factors, position)?, fields))
        }
        FrameSpec::Dh(table) => {
            let parameters = dh_parameters(g, table, scope)?;
            Ok((
                frames::dh(g, motion, parameters)?,
                FrameFields {
                    rotation: "dh",
                    translation: "dh",
                    axis: "dh",
                },
            ))
        }
        FrameSpec::Mdh(table) => {
            let parameters = dh_parameters(g, table, scope)?;
            Ok((
                frames::mdh(g, motion, parameters)?,
                FrameFields {
                    rotation: "mdh",
                    translation: "mdh",
                    axis: "mdh",
                },
            ))
        }
        FrameSpec::Urdf { xyz, rpy, axis } => {
            // The origin and axis of a URDF joint never contain its variable.
            let scope = &scope.without_joint();
            let xyz = match xyz {
                None => g.zero_vec(),
                Some(v) => scope.vector(g, v)?,
            };
            let rpy = match rpy {
                None => g.zero_vec(),
                Some(v) => scope.vector(g, v)?,
            };
            let axis = match axis {
                None => g.const_vec([1.0, 0.0, 0.0]),
                Some(v) => scope.vector(g, v)?,
            };
            let fields = FrameFields {
                rotation: "origin.rpy",
                translation: "origin.xyz",
                axis: "axis",
            };
            Ok((frames::urdf(g, motion, xyz, rpy, axis)?, fields))
        }
    }
}

fn dh_parameters(
    g: &mut ExprGraph,
    table: &DhSpec<'_>,
    scope: &Scope<'_>,
) -> Result<DhParameters, SpecError> {
    Ok(DhParameters {
        a: scope.number_or_zero(g, table.a.as_ref())?,
        alpha: scope.number_or_zero(g, table.alpha.as_ref())?,
        d: scope.number_or_zero(g, table.d.as_ref())?,
        theta: scope.number_or_zero(g, table.theta.as_ref())?,
    })
}

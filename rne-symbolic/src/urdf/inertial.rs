//! A link's `<inertial>`: checked as a TOML link's inertials are, then expressed in the link
//! frame.
//!
//! The `<inertial>` element gives the mass, and the inertia tensor about the COM in the axes of
//! an inertial frame placed by its `<origin xyz rpy>` in the link frame. In the link frame the
//! COM is `xyz` and the tensor is `R I Rᵀ` with `R = Rz(yaw) Ry(pitch) Rx(roll)` ((3.5)–(3.6)).

use urdf_rs::Link;

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::{rpy_rotation, Transform};
use crate::spec::inertia::{from_components, to_body};
use crate::spec::validate::{finite, inertia_tensor, non_negative_mass};
use crate::spec::SpecError;

/// The inertia tensor of `<inertia ixx .. izz>`, row-major.
fn tensor(link: &Link) -> [[f64; 3]; 3] {
    let i = &link.inertial.inertia;
    [
        [i.ixx, i.ixy, i.ixz],
        [i.ixy, i.iyy, i.iyz],
        [i.ixz, i.iyz, i.izz],
    ]
}

/// Checks the numbers of `link`'s inertial: all finite, mass ≥ 0, the tensor positive
/// semi-definite and, with mass, satisfying the triangle inequality (its eigenvalues do not
/// depend on the inertial frame's orientation). The caller names the link.
pub(crate) fn validate(link: &Link) -> Result<(), SpecError> {
    let inertial = &link.inertial;
    let mass = inertial.mass.value;
    finite(&[mass], "inertial.mass")?;
    non_negative_mass(mass).map_err(|e| e.at_field("inertial.mass"))?;
    finite(&inertial.origin.xyz.0, "inertial.origin.xyz")?;
    finite(&inertial.origin.rpy.0, "inertial.origin.rpy")?;
    let inertia = tensor(link);
    finite(&inertia.concat(), "inertial.inertia")?;
    inertia_tensor(&inertia, mass, true).map_err(|e| e.at_field("inertial.inertia"))
}

/// Mass, COM and inertia about the COM of `link` in its own frame, as constants of `g`.
pub(crate) fn in_link_frame(g: &mut ExprGraph, link: &Link) -> (Id, Vec3, Mat3) {
    let inertial = &link.inertial;
    let mass = g.constant(inertial.mass.value);
    let xyz = g.const_vec(inertial.origin.xyz.0);
    let rpy = g.const_vec(inertial.origin.rpy.0);
    let place = Transform::translation(g, xyz);
    let rotation = rpy_rotation(g, rpy);
    let orient = Transform::rotation(g, rotation);
    let frame = place.then(g, &orient);
    let i = &inertial.inertia;
    let diagonal = g.const_vec([i.ixx, i.iyy, i.izz]);
    let products = g.const_vec([i.ixy, i.ixz, i.iyz]);
    let at_com = g.zero_vec();
    let (com, inertia) = to_body(g, &frame, at_com, &from_components(diagonal, products));
    (mass, com, inertia)
}

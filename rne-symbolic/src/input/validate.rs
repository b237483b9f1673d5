//! Numeric validation of the input links at the parameters' values (docs/design.md §2.3–§2.4),
//! graded: **errors** for what makes the model meaningless — a number that is not finite, a
//! negative mass, a non-unit joint axis, a 3×3 inertia array that is not symmetric, negative box
//! edges, a clearly negative principal moment of inertia — and **warnings** for what published data
//! often gets slightly wrong: principal moments that break the triangle inequality
//! I1 + I2 ≥ I3 (for a link with mass, unless a TOML spec opts out), and a negative principal
//! moment negligible against the robot's inertia scale ([`NEGLIGIBLE_INERTIA`]).

use super::{InputLink, Place};
use crate::expr::{ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::model::{JointKind, Parameter};
use crate::spec::{SpecError, SpecErrorKind, SpecWarning, SpecWarningKind};

/// A negative principal moment of inertia λ is a warning, not an error, when
/// |λ| ≤ `NEGLIGIBLE_INERTIA` × the robot's inertia scale (the largest principal moment of any
/// of its links). Published URDFs carry values like −1e-8 kg·m² against moments of 1e-3 to
/// 1 kg·m² (rounding of a CAD export); a millionth of the scale is far above such rounding and
/// far below any inertia that matters for the dynamics, while a clearly negative moment
/// (−1e-3 against 1) is a mistake and stays an error.
pub const NEGLIGIBLE_INERTIA: f64 = 1e-6;
/// Relative tolerance below which a negative principal moment is rounding in the arithmetic
/// (eigenvalues >= −tol · the link's largest entry) and passes silently.
const PSD_TOLERANCE: f64 = 1e-12;
/// Relative tolerance of the symmetry test of a 3×3 inertia array.
const SYMMETRY_TOLERANCE: f64 = 1e-12;
/// Relative tolerance of the triangle inequality (I1 + I2 >= I3 − tol · I3).
const TRIANGLE_TOLERANCE: f64 = 1e-9;
/// Tolerance on the length of a joint axis.
const UNIT_TOLERANCE: f64 = 1e-9;

/// Numeric values of a graph's expressions at the parameters' values.
pub(crate) struct Values<'a> {
    graph: &'a ExprGraph,
    parameters: &'a [Parameter],
}

impl<'a> Values<'a> {
    /// Evaluates `graph` with parameter symbols at `parameters` (other symbols are NaN).
    pub(crate) fn new(graph: &'a ExprGraph, parameters: &'a [Parameter]) -> Values<'a> {
        Values { graph, parameters }
    }

    fn eval(&self, ids: &[Id]) -> Vec<f64> {
        self.graph.eval::<f64>(ids, |s| match s {
            Symbol::Parameter(k) => self
                .parameters
                .get(k as usize)
                .map_or(f64::NAN, |p| p.value),
            _ => f64::NAN,
        })
    }

    /// The value of a scalar.
    pub(crate) fn scalar(&self, id: Id) -> f64 {
        self.eval(&[id]).first().copied().unwrap_or(f64::NAN)
    }

    /// The value of a vector.
    pub(crate) fn vector(&self, v: &Vec3) -> [f64; 3] {
        let values = self.eval(v);
        [0, 1, 2].map(|i| values.get(i).copied().unwrap_or(f64::NAN))
    }

    fn matrix(&self, m: &Mat3) -> [[f64; 3]; 3] {
        [self.vector(&m[0]), self.vector(&m[1]), self.vector(&m[2])]
    }
}

/// What the robot-wide checks need to know of a link that passed [`link`].
#[derive(Copy, Clone, Debug)]
pub(crate) struct LinkNumbers {
    /// The mass.
    pub(crate) mass: f64,
    /// The principal moments of inertia about the COM, increasing.
    pub(crate) principal: [f64; 3],
    /// Whether the link has mass or inertia.
    pub(crate) carries: bool,
}

/// Checks that a vector that is not a link's (gravity) is finite.
pub(crate) fn finite_vector(values: &Values<'_>, v: &Vec3, field: &str) -> Result<(), SpecError> {
    finite(&values.vector(v), field)
}

/// Checks a built link, except the grading of its principal moments ([`inertia_tensor`]);
/// errors name the field and the link or joint the field belongs to.
pub(crate) fn link(values: &Values<'_>, input: &InputLink) -> Result<LinkNumbers, SpecError> {
    let fields = input.fields;
    let frames = &input.frames;
    let joint_field = |e: SpecError| input.place(Place::Joint, e);
    let link_field = |e: SpecError| input.place(Place::Link, e);
    finite(
        &values.matrix(&frames.pre.rotation).concat(),
        fields.rotation,
    )
    .map_err(joint_field)?;
    finite(
        &values.matrix(&frames.post.rotation).concat(),
        fields.rotation,
    )
    .map_err(joint_field)?;
    finite(&values.vector(&frames.pre.translation), fields.translation).map_err(joint_field)?;
    finite(&values.vector(&frames.post.translation), fields.translation).map_err(joint_field)?;
    if input.link.kind != JointKind::Fixed {
        let axis = values.vector(&input.link.axis);
        finite(&axis, fields.axis).map_err(joint_field)?;
        let length = axis.iter().map(|u| u * u).sum::<f64>().sqrt();
        if (length - 1.0).abs() > UNIT_TOLERANCE {
            return Err(joint_field(
                SpecError::new(
                    SpecErrorKind::Kinematics,
                    format!("the joint axis must be a unit vector, got length {length}"),
                )
                .at_field(fields.axis),
            ));
        }
    }
    dynamics_numbers(values, input).map_err(joint_field)?;
    let mass = values.scalar(input.link.mass);
    finite(&[mass], fields.mass).map_err(link_field)?;
    if mass < 0.0 {
        return Err(link_field(
            physics(format!("mass must be >= 0, got {mass}")).at_field(fields.mass),
        ));
    }
    finite(&values.vector(&input.link.com), fields.com).map_err(link_field)?;
    if let Some(edges) = &input.box_edges {
        let edges = values.vector(edges);
        finite(&edges, "inertia.box").map_err(link_field)?;
        if edges.iter().any(|&l| l < 0.0) {
            return Err(link_field(
                physics(format!(
                    "box edge lengths must be >= 0, got {}",
                    list(&edges)
                ))
                .at_field("inertia.box"),
            ));
        }
    }
    if let Some(declared) = &input.declared_inertia {
        symmetric(&values.matrix(declared))
            .map_err(|e| e.at_field(fields.inertia))
            .map_err(link_field)?;
    }
    let inertia = values.matrix(&input.link.inertia);
    finite(&inertia.concat(), fields.inertia).map_err(link_field)?;
    Ok(LinkNumbers {
        mass,
        principal: eigenvalues(&inertia),
        carries: mass != 0.0 || inertia.concat().iter().any(|&i| i != 0.0),
    })
}

/// The mimic, friction and armature numbers: finite, friction coefficients and armature >= 0.
fn dynamics_numbers(values: &Values<'_>, input: &InputLink) -> Result<(), SpecError> {
    let fields = input.fields;
    let link = &input.link;
    if let Some(mimic) = &link.mimic {
        finite(&[values.scalar(mimic.multiplier)], fields.mimic_multiplier)?;
        finite(&[values.scalar(mimic.offset)], fields.mimic_offset)?;
    }
    if let Some(friction) = &link.friction {
        for (id, field, signed) in [
            (friction.viscous, fields.viscous, false),
            (friction.coulomb, fields.coulomb, false),
            (friction.offset, fields.friction_offset, true),
        ] {
            let value = values.scalar(id);
            finite(&[value], field)?;
            if !signed && value < 0.0 {
                return Err(physics(format!("{field} must be >= 0, got {value}")).at_field(field));
            }
        }
    }
    if let Some(armature) = link.armature {
        let value = values.scalar(armature);
        finite(&[value], "armature")?;
        if value < 0.0 {
            return Err(physics(format!("armature must be >= 0, got {value}")).at_field("armature"));
        }
    }
    Ok(())
}

/// Grades the principal moments `[i1, i2, i3]` (increasing) of a link of mass `mass` in a robot
/// whose largest principal moment is `scale`: a clearly negative moment is an error; a
/// negligible one ([`NEGLIGIBLE_INERTIA`]) and, for a link with mass that asks for the test,
/// a broken triangle inequality are warnings (a negative moment always breaks the triangle
/// inequality, which is then not reported again). The caller names the field and the link.
pub(crate) fn inertia_tensor(
    principal: [f64; 3],
    mass: f64,
    triangle_inequality: bool,
    scale: f64,
) -> Result<Vec<SpecWarning>, SpecError> {
    let [i1, i2, i3] = principal;
    let largest = i1.abs().max(i3.abs());
    if i1 < -PSD_TOLERANCE * largest {
        let moments = list(&principal);
        if -i1 > NEGLIGIBLE_INERTIA * scale {
            return Err(physics(format!(
                "inertia is not positive semi-definite: principal moments {moments}"
            )));
        }
        return Ok(vec![SpecWarning::new(
            SpecWarningKind::NegligibleNegativeInertia,
            format!(
                "inertia has a negative principal moment, negligible against the robot's \
                 largest principal moment {} (at most {NEGLIGIBLE_INERTIA:e} of it): principal \
                 moments {moments}",
                short(scale)
            ),
        )]);
    }
    let mut warnings = Vec::new();
    if mass > 0.0 && triangle_inequality && i1 + i2 < i3 - TRIANGLE_TOLERANCE * i3 {
        warnings.push(SpecWarning::new(
            SpecWarningKind::TriangleInequality,
            format!(
                "inertia breaks the triangle inequality: principal moments {} + {} < {} (a TOML \
                 spec may set triangle_inequality = false for published data that does, saying \
                 why in a comment)",
                short(i1),
                short(i2),
                short(i3)
            ),
        ));
    }
    Ok(warnings)
}

fn symmetric(m: &[[f64; 3]; 3]) -> Result<(), SpecError> {
    let scale = m.concat().iter().fold(0.0_f64, |s, x| s.max(x.abs()));
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (m[i][j] - m[j][i]).abs() > SYMMETRY_TOLERANCE * scale {
            return Err(physics(format!(
                "inertia is not symmetric: [{i}][{j}] = {} but [{j}][{i}] = {}",
                m[i][j], m[j][i]
            )));
        }
    }
    Ok(())
}

/// Checks that every value is finite; the error names `field`.
pub(crate) fn finite(values: &[f64], field: &str) -> Result<(), SpecError> {
    match values.iter().find(|x| !x.is_finite()) {
        None => Ok(()),
        Some(x) => Err(physics(format!("{field} is not finite ({x})")).at_field(field)),
    }
}

/// The eigenvalues of a symmetric 3×3 matrix in increasing order (cyclic Jacobi rotations).
fn eigenvalues(m: &[[f64; 3]; 3]) -> [f64; 3] {
    let mut a = *m;
    for _ in 0..64 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diagonal = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off == 0.0 || off <= 1e-18 * diagonal {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in a.iter_mut() {
                let (kp, kq) = (row[p], row[q]);
                row[p] = c * kp - s * kq;
                row[q] = s * kp + c * kq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            a[p] = [0, 1, 2].map(|k| c * row_p[k] - s * row_q[k]);
            a[q] = [0, 1, 2].map(|k| s * row_p[k] + c * row_q[k]);
        }
    }
    let mut d = [a[0][0], a[1][1], a[2][2]];
    d.sort_by(f64::total_cmp);
    d
}

fn physics(message: String) -> SpecError {
    SpecError::new(SpecErrorKind::Physics, message)
}

/// A number with at most 6 significant digits, for messages.
fn short(x: f64) -> String {
    let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    format!("{rounded}")
}

fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|&x| short(x))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_of_known_matrices() {
        let e = eigenvalues(&[[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]]);
        for (x, y) in e.iter().zip([1.0, 3.0, 5.0]) {
            assert!((x - y).abs() < 1e-14, "{e:?}");
        }
        let e = eigenvalues(&[[4.0, 1.0, 2.0], [1.0, 3.0, 0.5], [2.0, 0.5, 6.0]]);
        let trace: f64 = e.iter().sum();
        assert!((trace - 13.0).abs() < 1e-13);
        let det = 4.0 * (3.0 * 6.0 - 0.25) - (6.0 - 1.0) + 2.0 * (0.5 - 6.0);
        assert!((e.iter().product::<f64>() - det).abs() < 1e-12);
        assert_eq!(eigenvalues(&[[0.0; 3]; 3]), [0.0; 3]);
    }

    fn principal(a: f64, b: f64, c: f64) -> [f64; 3] {
        eigenvalues(&[[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]])
    }

    fn kinds(warnings: &[SpecWarning]) -> Vec<SpecWarningKind> {
        warnings.iter().map(SpecWarning::kind).collect()
    }

    #[test]
    fn a_valid_inertia_gives_no_warning() {
        for (moments, mass) in [
            (principal(0.0, 0.35, 0.0), 0.0),
            (principal(0.0, 0.0, 0.0), 1.0),
            (principal(0.0, 1.0, 1.0), 1.0),
        ] {
            assert_eq!(inertia_tensor(moments, mass, true, 1.0), Ok(Vec::new()));
        }
    }

    #[test]
    fn a_broken_triangle_inequality_is_a_warning_unless_opted_out_or_massless() {
        let puma3 = principal(0.066, 0.086, 0.0125);
        let warnings = inertia_tensor(puma3, 4.8, true, 1.0).unwrap();
        assert_eq!(kinds(&warnings), [SpecWarningKind::TriangleInequality]);
        assert_eq!(
            warnings[0].message(),
            "inertia breaks the triangle inequality: principal moments 0.0125 + 0.066 < 0.086 (a \
             TOML spec may set triangle_inequality = false for published data that does, saying \
             why in a comment)"
        );
        assert_eq!(inertia_tensor(puma3, 4.8, false, 1.0), Ok(Vec::new()));
        assert_eq!(inertia_tensor(puma3, 0.0, true, 1.0), Ok(Vec::new()));
    }

    #[test]
    fn a_negative_moment_is_a_warning_up_to_a_millionth_of_the_robot_scale() {
        // Tiago's antenna: -1e-8 against moments of the robot up to about 1.
        let antenna = principal(-1e-8, 2e-5, 2e-5);
        let warnings = inertia_tensor(antenna, 0.1, true, 1.0).unwrap();
        assert_eq!(
            kinds(&warnings),
            [SpecWarningKind::NegligibleNegativeInertia]
        );
        assert!(inertia_tensor(principal(-1e-6, 1.0, 1.0), 1.0, true, 1.0).is_ok());
        let error = inertia_tensor(principal(-1.01e-6, 1.0, 1.0), 1.0, true, 1.0).unwrap_err();
        assert_eq!(error.kind(), SpecErrorKind::Physics);
        // The scale is the robot's, not the link's: a tiny link's own moments do not excuse it.
        assert!(inertia_tensor(antenna, 0.1, true, 1e-5).is_err());
        assert_eq!(
            inertia_tensor(principal(1.0, -1.0, 1.0), 1.0, true, 1.0)
                .unwrap_err()
                .message(),
            "inertia is not positive semi-definite: principal moments -1, 1, 1"
        );
    }

    #[test]
    fn rounding_below_the_link_scale_passes_silently() {
        let moments = principal(-1e-15, 1.0, 1.0);
        assert_eq!(inertia_tensor(moments, 1.0, true, 1.0), Ok(Vec::new()));
    }
}

//! Physical validation of a built link at the parameters' values: every number finite, a mass
//! of at least zero, a symmetric positive semi-definite inertia whose principal moments satisfy
//! the triangle inequality I1 + I2 >= I3 (for a link with mass, unless the spec opts out), unit
//! joint axes.

use super::assemble::Assembled;
use super::error::{SpecError, SpecErrorKind};
use crate::expr::{ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::model::{JointKind, Parameter};

/// Relative tolerance of the positive semi-definiteness test (eigenvalues >= −tol · scale).
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

    fn scalar(&self, id: Id) -> f64 {
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

/// Checks that a vector that is not a link's (gravity) is finite.
pub(crate) fn finite_vector(values: &Values<'_>, v: &Vec3, field: &str) -> Result<(), SpecError> {
    finite(&values.vector(v), field)
}

/// Checks a built link; errors name the field (the caller adds the link).
pub(crate) fn link(values: &Values<'_>, built: &Assembled) -> Result<(), SpecError> {
    let fields = built.frame_fields;
    finite(
        &values.matrix(&built.frames.pre.rotation).concat(),
        fields.rotation,
    )?;
    finite(
        &values.matrix(&built.frames.post.rotation).concat(),
        fields.rotation,
    )?;
    finite(
        &values.vector(&built.frames.pre.translation),
        fields.translation,
    )?;
    finite(
        &values.vector(&built.frames.post.translation),
        fields.translation,
    )?;
    if built.link.kind != JointKind::Fixed {
        let axis = values.vector(&built.link.axis);
        finite(&axis, fields.axis)?;
        let length = axis.iter().map(|u| u * u).sum::<f64>().sqrt();
        if (length - 1.0).abs() > UNIT_TOLERANCE {
            return Err(SpecError::new(
                SpecErrorKind::Kinematics,
                format!("the joint axis must be a unit vector, got length {length}"),
            )
            .at_field(fields.axis));
        }
    }
    let mass = values.scalar(built.link.mass);
    finite(&[mass], "mass")?;
    non_negative_mass(mass).map_err(|e| e.at_field("mass"))?;
    finite(&values.vector(&built.link.com), built.com_field)?;
    if let Some(edges) = &built.box_edges {
        let edges = values.vector(edges);
        finite(&edges, "inertia.box")?;
        if edges.iter().any(|&l| l < 0.0) {
            return Err(physics(format!(
                "box edge lengths must be >= 0, got {}",
                list(&edges)
            ))
            .at_field("inertia.box"));
        }
    }
    if let Some(declared) = &built.declared_inertia {
        symmetric(&values.matrix(declared))?;
    }
    let inertia = values.matrix(&built.link.inertia);
    finite(&inertia.concat(), "inertia")?;
    inertia_tensor(&inertia, mass, built.triangle_inequality).map_err(|e| e.at_field("inertia"))
}

/// A mass of at least zero (the caller names the field).
pub(crate) fn non_negative_mass(mass: f64) -> Result<(), SpecError> {
    if mass < 0.0 {
        return Err(physics(format!("mass must be >= 0, got {mass}")));
    }
    Ok(())
}

/// Positive semi-definiteness and, for a link with mass, the triangle inequality of the
/// principal moments (the caller names the field).
pub(crate) fn inertia_tensor(
    inertia: &[[f64; 3]; 3],
    mass: f64,
    triangle_inequality: bool,
) -> Result<(), SpecError> {
    let scale = inertia.concat().iter().fold(0.0_f64, |s, x| s.max(x.abs()));
    let [i1, i2, i3] = eigenvalues(inertia);
    if i1 < -PSD_TOLERANCE * scale {
        return Err(physics(format!(
            "inertia is not positive semi-definite: principal moments {}",
            list(&[i1, i2, i3])
        )));
    }
    if mass > 0.0 && triangle_inequality && i1 + i2 < i3 - TRIANGLE_TOLERANCE * i3 {
        return Err(physics(format!(
            "inertia breaks the triangle inequality: principal moments {} + {} < {} (a spec may set \
             triangle_inequality = false for published data that does, saying why in a comment)",
            short(i1),
            short(i2),
            short(i3)
        )));
    }
    Ok(())
}

fn symmetric(m: &[[f64; 3]; 3]) -> Result<(), SpecError> {
    let scale = m.concat().iter().fold(0.0_f64, |s, x| s.max(x.abs()));
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (m[i][j] - m[j][i]).abs() > SYMMETRY_TOLERANCE * scale {
            return Err(physics(format!(
                "inertia is not symmetric: [{i}][{j}] = {} but [{j}][{i}] = {}",
                m[i][j], m[j][i]
            ))
            .at_field("inertia"));
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

    #[test]
    fn inertia_checks() {
        let diag = |a, b, c| [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]];
        assert!(inertia_tensor(&diag(0.0, 0.35, 0.0), 0.0, true).is_ok());
        assert!(inertia_tensor(&diag(0.0, 0.0, 0.0), 1.0, true).is_ok());
        assert!(inertia_tensor(&diag(0.0, 1.0, 1.0), 1.0, true).is_ok());
        let puma3 = diag(0.066, 0.086, 0.0125);
        assert_eq!(
            inertia_tensor(&puma3, 4.8, true).unwrap_err().message(),
            "inertia breaks the triangle inequality: principal moments 0.0125 + 0.066 < 0.086 (a spec may \
             set triangle_inequality = false for published data that does, saying why in a comment)"
        );
        assert!(inertia_tensor(&puma3, 4.8, false).is_ok());
        assert!(inertia_tensor(&puma3, 0.0, true).is_ok());
        assert_eq!(
            inertia_tensor(&diag(1.0, -1.0, 1.0), 1.0, true)
                .unwrap_err()
                .message(),
            "inertia is not positive semi-definite: principal moments -1, 1, 1"
        );
    }
}

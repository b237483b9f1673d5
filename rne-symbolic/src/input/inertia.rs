//! Inertials: the three ways a spec writes an inertia tensor (about the COM, axes of frame i),
//! and their conversion into the body frame through the convention's post-transform.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::Transform;

/// The inertia tensor of a uniform box of mass `m` and edge lengths `edges` along the axes,
/// about its centre: `Ixx = m (ly² + lz²) / 12` and cyclically ((6.19)–(6.21), (6.45)–(6.47)).
pub(crate) fn box_inertia(g: &mut ExprGraph, mass: Id, edges: Vec3) -> Mat3 {
    let squares = edges.map(|l| g.square(l));
    let twelve = g.constant(12.0);
    let moment = |g: &mut ExprGraph, i: usize, j: usize| {
        let sum = g.add(squares[i], squares[j]);
        let weighted = g.mul(mass, sum);
        g.div(weighted, twelve)
    };
    let diagonal = [moment(g, 1, 2), moment(g, 0, 2), moment(g, 0, 1)];
    diagonal_matrix(g, diagonal)
}

/// The symmetric tensor with diagonal `[xx, yy, zz]` and products of inertia `[xy, xz, yz]`.
pub(crate) fn from_components(diagonal: Vec3, products: Vec3) -> Mat3 {
    let [xx, yy, zz] = diagonal;
    let [xy, xz, yz] = products;
    [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
}

/// The symmetric matrix with the upper triangle of `m` (a 3×3 array after its symmetry has
/// been checked).
pub(crate) fn upper_symmetric(m: &Mat3) -> Mat3 {
    let mut s = *m;
    for i in 0..3 {
        for j in 0..i {
            s[i][j] = m[j][i];
        }
    }
    s
}

/// COM and inertia given in frame i, expressed in the body frame B_i, which `post` maps
/// frame i into: `com_B = R com + t`, `I_B = R I Rᵀ` ((3.5)–(3.6)).
pub(crate) fn to_body(
    g: &mut ExprGraph,
    post: &Transform,
    com: Vec3,
    inertia: &Mat3,
) -> (Vec3, Mat3) {
    let com = post.apply(g, com);
    let inertia = g.similarity(&post.rotation, inertia);
    (com, inertia)
}

fn diagonal_matrix(g: &mut ExprGraph, d: Vec3) -> Mat3 {
    let z = g.zero();
    [[d[0], z, z], [z, d[1], z], [z, z, d[2]]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Symbol;
    use crate::model::{rotation_about, Axis};
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn box_moments() {
        let mut g = ExprGraph::default();
        let m = g.constant(12.0);
        let edges = g.const_vec([1.0, 2.0, 3.0]);
        let i = box_inertia(&mut g, m, edges);
        let d: Vec<Option<f64>> = (0..3).map(|k| g.as_const(i[k][k])).collect();
        assert_eq!(d, [Some(13.0), Some(10.0), Some(5.0)]);
        assert!(g.is_zero(i[0][1]));
    }

    #[test]
    fn conversion_rotates_and_shifts() {
        let mut g = ExprGraph::default();
        let angle = g.constant(FRAC_PI_2);
        let r = rotation_about(&mut g, Axis::X, angle);
        let t = g.const_vec([1.0, 0.0, 0.0]);
        let post = Transform {
            rotation: r,
            translation: t,
        };
        let a = g.symbol(Symbol::Parameter(0));
        let b = g.symbol(Symbol::Parameter(1));
        let z = g.zero();
        let inertia = [[a, z, z], [z, a, z], [z, z, b]];
        let com = g.const_vec([0.0, 1.0, 0.0]);
        let (com_b, inertia_b) = to_body(&mut g, &post, com, &inertia);
        let c: Vec<Option<f64>> = com_b.iter().map(|&x| g.as_const(x)).collect();
        assert_eq!(c, [Some(1.0), Some(0.0), Some(1.0)]);
        assert_eq!(inertia_b[1][1], b);
        assert_eq!(inertia_b[2][2], a);
        assert!(g.is_zero(inertia_b[1][2]));
    }
}

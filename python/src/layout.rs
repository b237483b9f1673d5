//! How a kernel's values (rne's layout: matrices row-major, tuples concatenated, per frame a
//! row-major rotation then the origin) become numpy arrays: one or more parts, each a list of
//! segments of the kernel's output gathered into one C-contiguous array.

use rne_codegen_core::{Kernel, Shape};

/// The sizes a kernel's output depends on.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Sizes {
    /// Velocities NV.
    pub nv: usize,
    /// Frames of the kinematics kernels NF.
    pub nf: usize,
    /// Standard parameters NP.
    pub np: usize,
    /// Base parameters NB.
    pub nb: usize,
}

/// One array of a kernel's result: its shape for one state, and the (start, length) segments
/// of the kernel's output it gathers, in order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Part {
    /// The array's shape for one state (a batch puts N first).
    pub shape: Vec<usize>,
    /// The segments of one state's output, in order.
    pub segments: Vec<(usize, usize)>,
}

impl Part {
    /// A part that is the whole output, of `shape`.
    fn whole(shape: Vec<usize>) -> Part {
        let len = shape.iter().product();
        Part {
            shape,
            segments: vec![(0, len)],
        }
    }

    /// The number of values per state.
    pub fn len(&self) -> usize {
        self.segments.iter().map(|&(_, n)| n).sum()
    }
}

/// The arrays `kernel` returns, in order: a tuple of them when there are several.
pub(crate) fn parts(kernel: Kernel, s: Sizes, output_len: usize) -> Vec<Part> {
    let (nv, nf) = (s.nv, s.nf);
    match kernel.shape() {
        Shape::Scalar => vec![Part::whole(vec![])],
        Shape::Vector => vec![Part::whole(vec![nv])],
        Shape::Matrix => vec![Part::whole(vec![nv, nv])],
        Shape::Matrices(k) => (0..k)
            .map(|i| Part {
                shape: vec![nv, nv],
                segments: vec![(i * nv * nv, nv * nv)],
            })
            .collect(),
        Shape::Placements => vec![
            Part {
                shape: vec![nf, 3, 3],
                segments: (0..nf).map(|f| (12 * f, 9)).collect(),
            },
            Part {
                shape: vec![nf, 3],
                segments: (0..nf).map(|f| (12 * f + 9, 3)).collect(),
            },
        ],
        Shape::FrameMatrices => vec![Part::whole(vec![nf, 6, nv])],
        Shape::FrameVectors => vec![Part::whole(vec![nf, 6])],
        Shape::Regressor => vec![Part::whole(vec![nv, s.np])],
        Shape::BaseRegressor => vec![Part::whole(vec![nv, s.nb])],
        Shape::BaseVector => vec![Part::whole(vec![s.nb])],
        _ => vec![Part::whole(vec![output_len])],
    }
}

/// Whether `parts` is one part that is the whole output in order (no gathering needed).
pub(crate) fn is_whole(parts: &[Part], output_len: usize) -> bool {
    matches!(parts, [part] if part.segments == [(0, output_len)])
}

/// Gathers consecutive outputs of `per` values each from `values` into one slice per part,
/// from state `first` of the slices on (each slice holds `part.len()` values per state).
pub(crate) fn gather(
    values: &[f64],
    per: usize,
    parts: &[Part],
    outs: &mut [&mut [f64]],
    first: usize,
) {
    for (part, out) in parts.iter().zip(outs.iter_mut()) {
        let mut k = first * part.len();
        for state in values.chunks_exact(per.max(1)) {
            for &(start, len) in &part.segments {
                out[k..k + len].copy_from_slice(&state[start..start + len]);
                k += len;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZES: Sizes = Sizes {
        nv: 2,
        nf: 2,
        np: 20,
        nb: 5,
    };

    #[test]
    fn every_kernels_parts_cover_its_output_once() {
        for kernel in Kernel::ALL {
            let len = match kernel.shape() {
                Shape::Scalar => 1,
                Shape::Vector => 2,
                Shape::Matrix => 4,
                Shape::Matrices(k) => 4 * k,
                Shape::Placements => 24,
                Shape::FrameMatrices => 24,
                Shape::FrameVectors => 12,
                Shape::Regressor => 40,
                Shape::BaseRegressor => 10,
                _ => 5,
            };
            let parts = parts(kernel, SIZES, len);
            let mut covered = vec![0; len];
            for part in &parts {
                assert_eq!(part.len(), part.shape.iter().product::<usize>(), "{kernel}");
                for &(start, n) in &part.segments {
                    covered[start..start + n].iter_mut().for_each(|c| *c += 1);
                }
            }
            assert!(covered.iter().all(|&c| c == 1), "{kernel}: {covered:?}");
        }
    }

    #[test]
    fn placements_split_into_rotations_and_origins() {
        let values: Vec<f64> = (0..48).map(f64::from).collect(); // two states, two frames
        let parts = parts(Kernel::FramePlacements, SIZES, 24);
        let (mut r, mut p) = (vec![0.0; 36], vec![0.0; 12]);
        gather(&values, 24, &parts, &mut [&mut r, &mut p], 0);
        assert_eq!(&r[..9], &values[..9]);
        assert_eq!(&r[9..18], &values[12..21]);
        assert_eq!(&p[..3], &[9.0, 10.0, 11.0]);
        assert_eq!(&p[9..12], &[45.0, 46.0, 47.0]);
        assert!(!is_whole(&parts, 24));
        assert!(is_whole(&self::parts(Kernel::MassMatrix, SIZES, 4), 4));
    }
}

//! Many states through one kernel: the states are gathered into lanes ([`Lanes`]), the
//! kernel runs once per group of `LANES` states, and each lane's result is scattered back.
//! A full group's result is scattered value by value ([`LaneData::leaf`]): the lanes of each
//! value go straight to their places in the states' results, which for UR5's mass matrix in
//! `F64x4` took the helper from 21 to 31 million states per second (docs/performance.md).
//!
//! A kernel is given as a closure over its arguments in lanes, so any generated function
//! fits:
//!
//! ```
//! use rne_runtime::batch;
//!
//! // A stand-in for a generated `scalar: generic` kernel.
//! fn kinetic<T: rne_runtime::Real>(q: &[T; 2], qd: &[T; 2]) -> T {
//!     T::from_f64(0.5) * (qd[0] * qd[0] + q[0].cos() * qd[1] * qd[1])
//! }
//!
//! let states: Vec<([f64; 2], [f64; 2])> = (0..7).map(|k| ([k as f64, 0.0], [1.0, 2.0])).collect();
//! let mut energies = vec![0.0; states.len()];
//! // One lane per call here; with the feature `simd`, `F64x4` in place of `f64` takes four.
//! batch::evaluate(&states, &mut energies, |(q, qd): &([f64; 2], [f64; 2])| kinetic(q, qd));
//! assert_eq!(energies[3], kinetic(&states[3].0, &states[3].1));
//! ```
//!
//! The last group, when the number of states is not a multiple of `LANES`, repeats its last
//! state in the lanes left over (so they hold valid values) and drops their results. With the
//! feature `threads`, [`evaluate_threaded`] splits the states between threads.

use crate::lanes::Lanes;

/// A kernel argument or result made of lanes of one type `Lanes`: the lane type itself,
/// arrays of such data (vectors, matrices) and pairs and triples of them (a kernel's
/// arguments). [`LaneData::State`] is the same shape in the lane scalar: one state's.
pub trait LaneData: Sized {
    /// The lane type.
    type Lanes: Lanes;
    /// One lane's value: the same shape in `<Self::Lanes as Lanes>::Lane`.
    type State: 'static;
    /// The value whose lane `i` is `state(i)`, for `i` in `0..LANES`.
    fn gather<'a>(state: impl Fn(usize) -> &'a Self::State + Copy) -> Self;
    /// Lane `i`.
    fn lane(&self, i: usize) -> Self::State;
    /// The number of lane values in the data (1 for a lane type, `N` times the element's for
    /// an array, the sum of the fields' for a tuple).
    const LEAVES: usize;
    /// Lane value `j`, in the order of the data's layout (`j < LEAVES`).
    fn leaf(&self, j: usize) -> Self::Lanes;
    /// The place of scalar `j` in one state's value.
    fn leaf_mut(state: &mut Self::State, j: usize) -> &mut <Self::Lanes as Lanes>::Lane;
}

/// Each lane type (and scalar) is lane data of itself.
macro_rules! lane_data {
    ($($t:ty),*) => {$(
        impl LaneData for $t {
            type Lanes = $t;
            type State = <$t as Lanes>::Lane;
            #[inline(always)]
            fn gather<'a>(state: impl Fn(usize) -> &'a Self::State + Copy) -> $t {
                <$t as Lanes>::from_fn(|i| *state(i))
            }
            #[inline(always)]
            fn lane(&self, i: usize) -> Self::State {
                Lanes::lane(*self, i)
            }
            const LEAVES: usize = 1;
            #[inline(always)]
            fn leaf(&self, _: usize) -> $t {
                *self
            }
            #[inline(always)]
            fn leaf_mut(state: &mut Self::State, _: usize) -> &mut Self::State {
                state
            }
        }
    )*};
}

lane_data!(f64, f32, crate::DoubleDouble);
#[cfg(feature = "simd")]
lane_data!(crate::F64x4, crate::F32x8);

impl<D: LaneData, const N: usize> LaneData for [D; N] {
    type Lanes = D::Lanes;
    type State = [D::State; N];
    #[inline(always)]
    fn gather<'a>(state: impl Fn(usize) -> &'a Self::State + Copy) -> Self {
        core::array::from_fn(|k| D::gather(move |i| &state(i)[k]))
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> Self::State {
        core::array::from_fn(|k| self[k].lane(i))
    }
    const LEAVES: usize = N * D::LEAVES;
    #[inline(always)]
    fn leaf(&self, j: usize) -> Self::Lanes {
        self[j / D::LEAVES].leaf(j % D::LEAVES)
    }
    #[inline(always)]
    fn leaf_mut(state: &mut Self::State, j: usize) -> &mut <Self::Lanes as Lanes>::Lane {
        D::leaf_mut(&mut state[j / D::LEAVES], j % D::LEAVES)
    }
}

impl<A: LaneData, B: LaneData<Lanes = A::Lanes>> LaneData for (A, B) {
    type Lanes = A::Lanes;
    type State = (A::State, B::State);
    #[inline(always)]
    fn gather<'a>(state: impl Fn(usize) -> &'a Self::State + Copy) -> Self {
        (
            A::gather(move |i| &state(i).0),
            B::gather(move |i| &state(i).1),
        )
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> Self::State {
        (self.0.lane(i), self.1.lane(i))
    }
    const LEAVES: usize = A::LEAVES + B::LEAVES;
    #[inline(always)]
    fn leaf(&self, j: usize) -> Self::Lanes {
        if j < A::LEAVES {
            self.0.leaf(j)
        } else {
            self.1.leaf(j - A::LEAVES)
        }
    }
    #[inline(always)]
    fn leaf_mut(state: &mut Self::State, j: usize) -> &mut <Self::Lanes as Lanes>::Lane {
        if j < A::LEAVES {
            A::leaf_mut(&mut state.0, j)
        } else {
            B::leaf_mut(&mut state.1, j - A::LEAVES)
        }
    }
}

impl<A, B, C> LaneData for (A, B, C)
where
    A: LaneData,
    B: LaneData<Lanes = A::Lanes>,
    C: LaneData<Lanes = A::Lanes>,
{
    type Lanes = A::Lanes;
    type State = (A::State, B::State, C::State);
    #[inline(always)]
    fn gather<'a>(state: impl Fn(usize) -> &'a Self::State + Copy) -> Self {
        (
            A::gather(move |i| &state(i).0),
            B::gather(move |i| &state(i).1),
            C::gather(move |i| &state(i).2),
        )
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> Self::State {
        (self.0.lane(i), self.1.lane(i), self.2.lane(i))
    }
    const LEAVES: usize = A::LEAVES + B::LEAVES + C::LEAVES;
    #[inline(always)]
    fn leaf(&self, j: usize) -> Self::Lanes {
        if j < A::LEAVES {
            self.0.leaf(j)
        } else if j < A::LEAVES + B::LEAVES {
            self.1.leaf(j - A::LEAVES)
        } else {
            self.2.leaf(j - A::LEAVES - B::LEAVES)
        }
    }
    #[inline(always)]
    fn leaf_mut(state: &mut Self::State, j: usize) -> &mut <Self::Lanes as Lanes>::Lane {
        if j < A::LEAVES {
            A::leaf_mut(&mut state.0, j)
        } else if j < A::LEAVES + B::LEAVES {
            B::leaf_mut(&mut state.1, j - A::LEAVES)
        } else {
            C::leaf_mut(&mut state.2, j - A::LEAVES - B::LEAVES)
        }
    }
}

/// `results[i] = kernel(states[i])` for every state, `LANES` states per call of `kernel`
/// (the last call's spare lanes repeat its last state).
///
/// # Panics
/// If `states` and `results` differ in length.
pub fn evaluate<I: LaneData, O: LaneData<Lanes = I::Lanes>>(
    states: &[I::State],
    results: &mut [O::State],
    kernel: impl Fn(&I) -> O,
) {
    assert_eq!(
        states.len(),
        results.len(),
        "batch::evaluate: as many results as states"
    );
    let lanes = <I::Lanes as Lanes>::LANES;
    let mut groups = states.chunks_exact(lanes);
    let mut outs = results.chunks_exact_mut(lanes);
    // Whole groups: every lane at a constant index, so that gathering is a transposition in
    // registers and the result is scattered value by value.
    for (group, out) in (&mut groups).zip(&mut outs) {
        let value = kernel(&I::gather(|i| &group[i]));
        for j in 0..O::LEAVES {
            let v = value.leaf(j);
            for i in 0..lanes {
                *O::leaf_mut(&mut out[i], j) = v.lane(i);
            }
        }
    }
    let (group, out) = (groups.remainder(), outs.into_remainder());
    if let Some(last) = group.len().checked_sub(1) {
        let value = kernel(&I::gather(|i| &group[i.min(last)]));
        for (i, r) in out.iter_mut().enumerate() {
            *r = value.lane(i);
        }
    }
}

/// [`evaluate`] on `threads` threads (at least one), each given a contiguous share of the
/// states in whole groups of `LANES` (feature `threads`, which needs the standard library).
///
/// # Panics
/// If `states` and `results` differ in length, or a thread panics.
#[cfg(feature = "threads")]
pub fn evaluate_threaded<I, O, K>(
    states: &[I::State],
    results: &mut [O::State],
    kernel: K,
    threads: usize,
) where
    I: LaneData,
    O: LaneData<Lanes = I::Lanes>,
    I::State: Sync,
    O::State: Send,
    K: Fn(&I) -> O + Sync,
{
    assert_eq!(
        states.len(),
        results.len(),
        "batch::evaluate_threaded: as many results as states"
    );
    let lanes = <I::Lanes as Lanes>::LANES;
    let groups = states.len().div_ceil(lanes);
    let share = groups.div_ceil(threads.max(1)).max(1) * lanes;
    let kernel = &kernel;
    std::thread::scope(|scope| {
        for (part, out) in states.chunks(share).zip(results.chunks_mut(share)) {
            scope.spawn(move || evaluate(part, out, kernel));
        }
    });
}

#[cfg(test)]
mod tests {
    use super::evaluate;
    use crate::Real;
    use std::vec::Vec;

    /// A kernel with a vector, a scalar and a matrix result, in any scalar.
    fn kernel<T: Real>(q: &[T; 2], qd: &[T; 2]) -> ([T; 2], T, [[T; 2]; 2]) {
        let (s, c) = q[0].sin_cos();
        (
            [s * qd[0], c * qd[1] + q[1]],
            q[1] * qd[1],
            [[q[0] * qd[1], s], [c, qd[0] - q[1]]],
        )
    }

    fn states(n: usize) -> Vec<([f64; 2], [f64; 2])> {
        (0..n)
            .map(|k| {
                let x = k as f64;
                ([0.3 * x - 1.0, x * x], [1.0 / (x + 1.0), -x])
            })
            .collect()
    }

    #[test]
    fn every_result_is_the_kernel_at_its_own_state() {
        let states = states(9);
        let mut results = [([0.0; 2], 0.0, [[0.0; 2]; 2]); 9];
        evaluate(&states, &mut results, |(q, qd): &([f64; 2], [f64; 2])| {
            kernel(q, qd)
        });
        for (state, result) in states.iter().zip(&results) {
            assert_eq!(*result, kernel(&state.0, &state.1));
        }
    }

    #[cfg(feature = "simd")]
    #[test]
    fn lanes_fill_groups_and_the_tail_repeats_the_last_state() {
        use crate::{F32x8, F64x4};
        for n in [0, 1, 3, 4, 5, 8, 11, 17] {
            let states = states(n);
            let mut wide = std::vec![([0.0; 2], 0.0, [[0.0; 2]; 2]); n];
            evaluate(&states, &mut wide, |(q, qd): &([F64x4; 2], [F64x4; 2])| {
                kernel(q, qd)
            });
            let single: Vec<_> = states
                .iter()
                .map(|(q, qd)| (q.map(|x| x as f32), qd.map(|x| x as f32)))
                .collect();
            let mut eight = std::vec![([0.0f32; 2], 0.0f32, [[0.0f32; 2]; 2]); n];
            evaluate(&single, &mut eight, |(q, qd): &([F32x8; 2], [F32x8; 2])| {
                kernel(q, qd)
            });
            for k in 0..n {
                assert_eq!(
                    wide[k],
                    kernel(&states[k].0, &states[k].1),
                    "{n} states, #{k}"
                );
                let (q, qd) = single[k];
                assert_eq!(eight[k], kernel(&q, &qd), "{n} states, #{k} in f32");
            }
        }
    }

    #[cfg(feature = "threads")]
    #[test]
    fn threads_split_the_states_and_keep_their_order() {
        for (n, threads) in [(0, 3), (1, 2), (10, 3), (33, 4), (5, 0)] {
            let states = states(n);
            let mut alone = std::vec![([0.0; 2], 0.0, [[0.0; 2]; 2]); n];
            let mut shared = alone.clone();
            let run = |(q, qd): &([f64; 2], [f64; 2])| kernel(q, qd);
            evaluate(&states, &mut alone, run);
            super::evaluate_threaded(&states, &mut shared, run, threads);
            assert_eq!(alone, shared, "{n} states on {threads} threads");
        }
    }
}

//! Many states through one kernel: the states are gathered into lanes ([`Lanes`]), the
//! kernel runs once per group of `LANES` states, and each lane's result is scattered back.
//! A full group's result is scattered at constant indices, `LANES` values at a time where
//! they lie one after the other in a state's result ([`LaneData::leaves_mut`]): the block is
//! transposed in registers ([`Lanes::transposed`]) and each state's values stored at once;
//! the values left over go lane by lane ([`LaneData::leaf`]) straight to their places. Lane
//! by lane took UR5's mass matrix in `F64x4` from 21 to 31 million states per second; the
//! transposition took the `F32x8` mass matrices from 2.6–3.0× to 3.2–3.5× `f64`
//! (docs/performance.md).
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
//! feature `threads`, [`evaluate_threaded`] splits the states between the threads of
//! rayon's pool.

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
    /// Whether a state's value is its leaves one after the other and nothing else (a lane
    /// scalar, and arrays of such data; not a tuple, whose fields Rust may reorder).
    const DENSE: bool;
    /// `states`' leaves as one slice, in order, when the data is [`LaneData::DENSE`].
    fn dense_mut(states: &mut [Self::State]) -> Option<&mut [<Self::Lanes as Lanes>::Lane]>;
    /// Scalars `j..j + n` of one state's value as one slice, when they lie one after the
    /// other in memory.
    fn leaves_mut(
        state: &mut Self::State,
        j: usize,
        n: usize,
    ) -> Option<&mut [<Self::Lanes as Lanes>::Lane]>;
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
            const DENSE: bool = true;
            #[inline(always)]
            fn dense_mut(states: &mut [Self::State]) -> Option<&mut [Self::State]> {
                Some(states)
            }
            #[inline(always)]
            fn leaves_mut(
                state: &mut Self::State,
                j: usize,
                n: usize,
            ) -> Option<&mut [Self::State]> {
                (j == 0 && n == 1).then(|| core::slice::from_mut(state))
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
    const DENSE: bool = D::DENSE;
    #[inline(always)]
    fn dense_mut(states: &mut [Self::State]) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        D::dense_mut(states.as_flattened_mut())
    }
    #[inline(always)]
    fn leaves_mut(
        state: &mut Self::State,
        j: usize,
        n: usize,
    ) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        if D::DENSE {
            D::dense_mut(state)?.get_mut(j..j + n)
        } else if j % D::LEAVES + n <= D::LEAVES {
            D::leaves_mut(&mut state[j / D::LEAVES], j % D::LEAVES, n)
        } else {
            None
        }
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
    const DENSE: bool = false;
    #[inline(always)]
    fn dense_mut(_: &mut [Self::State]) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        None
    }
    #[inline(always)]
    fn leaves_mut(
        state: &mut Self::State,
        j: usize,
        n: usize,
    ) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        if j + n <= A::LEAVES {
            A::leaves_mut(&mut state.0, j, n)
        } else if j >= A::LEAVES {
            B::leaves_mut(&mut state.1, j - A::LEAVES, n)
        } else {
            None
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
    const DENSE: bool = false;
    #[inline(always)]
    fn dense_mut(_: &mut [Self::State]) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        None
    }
    #[inline(always)]
    fn leaves_mut(
        state: &mut Self::State,
        j: usize,
        n: usize,
    ) -> Option<&mut [<Self::Lanes as Lanes>::Lane]> {
        let ab = A::LEAVES + B::LEAVES;
        if j + n <= A::LEAVES {
            A::leaves_mut(&mut state.0, j, n)
        } else if j >= A::LEAVES && j + n <= ab {
            B::leaves_mut(&mut state.1, j - A::LEAVES, n)
        } else if j >= ab {
            C::leaves_mut(&mut state.2, j - ab, n)
        } else {
            None
        }
    }
}

/// The most blocks of `LANES` values of a result [`evaluate`] scatters at constant indices.
const UNROLLED_BLOCKS: usize = 32;

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
    // registers, and the result written a block of `LANES` values at a time.
    for (group, out) in (&mut groups).zip(&mut outs) {
        let value = kernel(&I::gather(|i| &group[i]));
        let blocks = O::LEAVES / lanes;
        if blocks <= UNROLLED_BLOCKS {
            // The conditions fold: every block at a constant index.
            macro_rules! unrolled {
                ($($b:literal)*) => {$(
                    if $b < blocks {
                        write_block(&value, $b * lanes, out);
                    }
                )*};
            }
            unrolled!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31);
        } else {
            (0..blocks).for_each(|block| write_block(&value, block * lanes, out));
        }
        (blocks * lanes..O::LEAVES).for_each(|j| write_leaf(&value, j, out));
    }
    let (group, out) = (groups.remainder(), outs.into_remainder());
    if let Some(last) = group.len().checked_sub(1) {
        let value = kernel(&I::gather(|i| &group[i.min(last)]));
        for (i, r) in out.iter_mut().enumerate() {
            *r = value.lane(i);
        }
    }
}

/// Writes result values `j..j + LANES` of a group of states to the states' results: by one
/// transposition when they lie one after the other in a result, else value by value.
#[inline(always)]
fn write_block<O: LaneData>(value: &O, j: usize, out: &mut [O::State]) {
    let lanes = <O::Lanes as Lanes>::LANES;
    if O::leaves_mut(&mut out[0], j, lanes).is_some() {
        <O::Lanes as Lanes>::transposed(
            |k| value.leaf(j + k),
            |i, row| {
                if let Some(leaves) = O::leaves_mut(&mut out[i], j, lanes) {
                    leaves.copy_from_slice(row);
                }
            },
        );
    } else {
        (j..j + lanes).for_each(|j| write_leaf(value, j, out));
    }
}

/// Writes result value `j` of a group of states to the states' results, lane by lane.
#[inline(always)]
fn write_leaf<O: LaneData>(value: &O, j: usize, out: &mut [O::State]) {
    let v = value.leaf(j);
    for (i, state) in out.iter_mut().enumerate() {
        *O::leaf_mut(state, j) = v.lane(i);
    }
}

/// [`evaluate`] on `threads` threads (at least one; feature `threads`, which needs the
/// standard library): the states are cut into chunks of whole groups of `LANES`, about eight
/// per thread, and `threads` tasks on rayon's global thread pool (a scope's own task and the
/// `threads − 1` it spawns; the caller waits for the scope) take the next chunk whenever they
/// are done with one, so that at most `threads` of the pool's threads work on them at once.
/// The pool's threads are started once and kept, so a call costs a few to some twenty
/// microseconds beyond its work, where starting threads per call cost tens; on some hosts that
/// is about what 1 024 states of a small kernel take on one thread, so the helper is for large
/// batches. A thread the machine slows down (a vCPU shared with another guest) holds the batch
/// up by a chunk, not by a fixed share of it (docs/performance.md).
///
/// # Panics
/// If `states` and `results` differ in length, or the kernel panics.
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
    let threads = threads.clamp(1, groups.max(1));
    let chunk = groups.div_ceil(threads * CHUNKS_PER_THREAD).max(1) * lanes;
    // The chunks not taken yet. A task holds the lock only to take one, never while a kernel
    // runs, so a panicking kernel leaves it unpoisoned.
    let chunks = std::sync::Mutex::new(states.chunks(chunk).zip(results.chunks_mut(chunk)));
    let work = || loop {
        let next = chunks
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .next();
        let Some((part, out)) = next else { break };
        evaluate(part, out, &kernel);
    };
    rayon::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(|_| work());
        }
        work();
    });
}

/// How many chunks [`evaluate_threaded`] cuts each thread's share into: enough that a thread
/// slowed down leaves little to wait for, few enough that taking a chunk (a lock) costs
/// nothing beside its work (at 1 024 states in `F64x4`, 16 groups, a few microseconds).
#[cfg(feature = "threads")]
const CHUNKS_PER_THREAD: usize = 8;

#[cfg(test)]
mod tests {
    use super::{evaluate, LaneData};
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

    /// A kernel whose result has 9 + 8 distinct values: in `F64x4` its blocks of four lie in
    /// the matrix (0–3, 4–7), across the two fields (8–11) and in the vector (12–15), with
    /// one value left over; in `F32x8` one block in the matrix, one across, one left over.
    #[cfg(feature = "simd")]
    fn wide_kernel<T: Real>(q: &[T; 2], qd: &[T; 2]) -> ([[T; 3]; 3], [T; 8]) {
        let step = |k: usize| T::from_f64(k as f64 + 0.5);
        (
            core::array::from_fn(|r| {
                core::array::from_fn(|c| q[0] * step(3 * r + c) + qd[1] * q[1])
            }),
            core::array::from_fn(|k| qd[0] * step(k) - q[1] * step(k * k)),
        )
    }

    /// Results whose values lie one after the other are transposed a block at a time, the
    /// rest written value by value: every state still gets its own result, whichever way
    /// each of its values took.
    #[cfg(feature = "simd")]
    #[test]
    fn blocks_of_a_result_reach_each_state_whichever_way_they_are_written() {
        use crate::{F32x8, F64x4};
        for n in [0, 1, 4, 5, 8, 9, 13, 17] {
            let states = states(n);
            let mut wide = std::vec![([[0.0; 3]; 3], [0.0; 8]); n];
            evaluate(&states, &mut wide, |(q, qd): &([F64x4; 2], [F64x4; 2])| {
                wide_kernel(q, qd)
            });
            let single: Vec<_> = states
                .iter()
                .map(|(q, qd)| (q.map(|x| x as f32), qd.map(|x| x as f32)))
                .collect();
            let mut eight = std::vec![([[0.0f32; 3]; 3], [0.0f32; 8]); n];
            evaluate(&single, &mut eight, |(q, qd): &([F32x8; 2], [F32x8; 2])| {
                wide_kernel(q, qd)
            });
            for k in 0..n {
                let (q, qd) = &states[k];
                assert_eq!(wide[k], wide_kernel(q, qd), "{n} states, #{k}");
                let (q, qd) = &single[k];
                assert_eq!(eight[k], wide_kernel(q, qd), "{n} states, #{k} in f32");
            }
        }
    }

    /// A run of values is one slice exactly when it lies within a field of the result, and
    /// it is the right slice.
    #[test]
    fn runs_of_values_are_slices_only_within_a_field() {
        type Result = ([[f64; 3]; 3], [f64; 8]);
        let mut result: Result = (
            core::array::from_fn(|r| core::array::from_fn(|c| (3 * r + c) as f64)),
            core::array::from_fn(|k| (9 + k) as f64),
        );
        for (j, n) in [(0, 4), (4, 4), (5, 4), (0, 9), (9, 8), (12, 4), (13, 4)] {
            let run = <Result as LaneData>::leaves_mut(&mut result, j, n).map(|r| r.to_vec());
            let expected: Vec<f64> = (j..j + n).map(|k| k as f64).collect();
            assert_eq!(run, Some(expected), "values {j}..{}", j + n);
        }
        for (j, n) in [(8, 4), (6, 4), (16, 2), (14, 4)] {
            assert!(
                <Result as LaneData>::leaves_mut(&mut result, j, n).is_none(),
                "values {j}..{} are not one slice",
                j + n
            );
        }
        let mut three = (1.0, [2.0, 3.0], [[4.0, 5.0], [6.0, 7.0]]);
        type Three = (f64, [f64; 2], [[f64; 2]; 2]);
        let run = <Three as LaneData>::leaves_mut(&mut three, 3, 4).map(|r| r.to_vec());
        assert_eq!(run, Some(std::vec![4.0, 5.0, 6.0, 7.0]));
        assert!(<Three as LaneData>::leaves_mut(&mut three, 0, 2).is_none());
        assert!(<Three as LaneData>::leaves_mut(&mut three, 2, 2).is_none());
    }

    #[cfg(feature = "threads")]
    #[test]
    fn threads_split_the_states_and_keep_their_order() {
        // Up to one chunk per group, and many chunks per thread (1 000 and 257 states).
        let cases = [
            (0, 3),
            (1, 2),
            (10, 3),
            (33, 4),
            (5, 0),
            (1000, 2),
            (257, 3),
        ];
        for (n, threads) in cases {
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

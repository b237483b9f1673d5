//! A benchmarked implementation of one kernel on its own inputs: called in timed batches, and
//! evaluated state by state for its error.

use std::hint::black_box;

/// One state as a generated function takes it: fixed-size arrays of its scalar `T`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Input<T, const N: usize> {
    /// Joint positions.
    pub q: [T; N],
    /// Joint velocities.
    pub qd: [T; N],
    /// Joint accelerations (inverse dynamics).
    pub qdd: [T; N],
    /// Joint torques (forward dynamics).
    pub tau: [T; N],
}

/// A kernel's result, appended to a list of `f64` (matrices row by row) for the error
/// measures. `f32` results convert exactly.
pub trait Output {
    /// Appends the result to `out`.
    fn append_to(&self, out: &mut Vec<f64>);
}

/// Implements [`Output`] for vectors and matrices of a scalar type.
macro_rules! array_output {
    ($($t:ty),*) => {$(
        impl<const N: usize> Output for [$t; N] {
            fn append_to(&self, out: &mut Vec<f64>) {
                out.extend(self.iter().map(|&x| f64::from(x)));
            }
        }

        impl<const N: usize> Output for [[$t; N]; N] {
            fn append_to(&self, out: &mut Vec<f64>) {
                for row in self {
                    row.append_to(out);
                }
            }
        }
    )*};
}

array_output!(f32, f64);

impl Output for Vec<f64> {
    fn append_to(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self);
    }
}

/// An implementation of one kernel with its inputs.
pub trait Subject {
    /// Makes `calls` calls on the timing pool (the first states of the inputs, cycled through
    /// in order), each input and result passed through [`black_box`].
    fn run(&mut self, calls: u64);
    /// Number of input states.
    fn len(&self) -> usize;
    /// Whether there is no input state.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Replaces `out` with the result on input state `k` (`k < len()`), as `f64`.
    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>);
}

/// A subject whose kernel returns its result: the generated functions, and the interpreted
/// programs.
pub struct Returning<I, F> {
    inputs: Vec<I>,
    pool: usize,
    next: usize,
    kernel: F,
}

impl<I, F> Returning<I, F> {
    /// `kernel` on `inputs`, timed on the first `pool` of them (at least one).
    pub fn new(inputs: Vec<I>, pool: usize, kernel: F) -> Returning<I, F> {
        let pool = pool.clamp(1, inputs.len().max(1));
        Returning {
            inputs,
            pool,
            next: 0,
            kernel,
        }
    }
}

impl<I, R: Output, F: FnMut(&I) -> R> Subject for Returning<I, F> {
    fn run(&mut self, calls: u64) {
        if self.inputs.is_empty() {
            return;
        }
        for _ in 0..calls {
            let input = black_box(&self.inputs[self.next]);
            self.next = if self.next + 1 == self.pool {
                0
            } else {
                self.next + 1
            };
            black_box((self.kernel)(input));
        }
    }

    fn len(&self) -> usize {
        self.inputs.len()
    }

    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>) {
        out.clear();
        (self.kernel)(&self.inputs[k]).append_to(out);
    }
}

/// A subject whose kernel writes its result into a buffer it is given: the numeric reference's
/// allocation-free `*_into` methods. The buffer is allocated once, with the subject.
pub struct Writing<I, F> {
    inputs: Vec<I>,
    pool: usize,
    next: usize,
    buffer: Vec<f64>,
    kernel: F,
}

impl<I, F> Writing<I, F> {
    /// `kernel` on `inputs` writing `outputs` values, timed on the first `pool` inputs.
    pub fn new(inputs: Vec<I>, pool: usize, outputs: usize, kernel: F) -> Writing<I, F> {
        let pool = pool.clamp(1, inputs.len().max(1));
        Writing {
            inputs,
            pool,
            next: 0,
            buffer: vec![0.0; outputs],
            kernel,
        }
    }
}

impl<I, F: FnMut(&I, &mut [f64])> Subject for Writing<I, F> {
    fn run(&mut self, calls: u64) {
        if self.inputs.is_empty() {
            return;
        }
        for _ in 0..calls {
            let input = black_box(&self.inputs[self.next]);
            self.next = if self.next + 1 == self.pool {
                0
            } else {
                self.next + 1
            };
            (self.kernel)(input, &mut self.buffer);
            black_box(&mut self.buffer);
        }
    }

    fn len(&self) -> usize {
        self.inputs.len()
    }

    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>) {
        (self.kernel)(&self.inputs[k], &mut self.buffer);
        out.clear();
        out.extend_from_slice(&self.buffer);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs cycle through the pool only; evaluation reaches every input.
    #[test]
    fn pool_cycling_and_evaluation() {
        let inputs: Vec<f64> = (0..10).map(f64::from).collect();
        let mut seen = Vec::new();
        let mut subject = Returning::new(inputs, 3, |x: &f64| {
            seen.push(*x);
            [*x * 2.0]
        });
        subject.run(7);
        let mut out = Vec::new();
        subject.evaluate(9, &mut out);
        assert_eq!(out, vec![18.0]);
        assert_eq!(subject.len(), 10);
        drop(subject);
        assert_eq!(seen, vec![0.0, 1.0, 2.0, 0.0, 1.0, 2.0, 0.0, 9.0]);

        let mut writing = Writing::new(vec![1.0, 2.0], 5, 2, |x: &f64, out: &mut [f64]| {
            out[0] = *x;
            out[1] = -*x;
        });
        writing.run(3);
        writing.evaluate(1, &mut out);
        assert_eq!(out, vec![2.0, -2.0]);
    }
}

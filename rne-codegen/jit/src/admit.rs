//! What a call checks before the compiled code runs: that the arrays a kernel takes have the
//! robot's lengths and finite values, so that no input reaches the code that it could read
//! out of bounds, and a bad state is an error naming its array and entry.
//!
//! A call that runs is checked in one pass that builds no error ([`JitModel::admits`]): the
//! arrays the kernel takes chosen by a bit mask, each compared with its length and tested for
//! finite values without a branch per value. Only a call that fails is checked again, array
//! by array, for the error it returns ([`JitModel::refusal`]). The check is most of what a
//! single call adds to the kernel (docs/performance.md, "A call's checks"), so it is kept
//! apart from the work that explains a failure.

use rne_codegen_core::{Input, Kernel};

use crate::error::JitError;
use crate::model::{Compiled, JitModel, State};

/// The arrays a kernel takes, one bit each.
const Q: u8 = 1;
const QD: u8 = 2;
const QDD: u8 = 4;
const TAU: u8 = 8;
const STANDARD: u8 = 16;

/// The arrays `kernel` takes ([`Kernel::inputs`]) as bits: computed once, when the kernel is
/// compiled ([`Compiled::taken`]), where going through the list at every call was a loop.
pub(crate) fn taken(kernel: Kernel) -> u8 {
    kernel.inputs().iter().fold(0, |bits, input| {
        bits | match input {
            Input::Q => Q,
            Input::Qd => QD,
            Input::Qdd => QDD,
            Input::Tau => TAU,
            Input::Standard => STANDARD,
        }
    })
}

/// Whether every value of `values` is finite: 0·x is ±0 for a finite x and NaN for an
/// infinite or NaN one, and a sum with a NaN is NaN. Two operations a value, no branch.
fn all_finite(values: &[f64]) -> bool {
    values.iter().fold(0.0, |sum, &x| sum + 0.0 * x) == 0.0
}

impl JitModel {
    /// Whether `state` passes every check of [`JitModel::check_state`]: the arrays `compiled`
    /// takes have the robot's lengths and finite values. A kernel of the standard parameters
    /// is never admitted with a state (it is called through [`JitModel::base_parameters`]).
    #[inline]
    pub(crate) fn admits(&self, compiled: &Compiled, state: &State<'_>) -> bool {
        let bits = compiled.taken();
        let fits = |bit: u8, values: &[f64], n: usize| {
            bits & bit == 0 || (values.len() == n && all_finite(values))
        };
        let (nq, nv) = (self.nq(), self.nv());
        bits & STANDARD == 0
            && fits(Q, state.q, nq)
            && fits(QD, state.qd, nv)
            && fits(QDD, state.qdd, nv)
            && fits(TAU, state.tau, nv)
    }

    /// The error of a single call of `kernel` at `state` into an output of `got` values, where
    /// `expected` are the kernel's, that [`JitModel::admits`] or the output's length refused.
    #[cold]
    pub(crate) fn refusal(
        &self,
        kernel: Kernel,
        state: &State<'_>,
        got: usize,
        expected: usize,
    ) -> JitError {
        match self.check_state(kernel, state) {
            Err(e) => e,
            Ok(()) => JitError::OutputLength {
                kernel,
                got,
                expected,
            },
        }
    }

    /// The lengths and finiteness of the arrays `kernel` takes, the first that fails as the
    /// error.
    pub(crate) fn check_state(&self, kernel: Kernel, state: &State<'_>) -> Result<(), JitError> {
        self.check_lengths(kernel, state)?;
        for &input in kernel.inputs() {
            check_finite(kernel, input, state.input(input))?;
        }
        Ok(())
    }

    /// The lengths of the arrays `kernel` takes.
    pub(crate) fn check_lengths(&self, kernel: Kernel, state: &State<'_>) -> Result<(), JitError> {
        for &input in kernel.inputs() {
            let expected = self.width(kernel, input)?;
            let got = state.input(input).len();
            if got != expected {
                return Err(JitError::InputLength {
                    kernel,
                    input,
                    got,
                    expected,
                });
            }
        }
        Ok(())
    }

    /// Values per state of `kernel`'s `input`: NQ for q, NV for q̇, q̈ and τ. The standard
    /// parameters are no state's: a kernel taking them is called through
    /// [`JitModel::base_parameters`], not with states.
    pub(crate) fn width(&self, kernel: Kernel, input: Input) -> Result<usize, JitError> {
        match input {
            Input::Q => Ok(self.nq()),
            Input::Qd | Input::Qdd | Input::Tau => Ok(self.nv()),
            Input::Standard => Err(JitError::MissingKernel { kernel }),
        }
    }
}

/// An error naming the first non-finite entry of `values`.
pub(crate) fn check_finite(kernel: Kernel, input: Input, values: &[f64]) -> Result<(), JitError> {
    if all_finite(values) {
        return Ok(());
    }
    match values.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(index) => Err(JitError::NonFinite {
            kernel,
            input,
            index,
            value: values[index],
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mask_names_exactly_the_arrays_each_kernel_takes() {
        for kernel in Kernel::ALL {
            let bits = taken(kernel);
            let named = [
                (Q, Input::Q),
                (QD, Input::Qd),
                (QDD, Input::Qdd),
                (TAU, Input::Tau),
                (STANDARD, Input::Standard),
            ];
            for (bit, input) in named {
                assert_eq!(
                    bits & bit != 0,
                    kernel.inputs().contains(&input),
                    "{kernel:?} {input:?}"
                );
            }
        }
    }

    #[test]
    fn finiteness_fails_on_any_nan_or_infinity_wherever_it_is() {
        for len in 0..9 {
            assert!(all_finite(&vec![1.5; len]));
            for at in 0..len {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let mut values = vec![-2.0; len];
                    values[at] = bad;
                    assert!(!all_finite(&values), "{len} values, {bad} at {at}");
                }
            }
        }
        assert!(all_finite(&[
            f64::MAX,
            f64::MIN,
            0.0,
            -0.0,
            f64::MIN_POSITIVE
        ]));
    }
}

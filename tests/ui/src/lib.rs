//! Compile-fail tests of `derive_dynamics!` live in `tests/`; this crate has no library code.

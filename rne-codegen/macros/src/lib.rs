//! The derive_dynamics! macro.

//! Code generator core.

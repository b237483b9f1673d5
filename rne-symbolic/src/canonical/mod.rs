//! Canonical polynomial form of expressions, for exact comparison and readable printing.

//! Double-double arithmetic: about 32 significant digits from a pair of `f64`.

//! The state (q, v) of a model whose configuration is not a vector: q on the configuration
//! manifold, v in its tangent space (docs/design.md §4.5).

/// The state of a [`Dynamics<NQ, NV>`](rne_runtime::Dynamics) model: the configuration q
/// (NQ entries) and the velocity v (NV entries). On a floating base
/// q = [p, quaternion xyzw, joints] and v = [v_base, ω_base, joint rates], both base velocities
/// in the base frame, NQ = NV + 1; on a fixed base NQ = NV and v = q̇.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ManifoldState<const NQ: usize, const NV: usize> {
    /// The configuration q.
    pub q: [f64; NQ],
    /// The velocity v.
    pub v: [f64; NV],
}

impl<const NQ: usize, const NV: usize> ManifoldState<NQ, NV> {
    /// The state (q, v).
    pub fn new(q: [f64; NQ], v: [f64; NV]) -> Self {
        Self { q, v }
    }

    /// The state (q, 0): released from rest.
    pub fn at_rest(q: [f64; NQ]) -> Self {
        Self { q, v: [0.0; NV] }
    }

    /// Whether every entry is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.q.iter().chain(&self.v).all(|x| x.is_finite())
    }
}

//! The joint-space state a kernel is evaluated at, when the number of joints is known only at
//! run time.

/// The arrays of one state, borrowed: each kernel reads the ones it takes (docs/design.md §4,
/// [`Kernel::inputs`](rne_codegen::Kernel::inputs)) and ignores the others, which may then be
/// empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateRef<'a, T = f64> {
    /// Joint positions q.
    pub q: &'a [T],
    /// Joint velocities q̇.
    pub qd: &'a [T],
    /// Joint accelerations q̈ (inverse dynamics).
    pub qdd: &'a [T],
    /// Joint torques τ (forward dynamics).
    pub tau: &'a [T],
}

/// The arrays of one state, owned; see [`StateRef`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointState {
    /// Joint positions q.
    pub q: Vec<f64>,
    /// Joint velocities q̇.
    pub qd: Vec<f64>,
    /// Joint accelerations q̈ (inverse dynamics).
    pub qdd: Vec<f64>,
    /// Joint torques τ (forward dynamics).
    pub tau: Vec<f64>,
}

impl JointState {
    /// The state at positions `q` with every other array empty.
    pub fn at(q: &[f64]) -> JointState {
        JointState {
            q: q.to_vec(),
            ..JointState::default()
        }
    }

    /// The state, borrowed.
    pub fn as_ref(&self) -> StateRef<'_> {
        StateRef {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
            tau: &self.tau,
        }
    }
}

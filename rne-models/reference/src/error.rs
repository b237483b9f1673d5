//! What can go wrong when building or calling the numeric reference.

/// An error of the numeric reference.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// A joint-space argument or output buffer does not have the model's length.
    #[error("`{argument}` has {found} entries, but the model has {expected}")]
    WrongLength {
        /// The argument's name (`q`, `qd`, `qdd`, `tau`, `out`).
        argument: &'static str,
        /// The number of entries the model needs (`dof`, or `dof²` for a matrix buffer).
        expected: usize,
        /// The number of entries given.
        found: usize,
    },
    /// The [`NumericModel`](rne_symbolic::NumericModel) breaks one of its invariants.
    #[error("robot `{robot}`, link `{link}`, {field}: {problem}")]
    InvalidModel {
        /// The robot's name.
        robot: String,
        /// The offending link's name (or `joint_names` for the joint list itself).
        link: String,
        /// The offending field of the link.
        field: &'static str,
        /// What is wrong with it.
        problem: String,
    },
}

//! How a robot file is read.

/// How a robot file (TOML spec or URDF) is read.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Keep every parameter as its own symbol `Symbol::Parameter(k)` (k in spec order) instead
    /// of folding it into a constant (the CLI's `--symbolic-params`, the macro's
    /// `parameters: runtime`). [`RobotModel::parameters`](crate::RobotModel::parameters) holds
    /// the values either way. A URDF has no parameters.
    pub symbolic_parameters: bool,
    /// Strict validation (the CLI's `--strict`, the macro's `validation: strict`): the first
    /// warning ([`SpecWarning`](crate::spec::SpecWarning)) is returned as an error of kind
    /// [`SpecErrorKind::Strict`](crate::spec::SpecErrorKind::Strict).
    pub strict: bool,
    /// Mimic joints will be independent joints (the CLI's `--mimic free`, the macro's
    /// `mimic: free`): a `<mimic>` (or `mimic = {..}`) naming a leader that is not a moving
    /// joint of the robot is then dropped with a warning instead of refused, as Pinocchio's
    /// default reader, which ignores mimic tags, loads such a file.
    pub free_mimic: bool,
}

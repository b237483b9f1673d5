//! How a robot file is read.

/// How a robot file (TOML spec or URDF) is read.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
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
    /// Rotations by an angle within a few ulps of a multiple of π/2 (URDF `rpy="0 1.5707963267948966 0"`,
    /// a TOML `Rz(pi/2)`) have exact 0 and ±1 entries (the default): `cos(1.5707963267948966)`
    /// is 6.1·10⁻¹⁷ in `f64`, a term that would travel through the recursion into every
    /// equation `rne show` prints (a gravity torque of 10⁻¹⁸ sin(2 q5) where the true one is
    /// 0) and into the kernels' operation counts. Off (the CLI's `--literal-angles`), the sine
    /// and cosine of each angle are the `f64` values of the number as written
    /// ([`ExprGraph::exact_right_angles`](crate::ExprGraph::exact_right_angles),
    /// [`RIGHT_ANGLE_ULPS`](crate::expr::RIGHT_ANGLE_ULPS)).
    pub exact_right_angles: bool,
}

impl Default for LoadOptions {
    fn default() -> LoadOptions {
        LoadOptions {
            symbolic_parameters: false,
            strict: false,
            free_mimic: false,
            exact_right_angles: true,
        }
    }
}

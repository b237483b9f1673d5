//! The implementations of a kernel that rne offers, and what each is measured on.

use rne_figures::Format;

/// One way rne offers to evaluate a kernel.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Implementation {
    /// The built-in robot's generated module ([`rne_models::generated`]): `f64`, constant
    /// parameters, the spec's gravity.
    Generated,
    /// Generated with `scalar: f32`.
    Single,
    /// Generated with `parameters: runtime`, called with `Params::default()` (the spec's
    /// values); robots with named parameters only.
    RuntimeParameters,
    /// Generated with `gravity: [0.0, 0.0, 0.0]`.
    ZeroGravity,
    /// Generated with the first joint locked at 0.
    Locked,
    /// Generated with `at_rest: true` (a static scene), called at q̇ = 0.
    AtRest,
    /// The same optimised programs evaluated without compiling them
    /// ([`rne_interpreted::Interpreted`]), in `f64`.
    Interpreted,
    /// The independent numeric reference: spatial RNEA, CRBA and ABA on nalgebra
    /// ([`rne_reference::Reference`], its allocation-free `*_into` methods).
    Reference,
}

/// The model and the inputs an implementation is measured on; its exact values are those of
/// this case's model at these inputs.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Case {
    /// The robot as specified, at the sampled states.
    Full,
    /// The robot as specified, at the sampled states rounded to `f32`.
    Single,
    /// The robot without gravity.
    ZeroGravity,
    /// The robot with its first joint locked at 0, at the sampled states without that joint.
    Locked,
    /// The robot as specified, at the sampled states with q̇ = 0.
    AtRest,
}

impl Case {
    /// Every case.
    pub const ALL: [Case; 5] = [
        Case::Full,
        Case::Single,
        Case::ZeroGravity,
        Case::Locked,
        Case::AtRest,
    ];

    /// Position in [`Case::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}

impl Implementation {
    /// Every implementation, in table order.
    pub const ALL: [Implementation; 8] = [
        Implementation::Generated,
        Implementation::Single,
        Implementation::RuntimeParameters,
        Implementation::ZeroGravity,
        Implementation::Locked,
        Implementation::AtRest,
        Implementation::Interpreted,
        Implementation::Reference,
    ];

    /// The name in tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            Implementation::Generated => "generated f64",
            Implementation::Single => "generated f32",
            Implementation::RuntimeParameters => "runtime parameters",
            Implementation::ZeroGravity => "zero gravity",
            Implementation::Locked => "joint 1 locked",
            Implementation::AtRest => "static scene",
            Implementation::Interpreted => "interpreted",
            Implementation::Reference => "numeric reference",
        }
    }

    /// What it is measured on.
    pub fn case(self) -> Case {
        match self {
            Implementation::Single => Case::Single,
            Implementation::ZeroGravity => Case::ZeroGravity,
            Implementation::Locked => Case::Locked,
            Implementation::AtRest => Case::AtRest,
            _ => Case::Full,
        }
    }

    /// The format of its results.
    pub fn format(self) -> Format {
        match self {
            Implementation::Single => Format::F32,
            _ => Format::F64,
        }
    }

    /// Whether it is a generated variant for a different scene than the robot's own (the
    /// subjects of the scene-savings table).
    pub fn is_scene(self) -> bool {
        matches!(
            self,
            Implementation::ZeroGravity | Implementation::Locked | Implementation::AtRest
        )
    }
}

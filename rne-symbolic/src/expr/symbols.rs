//! Names of the symbols of an expression graph.

use super::node::Symbol;

/// The names of a graph's joint variables and parameters.
///
/// Printed names follow the thesis's Maple code (Appendix B): a joint `q1` has velocity `Dq1`
/// and acceleration `DDq1`; its generalised force prints as `tau_q1`. Joint names are any
/// string (a URDF joint may be called `8`, `FL-hip` or `sin`); a name that would not print
/// unambiguously — not an identifier, a word of the expression language, printed like
/// another joint's velocity, acceleration or force, or a floating base's coordinate — is
/// printed between backticks (`` `FL-hip` ``, `` D`FL-hip` ``, `` tau_`8` ``), a backtick in it
/// doubled.
///
/// On a floating base, q, v, q̈ and τ begin with the base's coordinates ([`BaseCoordinate`]):
/// q with `x y z qx qy qz qw` (position, then the orientation quaternion), v with
/// `vx vy vz wx wy wz` (linear, then angular velocity in the base frame), q̈ with their
/// derivatives `Dvx … Dwz`, and τ with the force and moment on the base `fx fy fz nx ny nz`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SymbolTable {
    joints: Vec<String>,
    parameters: Vec<String>,
    /// Whether q, v, q̈ and τ begin with a floating base's coordinates.
    floating_base: bool,
}

/// What a floating base's coordinate measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BaseQuantity {
    /// The base's position in the world (`x`).
    Position,
    /// A component of the base's orientation quaternion (`qx`, …, `qw`).
    Orientation,
    /// The base's linear velocity in its own frame (`vx`).
    LinearVelocity,
    /// The base's angular velocity in its own frame (`wx`).
    AngularVelocity,
    /// The derivative of the linear velocity (`Dvx`).
    LinearAcceleration,
    /// The derivative of the angular velocity (`Dwx`).
    AngularAcceleration,
    /// The force on the base (`fx`).
    Force,
    /// The moment on the base (`nx`).
    Moment,
}

impl BaseQuantity {
    /// The printed prefix of the quantity's coordinates, before the axis.
    pub fn prefix(self) -> &'static str {
        match self {
            BaseQuantity::Position => "",
            BaseQuantity::Orientation => "q",
            BaseQuantity::LinearVelocity => "v",
            BaseQuantity::AngularVelocity => "w",
            BaseQuantity::LinearAcceleration => "Dv",
            BaseQuantity::AngularAcceleration => "Dw",
            BaseQuantity::Force => "f",
            BaseQuantity::Moment => "n",
        }
    }
}

/// A coordinate of a floating base: the quantity and its axis (`x`, `y`, `z`, or `w` for the
/// quaternion's scalar part).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BaseCoordinate {
    /// What the coordinate measures.
    pub quantity: BaseQuantity,
    /// The axis: `x`, `y`, `z`, or `w`.
    pub axis: char,
}

impl BaseCoordinate {
    /// The printed name: `x`, `qw`, `vx`, `Dwz`, `fy`.
    pub fn name(self) -> String {
        format!("{}{}", self.quantity.prefix(), self.axis)
    }
}

/// What a symbol of q, v, q̈ or τ belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinate {
    /// A floating base's coordinate.
    Base(BaseCoordinate),
    /// A joint, by its index in the joint list.
    Joint(u16),
}

/// The floating base's coordinate a symbol of q, v, q̈ or τ names when its index falls in the
/// base's part (the first 7 of q, the first 6 of the others).
fn base_coordinate(symbol: Symbol) -> Option<BaseCoordinate> {
    const XYZ: [char; 3] = ['x', 'y', 'z'];
    let (first, second, index) = match symbol {
        Symbol::Position(i) => (BaseQuantity::Position, BaseQuantity::Orientation, i),
        Symbol::Velocity(i) => (
            BaseQuantity::LinearVelocity,
            BaseQuantity::AngularVelocity,
            i,
        ),
        Symbol::Acceleration(i) => (
            BaseQuantity::LinearAcceleration,
            BaseQuantity::AngularAcceleration,
            i,
        ),
        Symbol::Force(i) => (BaseQuantity::Force, BaseQuantity::Moment, i),
        Symbol::Parameter(_) | Symbol::Lane(_) => return None,
    };
    let index = usize::from(index);
    let (quantity, axis) = match (symbol, index) {
        (_, 0..=2) => (first, XYZ[index]),
        (_, 3..=5) => (second, XYZ[index - 3]),
        (Symbol::Position(_), 6) => (second, 'w'),
        _ => return None,
    };
    Some(BaseCoordinate { quantity, axis })
}

/// The number of a floating base's entries in q (7) or in v, q̈ and τ (6).
fn base_len(symbol: Symbol) -> u16 {
    match symbol {
        Symbol::Position(_) => 7,
        _ => 6,
    }
}

impl SymbolTable {
    /// A table with these joint variable names and no parameters.
    pub fn with_joints<S: Into<String>>(joints: impl IntoIterator<Item = S>) -> SymbolTable {
        SymbolTable {
            joints: joints.into_iter().map(Into::into).collect(),
            parameters: Vec::new(),
            floating_base: false,
        }
    }

    /// Joint variable names, in joint order.
    pub fn joints(&self) -> &[String] {
        &self.joints
    }

    /// Parameter names, in spec order.
    pub fn parameters(&self) -> &[String] {
        &self.parameters
    }

    /// Replaces the joint variable names (after joints were locked or reordered).
    pub fn set_joints<S: Into<String>>(&mut self, joints: impl IntoIterator<Item = S>) {
        self.joints = joints.into_iter().map(Into::into).collect();
    }

    /// Says whether q, v, q̈ and τ begin with a floating base's coordinates.
    pub fn set_floating_base(&mut self, floating: bool) {
        self.floating_base = floating;
    }

    /// Adds a joint variable and returns its index.
    pub fn push_joint(&mut self, name: impl Into<String>) -> u16 {
        self.joints.push(name.into());
        u16::try_from(self.joints.len() - 1).expect("at most 65536 joints")
    }

    /// Adds a parameter and returns its symbol.
    pub fn push_parameter(&mut self, name: impl Into<String>) -> Symbol {
        self.parameters.push(name.into());
        Symbol::Parameter(
            u16::try_from(self.parameters.len() - 1).expect("at most 65536 parameters"),
        )
    }

    /// The parameter symbol with this name.
    pub fn parameter(&self, name: &str) -> Option<Symbol> {
        self.parameters
            .iter()
            .position(|p| p == name)
            .map(|i| Symbol::Parameter(i as u16))
    }

    /// What a symbol of q, v, q̈ or τ belongs to: the floating base or a joint (its index in
    /// [`SymbolTable::joints`]); `None` for a parameter or a lane.
    pub fn coordinate(&self, symbol: Symbol) -> Option<Coordinate> {
        let index = match symbol {
            Symbol::Position(i)
            | Symbol::Velocity(i)
            | Symbol::Acceleration(i)
            | Symbol::Force(i) => i,
            Symbol::Parameter(_) | Symbol::Lane(_) => return None,
        };
        if !self.floating_base {
            return Some(Coordinate::Joint(index));
        }
        match index.checked_sub(base_len(symbol)) {
            Some(joint) => Some(Coordinate::Joint(joint)),
            None => base_coordinate(symbol).map(Coordinate::Base),
        }
    }

    /// The position symbol of joint `joint` (its index in [`SymbolTable::joints`]): past the
    /// floating base's seven coordinates when there is one.
    pub fn joint_position(&self, joint: u16) -> Symbol {
        let offset = if self.floating_base { 7 } else { 0 };
        Symbol::Position(joint.saturating_add(offset))
    }

    /// The printed name of a symbol.
    pub fn name(&self, symbol: Symbol) -> String {
        let joint = match self.coordinate(symbol) {
            Some(Coordinate::Base(base)) => return base.name(),
            Some(Coordinate::Joint(j)) => match self.joints.get(usize::from(j)) {
                Some(name) if self.plain(name) => name.clone(),
                Some(name) => format!("`{}`", name.replace('`', "``")),
                None => format!("q{}", j + 1),
            },
            None => String::new(),
        };
        match symbol {
            Symbol::Position(_) => joint,
            Symbol::Velocity(_) => format!("D{joint}"),
            Symbol::Acceleration(_) => format!("DD{joint}"),
            Symbol::Force(_) => format!("tau_{joint}"),
            Symbol::Parameter(i) => self
                .parameters
                .get(usize::from(i))
                .cloned()
                .unwrap_or_else(|| format!("p{i}")),
            Symbol::Lane(l) => format!("lane{l}"),
        }
    }

    /// Whether a joint name prints as itself: an identifier, no word of the expression
    /// language, not the printed velocity, acceleration or force of another joint, and not a
    /// floating base's coordinate.
    fn plain(&self, name: &str) -> bool {
        const RESERVED: [&str; 7] = ["pi", "sqrt", "sin", "cos", "Rx", "Ry", "Rz"];
        let mut chars = name.chars();
        let identifier = chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        identifier
            && !RESERVED.contains(&name)
            && (!self.floating_base || !is_base_name(name))
            && !self
                .joints
                .iter()
                .any(|other| derived(name, other) || derived(other, name))
    }

    /// The symbol printed as `name` (by [`SymbolTable::name`]), if any, else the joint written
    /// `name`. Parameters take precedence over joint names.
    pub fn lookup(&self, name: &str) -> Option<Symbol> {
        if let Some(p) = self.parameter(name) {
            return Some(p);
        }
        let offset = |form: fn(u16) -> Symbol| match self.floating_base {
            true => base_len(form(0)),
            false => 0,
        };
        let joints = u16::try_from(self.joints.len()).unwrap_or(u16::MAX);
        let printed = COORDINATE_FORMS.into_iter().find_map(|form| {
            (0..offset(form).saturating_add(joints))
                .map(form)
                .find(|&symbol| self.name(symbol) == name)
        });
        printed.or_else(|| {
            let j = self.joints.iter().position(|joint| joint == name)?;
            let j = u16::try_from(j).ok()?;
            Some(self.joint_position(j))
        })
    }
}

/// The kinds of symbol that are coordinates of q, v, q̈ and τ.
const COORDINATE_FORMS: [fn(u16) -> Symbol; 4] = [
    Symbol::Position,
    Symbol::Velocity,
    Symbol::Acceleration,
    Symbol::Force,
];

/// Whether `name` is how a floating base's coordinate prints.
fn is_base_name(name: &str) -> bool {
    COORDINATE_FORMS.iter().any(|form| {
        (0..base_len(form(0))).any(|i| base_coordinate(form(i)).is_some_and(|b| b.name() == name))
    })
}

/// Whether `name` is how a joint named `joint` prints its velocity, acceleration or force
/// (`Djoint`, `DDjoint`, `tau_joint`); compared without building the names, as every printed
/// joint symbol asks it of every other joint.
fn derived(name: &str, joint: &str) -> bool {
    ["D", "DD", "tau_"]
        .iter()
        .any(|prefix| name.strip_prefix(prefix) == Some(joint))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Looks up the printed name of every symbol of q, v, q̈ and τ below index `n`.
    fn every_name_is_found_again(table: &SymbolTable, n: u16) {
        for form in COORDINATE_FORMS {
            for symbol in (0..n).map(form) {
                assert_eq!(
                    table.lookup(&table.name(symbol)),
                    Some(symbol),
                    "{symbol:?}"
                );
            }
        }
    }

    #[test]
    fn any_joint_name_prints_unambiguously_and_is_found_again() {
        let table = SymbolTable::with_joints(["q1", "8", "FL-hip", "sin", "a`b", "x", "Dx"]);
        let printed: Vec<String> = (0..7).map(|k| table.name(Symbol::Position(k))).collect();
        assert_eq!(
            printed,
            ["q1", "`8`", "`FL-hip`", "`sin`", "`a``b`", "`x`", "`Dx`"]
        );
        assert_eq!(table.name(Symbol::Velocity(0)), "Dq1");
        assert_eq!(table.name(Symbol::Velocity(1)), "D`8`");
        assert_eq!(table.name(Symbol::Acceleration(2)), "DD`FL-hip`");
        assert_eq!(table.name(Symbol::Force(1)), "tau_`8`");
        every_name_is_found_again(&table, 7);
        assert_eq!(table.lookup("FL-hip"), Some(Symbol::Position(2)));
    }

    #[test]
    fn a_floating_base_names_its_coordinates_and_the_joints_follow_them() {
        let mut table = SymbolTable::with_joints(["q1", "x", "shoulder"]);
        table.set_floating_base(true);
        let q: Vec<String> = (0..10).map(|k| table.name(Symbol::Position(k))).collect();
        assert_eq!(
            q,
            ["x", "y", "z", "qx", "qy", "qz", "qw", "q1", "`x`", "shoulder"]
        );
        let v: Vec<String> = (0..9).map(|k| table.name(Symbol::Velocity(k))).collect();
        assert_eq!(
            v,
            [
                "vx",
                "vy",
                "vz",
                "wx",
                "wy",
                "wz",
                "Dq1",
                "D`x`",
                "Dshoulder"
            ]
        );
        assert_eq!(table.name(Symbol::Acceleration(4)), "Dwy");
        assert_eq!(table.name(Symbol::Acceleration(8)), "DDshoulder");
        assert_eq!(table.name(Symbol::Force(2)), "fz");
        assert_eq!(table.name(Symbol::Force(5)), "nz");
        assert_eq!(table.name(Symbol::Force(6)), "tau_q1");
        assert_eq!(table.joint_position(2), Symbol::Position(9));
        every_name_is_found_again(&table, 9);
        assert_eq!(
            table.lookup("x"),
            Some(Symbol::Position(0)),
            "the base's x wins"
        );
        assert_eq!(table.lookup("`x`"), Some(Symbol::Position(8)));
        table.set_floating_base(false);
        assert_eq!(table.name(Symbol::Position(1)), "x");
    }
}

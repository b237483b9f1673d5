//! Names of the symbols of an expression graph.

use super::node::Symbol;

/// The names of a graph's joint variables and parameters.
///
/// Printed names follow the thesis's Maple code (Appendix B): a joint `q1` has velocity `Dq1`
/// and acceleration `DDq1`; its generalised force prints as `tau_q1`. Joint names are any
/// string (a URDF joint may be called `8`, `FL-hip` or `sin`); a name that would not print
/// unambiguously — not an identifier, a word of the expression language, or printed like
/// another joint's velocity, acceleration or force — is printed between backticks
/// (`` `FL-hip` ``, `` D`FL-hip` ``, `` tau_`8` ``), a backtick in it doubled.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SymbolTable {
    joints: Vec<String>,
    parameters: Vec<String>,
}

impl SymbolTable {
    /// A table with these joint variable names and no parameters.
    pub fn with_joints<S: Into<String>>(joints: impl IntoIterator<Item = S>) -> SymbolTable {
        SymbolTable {
            joints: joints.into_iter().map(Into::into).collect(),
            parameters: Vec::new(),
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

    /// The printed name of a symbol.
    pub fn name(&self, symbol: Symbol) -> String {
        let joint = |i: u16| match self.joints.get(i as usize) {
            Some(name) if self.plain(name) => name.clone(),
            Some(name) => format!("`{}`", name.replace('`', "``")),
            None => format!("q{}", i + 1),
        };
        match symbol {
            Symbol::Position(i) => joint(i),
            Symbol::Velocity(i) => format!("D{}", joint(i)),
            Symbol::Acceleration(i) => format!("DD{}", joint(i)),
            Symbol::Force(i) => format!("tau_{}", joint(i)),
            Symbol::Parameter(i) => self
                .parameters
                .get(i as usize)
                .cloned()
                .unwrap_or_else(|| format!("p{i}")),
            Symbol::Lane(l) => format!("lane{l}"),
        }
    }

    /// Whether a joint name prints as itself: an identifier, no word of the expression
    /// language, and not the printed velocity, acceleration or force of another joint.
    fn plain(&self, name: &str) -> bool {
        const RESERVED: [&str; 7] = ["pi", "sqrt", "sin", "cos", "Rx", "Ry", "Rz"];
        let mut chars = name.chars();
        let identifier = chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        identifier
            && !RESERVED.contains(&name)
            && !self
                .joints
                .iter()
                .any(|other| derived(name, other) || derived(other, name))
    }

    /// The symbol printed as `name` (by [`SymbolTable::name`]), if any; a joint is also found
    /// by its name as written. Parameters take precedence over joint names.
    pub fn lookup(&self, name: &str) -> Option<Symbol> {
        if let Some(p) = self.parameter(name) {
            return Some(p);
        }
        let forms: [fn(u16) -> Symbol; 4] = [
            Symbol::Position,
            Symbol::Velocity,
            Symbol::Acceleration,
            Symbol::Force,
        ];
        for (k, joint) in self.joints.iter().enumerate() {
            let Ok(k) = u16::try_from(k) else { break };
            if joint == name {
                return Some(Symbol::Position(k));
            }
            for form in forms {
                if self.name(form(k)) == name {
                    return Some(form(k));
                }
            }
        }
        None
    }
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
        for k in 0..7 {
            for symbol in [
                Symbol::Position(k),
                Symbol::Velocity(k),
                Symbol::Acceleration(k),
                Symbol::Force(k),
            ] {
                assert_eq!(
                    table.lookup(&table.name(symbol)),
                    Some(symbol),
                    "{symbol:?}"
                );
            }
        }
        assert_eq!(table.lookup("FL-hip"), Some(Symbol::Position(2)));
    }
}

//! Names of the symbols of an expression graph.

use super::node::Symbol;

/// The names of a graph's joint variables and parameters.
///
/// Printed names follow the thesis's Maple code (Appendix B): a joint `q1` has velocity `Dq1`
/// and acceleration `DDq1`; its generalised force prints as `tau_q1`.
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
        let joint = |i: u16| {
            self.joints
                .get(i as usize)
                .cloned()
                .unwrap_or_else(|| format!("q{}", i + 1))
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
        }
    }

    /// The symbol printed as `name`, if any (parameters take precedence over joint names).
    pub fn lookup(&self, name: &str) -> Option<Symbol> {
        if let Some(p) = self.parameter(name) {
            return Some(p);
        }
        let joint = |n: &str| self.joints.iter().position(|j| j == n).map(|i| i as u16);
        if let Some(i) = joint(name) {
            return Some(Symbol::Position(i));
        }
        if let Some(i) = name.strip_prefix("DD").and_then(joint) {
            return Some(Symbol::Acceleration(i));
        }
        if let Some(i) = name.strip_prefix('D').and_then(joint) {
            return Some(Symbol::Velocity(i));
        }
        name.strip_prefix("tau_").and_then(joint).map(Symbol::Force)
    }
}

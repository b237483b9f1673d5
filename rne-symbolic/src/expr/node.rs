//! Node and symbol types of the expression graph.

use std::fmt;

/// Index of a node in an [`ExprGraph`](super::ExprGraph).
///
/// Invariant: every child of a node has a smaller `Id` than the node itself, so iterating ids in
/// increasing order visits children before parents (a topological order of the DAG).
#[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Id(u32);

impl Id {
    /// The position of the node in the graph's arena.
    pub fn index(self) -> usize {
        self.0 as usize
    }

    pub(crate) fn from_index(index: usize) -> Id {
        Id(u32::try_from(index).expect("expression graph holds at most 2^32 nodes"))
    }
}

impl fmt::Display for Id {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "%{}", self.0)
    }
}

/// A free variable of an expression.
///
/// Joint symbols are indexed by the joint's position in the robot's joint order; parameter
/// symbols by the parameter's position in the spec's `[parameters]` table.
#[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Symbol {
    /// Joint position q_i.
    Position(u16),
    /// Joint velocity q̇_i.
    Velocity(u16),
    /// Joint acceleration q̈_i.
    Acceleration(u16),
    /// Generalised force u_i applied at joint i (the input of forward dynamics).
    Force(u16),
    /// A named model parameter kept symbolic (mass, length, inertia, gravity, ...).
    Parameter(u16),
    /// The unit vector e_l of lane l: 1 in lane l, 0 in the others. The seed of a derivative
    /// built in lanes ([`crate::dynamics::LanePartials`]): a value that reads it is a vector
    /// whose lane l is the derivative along the direction seeded with e_l. Nothing else
    /// reads it, and a kernel that does is emitted with vector values.
    Lane(u16),
}

impl Symbol {
    /// The joint index of a joint symbol, `None` for parameters.
    pub fn joint(self) -> Option<usize> {
        match self {
            Symbol::Position(i)
            | Symbol::Velocity(i)
            | Symbol::Acceleration(i)
            | Symbol::Force(i) => Some(i as usize),
            Symbol::Parameter(_) | Symbol::Lane(_) => None,
        }
    }
}

/// A finite `f64` constant, compared and hashed by its bits (with `-0.0` stored as `0.0`).
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub struct Constant(u64);

impl Constant {
    /// The constant 0.
    pub const ZERO: Constant = Constant(0);

    /// Wraps a value; `-0.0` becomes `0.0` so that both hash-cons to one node.
    pub fn new(value: f64) -> Constant {
        let value = if value == 0.0 { 0.0 } else { value };
        Constant(value.to_bits())
    }

    /// The wrapped value.
    pub fn value(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// One operation of the expression graph. Subtraction is `Add(a, Neg(b))`; commutative
/// operations store their children in increasing `Id` order.
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// A numeric constant.
    Const(Constant),
    /// A free variable.
    Symbol(Symbol),
    /// `a + b`.
    Add(Id, Id),
    /// `a * b`.
    Mul(Id, Id),
    /// `a / b`.
    Div(Id, Id),
    /// `-a`.
    Neg(Id),
    /// `sin a`.
    Sin(Id),
    /// `cos a`.
    Cos(Id),
    /// `sqrt a`.
    Sqrt(Id),
    /// `sign a`: −1, 0 or 1 (NaN for NaN); the Coulomb friction law's sign(q̇).
    Sign(Id),
}

impl Node {
    /// The children of this node, in order.
    pub fn children(&self) -> impl Iterator<Item = Id> {
        let (a, b) = match *self {
            Node::Const(_) | Node::Symbol(_) => (None, None),
            Node::Add(a, b) | Node::Mul(a, b) | Node::Div(a, b) => (Some(a), Some(b)),
            Node::Neg(a) | Node::Sin(a) | Node::Cos(a) | Node::Sqrt(a) | Node::Sign(a) => {
                (Some(a), None)
            }
        };
        a.into_iter().chain(b)
    }
}

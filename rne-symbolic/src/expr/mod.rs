//! The expression graph: a hash-consed DAG of scalar expressions with simplifying
//! constructors, evaluation, differentiation, operation counts and s-expression text.

mod adjoint;
mod count;
mod derivative;
mod eval;
mod graph;
mod linalg;
mod node;
mod sexpr;
mod substitute;
mod symbols;

pub use count::OpCount;
pub use derivative::Differentiator;
pub use eval::Evaluator;
pub use graph::{ExprGraph, NODE_LIMIT, RIGHT_ANGLE_ULPS};
pub use linalg::{transpose, Mat3, Vec3};
pub use node::{Constant, Id, Node, Symbol};
pub use sexpr::SexprError;
pub use symbols::{BaseCoordinate, BaseQuantity, Coordinate, SymbolTable};

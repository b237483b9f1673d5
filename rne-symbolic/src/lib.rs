//! Symbolic Newton–Euler dynamics of robot arms.
//!
//! The pipeline: a robot spec (TOML) is read into a [`RobotModel`] whose geometry and inertia
//! are expressions in an [`ExprGraph`]; the Newton–Euler recursion of the thesis's chapter 3
//! runs on those expressions; the joint torques are then taken apart into M(q), the
//! Christoffel C(q, q̇), g(q), the bias and the energies.
#![deny(missing_docs)]
// Index loops over 0..3 mirror the vector and matrix notation of the equations they implement.
#![allow(clippy::needless_range_loop)]

pub mod canonical;
pub mod dynamics;
pub mod expr;
pub mod input;
pub mod model;
pub mod motion;
pub mod newton_euler;
pub mod spec;
mod urdf;

pub use dynamics::SymbolicDynamics;
pub use expr::{
    BaseCoordinate, BaseQuantity, Coordinate, ExprGraph, Id, Mat3, Node, OpCount, Symbol,
    SymbolTable, Vec3,
};
pub use input::{read_robot, Description, LoadOptions, RobotFormat};
pub use model::{JointKind, Link, NumericLink, NumericModel, RobotModel};
/// Sine and cosine for the kernels (`rne_runtime::trig`).
pub use rne_runtime::trig;
/// The scalar trait and the high-precision scalar, from the runtime that generated code
/// links (`rne-runtime`).
pub use rne_runtime::{DoubleDouble, Real};

//! Code generation for robot dynamics.

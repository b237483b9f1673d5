//! Real robots against Pinocchio (docs/design.md §6: "every URDF of the `example-robot-data`
//! package that Pinocchio loads, rne loads and agrees with Pinocchio's values"): Pinocchio's values
//! at seeded states, read from the JSON of `tools/peers/pinocchio_values.py`, against rne's
//! interpreted symbolic kernels and its numeric reference, fixed base with mimic semantics and
//! floating base.
//!
//! CI has no Python: small fixture URDFs with Pinocchio's values committed beside them
//! (`rne-models/corpus/tests/fixtures/`), and rne-models' quadruped with its values there too,
//! are checked by the same code in a test.

mod compare;
mod kernels;
mod report;
mod values;

pub use compare::{
    check_robot, CaseReport, Comparison, Errors, RobotReport, CORPUS_KERNELS, KERNEL_STATES,
};
pub use kernels::{check_every_kernel, summary, KernelCheck, KernelOutcome, KernelSummary};
pub use report::{markdown_table, replace_table, TABLE_BEGIN, TABLE_END};
pub use values::{BaseValues, PinocchioValues, RobotValues, State};

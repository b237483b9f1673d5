//! Robot specs: TOML files (format 1 of DESIGN.md §2) read into a [`RobotModel`](crate::RobotModel).

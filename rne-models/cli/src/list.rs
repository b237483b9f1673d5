//! `rne models`.

use std::io::Write;

use rne_symbolic::spec::LoadOptions;

use super::CliError;
use rne_models::{RobotSource, BUILTIN_ROBOTS};

/// Lists the built-in robots with their joint counts.
pub fn run(out: &mut dyn Write) -> Result<(), CliError> {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot).load(&LoadOptions::default())?;
        writeln!(
            out,
            "{:<14} {} joints  {}  ({})",
            robot.name,
            model.dof(),
            robot.description,
            robot.file
        )?;
    }
    Ok(())
}

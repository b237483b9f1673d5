//! What a run found: counts per target and the failures, each with the input that caused it.

use std::fmt;
use std::time::Duration;

use crate::targets::Input;
use crate::Target;

/// At most this many samples of messages are kept of each kind.
pub const KEPT_SAMPLES: usize = 20;

/// At most this many failures are kept with their inputs (all are counted).
pub const KEPT_FAILURES: usize = 50;

/// Why an input failed.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum FailureClass {
    /// It panicked (a Rust backtrace for the user).
    Panic,
    /// It ran longer than the budget.
    Hang,
    /// A reader rejected it with a message that does not name the file.
    UnclearError,
    /// A reader accepted it but the model has a non-finite number, a negative mass or a parent
    /// after its child.
    BadModel,
    /// The generator wrote a module that does not lex as Rust.
    BadModule,
    /// The harness's own mutation panicked (a bug of `rne-fuzz`, not of rne).
    Mutator,
}

/// One failing input.
#[derive(Clone, Debug)]
pub struct Failure {
    /// Why it failed.
    pub class: FailureClass,
    /// The panic message, the error, or what is wrong.
    pub message: String,
    /// The input, which [`crate::input`] rebuilds from its target, seed and iteration.
    pub input: Input,
}

/// The figures of one target's run.
#[derive(Clone, Debug)]
pub struct Report {
    /// The target.
    pub target: Target,
    /// The run's seed.
    pub seed: u64,
    /// Inputs tried.
    pub inputs: u64,
    /// Inputs a reader loaded.
    pub loaded: u64,
    /// Inputs a reader rejected with an error.
    pub rejected: u64,
    /// Rejected inputs whose mutations aimed at an element, and of those, errors naming it.
    pub element: (u64, u64),
    /// Rejected inputs whose mutations aimed at a field, and of those, errors naming it.
    pub field: (u64, u64),
    /// Modules generated (generate target: one per loaded input and base).
    pub generated: u64,
    /// Loaded robots not generated for having more links than the generate target takes.
    pub too_large: u64,
    /// Generator errors (generate target: a scene the robot cannot have, a massless joint).
    pub generate_errors: u64,
    /// Failures found, all classes.
    pub failure_count: u64,
    /// The first [`KEPT_FAILURES`] failures.
    pub failures: Vec<Failure>,
    /// Samples of what inputs were told: reader errors that name neither the element nor the
    /// field aimed at, and generator errors (at most [`KEPT_SAMPLES`] of each).
    pub samples: Vec<String>,
    /// Wall time of the run.
    pub elapsed: Duration,
    /// The slowest input that finished, and its iteration.
    pub slowest: (Duration, u64),
}

impl Report {
    /// An empty report for `target`'s run from `seed`.
    pub fn new(target: Target, seed: u64) -> Report {
        Report {
            target,
            seed,
            inputs: 0,
            loaded: 0,
            rejected: 0,
            element: (0, 0),
            field: (0, 0),
            generated: 0,
            too_large: 0,
            generate_errors: 0,
            failure_count: 0,
            failures: Vec::new(),
            samples: Vec::new(),
            elapsed: Duration::ZERO,
            slowest: (Duration::ZERO, 0),
        }
    }

    /// Records a failure.
    pub fn fail(&mut self, class: FailureClass, message: String, input: &Input) {
        self.failure_count += 1;
        if self.failures.len() < KEPT_FAILURES {
            self.failures.push(Failure {
                class,
                message,
                input: input.clone(),
            });
        }
    }

    /// Keeps `message` as a sample of its `kind` (a prefix) unless enough are kept.
    pub fn sample(&mut self, kind: &str, message: &str) {
        let kept = self.samples.iter().filter(|s| s.starts_with(kind)).count();
        if kept < KEPT_SAMPLES {
            self.samples.push(format!("{kind}{message}"));
        }
    }

    /// The number of failures of `class`.
    pub fn count(&self, class: FailureClass) -> usize {
        self.failures.iter().filter(|f| f.class == class).count()
    }
}

fn percent((aimed, named): (u64, u64)) -> String {
    if aimed == 0 {
        "-".to_owned()
    } else {
        format!(
            "{named}/{aimed} ({:.0} %)",
            100.0 * named as f64 / aimed as f64
        )
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let seconds = self.elapsed.as_secs_f64();
        writeln!(f, "target {} (seed {})", self.target.name(), self.seed)?;
        writeln!(
            f,
            "  inputs tried      {} in {seconds:.1} s ({:.0}/s)",
            self.inputs,
            self.inputs as f64 / seconds.max(1e-9)
        )?;
        writeln!(f, "  loaded            {}", self.loaded)?;
        writeln!(f, "  rejected (error)  {}", self.rejected)?;
        writeln!(
            f,
            "  errors naming the aimed element  {}",
            percent(self.element)
        )?;
        writeln!(
            f,
            "  errors naming the aimed field    {}",
            percent(self.field)
        )?;
        if self.target == Target::Generate {
            writeln!(f, "  modules generated {}", self.generated)?;
            writeln!(f, "  generator errors  {}", self.generate_errors)?;
            writeln!(f, "  loaded, too large to generate {}", self.too_large)?;
        }
        writeln!(
            f,
            "  slowest input     {:.3} s (iteration {})",
            self.slowest.0.as_secs_f64(),
            self.slowest.1
        )?;
        writeln!(f, "  failures          {}", self.failure_count)?;
        for failure in &self.failures {
            writeln!(
                f,
                "    {:?} at iteration {} ({}): {}",
                failure.class,
                failure.input.iteration,
                failure.input.describe(),
                failure.message
            )?;
        }
        Ok(())
    }
}

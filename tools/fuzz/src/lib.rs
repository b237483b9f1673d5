//! Structure-aware fuzzing of rne's robot readers and its generator, on stable Rust.
//!
//! Three targets ([`Target`]):
//!
//! - `urdf`: every committed fixture URDF, mutated as a URDF ([`mutate::urdf`]: elements
//!   removed, duplicated or renamed, joints relinked into cycles and orphans, joint types
//!   changed, odd numbers in attributes, entities, deep nesting) and as bytes
//!   ([`mutate::bytes`]: truncation, stray bytes, NUL, invalid UTF-8), read by
//!   `rne_symbolic::read_robot` (from memory, or, when the bytes are not UTF-8, from a file);
//! - `toml`: every committed fixture TOML spec, mutated as a spec ([`mutate::toml`]: links
//!   removed, duplicated or moved, parents relinked, joint kinds changed, odd values, keys
//!   removed, duplicated or renamed, parameter cycles) and as bytes;
//! - `generate`: small random robots ([`random_robot`]) and mutated fixtures that load, taken
//!   through `rne_codegen_core::generate` for every kernel on a fixed and a floating base.
//!
//! Each input runs on a thread of its own under [`std::panic::catch_unwind`] with the panic
//! message recorded and the default hook silenced ([`harness`]), within a time budget: a
//! panic, an input that takes longer than the budget, and a reader error whose message does
//! not name the file are failures ([`report::FailureClass`]). Inputs are drawn from a
//! ChaCha8 generator seeded by (target, seed, iteration), so [`input`] replays any of them.

#![deny(missing_docs)]

pub mod clarity;
pub mod harness;
pub mod mutate;
pub mod odd;
pub mod random_robot;
pub mod report;
pub mod seeds;
mod targets;

use std::path::PathBuf;
use std::time::Duration;

pub use report::{Failure, FailureClass, Report};
pub use targets::{input, run, Corpus, Input};

/// What is fuzzed.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Target {
    /// The URDF reader.
    Urdf,
    /// The TOML spec reader.
    Toml,
    /// The generator, on robots the readers load.
    Generate,
}

impl Target {
    /// Every target, in the order the command runs them.
    pub const ALL: [Target; 3] = [Target::Urdf, Target::Toml, Target::Generate];

    /// The target's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Target::Urdf => "urdf",
            Target::Toml => "toml",
            Target::Generate => "generate",
        }
    }

    /// The target named `name`.
    pub fn from_name(name: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == name)
    }
}

/// How long and from what a target is fuzzed.
#[derive(Clone, Debug)]
pub struct Config {
    /// The seed every input's generator derives from, with the target and the iteration.
    pub seed: u64,
    /// Stop after this long (checked between inputs).
    pub seconds: Option<f64>,
    /// Stop after this many inputs.
    pub iterations: Option<u64>,
    /// The first iteration (to resume or replay a range).
    pub first: u64,
    /// Longer than this, an input is a hang.
    pub budget: Duration,
    /// The repository whose fixture robot files seed the mutations.
    pub root: PathBuf,
    /// The longest chain of copied joints or links a mutation builds (of
    /// [`mutate::CHAIN_LENGTHS`]): 3000 by default; CI's debug build takes 100.
    pub longest_chain: usize,
}

impl Config {
    /// A run of `iterations` inputs from `seed` over the fixtures under `root`, with the
    /// default budget of 10 s an input.
    pub fn iterations(root: PathBuf, seed: u64, iterations: u64) -> Config {
        Config {
            seed,
            seconds: None,
            iterations: Some(iterations),
            first: 0,
            budget: DEFAULT_BUDGET,
            root,
            longest_chain: DEFAULT_LONGEST_CHAIN,
        }
    }
}

/// The longest chain a mutation builds unless told otherwise.
pub const DEFAULT_LONGEST_CHAIN: usize = 3000;

/// The time an input may take before it counts as a hang.
pub const DEFAULT_BUDGET: Duration = Duration::from_secs(10);

/// The repository this crate is built in (`tools/fuzz` two levels down).
pub fn repository_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

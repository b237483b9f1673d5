//! Mutations of robot files: structure-aware ones for each format ([`urdf`], [`toml`]) and
//! byte-level ones for both ([`bytes`]). Each says what it did and which element and field it
//! aimed at ([`Focus`]), so that the error it causes can be checked for naming them.

pub mod bytes;
pub mod toml;
pub mod urdf;

use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The element (a URDF joint or link, a TOML spec's link) and field a mutation aimed at.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Focus {
    /// The name of the joint or link whose text was changed.
    pub element: Option<String>,
    /// The attribute, key or child element changed (`type`, `xyz`, `mass`, `parent`).
    pub field: Option<String>,
}

/// One mutation applied: what it did, and what it aimed at.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Applied {
    /// A short description (`remove joint 'elbow'`).
    pub description: String,
    /// The element and field it aimed at.
    pub focus: Focus,
}

impl Applied {
    /// A mutation that aimed at no element in particular.
    pub fn anywhere(description: impl Into<String>) -> Applied {
        Applied {
            description: description.into(),
            focus: Focus::default(),
        }
    }

    /// A mutation aimed at `field` of `element`.
    pub fn at(description: impl Into<String>, element: &str, field: &str) -> Applied {
        Applied {
            description: description.into(),
            focus: Focus {
                element: Some(element.to_owned()),
                field: Some(field.to_owned()),
            },
        }
    }
}

/// The lengths of the long chains the mutations build (copies of a joint or a link).
pub const CHAIN_LENGTHS: [usize; 3] = [100, 1000, 3000];

/// A chain length of [`CHAIN_LENGTHS`], at most `longest` (and at least the shortest).
pub fn chain_length(rng: &mut ChaCha8Rng, longest: usize) -> usize {
    let allowed: Vec<usize> = CHAIN_LENGTHS
        .into_iter()
        .filter(|&n| n <= longest)
        .collect();
    if allowed.is_empty() {
        CHAIN_LENGTHS[0]
    } else {
        *pick(rng, &allowed)
    }
}

/// A uniformly chosen element of `items` (which must not be empty).
pub fn pick<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> &'a T {
    &items[rng.gen_range(0..items.len())]
}

/// The largest character boundary of `text` at or before `at`.
pub fn floor_boundary(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

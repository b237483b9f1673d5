//! Base parameters: the combinations of the standard inertial parameters that the dynamics
//! determine (Gautier, "Numerical calculation of the base inertial parameters of robots",
//! J. Robotic Systems 8(4), 1991).
//!
//! The regressor is evaluated at seeded random states and stacked into W (rows: equations,
//! columns: standard parameters). Columns are taken in the standard order; a column that is a
//! linear combination of the columns kept before it (its residual after projection on them
//! vanishes to a relative 1e-9) is *dependent*. With π₁ the kept and π₂ the dependent
//! parameters and W₂ = W₁ K, τ = W₁ π₁ + W₂ π₂ = W₁ (π₁ + K π₂): the base parameters are
//! π_b = π₁ + K π₂ and the base regressor is the kept columns of Y, of full column rank. The
//! order makes a later body's parameters regroup onto earlier ones, as Khalil and
//! Kleinfinger's rules do for serial chains. Parameters whose column is zero (they never act)
//! drop out.

use nalgebra::{DMatrix, DVector};

use crate::expr::{Id, Symbol};
use crate::model::{RobotModel, StateLayout};

/// Relative size of a column's residual below which it is dependent on the columns before it.
pub const DEPENDENCE_TOLERANCE: f64 = 1e-9;

/// Entries of K smaller than this (relative to the largest) are set to exactly zero.
const SNAP_TOLERANCE: f64 = 1e-11;

/// The base parameters of a regressor.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParameters {
    /// The standard-parameter columns kept (π₁), in order: base parameter b is
    /// `π[independent[b]] + Σ_d k[b][d] π[dependent[d]]`.
    pub independent: Vec<usize>,
    /// The standard-parameter columns regrouped into the kept ones (π₂).
    pub dependent: Vec<usize>,
    /// K: one row per base parameter, one column per dependent parameter.
    pub k: Vec<Vec<f64>>,
}

impl BaseParameters {
    /// Finds the base parameters of the regressor `y` of `model` (NV rows of expressions in
    /// the model's graph; parameters at their values) from `samples` seeded random states.
    pub fn find(model: &RobotModel, y: &[Vec<Id>], samples: usize) -> BaseParameters {
        let (graph, layout) = (&model.graph, model.state_layout());
        let columns = y.first().map_or(0, Vec::len);
        let flat: Vec<Id> = y.concat();
        let evaluator = crate::expr::Evaluator::new(graph, &flat);
        let rows = samples * y.len();
        let mut w = DMatrix::<f64>::zeros(rows, columns);
        let mut random = SplitMix(0x5eed_ba5e);
        for s in 0..samples {
            let q: Vec<f64> = random_configuration(&mut random, layout);
            let v: Vec<f64> = (0..layout.nv())
                .map(|_| random.uniform(-3.0, 3.0))
                .collect();
            let a: Vec<f64> = (0..layout.nv())
                .map(|_| random.uniform(-5.0, 5.0))
                .collect();
            let values = evaluator.eval::<f64>(graph, |symbol| match symbol {
                Symbol::Position(k) => q[k as usize],
                Symbol::Velocity(k) => v[k as usize],
                Symbol::Acceleration(k) => a[k as usize],
                _ => model.parameter_value(symbol).unwrap_or(f64::NAN),
            });
            for i in 0..y.len() {
                for c in 0..columns {
                    w[(s * y.len() + i, c)] = values[i * columns + c];
                }
            }
        }
        Self::from_stacked(&w)
    }

    /// The base parameters of a stacked regressor W.
    pub fn from_stacked(w: &DMatrix<f64>) -> BaseParameters {
        let scale = w
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        let mut basis: Vec<DVector<f64>> = Vec::new();
        let (mut independent, mut dependent) = (Vec::new(), Vec::new());
        for c in 0..w.ncols() {
            let column = w.column(c).into_owned();
            let mut residual = column.clone();
            // Gram–Schmidt twice ("twice is enough", Giraud et al. 2005).
            for _ in 0..2 {
                for b in &basis {
                    let projection = b.dot(&residual);
                    residual.axpy(-projection, b, 1.0);
                }
            }
            let size = residual.norm();
            if size > DEPENDENCE_TOLERANCE * column.norm().max(scale) {
                basis.push(residual / size);
                independent.push(c);
            } else {
                dependent.push(c);
            }
        }
        let w1 = DMatrix::from_fn(w.nrows(), independent.len(), |i, j| w[(i, independent[j])]);
        let w2 = DMatrix::from_fn(w.nrows(), dependent.len(), |i, j| w[(i, dependent[j])]);
        let k = if dependent.is_empty() || independent.is_empty() {
            DMatrix::zeros(independent.len(), dependent.len())
        } else {
            // Least squares W₁ K = W₂; W₁ has full column rank by construction.
            w1.svd(true, true)
                .solve(&w2, f64::EPSILON * scale)
                .unwrap_or_else(|_| DMatrix::zeros(independent.len(), dependent.len()))
        };
        let largest = k.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let k = (0..independent.len())
            .map(|b| {
                (0..dependent.len())
                    .map(|d| {
                        let x = k[(b, d)];
                        if x.abs() <= SNAP_TOLERANCE * largest.max(1.0) {
                            0.0
                        } else {
                            x
                        }
                    })
                    .collect()
            })
            .collect();
        BaseParameters {
            independent,
            dependent,
            k,
        }
    }

    /// Number of base parameters.
    pub fn len(&self) -> usize {
        self.independent.len()
    }

    /// Whether the dynamics determine no parameter at all.
    pub fn is_empty(&self) -> bool {
        self.independent.is_empty()
    }

    /// The names of the base parameters given those of the standard ones: each is named after
    /// the standard parameter it keeps, with `R` appended when others are regrouped into it
    /// (Khalil and Dombre's notation, e.g. `link2.IzzR`).
    pub fn names(&self, standard: &[String]) -> Vec<String> {
        self.independent
            .iter()
            .zip(&self.k)
            .map(|(&i, row)| {
                let regrouped = row.iter().any(|&k| k != 0.0);
                format!("{}{}", standard[i], if regrouped { "R" } else { "" })
            })
            .collect()
    }

    /// π_b = π₁ + K π₂ of the standard parameters `standard`.
    pub fn of(&self, standard: &[f64]) -> Vec<f64> {
        self.independent
            .iter()
            .zip(&self.k)
            .map(|(&i, row)| {
                standard[i]
                    + row
                        .iter()
                        .zip(&self.dependent)
                        .map(|(k, &d)| k * standard[d])
                        .sum::<f64>()
            })
            .collect()
    }
}

/// Rust identifiers for parameter names, deterministically: every character other than an
/// ASCII letter, digit or `_` becomes `_` (`link2.IzzR` → `link2_IzzR`), a name that does not
/// start with a letter or `_` gets a `p_` in front, and a name met before gets `_2`, `_3`, ...
/// until it is new.
pub fn identifiers(names: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::with_capacity(names.len());
    for name in names {
        let mut ident: String = name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        if !ident.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
            ident.insert_str(0, "p_");
        }
        if ident == "_" {
            ident = "p_".to_owned();
        }
        let mut unique = ident.clone();
        let mut k = 2;
        while out.contains(&unique) {
            unique = format!("{ident}_{k}");
            k += 1;
        }
        out.push(unique);
    }
    out
}

/// A random configuration: uniform joint angles in [−π, π] and a random unit quaternion.
fn random_configuration(random: &mut SplitMix, layout: StateLayout) -> Vec<f64> {
    let mut q = Vec::with_capacity(layout.nq());
    if layout.floating {
        q.extend((0..3).map(|_| random.uniform(-1.0, 1.0)));
        let quaternion: Vec<f64> = (0..4).map(|_| random.uniform(-1.0, 1.0)).collect();
        let norm = quaternion
            .iter()
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt()
            .max(1e-3);
        q.extend(quaternion.iter().map(|x| x / norm));
    }
    q.extend((0..layout.ndof).map(|_| random.uniform(-std::f64::consts::PI, std::f64::consts::PI)));
    q
}

/// Steele, Lea and Flood's SplitMix64: a seeded, reproducible sequence.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        let unit = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        low + (high - low) * unit
    }
}

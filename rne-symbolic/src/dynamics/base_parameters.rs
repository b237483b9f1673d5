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

mod residual_update;
mod vector;

use nalgebra::{DMatrix, DVector};

use crate::expr::{Id, Symbol};
use crate::model::{RobotModel, StateLayout};
use crate::DoubleDouble;
use vector::{dot, subtract_scaled};

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
    ///
    /// The regressor is evaluated in double-double and K refined against it (iterative
    /// refinement, `Split::refine`). For a column that is exactly dependent — the
    /// regroupings that follow from the kinematic structure, all those of the built-in
    /// robots — each coefficient is then the `f64` nearest to the exact one for the model's
    /// data: the planar elbow's l₁² is `0.09`, not `0.09000000000000029`. A column that is
    /// only nearly dependent (its residual below [`DEPENDENCE_TOLERANCE`] but not zero; a few
    /// of Talos's, where refinement leaves corrections near 1e-11) is regrouped as well,
    /// since the data cannot identify it, with its least-squares coefficient over the
    /// sampled states: its last digits depend on the samples.
    pub fn find(model: &RobotModel, y: &[Vec<Id>], samples: usize) -> BaseParameters {
        let (graph, layout) = (&model.graph, model.state_layout());
        let columns = y.first().map_or(0, Vec::len);
        let flat: Vec<Id> = y.concat();
        let evaluator = crate::expr::Evaluator::new(graph, &flat);
        let rows = samples * y.len();
        let mut w = DMatrix::from_element(rows, columns, DoubleDouble::ZERO);
        let mut random = SplitMix(0x5eed_ba5e);
        for s in 0..samples {
            let q = random_configuration(&mut random, layout);
            let v: Vec<f64> = (0..layout.nv())
                .map(|_| random.uniform(-3.0, 3.0))
                .collect();
            let a: Vec<f64> = (0..layout.nv())
                .map(|_| random.uniform(-5.0, 5.0))
                .collect();
            let values = evaluator.eval::<DoubleDouble>(graph, |symbol| match symbol {
                Symbol::Position(k) => q[k as usize],
                Symbol::Velocity(k) => DoubleDouble::from_f64(v[k as usize]),
                Symbol::Acceleration(k) => DoubleDouble::from_f64(a[k as usize]),
                _ => DoubleDouble::from_f64(model.parameter_value(symbol).unwrap_or(f64::NAN)),
            });
            for i in 0..y.len() {
                for c in 0..columns {
                    w[(s * y.len() + i, c)] = values[i * columns + c];
                }
            }
        }
        let split = Split::of(&w.map(DoubleDouble::to_f64));
        let k = split.refine(split.coefficients(), &w);
        split.into_base_parameters(k)
    }

    /// The base parameters of a stacked regressor W.
    pub fn from_stacked(w: &DMatrix<f64>) -> BaseParameters {
        let split = Split::of(w);
        let k = split.coefficients();
        split.into_base_parameters(k)
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

/// The largest magnitude in `w` (at least the smallest normal number).
fn scale(w: &DMatrix<f64>) -> f64 {
    w.iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE)
}

/// Gram–Schmidt on W's columns in order: the columns kept (independent of those before them)
/// and regrouped (dependent), with the factorisation W₁ = Q₁ R₁₁, W₂ = Q₁ R₁₂ it builds on the
/// way, so that K = R₁₁⁻¹ R₁₂ needs no other decomposition.
struct Split {
    independent: Vec<usize>,
    dependent: Vec<usize>,
    /// Q₁: the orthonormal basis, one column per kept column of W.
    q1: DMatrix<f64>,
    /// R₁₁: upper triangular, the kept columns in the basis.
    r11: DMatrix<f64>,
    /// R₁₂: the regrouped columns in the basis.
    r12: DMatrix<f64>,
}

impl Split {
    fn of(w: &DMatrix<f64>) -> Split {
        let scale = scale(w);
        let mut basis: Vec<DVector<f64>> = Vec::new();
        let (mut independent, mut dependent) = (Vec::new(), Vec::new());
        let (mut kept, mut regrouped) = (Vec::new(), Vec::new());
        for c in 0..w.ncols() {
            let column = w.column(c).into_owned();
            let mut residual = column.clone();
            let mut coefficients = vec![0.0; basis.len()];
            // Gram–Schmidt, repeated once when the projection cancelled more than a factor √2
            // of the column (Daniel, Gragg, Kaufman and Stewart, Math. Comp. 30, 1976; "twice
            // is enough", Giraud et al. 2005): a column far from the span is orthogonal after
            // one pass, a dependent one after two.
            let mut size = column.norm();
            for _ in 0..2 {
                for (b, q) in basis.iter().enumerate() {
                    let projection = dot(q.as_slice(), residual.as_slice());
                    subtract_scaled(residual.as_mut_slice(), projection, q.as_slice());
                    coefficients[b] += projection;
                }
                let before = size;
                size = residual.norm();
                if size > std::f64::consts::FRAC_1_SQRT_2 * before {
                    break;
                }
            }
            if size > DEPENDENCE_TOLERANCE * column.norm().max(scale) {
                basis.push(residual / size);
                coefficients.push(size);
                kept.push(coefficients);
                independent.push(c);
            } else {
                regrouped.push(coefficients);
                dependent.push(c);
            }
        }
        let nb = basis.len();
        let r = |columns: &[Vec<f64>]| {
            DMatrix::from_fn(nb, columns.len(), |i, j| {
                columns[j].get(i).copied().unwrap_or(0.0)
            })
        };
        Split {
            q1: if basis.is_empty() {
                DMatrix::zeros(w.nrows(), 0)
            } else {
                DMatrix::from_columns(&basis)
            },
            r11: r(&kept),
            r12: r(&regrouped),
            independent,
            dependent,
        }
    }

    /// X of W₁ X = B in the least-squares sense: R₁₁⁻¹ Q₁ᵀ B.
    fn solve(&self, b: &DMatrix<f64>) -> Option<DMatrix<f64>> {
        self.r11.solve_upper_triangular(&self.q1.tr_mul(b))
    }

    /// K of W₁ K = W₂, a consistent system (W₂'s columns are combinations of W₁'s, which have
    /// full column rank by construction): R₁₁⁻¹ R₁₂, entries below [`SNAP_TOLERANCE`] set to
    /// exactly zero.
    fn coefficients(&self) -> DMatrix<f64> {
        let (nb, nd) = (self.independent.len(), self.dependent.len());
        let mut k = self
            .r11
            .solve_upper_triangular(&self.r12)
            .unwrap_or_else(|| DMatrix::zeros(nb, nd));
        let largest = k.amax();
        k.apply(|x| {
            *x = if x.abs() <= SNAP_TOLERANCE * largest.max(1.0) {
                0.0
            } else {
                *x
            }
        });
        k
    }

    /// Iterative refinement (Wilkinson; Higham, *Accuracy and Stability of Numerical
    /// Algorithms*, 2nd ed., 2002, §12.1) of K against W in double-double: the residual
    /// R = W₂ − W₁ K is formed in double-double and the correction solved in `f64` with the
    /// same factors ([`Split::solve`]). The zeros of K stay zeros (they are structural: no
    /// regrouping), so the residual costs one product per row and non-zero coefficient,
    /// each by [`residual_update::subtract_scaled`] (with the bits of the operators, through a
    /// fused multiply–add where the processor has one).
    fn refine(&self, k: DMatrix<f64>, w: &DMatrix<DoubleDouble>) -> DMatrix<f64> {
        let (nb, nd) = k.shape();
        let nonzero: Vec<(usize, usize)> = (0..nd)
            .flat_map(|d| (0..nb).map(move |b| (b, d)))
            .filter(|&(b, d)| k[(b, d)] != 0.0)
            .collect();
        let mut refined = k.map(DoubleDouble::from_f64);
        // Columns as slices of the column-major storage: no view's strides per element.
        let rows = w.nrows();
        let w_all = w.as_slice();
        let kept: Vec<residual_update::Column> = self
            .independent
            .iter()
            .map(|&c| residual_update::Column::new(&w_all[c * rows..(c + 1) * rows]))
            .collect();
        for _ in 0..REFINEMENT_STEPS {
            if nonzero.is_empty() {
                break;
            }
            let mut residual = DMatrix::from_fn(w.nrows(), nd, |i, d| w[(i, self.dependent[d])]);
            let r_all = residual.as_mut_slice();
            for &(b, d) in &nonzero {
                residual_update::subtract_scaled(
                    &mut r_all[d * rows..(d + 1) * rows],
                    kept[b],
                    refined[(b, d)],
                );
            }
            let Some(correction) = self.solve(&residual.map(DoubleDouble::to_f64)) else {
                break;
            };
            let mut changed = false;
            for &(b, d) in &nonzero {
                let next = refined[(b, d)] + DoubleDouble::from_f64(correction[(b, d)]);
                changed |= next.to_f64() != refined[(b, d)].to_f64();
                refined[(b, d)] = next;
            }
            if !changed {
                break;
            }
        }
        refined.map(DoubleDouble::to_f64)
    }

    /// The base parameters with regrouping coefficients `k`.
    fn into_base_parameters(self, k: DMatrix<f64>) -> BaseParameters {
        BaseParameters {
            independent: self.independent,
            dependent: self.dependent,
            k: k.row_iter()
                .map(|row| row.iter().copied().collect())
                .collect(),
        }
    }
}

/// Most corrections [`Split::refine`] applies; each gains about 16 digits less the digits
/// W₁'s condition number costs, and it stops when K's `f64` values no longer change.
const REFINEMENT_STEPS: usize = 4;

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

/// A random configuration: uniform joint angles in [−π, π] and a random unit quaternion,
/// normalised in double-double so that its rotation is orthogonal to about 32 digits.
fn random_configuration(random: &mut SplitMix, layout: StateLayout) -> Vec<DoubleDouble> {
    let mut q = Vec::with_capacity(layout.nq());
    if layout.floating {
        q.extend((0..3).map(|_| DoubleDouble::from_f64(random.uniform(-1.0, 1.0))));
        let quaternion: Vec<DoubleDouble> = (0..4)
            .map(|_| DoubleDouble::from_f64(random.uniform(-1.0, 1.0)))
            .collect();
        let squared = quaternion
            .iter()
            .fold(DoubleDouble::ZERO, |sum, &x| sum + x * x);
        let norm = if squared.to_f64() < 1e-6 {
            DoubleDouble::from_f64(1e-3)
        } else {
            squared.sqrt()
        };
        q.extend(quaternion.iter().map(|&x| x / norm));
    }
    q.extend((0..layout.ndof).map(|_| {
        DoubleDouble::from_f64(random.uniform(-std::f64::consts::PI, std::f64::consts::PI))
    }));
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

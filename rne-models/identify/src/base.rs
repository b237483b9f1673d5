//! The structural base parameters of a model: the regressor of the numeric reference
//! (`Reference::regressor`) stacked over seeded random states, reduced by Gautier's numerical
//! method (`BaseParameters::from_stacked`: "Numerical calculation of the base inertial
//! parameters of robots", J. Robotic Systems 8(4), 1991). The set depends only on the
//! model's structure (geometry, gravity, which joints have friction or armature), never on
//! its masses and inertias, so it is found once and reused for any data.

use nalgebra::DMatrix;
use rne_reference::Reference;

use crate::regressors::Regressors;
use rne_symbolic::dynamics::base_parameters::BaseParameters;

use crate::names::{combination, readable_names, short_value, ParameterName};
use crate::random::Random;
use crate::IdentifyError;

/// Seed of the states at which the regressor is stacked.
const SEED: u64 = 0x1d_e7_1f_e5;

/// Joint rates and accelerations of the random states are uniform in ±this.
const RATE_BOUND: f64 = 3.0;

/// Relative distance within which a regrouping coefficient is replaced by the short decimal
/// or fraction it stands for. The coefficients solved from the stacked `f64` regressor lie
/// within 1.2e-14 of their exact short values for every built-in robot and the random robots
/// of the tests (`tests/base_parameters.rs`); an irrational coefficient falls within 1e-12 of
/// a short number with a probability of about 1e-6, and snapping it would move it by as much.
/// (Snapping within the printing tolerance, 1e-10, moved a random robot's −0.558367000047 to
/// −0.558367 and Y_b π_b off τ by a relative 2e-12.)
const SHORT_VALUE_TOLERANCE: f64 = 1e-12;

/// A joint state (q, q̇, q̈).
pub type State = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The base parameters of a model, with names.
#[derive(Clone, Debug)]
pub struct BaseSet {
    /// Which standard parameters are kept and how the others regroup onto them.
    pub parameters: BaseParameters,
    /// The standard parameters' readable names, in the regressor's column order.
    pub standard_names: Vec<ParameterName>,
    /// The model's standard parameters π (`Reference::standard_parameters`).
    pub standard_values: Vec<f64>,
    /// The link name of each body number (index 0: body 1).
    pub bodies: Vec<String>,
}

impl BaseSet {
    /// Finds the base parameters of `reference`'s regressor (friction columns as the
    /// reference includes them) from enough seeded random states to over-determine every
    /// column three times.
    pub fn find(reference: &mut Reference) -> Result<BaseSet, IdentifyError> {
        let (nq, nv) = (reference.nq(), reference.nv());
        let columns = reference.parameter_count();
        let states = (3 * columns).div_ceil(nv.max(1)).max(20);
        let mut random = Random::new(SEED);
        let mut w = DMatrix::zeros(states * nv, columns);
        for s in 0..states {
            let q = random.configuration(nq, nv);
            let (v, a) = (random.vector(nv, RATE_BOUND), random.vector(nv, RATE_BOUND));
            let y = reference.regressor(&q, &v, &a)?;
            w.view_mut((s * nv, 0), (nv, columns)).copy_from(&y);
        }
        let names = reference.parameter_names();
        let (standard_names, bodies) = readable_names(&names).ok_or_else(|| {
            IdentifyError::Model(format!("unexpected parameter names: {names:?}"))
        })?;
        let mut parameters = BaseParameters::from_stacked(&w);
        // Coefficients are products of lengths (and of coupling multipliers): the short
        // decimal or fraction each stands for is taken as exact.
        for k in parameters.k.iter_mut().flatten() {
            if let Some((exact, _)) = short_value(*k, SHORT_VALUE_TOLERANCE) {
                *k = exact;
            }
        }
        Ok(BaseSet {
            parameters,
            standard_names,
            standard_values: reference.standard_parameters(),
            bodies,
        })
    }

    /// Number of base parameters.
    pub fn len(&self) -> usize {
        self.parameters.len()
    }

    /// Whether the model has no identifiable parameter.
    pub fn is_empty(&self) -> bool {
        self.parameters.is_empty()
    }

    /// Number of standard parameters.
    pub fn standard_len(&self) -> usize {
        self.standard_names.len()
    }

    /// Base parameter `b` as (standard index, coefficient) terms: its kept parameter with
    /// coefficient 1, then the regrouped ones with a non-zero coefficient.
    pub fn terms(&self, b: usize) -> Vec<(usize, f64)> {
        let p = &self.parameters;
        std::iter::once((p.independent[b], 1.0))
            .chain(
                p.dependent
                    .iter()
                    .zip(&p.k[b])
                    .filter(|(_, &k)| k != 0.0)
                    .map(|(&d, &k)| (d, k)),
            )
            .collect()
    }

    /// Base parameter `b` printed as a combination of standard ones, `I1zz + 0.09·m2`.
    pub fn combination(&self, b: usize) -> String {
        let names: Vec<String> = self
            .standard_names
            .iter()
            .map(ParameterName::text)
            .collect();
        combination(&self.terms(b), &names)
    }

    /// The same in LaTeX.
    pub fn combination_latex(&self, b: usize) -> String {
        let names: Vec<String> = self
            .standard_names
            .iter()
            .map(ParameterName::latex)
            .collect();
        combination(&self.terms(b), &names).replace('·', " ")
    }

    /// π_b of the model's own standard parameters.
    pub fn model_values(&self) -> Vec<f64> {
        self.parameters.of(&self.standard_values)
    }

    /// The base regressor Y_b(q, q̇, q̈): the kept columns of the reference's regressor,
    /// `nv × len()`, with Y_b π_b = τ.
    pub fn base_regressor<R: Regressors + ?Sized>(
        &self,
        reference: &mut R,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DMatrix<f64>, IdentifyError> {
        let y = reference.regressor(q, qd, qdd)?;
        Ok(y.select_columns(&self.parameters.independent))
    }

    /// The base regressors at `states`, stacked: rows `s·nv … s·nv + nv − 1` are state s.
    pub fn stack<'a, R: Regressors + ?Sized>(
        &self,
        reference: &mut R,
        states: impl IntoIterator<Item = (&'a [f64], &'a [f64], &'a [f64])>,
    ) -> Result<DMatrix<f64>, IdentifyError> {
        let nv = reference.nv();
        let blocks = states
            .into_iter()
            .map(|(q, qd, qdd)| self.base_regressor(reference, q, qd, qdd))
            .collect::<Result<Vec<_>, _>>()?;
        let mut w = DMatrix::zeros(blocks.len() * nv, self.len());
        for (s, block) in blocks.iter().enumerate() {
            w.view_mut((s * nv, 0), (nv, self.len())).copy_from(block);
        }
        Ok(w)
    }
}

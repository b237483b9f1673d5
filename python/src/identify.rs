//! Identification from Python, as `rne identify` does it (the rne-identify crate): an
//! excitation trajectory optimised for the condition number of the stacked base regressor with
//! simulated torques (Swevers et al., "Optimal robot excitation and identification", IEEE
//! T-RA 13(5), 1997), the base parameters estimated from measured q, v, a, τ by weighted least
//! squares (Gautier and Poignet, "Extended Kalman filtering and weighted least squares
//! dynamic identification of robot", Control Engineering Practice 9(12), 2001), and the
//! torques an identified model predicts on fresh data. The model is the one `rne.load` made
//! (base, mimic joints, gravity, locks), with the numeric reference's regressor.

use numpy::{PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rne_identify::{
    design, fit, identify as estimate, predict as predict_torques, simulate, BaseSet, Design,
    Limits, Measurements, Sample, Simulation,
};
use rne_reference::Reference;
use rne_symbolic::model::NumericFriction;
use rne_symbolic::RobotModel;

use crate::arrays::Array;
use crate::errors;
use crate::model::Model;

/// The numeric reference of `model` with friction (three parameters per joint) and armature
/// added to every joint when asked, and its base parameters.
fn setup(model: &RobotModel, friction: bool, armature: bool) -> PyResult<(Reference, BaseSet)> {
    let mut numeric = model.to_numeric();
    for link in numeric.links.iter_mut().filter(|l| l.joint.is_some()) {
        if friction && link.friction.is_none() {
            link.friction = Some(NumericFriction {
                viscous: 0.0,
                coulomb: 0.0,
                offset: 0.0,
            });
        }
        if armature && link.armature.is_none() {
            link.armature = Some(0.0);
        }
    }
    let mut reference = Reference::try_new(&numeric)
        .map_err(|e| PyValueError::new_err(e.to_string()))?
        .with_friction(true);
    let base = BaseSet::find(&mut reference).map_err(errors::identify)?;
    Ok((reference, base))
}

/// A limit for every joint: one number, or one per joint.
fn per_joint(name: &str, values: Vec<f64>, joints: usize) -> PyResult<Vec<f64>> {
    match values.len() {
        1 => Ok(vec![values[0]; joints]),
        n if n == joints => Ok(values),
        n => Err(PyValueError::new_err(format!(
            "{name}: {n} values for {joints} joints (give one, or one per joint)"
        ))),
    }
}

/// Measurements from N × width arrays (every one 2-D with the same N).
fn measurements(
    model: &Model,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
    a: &Bound<'_, PyAny>,
    tau: Option<&Bound<'_, PyAny>>,
) -> PyResult<Measurements> {
    let (nq, nv) = (model.jit().nq(), model.jit().nv());
    let q = Array::read(q, "q", nq)?;
    let v = Array::read(v, "v", nv)?;
    let a = Array::read(a, "a", nv)?;
    let tau = tau.map(|t| Array::read(t, "tau", nv)).transpose()?;
    let n = q
        .states
        .ok_or_else(|| PyValueError::new_err(format!("`q` must be 2-D (N, {nq}): N samples")))?;
    for (name, states) in [("v", v.states), ("a", a.states)]
        .into_iter()
        .chain(tau.as_ref().map(|t| ("tau", t.states)))
    {
        if states != Some(n) {
            return Err(PyValueError::new_err(format!(
                "`{name}` must be 2-D with one row per sample of `q` ({n})"
            )));
        }
    }
    let row = |values: &[f64], k: usize, w: usize| values[k * w..(k + 1) * w].to_vec();
    let samples = (0..n)
        .map(|k| Sample {
            t: None,
            q: row(q.values(), k, nq),
            qd: row(v.values(), k, nv),
            qdd: row(a.values(), k, nv),
            tau: tau
                .as_ref()
                .map_or_else(|| vec![0.0; nv], |t| row(t.values(), k, nv)),
        })
        .collect();
    Ok(Measurements {
        positions: nq,
        joints: nv,
        samples,
    })
}

/// Rows of `rows` (all `width` long) as an (N, width) array.
fn matrix<'py>(
    py: Python<'py>,
    rows: &[Vec<f64>],
    width: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    numpy::PyArray1::from_vec(py, flat).reshape([rows.len(), width])
}

/// An excitation trajectory for `model` and the measurements a perfect sensor of q, v, a and a
/// torque sensor with relative noise `noise` would record along it (`rne identify MODEL
/// --excite`). Returns a dict: `t`, `q`, `v`, `a`, `tau` (N rows), `condition_number`,
/// `base_parameters` (their number), and the Fourier series `period`, `offsets`, `fourier_a`,
/// `fourier_b` (q_i(t) = q_i0 + Σ_l (a_il sin(l ω t) − b_il cos(l ω t)) / (l ω)).
#[pyfunction]
#[pyo3(signature = (model, *, period=10.0, harmonics=5, q_limit=vec![1.5], v_limit=vec![2.0], a_limit=None, iterations=300, criterion_states=100, seed=1, duration=None, rate=100.0, noise=0.01, friction=false, armature=false))]
#[allow(clippy::too_many_arguments)]
pub fn excitation<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    period: f64,
    harmonics: usize,
    q_limit: Vec<f64>,
    v_limit: Vec<f64>,
    a_limit: Option<Vec<f64>>,
    iterations: usize,
    criterion_states: usize,
    seed: u64,
    duration: Option<f64>,
    rate: f64,
    noise: f64,
    friction: bool,
    armature: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let n = model.jit().nv();
    let limits = Limits {
        position: per_joint("q_limit", q_limit, n)?,
        velocity: per_joint("v_limit", v_limit, n)?,
        acceleration: match a_limit {
            Some(values) => per_joint("a_limit", values, n)?,
            None => vec![f64::INFINITY; n],
        },
    };
    let numeric = model.numeric();
    let (excitation, data) = py.detach(|| -> PyResult<_> {
        let (mut reference, base) = setup(numeric, friction, armature)?;
        let excitation = design(
            &mut reference,
            &base,
            &Design {
                period,
                harmonics,
                limits,
                iterations,
                criterion_states,
                seed,
            },
        )
        .map_err(errors::identify)?;
        let simulation = Simulation {
            duration: duration.unwrap_or(period),
            rate,
            noise,
            seed,
        };
        let data = simulate(&mut reference, &excitation.trajectory, &simulation)
            .map_err(errors::identify)?;
        Ok(((excitation, base.len()), data))
    })?;
    let ((excitation, base_len), s) = (excitation, &data.samples);
    let (nq, nv) = (data.positions, data.joints);
    let column = |f: fn(&Sample) -> &Vec<f64>| s.iter().map(f).cloned().collect::<Vec<_>>();
    let out = PyDict::new(py);
    let t: Vec<f64> = s.iter().map(|x| x.t.unwrap_or(f64::NAN)).collect();
    out.set_item("t", numpy::PyArray1::from_vec(py, t))?;
    out.set_item("q", matrix(py, &column(|x| &x.q), nq)?)?;
    out.set_item("v", matrix(py, &column(|x| &x.qd), nv)?)?;
    out.set_item("a", matrix(py, &column(|x| &x.qdd), nv)?)?;
    out.set_item("tau", matrix(py, &column(|x| &x.tau), nv)?)?;
    let f = &excitation.trajectory;
    out.set_item("condition_number", excitation.condition)?;
    out.set_item("base_parameters", base_len)?;
    out.set_item("period", f.period)?;
    out.set_item("offsets", f.offsets.clone())?;
    out.set_item("fourier_a", f.a.clone())?;
    out.set_item("fourier_b", f.b.clone())?;
    Ok(out)
}

/// The base parameters estimated from N samples of q, v, a and τ by weighted (or ordinary)
/// least squares (`rne identify MODEL DATA.csv`). Returns a dict: `values`, `std` (standard
/// deviations), `names` (each base parameter as a combination of standard ones), `model`
/// (the robot file's values), `condition_number`, `joint_std` (each joint's equation error),
/// `weighted`, `standard_parameters` (their number), `bodies` (link of each body number) and
/// `samples`.
#[pyfunction]
#[pyo3(signature = (model, q, v, a, tau, *, weighted=true, friction=false, armature=false))]
#[allow(clippy::too_many_arguments)]
pub fn identify<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    weighted: bool,
    friction: bool,
    armature: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let data = measurements(&model, q, v, a, Some(tau))?;
    let numeric = model.numeric();
    let (base, fitted) = py.detach(|| -> PyResult<_> {
        let (mut reference, base) = setup(numeric, friction, armature)?;
        let fitted = estimate(&mut reference, &base, &data, weighted).map_err(errors::identify)?;
        Ok((base, fitted))
    })?;
    let out = PyDict::new(py);
    out.set_item(
        "values",
        numpy::PyArray1::from_vec(py, fitted.values.clone()),
    )?;
    out.set_item(
        "std",
        numpy::PyArray1::from_vec(py, fitted.deviations.clone()),
    )?;
    let names: Vec<String> = (0..base.len()).map(|b| base.combination(b)).collect();
    out.set_item("names", names)?;
    out.set_item("model", numpy::PyArray1::from_vec(py, base.model_values()))?;
    out.set_item("condition_number", fitted.condition)?;
    out.set_item(
        "joint_std",
        numpy::PyArray1::from_vec(py, fitted.joint_deviations.clone()),
    )?;
    out.set_item("weighted", fitted.weighted)?;
    out.set_item("standard_parameters", base.standard_len())?;
    out.set_item("bodies", base.bodies.clone())?;
    out.set_item("samples", data.samples.len())?;
    Ok(out)
}

/// The torques τ̂ = Y_b(q, v, a) θ (N, nv) of base parameters `values` at N samples, and, when
/// `tau` is given, how well they match it: returns a dict with `tau` (predicted) and, with
/// measurements, `relative_rms` (‖τ̂ − τ‖ / ‖τ‖) and `joints` (that ratio per joint).
#[pyfunction]
#[pyo3(signature = (model, values, q, v, a, tau=None, *, friction=false, armature=false))]
#[allow(clippy::too_many_arguments)]
pub fn validate<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    values: Vec<f64>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    tau: Option<&Bound<'py, PyAny>>,
    friction: bool,
    armature: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let data = measurements(&model, q, v, a, tau)?;
    let numeric = model.numeric();
    let predicted = py.detach(|| -> PyResult<_> {
        let (mut reference, base) = setup(numeric, friction, armature)?;
        if values.len() != base.len() {
            return Err(PyValueError::new_err(format!(
                "{} values for {} base parameters",
                values.len(),
                base.len()
            )));
        }
        predict_torques(&mut reference, &base, &values, &data).map_err(errors::identify)
    })?;
    let out = PyDict::new(py);
    out.set_item("tau", matrix(py, &predicted, data.joints)?)?;
    if tau.is_some() {
        let fitted = fit(&predicted, &data);
        out.set_item("relative_rms", fitted.overall)?;
        out.set_item("joints", numpy::PyArray1::from_vec(py, fitted.joints))?;
    }
    Ok(out)
}

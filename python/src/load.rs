//! What `rne.load` does: the robot read (a built-in name or a file), the options turned into the
//! generator's scene and generation options, and every kernel the model supports compiled by
//! the JIT.

use std::path::{Path, PathBuf};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rne_codegen_core::{GenerationOptions, Kernel, MimicMode, ParameterMode, Scene};
use rne_jit::JitModel;
use rne_symbolic::model::Base;
use rne_symbolic::spec::{LoadOptions, RobotFormat};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

use crate::builtin::builtin;
use crate::errors;

/// The options of `rne.load`, as Python gave them.
pub(crate) struct Options<'py> {
    /// A free-flyer root.
    pub floating_base: bool,
    /// `"constrained"` or `"free"`.
    pub mimic: &'py str,
    /// Joint friction in the dynamics and the regressor.
    pub friction: bool,
    /// Gravity overriding the file's.
    pub gravity: Option<Vec<f64>>,
    /// Joints locked at values: a dict {name: value}.
    pub lock: Option<Bound<'py, PyDict>>,
    /// The frames of the kinematics kernels.
    pub frames: Option<Vec<String>>,
    /// `"constant"`, `"runtime"` or `"base"`.
    pub parameters: &'py str,
    /// Fused multiply-adds where the processor has FMA.
    pub fma: bool,
    /// Every warning about the robot file an error.
    pub strict: bool,
}

/// The robot read and compiled, with what identification needs.
pub(crate) struct Loaded {
    /// The kernels.
    pub jit: JitModel,
    /// The model as the scene sees it, parameters folded: identification's reference.
    pub numeric: RobotModel,
    /// The robot's file (a built-in's relative to `rne-models/`).
    pub origin: String,
}

/// Reads `robot` and compiles the kernels named in `kernels` (rne's names; `None` for every
/// kernel the robot has) in `scene` as `options` say (`rne.load`). Needs no GIL.
pub(crate) fn read_and_compile(
    robot: &Path,
    (scene, mut options): (Scene, GenerationOptions),
    kernels: Option<&[String]>,
) -> PyResult<Loaded> {
    let (text, origin) = source(robot)?;
    let read = |symbolic_parameters: bool| -> PyResult<RobotModel> {
        let load_options = LoadOptions {
            symbolic_parameters,
            strict: options.strict,
            free_mimic: scene.mimic == MimicMode::Free,
            ..LoadOptions::default()
        };
        let format = RobotFormat::from_path(Path::new(&origin))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        read_robot(Description::text(&text, format, &origin), &load_options)
            .map_err(|e| PyValueError::new_err(e.to_string()))
    };
    let numeric = scene.apply(&read(false)?).map_err(errors::codegen)?;
    options.outputs = kernel_list(kernels, &numeric)?;
    let model = match options.parameters {
        ParameterMode::Runtime => read(true)?,
        _ => read(false)?,
    };
    let jit = JitModel::compile(&model, &scene, &options, &origin).map_err(errors::jit)?;
    Ok(Loaded {
        jit,
        numeric,
        origin,
    })
}

/// The robot file's text and its name in messages: a built-in robot's embedded file, or the
/// file at `robot`.
fn source(robot: &Path) -> PyResult<(String, String)> {
    if let Some(b) = robot.to_str().and_then(builtin) {
        return Ok((b.source.to_owned(), b.file.to_owned()));
    }
    let origin = robot.display().to_string();
    let text = std::fs::read_to_string(robot).map_err(|e| errors::io(&origin, &e))?;
    Ok((text, origin))
}

/// The generator's scene and generation options for `options` (the outputs set by
/// [`read_and_compile`]).
pub(crate) fn settings(options: &Options<'_>) -> PyResult<(Scene, GenerationOptions)> {
    let mimic = match options.mimic {
        "constrained" => MimicMode::Constrained,
        "free" => MimicMode::Free,
        other => {
            return Err(PyValueError::new_err(format!(
                "mimic must be \"constrained\" or \"free\", not {other:?}"
            )))
        }
    };
    let parameters = match options.parameters {
        "constant" => ParameterMode::Constant,
        "runtime" => ParameterMode::Runtime,
        "base" => ParameterMode::Base,
        other => {
            return Err(PyValueError::new_err(format!(
                "parameters must be \"constant\", \"runtime\" or \"base\", not {other:?}"
            )))
        }
    };
    let scene = Scene {
        base: options.floating_base.then_some(Base::Floating),
        mimic,
        friction: options.friction,
        gravity: gravity(options.gravity.as_deref())?,
        lock: lock(options.lock.as_ref())?,
        ..Scene::default()
    };
    let generation = GenerationOptions {
        frames: options.frames.clone(),
        parameters,
        fma: options.fma,
        strict: options.strict,
        ..GenerationOptions::default()
    };
    Ok((scene, generation))
}

/// Three finite numbers.
fn gravity(values: Option<&[f64]>) -> PyResult<Option<[f64; 3]>> {
    let Some(values) = values else {
        return Ok(None);
    };
    let g: [f64; 3] = values.try_into().map_err(|_| {
        PyValueError::new_err(format!("gravity needs 3 values, got {}", values.len()))
    })?;
    if g.iter().any(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "gravity must be finite, got {g:?}"
        )));
    }
    Ok(Some(g))
}

/// The locked joints, in the dict's order.
fn lock(dict: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, f64)>> {
    let Some(dict) = dict else {
        return Ok(Vec::new());
    };
    dict.iter()
        .map(|(name, value)| {
            let name: String = name
                .extract()
                .map_err(|_| PyValueError::new_err("lock: joint names must be strings"))?;
            let value: f64 = value.extract().map_err(|_| {
                PyValueError::new_err(format!("lock: the value of `{name}` must be a number"))
            })?;
            if !value.is_finite() {
                return Err(PyValueError::new_err(format!(
                    "lock: the value of `{name}` must be finite, got {value}"
                )));
            }
            Ok((name, value))
        })
        .collect()
}

/// The kernels to compile: those named, or every kernel, less those that solve with M(q)
/// when a joint moves no mass (M is then singular at every q).
fn kernel_list(kernels: Option<&[String]>, model: &RobotModel) -> PyResult<Vec<Kernel>> {
    if let Some(names) = kernels {
        return names
            .iter()
            .map(|name| {
                name.parse::<Kernel>()
                    .map_err(|e| PyValueError::new_err(format!("unknown kernel `{name}`; {e}")))
            })
            .collect();
    }
    let singular = model.check_mass_matrix_invertible().is_err();
    Ok(Kernel::ALL
        .into_iter()
        .filter(|k| !(singular && k.inverts_mass_matrix()))
        .collect())
}

/// The path of a robot argument: a `str` or an `os.PathLike`.
pub(crate) fn robot_path(robot: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    robot.extract::<PathBuf>().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "the robot must be a built-in name or a path (str or os.PathLike), not {}",
            robot
                .get_type()
                .name()
                .map_or_else(|_| "this".to_owned(), |n| n.to_string())
        ))
    })
}

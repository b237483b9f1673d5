//! Checks the meaning of every setting and turns the syntax into a `Scene`, collecting all
//! errors (each spanned on the offending token) before reporting them.

use std::collections::BTreeSet;

use proc_macro2::Span;
use rne_codegen_core::{
    ForwardDynamicsMethod, Kernel, MimicMode, ParameterMode, ScalarType, Scene,
};
use rne_symbolic::model::Base;
use syn::{Attribute, Ident, LitStr, Visibility};

use crate::ast::{DynamicsModule, Element, Value};

/// A checked macro input.
pub struct CheckedModule {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub robot: LitStr,
    pub scene: Scene,
    /// The span of each locked joint's name, for errors about joints the robot lacks.
    pub lock_spans: Vec<Span>,
    /// The span of each listed output (empty when `outputs` is left to its default), for
    /// errors about a kernel the robot cannot have.
    pub output_spans: Vec<Span>,
    /// The span of each listed frame, for errors about frames the robot lacks.
    pub frame_spans: Vec<Span>,
}

const KEYS: [&str; 16] = [
    "robot",
    "outputs",
    "gravity",
    "lock",
    "velocities",
    "base",
    "mimic",
    "friction",
    "frames",
    "forward_dynamics",
    "parameters",
    "scalar",
    "validation",
    "fma",
    "derivatives",
    "crate",
];

struct Errors(Option<syn::Error>);

impl Errors {
    fn push(&mut self, span: Span, message: impl std::fmt::Display) {
        let error = syn::Error::new(span, message);
        match &mut self.0 {
            Some(existing) => existing.combine(error),
            None => self.0 = Some(error),
        }
    }
}

pub fn check(input: DynamicsModule) -> syn::Result<CheckedModule> {
    let mut errors = Errors(None);
    let mut seen = BTreeSet::new();
    let mut robot = None;
    let mut scene = Scene::default();
    let mut lock_spans = Vec::new();
    let mut output_spans = Vec::new();
    let mut frame_spans = Vec::new();
    for setting in &input.settings {
        let key = setting.key.to_string();
        if !KEYS.contains(&key.as_str()) {
            errors.push(
                setting.key.span(),
                format!(
                    "unknown setting `{key}`; expected one of: {}",
                    KEYS.join(", ")
                ),
            );
            continue;
        }
        if !seen.insert(key.clone()) {
            errors.push(setting.key.span(), format!("`{key}` is given twice"));
            continue;
        }
        match (key.as_str(), &setting.value) {
            ("robot", Value::Str(path)) => robot = Some(path.clone()),
            ("outputs", Value::List(bracket, elements)) => {
                let mut outputs = Vec::new();
                for element in elements {
                    match element {
                        Element::Ident(name) => {
                            match name.to_string().parse::<Kernel>() {
                                Ok(kernel) if outputs.contains(&kernel) => errors
                                    .push(name.span(), format!("output `{name}` is listed twice")),
                                Ok(kernel) => {
                                    outputs.push(kernel);
                                    output_spans.push(name.span());
                                }
                                Err(e) => errors
                                    .push(name.span(), format!("unknown output `{name}`; {e}")),
                            }
                        }
                        Element::Number(n) => errors.push(n.span, "expected an output name"),
                        Element::Str(s) => errors.push(s.span(), "expected an output name"),
                    }
                }
                if elements.is_empty() {
                    errors.push(
                        bracket.span.join(),
                        "`outputs` must name at least one function",
                    );
                }
                scene.outputs = outputs;
            }
            ("gravity", Value::List(bracket, elements)) => {
                let mut gravity = Vec::new();
                for element in elements {
                    match element {
                        Element::Number(n) if n.value.is_finite() => gravity.push(n.value),
                        Element::Number(n) => {
                            errors.push(n.span, "gravity components must be finite")
                        }
                        Element::Ident(name) => errors.push(name.span(), "expected a number"),
                        Element::Str(s) => errors.push(s.span(), "expected a number"),
                    }
                }
                match <[f64; 3]>::try_from(gravity) {
                    Ok(g) => scene.gravity = Some(g),
                    Err(v) if v.len() == elements.len() => errors.push(
                        bracket.span.join(),
                        format!("gravity needs 3 components, got {}", v.len()),
                    ),
                    Err(_) => {}
                }
            }
            ("lock", Value::Map(_, entries)) => {
                let mut names = BTreeSet::new();
                for (joint, value) in entries {
                    if !names.insert(joint.name.clone()) {
                        errors.push(
                            joint.span,
                            format!("joint `{}` is locked twice", joint.name),
                        );
                    } else if !value.value.is_finite() {
                        errors.push(value.span, "a locked joint's value must be finite");
                    } else {
                        scene.lock.push((joint.name.clone(), value.value));
                        lock_spans.push(joint.span);
                    }
                }
            }
            ("velocities", Value::Ident(v)) => match v.to_string().as_str() {
                "zero" => scene.zero_velocities = true,
                "free" => scene.zero_velocities = false,
                other => errors.push(
                    v.span(),
                    format!(
                        "unknown velocities `{other}`; expected `zero` (a static scene) or `free`"
                    ),
                ),
            },
            ("base", Value::Ident(base)) => match base.to_string().as_str() {
                "fixed" => scene.base = Some(Base::Fixed),
                "floating" => scene.base = Some(Base::Floating),
                other => errors.push(
                    base.span(),
                    format!("unknown base `{other}`; expected `fixed` or `floating`"),
                ),
            },
            ("mimic", Value::Ident(mode)) => match mode.to_string().as_str() {
                "constrained" => scene.mimic = MimicMode::Constrained,
                "free" => scene.mimic = MimicMode::Free,
                other => errors.push(
                    mode.span(),
                    format!("unknown mimic mode `{other}`; expected `constrained` or `free`"),
                ),
            },
            ("friction", Value::Ident(mode)) => match mode.to_string().as_str() {
                "include" => scene.friction = true,
                "exclude" => scene.friction = false,
                other => errors.push(
                    mode.span(),
                    format!("unknown friction `{other}`; expected `include` or `exclude`"),
                ),
            },
            ("frames", Value::List(bracket, elements)) => {
                let mut frames: Vec<String> = Vec::new();
                for element in elements {
                    let (name, span) = match element {
                        Element::Ident(name) => (name.to_string(), name.span()),
                        Element::Str(s) => (s.value(), s.span()),
                        Element::Number(n) => {
                            errors.push(n.span, "expected a frame (link) name");
                            continue;
                        }
                    };
                    if frames.contains(&name) {
                        errors.push(span, format!("frame `{name}` is listed twice"));
                    } else {
                        frames.push(name);
                        frame_spans.push(span);
                    }
                }
                if elements.is_empty() {
                    errors.push(bracket.span.join(), "`frames` must name at least one frame");
                }
                scene.frames = Some(frames);
            }
            ("forward_dynamics", Value::Ident(method)) => match method.to_string().as_str() {
                "auto" => scene.forward_dynamics = ForwardDynamicsMethod::Auto,
                "aba" => scene.forward_dynamics = ForwardDynamicsMethod::Aba,
                "ldlt" => scene.forward_dynamics = ForwardDynamicsMethod::Ldlt,
                other => errors.push(
                    method.span(),
                    format!("unknown forward_dynamics `{other}`; expected `auto`, `aba` or `ldlt`"),
                ),
            },
            ("parameters", Value::Ident(mode)) => match mode.to_string().as_str() {
                "constant" => scene.parameters = ParameterMode::Constant,
                "runtime" => scene.parameters = ParameterMode::Runtime,
                "base" => scene.parameters = ParameterMode::Base,
                other => errors.push(
                    mode.span(),
                    format!(
                        "unknown parameters mode `{other}`; expected `constant`, `runtime` or `base`"
                    ),
                ),
            },
            ("scalar", Value::Ident(scalar)) => match scalar.to_string().as_str() {
                "f64" => scene.scalar = ScalarType::F64,
                "f32" => scene.scalar = ScalarType::F32,
                "generic" => scene.scalar = ScalarType::Generic,
                other => errors.push(
                    scalar.span(),
                    format!("unknown scalar `{other}`; expected `f64`, `f32` or `generic`"),
                ),
            },
            ("validation", Value::Ident(mode)) => match mode.to_string().as_str() {
                "strict" => scene.strict = true,
                "warn" => scene.strict = false,
                other => errors.push(
                    mode.span(),
                    format!(
                        "unknown validation `{other}`; expected `warn` (warnings in the module's \
                         docs) or `strict` (warnings are errors)"
                    ),
                ),
            },
            ("fma", Value::Ident(fused)) => match fused.to_string().as_str() {
                "true" => scene.fma = true,
                "false" => scene.fma = false,
                other => errors.push(
                    fused.span(),
                    format!("unknown fma `{other}`; expected `true` or `false`"),
                ),
            },
            ("derivatives", Value::Ident(mode)) => match mode.to_string().as_str() {
                "lanes" => scene.derivative_lanes = true,
                "scalar" => scene.derivative_lanes = false,
                other => errors.push(
                    mode.span(),
                    format!(
                        "unknown derivatives `{other}`; expected `lanes` (four directions per \
                         vector instruction, needs rne-codegen's feature `simd`) or `scalar`"
                    ),
                ),
            },
            ("crate", Value::Path(path)) => scene.crate_path = quote::quote!(#path).to_string(),
            (key, value) => errors.push(value_span(value), expected_shape(key)),
        }
    }
    if robot.is_none() && !seen.contains("robot") {
        errors.push(input.name.span(), "missing `robot: \"path/to/robot.toml\"`");
    }
    match (errors.0, robot) {
        (Some(e), _) => Err(e),
        (None, Some(robot)) => Ok(CheckedModule {
            attrs: input.attrs,
            vis: input.vis,
            name: input.name,
            robot,
            scene,
            lock_spans,
            output_spans,
            frame_spans,
        }),
        (None, None) => Err(syn::Error::new(input.name.span(), "missing `robot`")),
    }
}

fn value_span(value: &Value) -> Span {
    match value {
        Value::Str(s) => s.span(),
        Value::Ident(i) => i.span(),
        Value::List(b, _) => b.span.join(),
        Value::Map(b, _) => b.span.join(),
        Value::Path(p) => syn::spanned::Spanned::span(p),
    }
}

fn expected_shape(key: &str) -> String {
    match key {
        "robot" => "expected a string: `robot: \"robots/arm.toml\"`".into(),
        "outputs" => {
            "expected a list of function names: `outputs: [inverse_dynamics, mass_matrix]`".into()
        }
        "gravity" => "expected three numbers: `gravity: [0.0, 0.0, -9.81]`".into(),
        "lock" => "expected joint values: `lock: { q1: 0.0 }`".into(),
        "velocities" => "expected `zero` or `free`".into(),
        "base" => "expected `fixed` or `floating`".into(),
        "mimic" => "expected `constrained` or `free`".into(),
        "friction" => "expected `include` or `exclude`".into(),
        "forward_dynamics" => "expected `auto`, `aba` or `ldlt`".into(),
        "frames" => "expected a list of link names: `frames: [tool0, \"camera-link\"]`".into(),
        "parameters" => "expected `constant`, `runtime` or `base`".into(),
        "validation" => "expected `warn` or `strict`".into(),
        "fma" => "expected `true` or `false`".into(),
        "derivatives" => "expected `lanes` or `scalar`".into(),
        "crate" => {
            "expected a path to the rne-codegen crate: `crate: ::my_reexport::rne_codegen`".into()
        }
        _ => "expected `f64`, `f32` or `generic`".into(),
    }
}

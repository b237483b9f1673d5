//! Checks the meaning of every setting and turns the syntax into a `Scene` (the physical
//! settings) and `GenerationOptions` (the others), collecting all errors (each spanned on the
//! offending token) before reporting them.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::Span;
use rne_codegen_core::{
    ForwardDynamicsMethod, GenerationOptions, Kernel, MimicMode, ParameterMode, ScalarType, Scene,
};
use rne_symbolic::model::Base;
use syn::{Attribute, Ident, LitStr, Visibility};

use crate::ast::{DynamicsModule, Element, Key, Number, Value};

/// A checked macro input.
pub struct CheckedModule {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub robot: LitStr,
    pub scene: Scene,
    pub options: GenerationOptions,
    /// The key of each setting given by a deprecated spelling, and its current spelling, for
    /// a deprecation warning spanned on it.
    pub deprecated: Vec<(Ident, &'static str)>,
    /// The span of each locked joint's name, for errors about joints the robot lacks.
    pub lock_spans: Vec<Span>,
    /// The span of each listed output (empty when `outputs` is left to its default), for
    /// errors about a kernel the robot cannot have.
    pub output_spans: Vec<Span>,
    /// The span of each listed frame, for errors about frames the robot lacks.
    pub frame_spans: Vec<Span>,
}

/// The settings, as the error about an unknown one lists them.
const KEYS: [&str; 16] = [
    "robot",
    "outputs",
    "gravity",
    "lock",
    "at_rest",
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

/// Settings kept under an old spelling: (old key, the key it is an alias of, how to write it
/// now). Accepted with a deprecation warning; giving both spellings is giving a key twice.
const DEPRECATED_KEYS: [(&str, &str, &str); 1] = [(
    "velocities",
    "at_rest",
    "`velocities: zero` is deprecated: write `at_rest: true` (and `velocities: free`, \
     `at_rest: false`)",
)];

#[derive(Default)]
struct Errors(Option<syn::Error>);

impl Errors {
    fn push(&mut self, span: Span, message: impl std::fmt::Display) {
        let error = syn::Error::new(span, message);
        match &mut self.0 {
            Some(existing) => existing.combine(error),
            None => self.0 = Some(error),
        }
    }

    /// The value of the option named `name`, or `None` after an error built by `unknown` from
    /// the name given.
    fn pick<T: Clone>(
        &mut self,
        name: &Ident,
        options: &[(&str, T)],
        unknown: impl FnOnce(&str) -> String,
    ) -> Option<T> {
        let given = name.to_string();
        let value = options.iter().find(|(option, _)| *option == given);
        if value.is_none() {
            self.push(name.span(), unknown(&given));
        }
        value.map(|(_, value)| value.clone())
    }
}

/// Sets `place` to `value` when there is one (a setting that was not an error).
fn set<T>(place: &mut T, value: Option<T>) {
    if let Some(value) = value {
        *place = value;
    }
}

/// Checks the settings in order, each key at most once, and builds the module's scene and
/// generation options.
pub fn check(input: DynamicsModule) -> syn::Result<CheckedModule> {
    let mut checker = Checker::default();
    for setting in &input.settings {
        if let Some(key) = checker.key(&setting.key) {
            checker.setting(key, &setting.value);
        }
    }
    checker.finish(input)
}

/// What the settings checked so far give, and the errors they have.
#[derive(Default)]
struct Checker {
    errors: Errors,
    /// The settings given so far, by their current key, as they were spelled.
    seen: BTreeMap<&'static str, String>,
    robot: Option<LitStr>,
    scene: Scene,
    options: GenerationOptions,
    deprecated: Vec<(Ident, &'static str)>,
    lock_spans: Vec<Span>,
    output_spans: Vec<Span>,
    frame_spans: Vec<Span>,
}

impl Checker {
    /// The setting's key if it is one of [`KEYS`] (or a deprecated spelling of one, noted for
    /// a warning) not given before; an error otherwise.
    fn key(&mut self, key: &Ident) -> Option<&'static str> {
        let name = key.to_string();
        let old = DEPRECATED_KEYS.iter().find(|(old, _, _)| *old == name);
        if let Some(&(_, _, note)) = old {
            self.deprecated.push((key.clone(), note));
        }
        let current = old.map_or(name.as_str(), |(_, current, _)| current);
        let Some(&known) = KEYS.iter().find(|&&k| k == current) else {
            let message = format!(
                "unknown setting `{name}`; expected one of: {}",
                KEYS.join(", ")
            );
            self.errors.push(key.span(), message);
            return None;
        };
        if let Some(earlier) = self.seen.insert(known, name.clone()) {
            let message = match earlier == name {
                true => format!("`{name}` is given twice"),
                false => format!(
                    "`{name}` is given already as `{earlier}` (one is the deprecated spelling \
                     of the other); give it once"
                ),
            };
            self.errors.push(key.span(), message);
            return None;
        }
        Some(match old {
            Some(&(old, _, _)) => old,
            None => known,
        })
    }

    /// One setting, by its key and the shape of its value.
    fn setting(&mut self, key: &str, value: &Value) {
        match (key, value) {
            ("robot", Value::Str(path)) => self.robot = Some(path.clone()),
            ("outputs", Value::List(bracket, elements)) => self.outputs(bracket, elements),
            ("gravity", Value::List(bracket, elements)) => self.gravity(bracket, elements),
            ("lock", Value::Map(_, entries)) => self.lock(entries),
            ("frames", Value::List(bracket, elements)) => self.frames(bracket, elements),
            ("at_rest" | "velocities" | "base" | "mimic" | "friction", Value::Ident(name)) => {
                self.scene_choice(key, name)
            }
            (
                "forward_dynamics" | "parameters" | "scalar" | "validation" | "fma" | "derivatives",
                Value::Ident(name),
            ) => self.generation_choice(key, name),
            ("crate", Value::Path(path)) => {
                self.options.crate_path = quote::quote!(#path).to_string()
            }
            (key, value) => self.errors.push(value_span(value), expected_shape(key)),
        }
    }

    /// `outputs: [..]`: known kernels, each once, at least one.
    fn outputs(&mut self, bracket: &syn::token::Bracket, elements: &[Element]) {
        let mut outputs = Vec::new();
        for element in elements {
            let name = match element {
                Element::Ident(name) => name,
                Element::Number(n) => {
                    self.errors.push(n.span, "expected an output name");
                    continue;
                }
                Element::Str(s) => {
                    self.errors.push(s.span(), "expected an output name");
                    continue;
                }
            };
            match name.to_string().parse::<Kernel>() {
                Ok(kernel) if outputs.contains(&kernel) => self
                    .errors
                    .push(name.span(), format!("output `{name}` is listed twice")),
                Ok(kernel) => {
                    outputs.push(kernel);
                    self.output_spans.push(name.span());
                }
                Err(e) => self
                    .errors
                    .push(name.span(), format!("unknown output `{name}`; {e}")),
            }
        }
        if elements.is_empty() {
            self.errors.push(
                bracket.span.join(),
                "`outputs` must name at least one function",
            );
        }
        self.options.outputs = outputs;
    }

    /// `gravity: [x, y, z]`: three finite numbers.
    fn gravity(&mut self, bracket: &syn::token::Bracket, elements: &[Element]) {
        let mut gravity = Vec::new();
        for element in elements {
            match element {
                Element::Number(n) if n.value.is_finite() => gravity.push(n.value),
                Element::Number(n) => self
                    .errors
                    .push(n.span, "gravity components must be finite"),
                Element::Ident(name) => self.errors.push(name.span(), "expected a number"),
                Element::Str(s) => self.errors.push(s.span(), "expected a number"),
            }
        }
        match <[f64; 3]>::try_from(gravity) {
            Ok(g) => self.scene.gravity = Some(g),
            Err(v) if v.len() == elements.len() => self.errors.push(
                bracket.span.join(),
                format!("gravity needs 3 components, got {}", v.len()),
            ),
            Err(_) => {}
        }
    }

    /// `lock: { joint: value, .. }`: each joint once, at a finite value.
    fn lock(&mut self, entries: &[(Key, Number)]) {
        let mut names = BTreeSet::new();
        for (joint, value) in entries {
            if !names.insert(joint.name.clone()) {
                self.errors.push(
                    joint.span,
                    format!("joint `{}` is locked twice", joint.name),
                );
            } else if !value.value.is_finite() {
                self.errors
                    .push(value.span, "a locked joint's value must be finite");
            } else {
                self.scene.lock.push((joint.name.clone(), value.value));
                self.lock_spans.push(joint.span);
            }
        }
    }

    /// `frames: [..]`: link names (identifiers or strings), each once, at least one.
    fn frames(&mut self, bracket: &syn::token::Bracket, elements: &[Element]) {
        let mut frames: Vec<String> = Vec::new();
        for element in elements {
            let (name, span) = match element {
                Element::Ident(name) => (name.to_string(), name.span()),
                Element::Str(s) => (s.value(), s.span()),
                Element::Number(n) => {
                    self.errors.push(n.span, "expected a frame (link) name");
                    continue;
                }
            };
            if frames.contains(&name) {
                self.errors
                    .push(span, format!("frame `{name}` is listed twice"));
            } else {
                frames.push(name);
                self.frame_spans.push(span);
            }
        }
        if elements.is_empty() {
            self.errors
                .push(bracket.span.join(), "`frames` must name at least one frame");
        }
        self.options.frames = Some(frames);
    }

    /// The scene's settings given by a name: what moves and what acts on it.
    fn scene_choice(&mut self, key: &str, name: &Ident) {
        let (errors, scene) = (&mut self.errors, &mut self.scene);
        match key {
            "at_rest" => set(
                &mut scene.at_rest,
                errors.pick(name, &[("true", true), ("false", false)], |other| {
                    format!(
                        "unknown at_rest `{other}`; expected `true` (a static scene) or `false`"
                    )
                }),
            ),
            "velocities" => set(
                &mut scene.at_rest,
                errors.pick(name, &[("zero", true), ("free", false)], |other| {
                    format!(
                        "unknown velocities `{other}`; expected `zero` (a static scene) or `free`"
                    )
                }),
            ),
            "base" => set(
                &mut scene.base,
                errors.pick(
                    name,
                    &[
                        ("fixed", Some(Base::Fixed)),
                        ("floating", Some(Base::Floating)),
                    ],
                    |other| format!("unknown base `{other}`; expected `fixed` or `floating`"),
                ),
            ),
            "mimic" => set(
                &mut scene.mimic,
                errors.pick(
                    name,
                    &[
                        ("constrained", MimicMode::Constrained),
                        ("free", MimicMode::Free),
                    ],
                    |other| {
                        format!("unknown mimic mode `{other}`; expected `constrained` or `free`")
                    },
                ),
            ),
            _ => set(
                &mut scene.friction,
                errors.pick(name, &[("include", true), ("exclude", false)], |other| {
                    format!("unknown friction `{other}`; expected `include` or `exclude`")
                }),
            ),
        }
    }

    /// The settings given by a name that choose how the module is generated.
    fn generation_choice(&mut self, key: &str, name: &Ident) {
        let (errors, options) = (&mut self.errors, &mut self.options);
        match key {
            "forward_dynamics" => set(
                &mut options.forward_dynamics,
                errors.pick(
                    name,
                    &[
                        ("auto", ForwardDynamicsMethod::Auto),
                        ("aba", ForwardDynamicsMethod::Aba),
                        ("ldlt", ForwardDynamicsMethod::Ldlt),
                    ],
                    |other| {
                        format!(
                            "unknown forward_dynamics `{other}`; expected `auto`, `aba` or `ldlt`"
                        )
                    },
                ),
            ),
            "parameters" => set(
                &mut options.parameters,
                errors.pick(
                    name,
                    &[
                        ("constant", ParameterMode::Constant),
                        ("runtime", ParameterMode::Runtime),
                        ("base", ParameterMode::Base),
                    ],
                    |other| {
                        format!(
                            "unknown parameters mode `{other}`; expected `constant`, `runtime` \
                             or `base`"
                        )
                    },
                ),
            ),
            "scalar" => set(
                &mut options.scalar,
                errors.pick(
                    name,
                    &[
                        ("f64", ScalarType::F64),
                        ("f32", ScalarType::F32),
                        ("generic", ScalarType::Generic),
                    ],
                    |other| format!("unknown scalar `{other}`; expected `f64`, `f32` or `generic`"),
                ),
            ),
            _ => self.switch(key, name),
        }
    }

    /// The generation settings that turn something on or off.
    fn switch(&mut self, key: &str, name: &Ident) {
        let (errors, options) = (&mut self.errors, &mut self.options);
        match key {
            "validation" => set(
                &mut options.strict,
                errors.pick(name, &[("strict", true), ("warn", false)], |other| {
                    format!(
                        "unknown validation `{other}`; expected `warn` (warnings in the module's \
                         docs) or `strict` (warnings are errors)"
                    )
                }),
            ),
            "fma" => set(
                &mut options.fma,
                errors.pick(name, &[("true", true), ("false", false)], |other| {
                    format!("unknown fma `{other}`; expected `true` or `false`")
                }),
            ),
            _ => set(
                &mut options.derivative_lanes,
                errors.pick(name, &[("lanes", true), ("scalar", false)], |other| {
                    format!(
                        "unknown derivatives `{other}`; expected `lanes` (four directions per \
                         vector instruction, needs rne-codegen's feature `simd`) or `scalar`"
                    )
                }),
            ),
        }
    }

    /// The checked module, or every error found.
    fn finish(mut self, input: DynamicsModule) -> syn::Result<CheckedModule> {
        if self.robot.is_none() && !self.seen.contains_key("robot") {
            self.errors
                .push(input.name.span(), "missing `robot: \"path/to/robot.toml\"`");
        }
        match (self.errors.0, self.robot) {
            (Some(e), _) => Err(e),
            (None, Some(robot)) => Ok(CheckedModule {
                attrs: input.attrs,
                vis: input.vis,
                name: input.name,
                robot,
                scene: self.scene,
                options: self.options,
                deprecated: self.deprecated,
                lock_spans: self.lock_spans,
                output_spans: self.output_spans,
                frame_spans: self.frame_spans,
            }),
            (None, None) => Err(syn::Error::new(input.name.span(), "missing `robot`")),
        }
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
        "at_rest" => "expected `true` or `false`".into(),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The checked module of `settings` (after `robot: "r.toml",`).
    fn checked(settings: &str) -> syn::Result<CheckedModule> {
        let input = format!("mod m {{ robot: \"r.toml\", {settings} }}");
        check(syn::parse_str(&input).expect("the settings parse"))
    }

    #[test]
    fn at_rest_true_makes_a_static_scene_without_a_deprecation() {
        let module = checked("at_rest: true,").unwrap();
        assert!(module.scene.at_rest);
        assert!(module.deprecated.is_empty());
        assert!(!checked("at_rest: false,").unwrap().scene.at_rest);
        assert!(!checked("").unwrap().scene.at_rest, "moving by default");
    }

    #[test]
    fn velocities_zero_is_at_rest_noted_as_deprecated_on_its_key() {
        let module = checked("velocities: zero,").unwrap();
        assert!(module.scene.at_rest);
        let [(key, note)] = &module.deprecated[..] else {
            panic!("one deprecation: {:?}", module.deprecated.len())
        };
        assert_eq!(key.to_string(), "velocities");
        assert!(note.contains("at_rest: true"), "{note}");
        assert!(!checked("velocities: free,").unwrap().scene.at_rest);
    }

    #[test]
    fn both_spellings_are_one_setting_given_twice() {
        for settings in [
            "at_rest: true, velocities: zero,",
            "velocities: zero, at_rest: true,",
        ] {
            let error = checked(settings).err().expect("an error").to_string();
            assert!(
                error.contains("is given already as") && error.contains("deprecated spelling"),
                "{settings}: {error}"
            );
        }
    }

    #[test]
    fn physical_settings_go_to_the_scene_and_the_others_to_the_options() {
        let module = checked(
            "gravity: [0.0, 0.0, 0.0], lock: { q1: 0.5 }, friction: include, \
             outputs: [mass_matrix], scalar: f32, fma: true, parameters: runtime,",
        )
        .unwrap();
        assert_eq!(module.scene.gravity, Some([0.0; 3]));
        assert_eq!(module.scene.lock, [("q1".to_owned(), 0.5)]);
        assert!(module.scene.friction);
        assert_eq!(module.options.outputs, [Kernel::MassMatrix]);
        assert_eq!(module.options.scalar, ScalarType::F32);
        assert!(module.options.fma);
        assert_eq!(module.options.parameters, ParameterMode::Runtime);
    }
}

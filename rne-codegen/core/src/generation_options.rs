//! The generation options: how a scene's dynamics are written as code — which functions, over
//! which scalar, with which parameters folded, by which algorithm and with which arithmetic.
//! None of them changes the equations the functions compute; that is the [`Scene`](crate::Scene).

use proc_macro2::TokenStream;
use quote::quote;
use rne_symbolic::model::Frame;

use crate::error::CodegenError;
use crate::kernel::Kernel;

/// Everything that decides how the code is generated besides the robot and its scene
/// (docs/design.md §3).
///
/// The line between the two: a [`Scene`](crate::Scene) setting changes the dynamics (a locked
/// joint, gravity, rest, friction), an option here only their code. `outputs` and `frames`
/// choose which quantities are written, not what they are; `parameters` decides whether the
/// spec's masses and inertias are folded as numbers or read at run time — the values are the
/// spec's either way; `forward_dynamics` picks one of two algorithms for the same q̈; `fma`
/// and `derivative_lanes` change the instructions, not the quantities; `strict` how the robot
/// file's warnings are treated; `node_limit` when building gives up.
#[derive(Clone, Debug, PartialEq)]
pub struct GenerationOptions {
    /// The kernels to generate, in the order they are emitted.
    pub outputs: Vec<Kernel>,
    /// The frames (link names) of the kinematics kernels, in output order; `None` for every
    /// link of the robot file (the `frames:` setting).
    pub frames: Option<Vec<String>>,
    /// Constant or runtime parameters.
    pub parameters: ParameterMode,
    /// The scalar type.
    pub scalar: ScalarType,
    /// The path of the `rne-codegen` crate as the generated code's crate sees it (the macro's
    /// `crate:` setting, `DEFAULT_CRATE_PATH` by default); the code reaches the runtime
    /// through `<path>::__private`.
    pub crate_path: String,
    /// How `forward_dynamics` solves for q̈ (the `forward_dynamics:` setting).
    pub forward_dynamics: ForwardDynamicsMethod,
    /// Strict validation (`validation: strict`): every warning about the robot file is an
    /// error (docs/design.md §2.4).
    pub strict: bool,
    /// Fused multiply-add (`fma: true`): a product used only by a sum is computed with the
    /// sum by the runtime's `Real::mul_add`, one rounding instead of two and one instruction
    /// where the target has FMA (e.g. `-C target-cpu=native`); elsewhere the same two
    /// operations as without.
    pub fma: bool,
    /// The derivative kernels built in lanes (`derivatives: lanes`): their forward sweeps
    /// carry four directions at a time in the runtime's `F64x4`, one vector instruction for
    /// four derivatives (`rne_symbolic::dynamics::LanePartials`). Needs rne-codegen's feature
    /// `simd`; applies to `f64` kernels (the others are built as without) short of the
    /// length at which kernels are split into parts (module `split`).
    /// It pays in a build for a target with AVX (`-C target-cpu=native`): in a baseline
    /// x86-64 build each vector is a pair of SSE2 registers and the kernels are slower than
    /// without (docs/performance.md, "Derivatives in lanes").
    pub derivative_lanes: bool,
    /// The most nodes the expression graph of one kernel may reach while it is built
    /// ([`rne_symbolic::ExprGraph::node_limit`]); a kernel that would need more is an error
    /// naming it ([`CodegenError::TooLarge`]) instead of minutes of work and gigabytes.
    pub node_limit: usize,
}

/// How model parameters enter the generated code.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ParameterMode {
    /// Folded as numbers at generation time (the default; the fastest code).
    #[default]
    Constant,
    /// Read at run time from a generated `Params` struct whose `Default` holds the spec's
    /// values; every function takes `p: &Params` first.
    Runtime,
    /// Runtime parameters that are the base parameters (`BASE_PARAMETERS`): the identifiable
    /// combinations of the standard ones, found at the spec's geometry. `Params::default()`
    /// holds the base parameters of the spec's masses and inertias,
    /// `Params::from_standard(&π)` those of any standard parameters, and every function is
    /// an exact function of them ([`rne_symbolic::SymbolicDynamics::in_base_parameters`]);
    /// `potential_energy` is exact up to a constant, which the base parameters do not fix.
    Base,
}

/// The scalar type of the generated functions.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ScalarType {
    /// `f64` (the default).
    #[default]
    F64,
    /// `f32`.
    F32,
    /// Generic over the runtime's `Real` (f32, f64, `DoubleDouble`, ...).
    Generic,
}

/// The algorithm of the `forward_dynamics` kernel.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ForwardDynamicsMethod {
    /// Whichever of the two costs fewer operations for this robot and scene (the default).
    #[default]
    Auto,
    /// The articulated-body algorithm (Featherstone, RBDA ch. 7), linear in the number of
    /// links; fixed-base models without mimic couplings only (others use `Ldlt`).
    Aba,
    /// M(q) and C q̇ + g, solved by a generated LᵀDL factorisation of M (thesis (6.2)).
    Ldlt,
}

/// Where generated code finds `rne-codegen` unless told otherwise.
pub const DEFAULT_CRATE_PATH: &str = "::rne_codegen";

impl Default for GenerationOptions {
    fn default() -> GenerationOptions {
        GenerationOptions {
            outputs: Kernel::DYNAMICS.to_vec(),
            frames: None,
            parameters: ParameterMode::Constant,
            scalar: ScalarType::F64,
            crate_path: DEFAULT_CRATE_PATH.to_owned(),
            forward_dynamics: ForwardDynamicsMethod::Auto,
            strict: false,
            fma: false,
            derivative_lanes: false,
            node_limit: rne_symbolic::expr::NODE_LIMIT,
        }
    }
}

impl GenerationOptions {
    /// The kernels to generate: each of `outputs` once, at its first mention (a Builder or
    /// `rne emit` may repeat one), and `base_parameters` after them when an identification
    /// kernel is asked for without it (the map from π to the base regressor's π_b).
    pub fn kernels(&self) -> Vec<Kernel> {
        let mut kernels: Vec<Kernel> = Vec::new();
        for &kernel in &self.outputs {
            if !kernels.contains(&kernel) {
                kernels.push(kernel);
            }
        }
        if kernels.iter().any(|k| k.is_identification())
            && !kernels.contains(&Kernel::BaseParameters)
        {
            kernels.push(Kernel::BaseParameters);
        }
        kernels
    }

    /// The indices into `frames` (the robot's, [`rne_symbolic::SymbolicDynamics::frames`]) of
    /// the frames these options ask for; an error names a frame the robot does not have.
    pub fn frame_indices(&self, frames: &[Frame]) -> Result<Vec<usize>, CodegenError> {
        let Some(names) = &self.frames else {
            return Ok((0..frames.len()).collect());
        };
        names
            .iter()
            .enumerate()
            .map(|(i, name)| {
                if names[..i].contains(name) {
                    return Err(CodegenError::FrameTwice(name.clone()));
                }
                frames.iter().position(|f| &f.name == name).ok_or_else(|| {
                    CodegenError::UnknownFrame {
                        frame: name.clone(),
                        known: frames.iter().map(|f| f.name.clone()).collect(),
                    }
                })
            })
            .collect()
    }

    /// The path generated code reaches the runtime by: `<crate_path>::__private`. An error
    /// when `crate_path` is not a Rust path.
    pub fn runtime_path(&self) -> Result<TokenStream, CodegenError> {
        let path: syn::Path = syn::parse_str(&self.crate_path)
            .map_err(|_| CodegenError::CratePath(self.crate_path.clone()))?;
        Ok(quote!(#path::__private))
    }
}

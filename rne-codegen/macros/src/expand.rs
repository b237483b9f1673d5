//! Expansion: read the robot, generate its module, and make cargo rebuild when the robot
//! file changes (an `include_bytes!` of it).

use std::path::PathBuf;

use quote::quote;
use rne_codegen_core::{generate, read_robot, CodegenError, Kernel};

use crate::check::CheckedModule;

/// A second base for relative robot paths that are not found under `CARGO_MANIFEST_DIR`. For
/// the crate's own compile-fail tests, which trybuild builds in a directory of its own.
const MANIFEST_DIR_FALLBACK: &str = "RNE_CODEGEN_MANIFEST_DIR";

pub fn expand(module: CheckedModule) -> syn::Result<proc_macro2::TokenStream> {
    let origin = module.robot.value();
    let base = |var: &str| std::env::var_os(var).map(|dir| PathBuf::from(dir).join(&origin));
    let path = match (base("CARGO_MANIFEST_DIR"), base(MANIFEST_DIR_FALLBACK)) {
        (Some(primary), Some(fallback)) if !primary.exists() && fallback.exists() => fallback,
        (Some(primary), _) => primary,
        (None, fallback) => fallback.unwrap_or_else(|| PathBuf::from(&origin)),
    };
    let generated = read_robot(&path, &origin, &module.scene)
        .and_then(|model| generate(&model, &module.scene, &origin))
        .map_err(|e| match &e {
            CodegenError::Lock(rne_symbolic::model::LockError::UnknownJoint { name, .. }) => {
                let span = module
                    .scene
                    .lock
                    .iter()
                    .position(|(joint, _)| joint == name)
                    .map_or(module.robot.span(), |k| module.lock_spans[k]);
                syn::Error::new(span, e.to_string())
            }
            CodegenError::Massless { .. } => {
                let span = module
                    .scene
                    .outputs
                    .iter()
                    .position(|k| {
                        matches!(
                            k,
                            Kernel::ForwardDynamics
                                | Kernel::ForwardDynamicsDerivatives
                                | Kernel::MassMatrixInverse
                        )
                    })
                    .and_then(|k| module.output_spans.get(k).copied())
                    .unwrap_or_else(|| module.robot.span());
                syn::Error::new(span, e.to_string())
            }
            CodegenError::UnknownFrame { frame, .. } => {
                let span = module
                    .scene
                    .frames
                    .iter()
                    .flatten()
                    .position(|f| f == frame)
                    .map_or(module.robot.span(), |k| module.frame_spans[k]);
                syn::Error::new(span, e.to_string())
            }
            _ => syn::Error::new(module.robot.span(), e.to_string()),
        })?;
    let CheckedModule {
        attrs, vis, name, ..
    } = module;
    let items = generated.items;
    let tracked = path.to_string_lossy().into_owned();
    Ok(quote! {
        #(#attrs)*
        #vis mod #name {
            const _: &[u8] = include_bytes!(#tracked);
            #items
        }
    })
}

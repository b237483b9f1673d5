//! Expansion: read the robot, generate its module, and make cargo rebuild when the robot
//! file changes (an `include_bytes!` of it).

use std::path::PathBuf;

use quote::quote;
use rne_codegen_core::{generate, read_robot, CodegenError};

use crate::check::CheckedModule;

/// Overrides `CARGO_MANIFEST_DIR` as the base of relative robot paths. For the crate's own
/// compile-fail tests, which trybuild builds in a directory of its own.
const MANIFEST_DIR_OVERRIDE: &str = "RNE_CODEGEN_MANIFEST_DIR";

pub fn expand(module: CheckedModule) -> syn::Result<proc_macro2::TokenStream> {
    let manifest_dir = std::env::var_os(MANIFEST_DIR_OVERRIDE)
        .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
        .map(PathBuf::from)
        .unwrap_or_default();
    let origin = module.robot.value();
    let path = manifest_dir.join(&origin);
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

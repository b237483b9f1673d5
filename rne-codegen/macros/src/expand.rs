//! Expansion: read the robot, generate its module, and make cargo rebuild when the robot
//! file changes (an `include_bytes!` of it).

use std::path::PathBuf;

use quote::quote;
use rne_codegen_core::{generate_from_path, CodegenError};

use crate::check::CheckedModule;

pub fn expand(module: CheckedModule) -> syn::Result<proc_macro2::TokenStream> {
    let manifest_dir = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    let path = manifest_dir.join(module.robot.value());
    let generated = generate_from_path(&path, &module.scene).map_err(|e| match &e {
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

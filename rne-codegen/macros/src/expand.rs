//! Expansion: read the robot, generate its module, list the warnings about the robot file in
//! the module's documentation (docs/design.md §2.4; under `validation: strict` they are errors),
//! and make cargo rebuild when the robot file changes (an `include_bytes!` of it).

use std::path::PathBuf;

use proc_macro2::Ident;
use quote::quote;
use rne_codegen_core::{generate, read_robot, CodegenError};
use rne_symbolic::spec::SpecWarning;

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
    let generated = read_robot(&path, &origin, &module.scene, &module.options)
        .and_then(|model| {
            let generated = generate(&model, &module.scene, &module.options, &origin)?;
            Ok((generated, model.warnings))
        })
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
                    .options
                    .outputs
                    .iter()
                    .position(|k| k.inverts_mass_matrix())
                    .and_then(|k| module.output_spans.get(k).copied())
                    .unwrap_or_else(|| module.robot.span());
                syn::Error::new(span, e.to_string())
            }
            CodegenError::UnknownFrame { frame, .. } => {
                let span = module
                    .options
                    .frames
                    .iter()
                    .flatten()
                    .position(|f| f == frame)
                    .map_or(module.robot.span(), |k| module.frame_spans[k]);
                syn::Error::new(span, e.to_string())
            }
            _ => syn::Error::new(module.robot.span(), e.to_string()),
        })?;
    let (generated, warnings) = generated;
    let items = generated.items().map_err(|e| {
        syn::Error::new(
            module.robot.span(),
            format!("rne generated a module that does not lex as Rust ({e}); please report this"),
        )
    })?;
    let deprecations = deprecations(&module.deprecated);
    let CheckedModule {
        attrs, vis, name, ..
    } = module;
    let warnings = warning_docs(&warnings);
    let tracked = path.to_string_lossy().into_owned();
    Ok(quote! {
        #(#attrs)*
        #(#warnings)*
        #vis mod #name {
            const _: &[u8] = include_bytes!(#tracked);
            #(#deprecations)*
            #items
        }
    })
}

/// A use of a `#[deprecated]` item for each setting given by an old spelling, spanned on its
/// key: the compiler's deprecation warning, which a stable proc macro cannot emit itself,
/// shown where the user wrote it (and silenced by `#[allow(deprecated)]` on the module).
fn deprecations(deprecated: &[(Ident, &str)]) -> Vec<proc_macro2::TokenStream> {
    deprecated
        .iter()
        .map(|(key, note)| {
            let item = Ident::new(&format!("{key}_setting"), key.span());
            quote! {
                const _: () = {
                    #[deprecated(note = #note)]
                    #[allow(non_camel_case_types)]
                    struct #item;
                    let _ = #item;
                };
            }
        })
        .collect()
}

/// A `# Warnings` section of doc attributes, one item per warning; nothing without warnings.
fn warning_docs(warnings: &[SpecWarning]) -> Vec<proc_macro2::TokenStream> {
    if warnings.is_empty() {
        return Vec::new();
    }
    let heading = [
        String::new(),
        "# Warnings".to_owned(),
        String::new(),
        "Read from the robot file and accepted (`validation: strict` makes them errors):"
            .to_owned(),
        String::new(),
    ];
    heading
        .into_iter()
        .chain(warnings.iter().map(|w| format!("- {w}")))
        .map(|line| quote!(#[doc = #line]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rne_symbolic::spec::LoadOptions;
    use rne_symbolic::Description;

    #[test]
    fn each_warning_is_an_item_of_a_warnings_section_of_the_module_docs() {
        let text = "name = \"t\"\n[[link]]\nname = \"upper\"\njoint = \"revolute\"\n\
                    origin = { xyz = [0, 0, 0] }\naxis = [0, 0, 1]\nmass = 2\n\
                    inertia = { xx = 0.01, yy = 0.01, zz = 0.05 }\n";
        let model = rne_symbolic::read_robot(
            Description::toml(text, "specs/t.toml"),
            &LoadOptions::default(),
        )
        .expect("warns");
        assert_eq!(model.warnings.len(), 1);
        let docs: Vec<String> = warning_docs(&model.warnings)
            .iter()
            .map(ToString::to_string)
            .collect();
        assert!(docs.iter().any(|d| d.contains("# Warnings")), "{docs:?}");
        let item = format!("- {}", model.warnings[0]);
        assert!(docs.last().is_some_and(|d| d.contains(&item)), "{docs:?}");
        assert!(warning_docs(&[]).is_empty(), "no section without warnings");
    }
}

//! The `derive_dynamics!` procedural macro. Users depend on `rne-codegen`, which re-exports
//! it; see that crate for the documentation.
//!
//! Parse (`ast.rs`) -> check (`check.rs`, every error with its span) -> expand (`expand.rs`).

mod ast;
mod check;
mod expand;
mod internal;

use proc_macro::TokenStream;

/// Generates a module of dynamics functions for a robot; documented in `rne-codegen`.
#[proc_macro]
pub fn derive_dynamics(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as ast::DynamicsModule);
    let span = input.robot_span();
    internal::guarded(span, || check::check(input).and_then(expand::expand))
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}

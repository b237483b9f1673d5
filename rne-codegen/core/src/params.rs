//! The generated `Params` struct of the two runtime-parameter modes: the spec's parameters
//! (`parameters: runtime`) or the base parameters (`parameters: base`, docs/design.md §4.6).

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::RobotModel;

use crate::emit::parameter_ident;

/// `value` as a literal, with its sign in front (`-0.5`), and 0 for a value that is not finite.
fn literal(value: f64) -> TokenStream {
    if !value.is_finite() {
        let zero = Literal::f64_unsuffixed(0.0);
        return quote!(#zero);
    }
    let magnitude = Literal::f64_unsuffixed(value.abs());
    if value.is_sign_negative() && value != 0.0 {
        quote!(-#magnitude)
    } else {
        quote!(#magnitude)
    }
}

/// `pub struct Params` with one `f64` field per spec parameter, `Default` = the spec's values.
pub(crate) fn spec_params(model: &RobotModel) -> TokenStream {
    let fields = model.parameters.iter().map(|p| {
        let name = parameter_ident(&p.name);
        let doc = format!("`{}` (spec value {}).", p.name, p.value);
        quote!(#[doc = #doc] pub #name: f64,)
    });
    let defaults = model.parameters.iter().map(|p| {
        let name = parameter_ident(&p.name);
        let value = literal(p.value);
        quote!(#name: #value,)
    });
    quote! {
        #[doc = "The model parameters, read at run time. `Default` gives the spec's values."]
        #[derive(Clone, Debug, PartialEq)]
        #[allow(non_snake_case)]
        pub struct Params {
            #(#fields)*
        }
        impl Default for Params {
            fn default() -> Params {
                Params { #(#defaults)* }
            }
        }
    }
}

/// Base parameter `b` as text: `link2.Izz + 0.09·link3.m`.
fn combination(base: &BaseParameters, b: usize, standard: &[String]) -> String {
    let mut text = standard[base.independent[b]].clone();
    for (&k, &d) in base.k[b].iter().zip(&base.dependent) {
        if k != 0.0 {
            let sign = if k < 0.0 { '−' } else { '+' };
            text += &format!(" {sign} {}·{}", k.abs(), standard[d]);
        }
    }
    text
}

/// `pub struct Params` of the base parameters: one `f64` field per base parameter, named by
/// the identifier `model.parameters` gives it ([`rne_symbolic::SymbolicDynamics::in_base_parameters`]),
/// `Default` = π_b of the spec's parameters, and `Params::from_standard(&π)` =
/// π₁ + K π₂ of any standard parameters (in `PARAMETERS` order, length `NP`).
pub(crate) fn base_params(
    model: &RobotModel,
    base: &BaseParameters,
    standard: &[String],
    names: &[String],
) -> TokenStream {
    let idents: Vec<Ident> = model
        .parameters
        .iter()
        .map(|p| parameter_ident(&p.name))
        .collect();
    let fields = idents.iter().enumerate().map(|(b, name)| {
        let doc = format!(
            "`{}` = {} (spec: {}).",
            names[b],
            combination(base, b, standard),
            model.parameters[b].value
        );
        quote!(#[doc = #doc] pub #name: f64,)
    });
    let defaults = idents.iter().zip(&model.parameters).map(|(name, p)| {
        let value = literal(p.value);
        quote!(#name: #value,)
    });
    let standard_arg = Ident::new("standard", Span::call_site());
    let mappings = idents.iter().enumerate().map(|(b, name)| {
        let kept = Literal::usize_unsuffixed(base.independent[b]);
        let terms = base.k[b]
            .iter()
            .zip(&base.dependent)
            .filter(|(k, _)| **k != 0.0)
            .map(|(&k, &d)| {
                let magnitude = Literal::f64_unsuffixed(k.abs());
                let d = Literal::usize_unsuffixed(d);
                if k < 0.0 {
                    quote!(- #magnitude * #standard_arg[#d])
                } else {
                    quote!(+ #magnitude * #standard_arg[#d])
                }
            });
        quote!(#name: #standard_arg[#kept] #(#terms)*,)
    });
    quote! {
        #[doc = "The base parameters π_b (`BASE_PARAMETERS`), read at run time: the combinations of the standard parameters (`PARAMETERS`) that the dynamics determine. `Default` gives those of the spec's masses and inertias; `Params::from_standard` those of any standard parameters."]
        #[derive(Clone, Debug, PartialEq)]
        #[allow(non_snake_case)]
        pub struct Params {
            #(#fields)*
        }
        impl Default for Params {
            fn default() -> Params {
                Params { #(#defaults)* }
            }
        }
        impl Params {
            #[doc = "The base parameters of the standard parameters `standard` (in `PARAMETERS` order): π_b = π₁ + K π₂."]
            #[allow(unused_variables, clippy::all)]
            pub fn from_standard(#standard_arg: &[f64; NP]) -> Params {
                Params { #(#mappings)* }
            }
        }
    }
}

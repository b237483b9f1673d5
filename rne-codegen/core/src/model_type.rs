//! The `Model` type of a generated module: a value implementing the runtime's `Dynamics`
//! trait by calling the module's functions, so that generic code can take any robot.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use crate::emit::{argument, return_type};
use crate::generation_options::{ParameterMode, ScalarType};
use crate::kernel::Kernel;

/// What the `Model` type depends on.
pub struct ModelType<'a> {
    /// The robot's name (`Dynamics::NAME`).
    pub robot: &'a str,
    /// The kernels the module generated, in emission order (`Dynamics::KERNELS`).
    pub kernels: &'a [Kernel],
    /// The scalar of the module's functions.
    pub scalar: ScalarType,
    /// Whether the functions take `p: &Params`.
    pub parameters: ParameterMode,
    /// The path of the runtime crate.
    pub runtime: &'a TokenStream,
    /// Whether the model has a free-flyer root (`Dynamics::FLOATING_BASE`).
    pub floating_base: bool,
}

impl ModelType<'_> {
    /// `pub struct Model` (a unit struct; with runtime parameters one holding them; generic
    /// over the scalar for `scalar: generic`), its constructors and standard traits, its
    /// `Dynamics<NQ, NV>` implementation, and `Kinematics<NQ, NV, NF>` and
    /// `Identification<NQ, NV, NP, NB>` when the module has such kernels.
    pub fn emit(&self) -> TokenStream {
        let rt = self.runtime;
        let floating_base = self.floating_base;
        let (definition, impl_generics, self_ty, scalar) = match self.scalar {
            ScalarType::Generic => (
                self.generic_definition(),
                quote!(<T: #rt::Real>),
                quote!(Model<T>),
                quote!(T),
            ),
            ScalarType::F64 => (self.definition(), quote!(), quote!(Model), quote!(f64)),
            ScalarType::F32 => (self.definition(), quote!(), quote!(Model), quote!(f32)),
        };
        let robot = self.robot;
        let kernels = self.kernels.iter().map(|k| {
            let variant = Ident::new(&format!("{k:?}"), Span::call_site());
            quote!(#rt::Kernel::#variant)
        });
        let methods = |select: fn(Kernel) -> bool| -> Vec<TokenStream> {
            self.kernels
                .iter()
                .filter(|&&k| select(k))
                .map(|&k| self.method(k, &scalar))
                .collect()
        };
        let dynamics = methods(|k| !k.is_kinematics() && !k.is_identification());
        let kinematics = self.kernels.iter().any(|k| k.is_kinematics()).then(|| {
            let methods = methods(Kernel::is_kinematics);
            quote! {
                impl #impl_generics #rt::Kinematics<NQ, NV, NF> for #self_ty {
                    const FRAMES: &'static [&'static str] = &FRAMES;
                    #(#methods)*
                }
            }
        });
        let identification = self.kernels.iter().any(|k| k.is_identification()).then(|| {
            let methods = methods(Kernel::is_identification);
            quote! {
                impl #impl_generics #rt::Identification<NQ, NV, NP, NB> for #self_ty {
                    const PARAMETERS: &'static [&'static str] = &PARAMETERS;
                    const BASE_PARAMETERS: &'static [&'static str] = &BASE_PARAMETERS;
                    #(#methods)*
                }
            }
        });
        quote! {
            #definition
            impl #impl_generics #rt::Dynamics<NQ, NV> for #self_ty {
                type Scalar = #scalar;
                const NAME: &'static str = #robot;
                const JOINTS: &'static [&'static str] = &JOINTS;
                const FLOATING_BASE: bool = #floating_base;
                const KERNELS: &'static [#rt::Kernel] = &[#(#kernels),*];
                #(#dynamics)*
            }
            #kinematics
            #identification
        }
    }

    /// The model of an `f64` or `f32` module.
    fn definition(&self) -> TokenStream {
        match self.parameters {
            ParameterMode::Constant => quote! {
                #[doc = "This robot's dynamics as a value implementing the runtime's `Dynamics` trait."]
                #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
                pub struct Model;
            },
            ParameterMode::Runtime | ParameterMode::Base => quote! {
                #[doc = "This robot's dynamics with its parameters, as a value implementing the runtime's `Dynamics` trait. `Default` holds the spec's parameters."]
                #[derive(Clone, Debug, Default, PartialEq)]
                pub struct Model {
                    #[doc = "The parameters every kernel reads."]
                    pub params: Params,
                }
                impl Model {
                    #[doc = "The model with these parameters."]
                    pub fn new(params: Params) -> Model {
                        Model { params }
                    }
                }
            },
        }
    }

    /// The model of a `scalar: generic` module: generic over the scalar (default `f64`),
    /// with the standard traits written out so that they do not require them of `T`.
    fn generic_definition(&self) -> TokenStream {
        let phantom = quote!(::core::marker::PhantomData);
        match self.parameters {
            ParameterMode::Constant => quote! {
                #[doc = "This robot's dynamics in scalar `T`, as a value implementing the runtime's `Dynamics` trait."]
                pub struct Model<T = f64> {
                    _scalar: #phantom<fn() -> T>,
                }
                impl<T> Model<T> {
                    #[doc = "The model (it holds nothing)."]
                    pub const fn new() -> Model<T> {
                        Model { _scalar: #phantom }
                    }
                }
                impl<T> ::core::clone::Clone for Model<T> {
                    fn clone(&self) -> Model<T> {
                        *self
                    }
                }
                impl<T> ::core::marker::Copy for Model<T> {}
                impl<T> ::core::default::Default for Model<T> {
                    fn default() -> Model<T> {
                        Model::new()
                    }
                }
                impl<T> ::core::fmt::Debug for Model<T> {
                    fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                        f.write_str("Model")
                    }
                }
            },
            ParameterMode::Runtime | ParameterMode::Base => quote! {
                #[doc = "This robot's dynamics in scalar `T` with its parameters, as a value implementing the runtime's `Dynamics` trait. `Default` holds the spec's parameters."]
                pub struct Model<T = f64> {
                    #[doc = "The parameters every kernel reads."]
                    pub params: Params,
                    _scalar: #phantom<fn() -> T>,
                }
                impl<T> Model<T> {
                    #[doc = "The model with these parameters."]
                    pub fn new(params: Params) -> Model<T> {
                        Model { params, _scalar: #phantom }
                    }
                }
                impl<T> ::core::clone::Clone for Model<T> {
                    fn clone(&self) -> Model<T> {
                        Model::new(self.params.clone())
                    }
                }
                impl<T> ::core::default::Default for Model<T> {
                    fn default() -> Model<T> {
                        Model::new(Params::default())
                    }
                }
                impl<T> ::core::fmt::Debug for Model<T> {
                    fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                        f.debug_struct("Model").field("params", &self.params).finish()
                    }
                }
            },
        }
    }

    /// The trait method of `kernel`: `Some` of the module's function.
    fn method(&self, kernel: Kernel, scalar: &TokenStream) -> TokenStream {
        let name = Ident::new(kernel.name(), Span::call_site());
        let inputs: Vec<Ident> = kernel
            .inputs()
            .iter()
            .map(|input| Ident::new(input.name(), Span::call_site()))
            .collect();
        let args = kernel.inputs().iter().map(|&input| argument(input, scalar));
        let params = match self.parameters {
            ParameterMode::Runtime | ParameterMode::Base => quote!(&self.params,),
            ParameterMode::Constant => quote!(),
        };
        let ret = return_type(kernel, scalar);
        quote! {
            #[inline]
            fn #name(&self, #(#args),*) -> ::core::option::Option<#ret> {
                ::core::option::Option::Some(#name(#params #(#inputs),*))
            }
        }
    }
}

//! Emission of a [`Program`] as a straight-line Rust function with `quote`.
//!
//! A result used more than once becomes a `let` binding; a result used once is written
//! inline where it is used, so the text follows the expression's shape. Operator precedence
//! is respected without ever re-associating: `a + (b + c)` keeps its parentheses, because
//! floating-point addition is not associative and the emitted code must compute exactly
//! what the program says. The sine and cosine of each joint angle are computed once, with
//! the runtime's `Real::sin_cos` (or `Real::sin_cos_array` for several), at the top of the
//! function.
//!
//! Emitted code names nothing but `core` and the runtime, which it reaches through the path
//! in [`EmitContext::runtime`] (`::rne_codegen::__private` unless the `crate:` setting says
//! otherwise).

use std::collections::BTreeMap;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use rne_symbolic::{Symbol, SymbolTable};

use crate::kernel::{Input, Kernel, Shape};
use crate::program::{Instr, Operand, Program};
use crate::scene::{ParameterMode, ScalarType};

/// What the emitter needs besides the program.
#[derive(Clone, Copy, Debug)]
pub struct EmitContext<'a> {
    /// Joint and parameter names.
    pub symbols: &'a SymbolTable,
    /// The scalar type.
    pub scalar: ScalarType,
    /// Constant or runtime parameters.
    pub parameters: ParameterMode,
    /// The path of the runtime crate (`rne-runtime`) from the generated code
    /// ([`Scene::runtime_path`](crate::Scene::runtime_path)).
    pub runtime: &'a TokenStream,
}

/// Binding strength of an emitted expression; a child is parenthesised when it binds less
/// tightly than its position requires.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Precedence {
    Sum = 1,
    Product = 2,
    Unary = 3,
    Atom = 4,
}

struct Emitter<'a> {
    program: &'a Program,
    ctx: EmitContext<'a>,
    /// Name of each materialised temporary.
    names: Vec<Option<Ident>>,
    /// `sin`/`cos` of joint k: which of the two are used.
    trig: BTreeMap<u16, (bool, bool)>,
}

impl Emitter<'_> {
    /// `<path to the runtime>::Real`.
    fn real(&self) -> TokenStream {
        let runtime = self.ctx.runtime;
        quote!(#runtime::Real)
    }

    fn scalar_type(&self) -> TokenStream {
        match self.ctx.scalar {
            ScalarType::F64 => quote!(f64),
            ScalarType::F32 => quote!(f32),
            ScalarType::Generic => quote!(T),
        }
    }

    fn constant(&self, c: f64) -> (TokenStream, Precedence) {
        let magnitude = if c.is_finite() {
            let lit = Literal::f64_unsuffixed(c.abs());
            let real = self.real();
            match self.ctx.scalar {
                ScalarType::Generic => quote!(<T as #real>::from_f64(#lit)),
                _ => quote!(#lit),
            }
        } else {
            let special = if c.is_nan() {
                quote!(NAN)
            } else {
                quote!(INFINITY)
            };
            let real = self.real();
            match self.ctx.scalar {
                ScalarType::F32 => quote!(f32::#special),
                ScalarType::F64 => quote!(f64::#special),
                ScalarType::Generic => quote!(<T as #real>::from_f64(f64::#special)),
            }
        };
        if c.is_sign_negative() && !c.is_nan() {
            (quote!(-#magnitude), Precedence::Unary)
        } else {
            (magnitude, Precedence::Atom)
        }
    }

    fn input(&self, s: Symbol) -> TokenStream {
        let index = |k: u16| Literal::usize_unsuffixed(k as usize);
        match s {
            Symbol::Position(k) => {
                let k = index(k);
                quote!(q[#k])
            }
            Symbol::Velocity(k) => {
                let k = index(k);
                quote!(qd[#k])
            }
            Symbol::Acceleration(k) => {
                let k = index(k);
                quote!(qdd[#k])
            }
            Symbol::Force(k) => {
                let k = index(k);
                quote!(tau[#k])
            }
            Symbol::Parameter(_) => {
                let field = parameter_ident(&self.ctx.symbols.name(s));
                let real = self.real();
                match self.ctx.scalar {
                    ScalarType::F64 => quote!(p.#field),
                    ScalarType::F32 => quote!((p.#field as f32)),
                    ScalarType::Generic => quote!(<T as #real>::from_f64(p.#field)),
                }
            }
        }
    }

    fn joint_trig(&self, instr: Instr) -> Option<Ident> {
        match instr {
            Instr::Sin(Operand::Input(Symbol::Position(k))) => Some(format_ident!("s{}", k + 1)),
            Instr::Cos(Operand::Input(Symbol::Position(k))) => Some(format_ident!("c{}", k + 1)),
            _ => None,
        }
    }

    fn operand(&self, o: Operand) -> (TokenStream, Precedence) {
        match o {
            Operand::Const(c) => self.constant(c),
            Operand::Input(s) => (self.input(s), Precedence::Atom),
            Operand::Temp(t) => match &self.names[t as usize] {
                Some(name) => (quote!(#name), Precedence::Atom),
                None => self.instr(self.program.instrs[t as usize]),
            },
        }
    }

    fn at_least(&self, o: Operand, min: Precedence) -> TokenStream {
        let (tokens, precedence) = self.operand(o);
        if precedence >= min {
            tokens
        } else {
            quote!((#tokens))
        }
    }

    /// `sin`, `cos` and `sqrt` go through the runtime's `Real` for every scalar type, so that
    /// `f64` kernels get the fast, accurate runtime `sin_cos` and no kernel needs `std`.
    fn call(&self, method: &str, a: Operand) -> (TokenStream, Precedence) {
        let method = Ident::new(method, Span::call_site());
        let arg = self.operand(a).0;
        let real = self.real();
        (quote!(#real::#method(#arg)), Precedence::Atom)
    }

    fn instr(&self, instr: Instr) -> (TokenStream, Precedence) {
        if let Some(name) = self.joint_trig(instr) {
            return (quote!(#name), Precedence::Atom);
        }
        use Precedence::*;
        match instr {
            Instr::Add(a, b) => {
                let (a, b) = (self.at_least(a, Sum), self.at_least(b, Product));
                (quote!(#a + #b), Sum)
            }
            Instr::Sub(a, b) => {
                let (a, b) = (self.at_least(a, Sum), self.at_least(b, Product));
                (quote!(#a - #b), Sum)
            }
            Instr::Mul(a, b) => {
                let (a, b) = (self.at_least(a, Product), self.at_least(b, Unary));
                (quote!(#a * #b), Product)
            }
            Instr::Div(a, b) => {
                let (a, b) = (self.at_least(a, Product), self.at_least(b, Unary));
                (quote!(#a / #b), Product)
            }
            Instr::Neg(a) => {
                let a = self.at_least(a, Unary);
                (quote!(-#a), Unary)
            }
            Instr::Sin(a) => self.call("sin", a),
            Instr::Cos(a) => self.call("cos", a),
            Instr::Sqrt(a) => self.call("sqrt", a),
        }
    }

    /// The sines and cosines of the joint angles the kernel uses (a mass matrix never needs
    /// the first joint's), all at once with `Real::sin_cos_array` when two or more are needed,
    /// else one. `f64` and `f32` evaluate the array in `f64`, two lanes per vector
    /// instruction, so an odd count is padded with a repeat of the last angle: a lane of its
    /// own costs more than a pair. Generic kernels, mostly evaluated in double-double, are not.
    fn trig_bindings(&self) -> TokenStream {
        if self.trig.len() >= 2 {
            let mut angles: Vec<TokenStream> = self
                .trig
                .keys()
                .map(|&k| self.input(Symbol::Position(k)))
                .collect();
            if self.ctx.scalar != ScalarType::Generic && angles.len() % 2 == 1 {
                angles.push(angles[angles.len() - 1].clone());
            }
            let lines = self
                .trig
                .iter()
                .enumerate()
                .map(|(lane, (&k, &(sin, cos)))| {
                    let lane = Literal::usize_unsuffixed(lane);
                    let (s, c) = (format_ident!("s{}", k + 1), format_ident!("c{}", k + 1));
                    let s = sin.then(|| quote!(let #s = sin_q[#lane];));
                    let c = cos.then(|| quote!(let #c = cos_q[#lane];));
                    quote!(#s #c)
                });
            let real = self.real();
            return quote! {
                let (sin_q, cos_q) = #real::sin_cos_array(&[#(#angles),*]);
                #(#lines)*
            };
        }
        let real = self.real();
        let lines = self.trig.iter().map(|(&k, &(sin, cos))| {
            let (s, c) = (format_ident!("s{}", k + 1), format_ident!("c{}", k + 1));
            let angle = self.input(Symbol::Position(k));
            match (sin, cos) {
                (true, true) => quote!(let (#s, #c) = #real::sin_cos(#angle);),
                (true, false) => quote!(let #s = #real::sin(#angle);),
                (false, _) => quote!(let #c = #real::cos(#angle);),
            }
        });
        quote!(#(#lines)*)
    }
}

/// The Rust field name of a parameter (`r#` for keywords).
pub fn parameter_ident(name: &str) -> Ident {
    if syn::parse_str::<Ident>(name).is_ok() {
        Ident::new(name, Span::call_site())
    } else {
        Ident::new_raw(name, Span::call_site())
    }
}

/// Whether `name` can be a field of the generated `Params`.
pub fn is_valid_parameter_name(name: &str) -> bool {
    let valid_ident = |n: &str| syn::parse_str::<Ident>(n).is_ok();
    valid_ident(name)
        || (!matches!(name, "self" | "Self" | "super" | "crate" | "_")
            && valid_ident(&format!("r#{name}")))
}

/// The return type of `kernel`'s function, in scalar `t`: a scalar, `[t; NV]` or
/// `[[t; NV]; NV]`.
pub fn return_type(kernel: Kernel, t: &TokenStream) -> TokenStream {
    match kernel.shape() {
        Shape::Scalar => quote!(#t),
        Shape::Vector => quote!([#t; NV]),
        Shape::Matrix => quote!([[#t; NV]; NV]),
    }
}

/// Emits `kernel` as a function computing `program`'s outputs.
pub fn emit_kernel(
    kernel: Kernel,
    program: &Program,
    nv: usize,
    ctx: EmitContext<'_>,
) -> TokenStream {
    let uses = program.use_counts();
    let mut emitter = Emitter {
        program,
        ctx,
        names: vec![None; program.instrs.len()],
        trig: BTreeMap::new(),
    };
    let mut body = Vec::new();
    let mut next = 0usize;
    for (t, &instr) in program.instrs.iter().enumerate() {
        if let Instr::Sin(Operand::Input(Symbol::Position(k)))
        | Instr::Cos(Operand::Input(Symbol::Position(k))) = instr
        {
            let entry = emitter.trig.entry(k).or_default();
            match instr {
                Instr::Sin(_) => entry.0 = true,
                _ => entry.1 = true,
            }
            continue;
        }
        if uses[t] >= 2 {
            let (value, _) = emitter.instr(instr);
            let name = format_ident!("t{}", next);
            next += 1;
            body.push(quote!(let #name = #value;));
            emitter.names[t] = Some(name);
        }
    }
    let trig = emitter.trig_bindings();
    let outputs: Vec<TokenStream> = program
        .outputs
        .iter()
        .map(|&o| emitter.operand(o).0)
        .collect();
    let result = match kernel.shape() {
        Shape::Scalar => quote!(#(#outputs)*),
        Shape::Vector => quote!([#(#outputs),*]),
        Shape::Matrix => {
            let rows = outputs.chunks(nv.max(1)).map(|row| quote!([#(#row),*]));
            quote!([#(#rows),*])
        }
    };

    let t = emitter.scalar_type();
    let name = Ident::new(kernel.name(), Span::call_site());
    let doc = kernel.summary();
    let real = emitter.real();
    let generics = match ctx.scalar {
        ScalarType::Generic => quote!(<T: #real>),
        _ => quote!(),
    };
    let params = match ctx.parameters {
        ParameterMode::Runtime => quote!(p: &Params,),
        ParameterMode::Constant => quote!(),
    };
    let args = kernel.inputs().iter().map(|&input| {
        let arg = Ident::new(input.name(), Span::call_site());
        let len = match input {
            Input::Q => quote!(NQ),
            _ => quote!(NV),
        };
        quote!(#arg: &[#t; #len])
    });
    let ret = return_type(kernel, &t);
    quote! {
        #[doc = #doc]
        #[inline]
        #[allow(unused_variables, unused_parens, clippy::all, clippy::pedantic)]
        pub fn #name #generics (#params #(#args),*) -> #ret {
            #trig
            #(#body)*
            #result
        }
    }
}

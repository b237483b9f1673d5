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

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};
use quote::{format_ident, quote};
use rne_symbolic::{Symbol, SymbolTable};

use crate::kernel::{Dims, Input, Kernel};
use crate::program::{Instr, Operand, Program};
use crate::scene::{ParameterMode, ScalarType};
use crate::shape::Layout;
use crate::split::{self, SplitPlan, Statement};

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
    /// Whether the kernel reads standard parameters (`base_parameters`), which its program
    /// holds as `Symbol::Parameter(i)` = `standard[i]`.
    reads_standard: bool,
    /// `<path to the runtime>::Real`.
    real: TokenStream,
}

/// `(tokens)`.
fn parenthesised(tokens: TokenStream) -> TokenTree {
    TokenTree::Group(Group::new(Delimiter::Parenthesis, tokens))
}

/// One punctuation character, as `quote!` writes an operator.
fn push_punct(out: &mut TokenStream, c: char) {
    out.extend([TokenTree::Punct(Punct::new(c, Spacing::Alone))]);
}

/// `::`, as `quote!` writes it.
fn push_path_separator(out: &mut TokenStream) {
    out.extend([
        TokenTree::Punct(Punct::new(':', Spacing::Joint)),
        TokenTree::Punct(Punct::new(':', Spacing::Alone)),
    ]);
}

impl Emitter<'_> {
    /// `<path to the runtime>::Real`.
    fn real(&self) -> TokenStream {
        self.real.clone()
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
            Symbol::Parameter(i) if self.reads_standard => {
                let i = index(i);
                quote!(standard[#i])
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

    /// How tightly operand `o` binds as written.
    fn precedence(&self, o: Operand) -> Precedence {
        match o {
            Operand::Const(c) if c.is_sign_negative() && !c.is_nan() => Precedence::Unary,
            Operand::Const(_) | Operand::Input(_) => Precedence::Atom,
            Operand::Temp(t) if self.names[t as usize].is_some() => Precedence::Atom,
            Operand::Temp(t) => {
                let instr = self.program.instrs[t as usize];
                if self.joint_trig(instr).is_some() {
                    return Precedence::Atom;
                }
                match instr {
                    Instr::Add(..) | Instr::Sub(..) => Precedence::Sum,
                    Instr::Mul(..) | Instr::Div(..) => Precedence::Product,
                    Instr::Neg(_) => Precedence::Unary,
                    _ => Precedence::Atom,
                }
            }
        }
    }

    /// The tokens of operand `o` (a name, a constant, an input, or an unnamed instruction
    /// written out), appended to `out`: every token is pushed once, so writing a kernel
    /// takes time linear in its text.
    fn write(&self, o: Operand, out: &mut TokenStream) {
        match o {
            Operand::Const(c) => out.extend(self.constant(c).0),
            Operand::Input(s) => out.extend(self.input(s)),
            Operand::Temp(t) => match &self.names[t as usize] {
                Some(name) => out.extend([TokenTree::Ident(name.clone())]),
                None => self.write_instr(self.program.instrs[t as usize], out),
            },
        }
    }

    /// The tokens of `o` as a `TokenStream` of its own.
    fn operand(&self, o: Operand) -> TokenStream {
        let mut tokens = TokenStream::new();
        self.write(o, &mut tokens);
        tokens
    }

    /// `o`, parenthesised when it binds less tightly than `min`.
    fn write_at_least(&self, o: Operand, min: Precedence, out: &mut TokenStream) {
        if self.precedence(o) >= min {
            self.write(o, out);
        } else {
            out.extend([parenthesised(self.operand(o))]);
        }
    }

    /// `Real::method(args)`, each argument negated where its flag says so. `sin`, `cos`,
    /// `sqrt` and `sign` go through the runtime's `Real` for every scalar type, so that `f64`
    /// kernels get the fast, accurate runtime `sin_cos` and no kernel needs `std`; so does
    /// `mul_add` (`fma: true`), whose variants fold a negated product or addend.
    fn write_call(&self, method: &str, args: &[(Operand, bool)], out: &mut TokenStream) {
        out.extend(self.real.clone());
        push_path_separator(out);
        out.extend([TokenTree::Ident(Ident::new(method, Span::call_site()))]);
        let mut inner = TokenStream::new();
        for (k, &(a, negated)) in args.iter().enumerate() {
            if k > 0 {
                push_punct(&mut inner, ',');
            }
            if negated {
                push_punct(&mut inner, '-');
                self.write_at_least(a, Precedence::Unary, &mut inner);
            } else {
                self.write(a, &mut inner);
            }
        }
        out.extend([parenthesised(inner)]);
    }

    fn write_instr(&self, instr: Instr, out: &mut TokenStream) {
        if let Some(name) = self.joint_trig(instr) {
            out.extend([TokenTree::Ident(name)]);
            return;
        }
        use Precedence::*;
        let mut binary = |a: Operand, op: char, b: Operand, left: Precedence, right: Precedence| {
            self.write_at_least(a, left, out);
            push_punct(out, op);
            self.write_at_least(b, right, out);
        };
        match instr {
            Instr::Add(a, b) => binary(a, '+', b, Sum, Product),
            Instr::Sub(a, b) => binary(a, '-', b, Sum, Product),
            Instr::Mul(a, b) => binary(a, '*', b, Product, Unary),
            Instr::Div(a, b) => binary(a, '/', b, Product, Unary),
            Instr::Neg(a) => {
                push_punct(out, '-');
                self.write_at_least(a, Unary, out);
            }
            Instr::Sin(a) => self.write_call("sin", &[(a, false)], out),
            Instr::Cos(a) => self.write_call("cos", &[(a, false)], out),
            Instr::Sqrt(a) => self.write_call("sqrt", &[(a, false)], out),
            Instr::Sign(a) => self.write_call("sign", &[(a, false)], out),
            Instr::MulAdd(a, b, c) => {
                self.write_call("mul_add", &[(a, false), (b, false), (c, false)], out)
            }
            Instr::MulSub(a, b, c) => {
                self.write_call("mul_add", &[(a, false), (b, false), (c, true)], out)
            }
            Instr::NegMulAdd(a, b, c) => {
                self.write_call("mul_add", &[(a, true), (b, false), (c, false)], out)
            }
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

/// The return type of `kernel`'s function in scalar `t` (DESIGN.md §4), naming the module's
/// sizes `NV`, `NF`, `NP`, `NB`.
pub fn return_type(kernel: Kernel, t: &TokenStream) -> TokenStream {
    Layout::of(kernel, Dims::default()).type_tokens(t)
}

/// The argument `input` of a kernel, in scalar `t`: `q: &[t; NQ]`, `standard: &[t; NP]`, or a
/// velocity-sized array.
pub fn argument(input: Input, t: &TokenStream) -> TokenStream {
    let arg = Ident::new(input.name(), Span::call_site());
    let len = match input {
        Input::Q => quote!(NQ),
        Input::Standard => quote!(NP),
        _ => quote!(NV),
    };
    quote!(#arg: &[#t; #len])
}

/// Emits `kernel` as a function computing `program`'s outputs, in a module of sizes `dims`:
/// one straight-line function, or for a large program a function calling its parts in turn
/// (module `split`: parts of about 1000 instructions above 15000).
pub fn emit_kernel(
    kernel: Kernel,
    program: &Program,
    dims: Dims,
    ctx: EmitContext<'_>,
) -> TokenStream {
    let uses = program.use_counts();
    let mut emitter = Emitter {
        program,
        ctx,
        names: vec![None; program.instrs.len()],
        trig: BTreeMap::new(),
        reads_standard: kernel.inputs().contains(&Input::Standard),
        real: {
            let runtime = ctx.runtime;
            quote!(#runtime::Real)
        },
    };
    let mut prologue = vec![false; program.instrs.len()];
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
            prologue[t] = true;
            continue;
        }
        if uses[t] >= 2 {
            emitter.names[t] = Some(format_ident!("t{}", next));
            next += 1;
        }
    }
    let trig = emitter.trig_bindings();
    let layout = Layout::of(kernel, dims);
    assert_eq!(
        layout.len(),
        program.outputs.len(),
        "`{kernel}` computes one output per scalar of its result"
    );
    let named: Vec<bool> = emitter.names.iter().map(Option::is_some).collect();
    let (body, result) = match split::plan(program, &named, &prologue) {
        None => {
            let mut body = TokenStream::new();
            for t in (0..program.instrs.len()).filter(|&t| named[t]) {
                emitter.write_binding(t, &mut body);
            }
            let mut outputs = program.outputs.iter().map(|&o| emitter.operand(o));
            (body, layout.value_tokens(&mut outputs))
        }
        Some(plan) => {
            let body = emitter.parts(kernel, &plan);
            let mut outputs = program.outputs.iter().enumerate().map(|(k, &o)| match o {
                Operand::Temp(_) => {
                    let k = Literal::usize_unsuffixed(k);
                    quote!(slots[#k])
                }
                _ => emitter.operand(o),
            });
            (body, layout.value_tokens(&mut outputs))
        }
    };

    let t = emitter.scalar_type();
    let name = Ident::new(kernel.name(), Span::call_site());
    let doc = kernel.summary();
    let generics = emitter.generics();
    let params = emitter.params();
    let args = kernel.inputs().iter().map(|&input| argument(input, &t));
    let ret = layout.type_tokens(&t);
    quote! {
        #[doc = #doc]
        #[inline]
        #[allow(unused_variables, unused_parens, clippy::all, clippy::pedantic)]
        pub fn #name #generics (#params #(#args),*) -> #ret {
            #trig
            #body
            #result
        }
    }
}

impl Emitter<'_> {
    /// `let t = …;` of named instruction `t`, appended to `out`.
    fn write_binding(&self, t: usize, out: &mut TokenStream) {
        let name = self.names[t].clone().expect("a named instruction");
        out.extend([
            TokenTree::Ident(Ident::new("let", Span::call_site())),
            TokenTree::Ident(name),
        ]);
        push_punct(out, '=');
        self.write_instr(self.program.instrs[t], out);
        push_punct(out, ';');
    }

    /// The name a named or prologue value is bound to.
    fn value_name(&self, t: usize) -> Ident {
        match &self.names[t] {
            Some(name) => name.clone(),
            None => self
                .joint_trig(self.program.instrs[t])
                .expect("a named or prologue value"),
        }
    }

    /// `<T: Real>` for a generic kernel.
    fn generics(&self) -> TokenStream {
        let real = self.real();
        match self.ctx.scalar {
            ScalarType::Generic => quote!(<T: #real>),
            _ => quote!(),
        }
    }

    /// `p: &Params,` with runtime or base parameters.
    fn params(&self) -> TokenStream {
        match self.ctx.parameters {
            ParameterMode::Runtime | ParameterMode::Base => quote!(p: &Params,),
            ParameterMode::Constant => quote!(),
        }
    }

    /// The body of a split kernel: the slot array, the prologue's values stored in it, and a
    /// call of each part, every part a function in a module of its own.
    fn parts(&self, kernel: Kernel, plan: &SplitPlan) -> TokenStream {
        let t = self.scalar_type();
        let generics = self.generics();
        let params = self.params();
        let len = Literal::usize_unsuffixed(plan.len);
        let slot = |value: usize| Literal::usize_unsuffixed(plan.slots[&value]);
        let args: Vec<TokenStream> = kernel
            .inputs()
            .iter()
            .map(|&input| argument(input, &t))
            .collect();
        let inputs: Vec<Ident> = kernel
            .inputs()
            .iter()
            .map(|input| Ident::new(input.name(), Span::call_site()))
            .collect();
        let param = match self.ctx.parameters {
            ParameterMode::Runtime | ParameterMode::Base => quote!(p,),
            ParameterMode::Constant => quote!(),
        };
        let zero = match self.ctx.scalar {
            ScalarType::Generic => self.constant(0.0).0,
            _ => quote!(0.0),
        };
        let stored = plan
            .slots
            .keys()
            .filter(|&&value| self.names[value].is_none())
            .map(|&value| {
                let (name, slot) = (self.value_name(value), slot(value));
                quote!(slots[#slot] = #name;)
            });
        let parts = plan.parts.iter().enumerate().map(|(p, statements)| {
            let module = format_ident!("part{}", p);
            let imports = plan.imports[p].iter().map(|&value| {
                let (name, slot) = (self.value_name(value), slot(value));
                quote!(let #name = slots[#slot];)
            });
            let mut body = TokenStream::new();
            for &statement in statements {
                match statement {
                    Statement::Let(i) => {
                        self.write_binding(i, &mut body);
                        if let Some(&s) = plan.slots.get(&i) {
                            let (name, s) = (&self.names[i], Literal::usize_unsuffixed(s));
                            body.extend(quote!(slots[#s] = #name;));
                        }
                    }
                    Statement::Output { output, instr } => {
                        let output = Literal::usize_unsuffixed(output);
                        body.extend(quote!(slots[#output] =));
                        self.write(Operand::Temp(instr as u32), &mut body);
                        push_punct(&mut body, ';');
                    }
                }
            }
            quote! {
                mod #module {
                    use super::*;
                    #[inline(never)]
                    #[allow(unused_variables, unused_parens, clippy::all, clippy::pedantic)]
                    pub(super) fn run #generics (#params #(#args,)* slots: &mut [#t; #len]) {
                        #(#imports)*
                        #body
                    }
                }
                #module::run(#param #(#inputs,)* &mut slots);
            }
        });
        quote! {
            let mut slots = [#zero; #len];
            #(#stored)*
            #(#parts)*
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Operand::{Const, Input as In, Temp};

    const QD0: Operand = In(Symbol::Velocity(0));
    const QD1: Operand = In(Symbol::Velocity(1));
    const QD2: Operand = In(Symbol::Velocity(2));

    /// The emitted function of a scalar kernel computing `instrs` (the last is the output),
    /// without whitespace.
    fn emit(instrs: Vec<Instr>, scalar: ScalarType) -> String {
        let output = Temp(instrs.len() as u32 - 1);
        emit_outputs(instrs, vec![output], scalar)
    }

    fn emit_outputs(instrs: Vec<Instr>, outputs: Vec<Operand>, scalar: ScalarType) -> String {
        let symbols = SymbolTable::with_joints(["q1", "q2", "q3"]);
        let runtime = quote!(::rt);
        let ctx = EmitContext {
            symbols: &symbols,
            scalar,
            parameters: ParameterMode::Constant,
            runtime: &runtime,
        };
        let program = Program { instrs, outputs };
        let dims = Dims {
            nv: 3,
            ..Dims::default()
        };
        emit_kernel(Kernel::KineticEnergy, &program, dims, ctx)
            .to_string()
            .replace(' ', "")
    }

    /// The function's body after its signature.
    fn body(code: &str) -> &str {
        &code[code.find("->f64{").map_or(0, |i| i + "->f64{".len())..]
    }

    #[test]
    fn right_nested_sums_and_products_keep_their_parentheses() {
        let sum = emit(
            vec![Instr::Add(QD1, QD2), Instr::Add(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&sum).starts_with("qd[0]+(qd[1]+qd[2])"), "{sum}");
        let left = emit(
            vec![Instr::Add(QD0, QD1), Instr::Add(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&left).starts_with("qd[0]+qd[1]+qd[2]"), "{left}");
        let product = emit(
            vec![Instr::Mul(QD1, QD2), Instr::Mul(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&product).starts_with("qd[0]*(qd[1]*qd[2])"),
            "{product}"
        );
        let difference = emit(
            vec![Instr::Sub(QD1, QD2), Instr::Sub(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&difference).starts_with("qd[0]-(qd[1]-qd[2])"),
            "{difference}"
        );
        let quotient = emit(
            vec![Instr::Mul(QD1, QD2), Instr::Div(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(
            body(&quotient).starts_with("qd[0]/(qd[1]*qd[2])"),
            "{quotient}"
        );
    }

    #[test]
    fn a_sum_inside_a_product_is_parenthesised_and_a_product_inside_a_sum_is_not() {
        let code = emit(
            vec![Instr::Add(QD0, QD1), Instr::Mul(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("(qd[0]+qd[1])*qd[2]"), "{code}");
        let code = emit(
            vec![Instr::Mul(QD0, QD1), Instr::Add(Temp(0), QD2)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("qd[0]*qd[1]+qd[2]"), "{code}");
    }

    #[test]
    fn negation_binds_tighter_than_products_and_wraps_sums() {
        let code = emit(
            vec![Instr::Add(QD0, QD1), Instr::Neg(Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("-(qd[0]+qd[1])"), "{code}");
        let code = emit(
            vec![Instr::Neg(QD0), Instr::Mul(Temp(0), QD1)],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("-qd[0]*qd[1]"), "{code}");
        let code = emit(
            vec![Instr::Neg(QD1), Instr::Mul(QD0, Temp(0))],
            ScalarType::F64,
        );
        assert!(body(&code).starts_with("qd[0]*-qd[1]"), "{code}");
    }

    #[test]
    fn negative_and_non_finite_constants() {
        let code = emit(vec![Instr::Mul(QD0, Const(-2.5))], ScalarType::F64);
        assert!(body(&code).starts_with("qd[0]*-2.5"), "{code}");
        let code = emit(vec![Instr::Sub(QD0, Const(-0.0))], ScalarType::F64);
        assert!(body(&code).starts_with("qd[0]--0.0"), "{code}");
        let code = emit_outputs(vec![], vec![Const(f64::NAN)], ScalarType::F64);
        assert!(code.contains("f64::NAN"), "{code}");
        let code = emit_outputs(vec![], vec![Const(f64::NEG_INFINITY)], ScalarType::F32);
        assert!(code.contains("-f32::INFINITY"), "{code}");
        let code = emit_outputs(vec![], vec![Const(0.5)], ScalarType::Generic);
        assert!(code.contains("<Tas::rt::Real>::from_f64(0.5)"), "{code}");
    }

    /// Sines of joints 1 to `joints`, summed.
    fn sines(joints: u16) -> Vec<Instr> {
        let mut instrs: Vec<Instr> = (0..joints)
            .map(|k| Instr::Sin(In(Symbol::Position(k))))
            .collect();
        instrs.push(Instr::Add(Temp(0), Temp(1)));
        for k in 2..u32::from(joints) {
            instrs.push(Instr::Add(Temp(instrs.len() as u32 - 1), Temp(k)));
        }
        instrs
    }

    #[test]
    fn an_odd_count_of_angles_is_padded_for_f64_and_f32_but_not_generic() {
        for scalar in [ScalarType::F64, ScalarType::F32] {
            let code = emit(sines(3), scalar);
            assert!(
                code.contains("::rt::Real::sin_cos_array(&[q[0],q[1],q[2],q[2]])"),
                "{code}"
            );
        }
        let code = emit(sines(3), ScalarType::Generic);
        assert!(
            code.contains("::rt::Real::sin_cos_array(&[q[0],q[1],q[2]])"),
            "{code}"
        );
        let even = emit(sines(2), ScalarType::F64);
        assert!(
            even.contains("::rt::Real::sin_cos_array(&[q[0],q[1]])"),
            "{even}"
        );
    }

    #[test]
    fn emitted_code_names_only_core_types_and_the_runtime_path() {
        let code = emit(sines(3), ScalarType::Generic);
        assert!(
            !code.contains("rne_codegen") && !code.contains("std::"),
            "{code}"
        );
        assert!(code.contains("<T:::rt::Real>"), "{code}");
    }
}

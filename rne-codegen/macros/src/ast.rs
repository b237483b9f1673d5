//! The macro's input syntax (docs/design.md §3):
//!
//! ```text
//! #[attrs] pub mod NAME { robot: "file", outputs: [..], gravity: [x, y, z],
//!                         lock: { q1: 0.0, "joint 8": 0.0, .. }, at_rest: true|false,
//!                         parameters: constant|runtime|base,
//!                         scalar: f64|f32|generic, base: fixed|floating,
//!                         mimic: constrained|free, validation: warn|strict,
//!                         crate: ::path::to::rne_codegen }
//! ```
//! Parsing only checks the shape of each setting; meaning is checked in `check.rs`.

use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{braced, bracketed, Attribute, Ident, LitStr, Token, Visibility};

/// The whole macro input.
pub struct DynamicsModule {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub settings: Vec<Setting>,
}

impl DynamicsModule {
    /// The span of the `robot:` path, or of the module's name when there is none: where an
    /// error about the robot as a whole points.
    pub fn robot_span(&self) -> proc_macro2::Span {
        self.settings
            .iter()
            .find(|s| s.key == "robot")
            .map_or(self.name.span(), |s| match &s.value {
                Value::Str(path) => path.span(),
                _ => s.key.span(),
            })
    }
}

/// One `key: value` entry.
pub struct Setting {
    pub key: Ident,
    pub value: Value,
}

/// The value of a setting, by its syntactic shape.
pub enum Value {
    /// `"path"`.
    Str(LitStr),
    /// `name`.
    Ident(Ident),
    /// `[a, b, ..]` of identifiers or numbers.
    List(syn::token::Bracket, Vec<Element>),
    /// `{ name: number, "name": number, .. }`.
    Map(syn::token::Brace, Vec<(Key, Number)>),
    /// `::a::b` (the value of `crate`).
    Path(syn::Path),
}

/// A key of a map: an identifier or a string (URDF joint names can be anything).
pub struct Key {
    pub name: String,
    pub span: proc_macro2::Span,
}

impl Parse for Key {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        if input.peek(LitStr) {
            let s: LitStr = input.parse()?;
            Ok(Key {
                name: s.value(),
                span: s.span(),
            })
        } else {
            let ident: Ident = input.parse()?;
            Ok(Key {
                name: ident.to_string(),
                span: ident.span(),
            })
        }
    }
}

/// An element of a list.
pub enum Element {
    Ident(Ident),
    Number(Number),
    /// A string, for names that are not identifiers (URDF link names can be anything).
    Str(LitStr),
}

/// A possibly negated numeric literal, with its span.
pub struct Number {
    pub value: f64,
    pub span: proc_macro2::Span,
}

impl Parse for DynamicsModule {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis: Visibility = input.parse()?;
        input.parse::<Token![mod]>()?;
        let name: Ident = input.parse()?;
        let content;
        braced!(content in input);
        let settings = Punctuated::<Setting, Token![,]>::parse_terminated(&content)?;
        Ok(DynamicsModule {
            attrs,
            vis,
            name,
            settings: settings.into_iter().collect(),
        })
    }
}

impl Parse for Setting {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        // `crate` is a keyword, hence `parse_any`.
        let key = Ident::parse_any(input)?;
        input.parse::<Token![:]>()?;
        let value = if key == "crate" && !input.peek(LitStr) {
            Value::Path(input.parse()?)
        } else if input.peek(LitStr) {
            Value::Str(input.parse()?)
        } else if input.peek(syn::token::Bracket) {
            let content;
            let bracket = bracketed!(content in input);
            let elements = Punctuated::<Element, Token![,]>::parse_terminated(&content)?;
            Value::List(bracket, elements.into_iter().collect())
        } else if input.peek(syn::token::Brace) {
            let content;
            let brace = braced!(content in input);
            let entries = Punctuated::<MapEntry, Token![,]>::parse_terminated(&content)?;
            Value::Map(
                brace,
                entries.into_iter().map(|e| (e.key, e.value)).collect(),
            )
        } else if input.peek(Ident::peek_any) {
            // `true` and `false` (of `fma`) are keywords, hence `peek_any` and `parse_any`.
            Value::Ident(Ident::parse_any(input)?)
        } else {
            return Err(input.error("expected a string, a name, `[..]` or `{..}`"));
        };
        Ok(Setting { key, value })
    }
}

struct MapEntry {
    key: Key,
    value: Number,
}

impl Parse for MapEntry {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let key = input.parse()?;
        input.parse::<Token![:]>()?;
        Ok(MapEntry {
            key,
            value: input.parse()?,
        })
    }
}

impl Parse for Element {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        if input.peek(Ident) {
            Ok(Element::Ident(input.parse()?))
        } else if input.peek(LitStr) {
            Ok(Element::Str(input.parse()?))
        } else {
            Ok(Element::Number(input.parse()?))
        }
    }
}

impl Parse for Number {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let negative = input.peek(Token![-]);
        let span = input.span();
        if negative {
            input.parse::<Token![-]>()?;
        }
        let value = if input.peek(syn::LitFloat) {
            input.parse::<syn::LitFloat>()?.base10_parse::<f64>()?
        } else if input.peek(syn::LitInt) {
            input.parse::<syn::LitInt>()?.base10_parse::<f64>()?
        } else {
            return Err(input.error("expected a number"));
        };
        Ok(Number {
            value: if negative { -value } else { value },
            span,
        })
    }
}

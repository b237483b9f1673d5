//! Kernels compiled twice, for the build's target and with AVX, the second called where the
//! processor has it (`rne_runtime::cpu`, whose docs say why).
//!
//! Only large kernels are. `rne bench --quick` on an AMD EPYC, two runs each, the portable
//! build before and with this dispatch (every kernel of 1800 instructions or more):
//! - UR5's forward-dynamics derivatives (3250 instructions): 663 → 518–523 ns;
//! - the Panda arm's inverse-dynamics derivatives (5470): 1340–1376 → 1016–1019 ns, its
//!   forward-dynamics derivatives (8260): 1870–1875 → 1454–1475 ns;
//! - UR5's inverse-dynamics derivatives (1910): 252 → 265–268 ns, slower: the call and the
//!   copy of the result cost more than AVX saves on a kernel that spills little.
//!
//! Building everything for AVX instead (`-C target-feature=+avx,+avx2`) made the Jacobians of
//! every frame (460–900 instructions) about 10 % slower and the Panda arm's inverse dynamics
//! (740) 18 % slower.

/// The fewest instructions a kernel has for it to be compiled for AVX too.
pub const DISPATCH_FROM: usize = 2500;

/// The body of a kernel function whose own body would be `body`, given its `generics`
/// (`<T: …>` or nothing), `parameters` (`name: type, ` each), return type `ret` and the
/// parameters' `names`: on x86-64 builds without AVX, `body` moves into an always-inlined
/// inner function `evaluate`, called through `with_avx`, compiled with AVX, where
/// `runtime::cpu::has_avx()`, else directly.
pub fn dispatching_body(
    generics: &str,
    parameters: &str,
    ret: &str,
    names: &[&str],
    body: &str,
    runtime: &str,
) -> String {
    let call = format!(
        "{}({})",
        if generics.is_empty() { "" } else { "::<T>" },
        names.join(", ")
    );
    format!(
        "#[inline(always)]\nfn evaluate{generics}({parameters}) -> {ret} {{\n{body}}}\n\
         #[cfg(all(target_arch = \"x86_64\", not(target_feature = \"avx\")))]\n{{\n\
         /// # Safety\n/// Only where the processor runs AVX.\n\
         #[target_feature(enable = \"avx\")]\n\
         unsafe fn with_avx{generics}({parameters}) -> {ret} {{\nevaluate{call}\n}}\n\
         if {runtime}::cpu::has_avx() {{\n\
         // SAFETY: the processor runs AVX.\n\
         return unsafe {{ with_avx{call} }};\n}}\n}}\n\
         evaluate{call}\n"
    )
}

#[cfg(test)]
mod tests {
    use super::dispatching_body;

    #[test]
    fn a_dispatching_body_calls_the_avx_copy_only_where_the_processor_has_it() {
        let body = dispatching_body(
            "<T: rt::Real>",
            "p: &Params, q: &[T; NQ], ",
            "[T; NV]",
            &["p", "q"],
            "let t0 = q[0];\n[t0]\n",
            "rt",
        );
        let block: syn::Block = syn::parse_str(&format!("{{{body}}}")).expect("Rust");
        let text = quote::quote!(#block).to_string();
        for part in [
            "# [inline (always)] fn evaluate < T : rt :: Real > (p : & Params , q : & [T ; NQ] ,) -> [T ; NV] { let t0 = q [0] ; [t0] }",
            "# [cfg (all (target_arch = \"x86_64\" , not (target_feature = \"avx\")))]",
            "# [target_feature (enable = \"avx\")] unsafe fn with_avx < T : rt :: Real >",
            "if rt :: cpu :: has_avx () { return unsafe { with_avx :: < T > (p , q) } ; }",
        ] {
            assert!(text.contains(part), "{part} in {text}");
        }
        assert!(text.ends_with("evaluate :: < T > (p , q) }"), "{text}");
    }
}

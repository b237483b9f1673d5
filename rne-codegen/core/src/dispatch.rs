//! Kernels compiled twice, for the build's target and with AVX and AVX2, the second called
//! where the processor has them (`rne_runtime::cpu`, whose docs say why).
//!
//! Only large kernels are: a portable x86-64 build targets SSE2, whose two-operand
//! instructions make a large kernel copy and spill values that AVX's three-operand forms keep
//! in registers, while for a small kernel the call and the copy of the result cost more than
//! AVX saves; building everything for AVX instead made the small kernels slower. The
//! measurements behind [`DISPATCH_FROM`] are in docs/performance.md ("The large kernels in a
//! portable build use AVX where the processor has it").

/// The fewest instructions a kernel has for it to be compiled for AVX and AVX2 too.
pub const DISPATCH_FROM: usize = 1400;

/// The body of a kernel function whose own body would be `body`, given its `generics`
/// (`<T: …>` or nothing), `parameters` (`name: type, ` each), return type `ret` and the
/// parameters' `names`: on x86-64 builds without AVX, `body` moves into an always-inlined
/// inner function `evaluate`, called through `with_avx2`, compiled with AVX and AVX2,
/// where `runtime::cpu::has_avx2()`, else directly.
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
         #[cfg(all(target_arch = \"x86_64\", not(target_feature = \"avx2\")))]\n{{\n\
         /// # Safety\n/// Only where the processor runs AVX and AVX2.\n\
         #[target_feature(enable = \"avx,avx2\")]\n\
         unsafe fn with_avx2{generics}({parameters}) -> {ret} {{\nevaluate{call}\n}}\n\
         if {runtime}::cpu::has_avx2() {{\n\
         // SAFETY: the processor runs AVX and AVX2.\n\
         return unsafe {{ with_avx2{call} }};\n}}\n}}\n\
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
            "# [cfg (all (target_arch = \"x86_64\" , not (target_feature = \"avx2\")))]",
            "# [target_feature (enable = \"avx,avx2\")] unsafe fn with_avx2 < T : rt :: Real >",
            "if rt :: cpu :: has_avx2 () { return unsafe { with_avx2 :: < T > (p , q) } ; }",
        ] {
            assert!(text.contains(part), "{part} in {text}");
        }
        assert!(text.ends_with("evaluate :: < T > (p , q) }"), "{text}");
    }
}

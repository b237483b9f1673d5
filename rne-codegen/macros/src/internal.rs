//! Internal failures: a panic while the macro reads, generates or expands (a bug of rne,
//! whatever the input) becomes a compile error that says what failed and asks for a report,
//! at the span given — the robot file's when it is known — never "proc macro panicked".

use std::panic::{catch_unwind, AssertUnwindSafe};

use proc_macro2::Span;

/// `expansion`'s result, or a compile error at `span` when it panics.
pub fn guarded<T>(span: Span, expansion: impl FnOnce() -> syn::Result<T>) -> syn::Result<T> {
    catch_unwind(AssertUnwindSafe(expansion)).unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".to_owned());
        Err(syn::Error::new(
            span,
            format!(
                "internal error in rne while generating this module: {message}; this is a \
                 bug: please report it with the robot file and the macro's settings"
            ),
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A panicking expansion is a compile error carrying the panic's message; one that
    /// returns gives its own result.
    #[test]
    fn a_panic_becomes_a_compile_error_with_its_message() {
        let error = guarded::<()>(Span::call_site(), || panic!("pivot 3 is zero")).unwrap_err();
        let text = error.to_string();
        assert!(text.contains("pivot 3 is zero"), "{text}");
        assert!(
            text.contains("internal error") && text.contains("report"),
            "{text}"
        );
        assert_eq!(guarded(Span::call_site(), || Ok(5)).unwrap(), 5);
    }
}

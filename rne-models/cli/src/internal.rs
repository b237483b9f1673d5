//! Internal failures: a panic anywhere in a command (a bug of rne, never the user's input)
//! becomes one error line and exit status 1, never a Rust backtrace.
//!
//! [`quiet_panics`] replaces the default panic hook, which prints the message and a backtrace
//! hint, by one that keeps the message and its location; [`guarded`] runs a command and turns
//! a panic into [`CliError::Internal`] with them. A panic on a thread the command spawned
//! reaches it when the thread is joined.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;

use crate::CliError;

/// The last panic's message and location, as the hook saw it.
static LAST_PANIC: Mutex<Option<(String, String)>> = Mutex::new(None);

/// Keeps panics quiet: their message and location are kept for [`guarded`], nothing is
/// printed. For the `rne` binary's `main`; a library's tests keep the default hook.
pub fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        let location = info
            .location()
            .map_or_else(String::new, |l| format!("{}:{}", l.file(), l.line()));
        let message = payload_message(info.payload());
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = Some((message, location));
        }
    }));
}

/// `command`'s result, or [`CliError::Internal`] when it panics.
pub fn guarded<T>(command: impl FnOnce() -> Result<T, CliError>) -> Result<T, CliError> {
    catch_unwind(AssertUnwindSafe(command)).unwrap_or_else(|payload| {
        let kept = LAST_PANIC.lock().ok().and_then(|mut last| last.take());
        let (message, location) =
            kept.unwrap_or_else(|| (payload_message(&*payload), String::new()));
        Err(CliError::Internal { message, location })
    })
}

/// A panic payload's text (`panic!` gives a `&str` or a `String`).
fn payload_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A panicking command is an internal error with the panic's message; a command that
    /// returns gives its own result.
    #[test]
    fn a_panic_becomes_an_internal_error_with_its_message() {
        let result: Result<(), CliError> = guarded(|| panic!("index 7 out of range"));
        let error = result.unwrap_err();
        assert!(
            matches!(&error, CliError::Internal { message, .. } if message.contains("index 7")),
            "{error:?}"
        );
        let text = error.to_string();
        assert!(
            text.contains("internal error") && text.contains("report"),
            "{text}"
        );
        assert_eq!(guarded(|| Ok::<_, CliError>(3)).unwrap(), 3);
    }

    /// A panic on a thread the command spawned and joined is caught the same way.
    #[test]
    fn a_panic_on_a_joined_thread_becomes_an_internal_error() {
        let result: Result<(), CliError> = guarded(|| {
            std::thread::scope(|s| {
                s.spawn(|| panic!("on the other thread"));
            });
            Ok(())
        });
        assert!(matches!(result, Err(CliError::Internal { .. })));
    }
}

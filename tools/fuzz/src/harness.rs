//! Running one input: on a thread of its own, under `catch_unwind`, within a time budget, with
//! panics recorded instead of printed.
//!
//! A panic hook installed once ([`silence_panics`]) records the message and location of every
//! panic while a [`Silenced`] guard is alive, instead of printing it: the message of a panic on
//! the input's own thread is kept for that thread; one on a thread the input started (the
//! generator builds kernels on two) is kept as the latest foreign panic. With no guard alive
//! the hook that was installed before prints as usual.

use std::any::Any;
use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe, PanicHookInfo};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

/// The stack of an input's thread: the size of a Linux main thread's, where the `rne` command
/// reads robot files (a test thread's 2 MiB would make stack overflows the harness's own).
const STACK: usize = 8 << 20;

/// How an input ended.
#[derive(Debug)]
pub enum Outcome<T> {
    /// It returned, after this long.
    Done(T, Duration),
    /// It panicked with this message (`file:line:col: payload`).
    Panicked(String),
    /// It was still running when the budget ran out; its thread is left to finish.
    Hung,
}

static SILENCED: AtomicUsize = AtomicUsize::new(0);
static FOREIGN: Mutex<Option<String>> = Mutex::new(None);
static INSTALL: Once = Once::new();

thread_local! {
    /// Set on an input's thread: its panic message, once it panicked.
    static OWN: RefCell<Option<Option<String>>> = const { RefCell::new(None) };
}

/// While alive, panics are recorded instead of printed.
pub struct Silenced(());

impl Drop for Silenced {
    fn drop(&mut self) {
        SILENCED.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Installs the recording hook (once) and silences panics until the guard is dropped.
pub fn silence_panics() -> Silenced {
    INSTALL.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if SILENCED.load(Ordering::SeqCst) == 0 {
                previous(info);
            } else {
                record(info);
            }
        }));
    });
    SILENCED.fetch_add(1, Ordering::SeqCst);
    Silenced(())
}

fn record(info: &PanicHookInfo<'_>) {
    let message = describe(info);
    let own = OWN.with(|own| {
        let mut own = own.borrow_mut();
        match own.as_mut() {
            Some(slot) => {
                slot.get_or_insert(message.clone());
                true
            }
            None => false,
        }
    });
    if !own {
        if let Ok(mut foreign) = FOREIGN.lock() {
            *foreign = Some(message);
        }
    }
}

fn describe(info: &PanicHookInfo<'_>) -> String {
    let at = info
        .location()
        .map(|l| format!("{}:{}:{}: ", l.file(), l.line(), l.column()))
        .unwrap_or_default();
    format!("{at}{}", payload(info.payload()))
}

fn payload(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(a panic without a message)".to_owned()
    }
}

/// Runs `work` on a thread of its own, returning within `budget` whatever happens. Call it
/// while a [`Silenced`] guard is alive, or panics are printed as well as recorded.
pub fn run<T: Send + 'static>(
    budget: Duration,
    work: impl FnOnce() -> T + Send + 'static,
) -> Outcome<T> {
    if let Ok(mut foreign) = FOREIGN.lock() {
        *foreign = None;
    }
    let (send, receive) = mpsc::channel();
    let spawned = std::thread::Builder::new()
        .name("rne-fuzz-input".to_owned())
        .stack_size(STACK)
        .spawn(move || {
            OWN.with(|own| *own.borrow_mut() = Some(None));
            let start = Instant::now();
            let result = panic::catch_unwind(AssertUnwindSafe(work));
            let elapsed = start.elapsed();
            let message = OWN.with(|own| own.borrow_mut().take().flatten());
            let _ = send.send(result.map(|value| (value, elapsed)).map_err(|_| message));
        });
    if let Err(e) = spawned {
        return Outcome::Panicked(format!("the harness could not start a thread: {e}"));
    }
    match receive.recv_timeout(budget) {
        Ok(Ok((value, elapsed))) => Outcome::Done(value, elapsed),
        Ok(Err(own)) => Outcome::Panicked(panic_message(own)),
        Err(_) => Outcome::Hung,
    }
}

/// The input thread's panic message, with the first panic of a thread it started when that
/// is what it re-raised (a scoped thread's panic reaches the scope as a generic one).
fn panic_message(own: Option<String>) -> String {
    let foreign = FOREIGN.lock().ok().and_then(|mut f| f.take());
    match (own, foreign) {
        (Some(own), Some(foreign)) => format!("{foreign} (re-raised as: {own})"),
        (Some(own), None) => own,
        (None, Some(foreign)) => foreign,
        (None, None) => "(no panic message recorded)".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_panics_values_and_hangs() {
        let _quiet = silence_panics();
        let budget = Duration::from_secs(5);
        match run(budget, || 7) {
            Outcome::Done(7, _) => {}
            other => panic!("{other:?}"),
        }
        match run(budget, || -> u8 { panic!("boom {}", 1) }) {
            Outcome::Panicked(message) => {
                assert!(message.contains("boom 1"), "{message}");
                assert!(message.contains("harness.rs"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        match run(budget, || {
            std::thread::scope(|s| s.spawn(|| panic!("inner")).join().unwrap())
        }) {
            Outcome::Panicked(message) => assert!(message.contains("inner"), "{message}"),
            other => panic!("{other:?}"),
        }
        let short = Duration::from_millis(50);
        match run(short, || std::thread::sleep(Duration::from_millis(500))) {
            Outcome::Hung => {}
            other => panic!("{other:?}"),
        }
    }
}

//! Work shared between threads as they become free: the items are handed out one at a time
//! from one queue, so that a thread that runs slower (its core busy with another program, or a
//! smaller core) takes fewer of them. With equal shares fixed in advance, the others would
//! wait for it at the end: on a machine whose cores are shared, a batch on two threads took
//! the time of its slower half (docs/performance.md).
//!
//! The threads are started per call (the standard library's scoped threads), not kept in a
//! pool as rayon's are for the compiled modules' batches (`rne_runtime::batch`): a kept pool
//! does not survive `fork`, which Python's `multiprocessing` uses, and a batch in the child
//! would wait for it forever.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};

/// `work` on every item of `items`, on `threads` threads (this one and `threads − 1` scoped
/// ones), each taking the next item when it has finished its last, with its own state made by
/// `state` (a buffer, say). After an error no item is taken; the error returned is that of the
/// earliest item that failed, the one a single thread would have met first (every item before
/// it was taken before it, so has been done).
pub fn for_each_shared<I, S, E>(
    items: I,
    threads: usize,
    state: impl Fn() -> S + Sync,
    work: impl Fn(&mut S, I::Item) -> Result<(), E> + Sync,
) -> Result<(), E>
where
    I: Iterator + Send,
    E: Send,
{
    let queue = Mutex::new(items.enumerate());
    let failed = AtomicBool::new(false);
    let run = || -> Option<(usize, E)> {
        let mut mine = state();
        while !failed.load(Ordering::Relaxed) {
            // Taking the next item cannot panic, so the lock is never poisoned.
            let next = queue.lock().unwrap_or_else(PoisonError::into_inner).next();
            let (k, item) = next?;
            if let Err(error) = work(&mut mine, item) {
                failed.store(true, Ordering::Relaxed);
                return Some((k, error));
            }
        }
        None
    };
    let errors: Vec<(usize, E)> = std::thread::scope(|scope| {
        let run = &run;
        let helpers: Vec<_> = (1..threads.max(1)).map(|_| scope.spawn(run)).collect();
        let own = run();
        helpers
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .chain([own])
            .flatten()
            .collect()
    });
    match errors.into_iter().min_by_key(|&(k, _)| k) {
        Some((_, error)) => Err(error),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::for_each_shared;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn every_item_is_done_once_on_any_number_of_threads() {
        for threads in [1, 2, 3, 8] {
            let done: Vec<AtomicUsize> = (0..100).map(|_| AtomicUsize::new(0)).collect();
            let result: Result<(), ()> = for_each_shared(
                0..100,
                threads,
                || (),
                |_, k| {
                    done[k].fetch_add(1, Ordering::Relaxed);
                    Ok(())
                },
            );
            assert_eq!(result, Ok(()));
            assert!(
                done.iter().all(|d| d.load(Ordering::Relaxed) == 1),
                "{threads}"
            );
        }
    }

    #[test]
    fn the_earliest_failing_items_error_is_returned() {
        for threads in [1, 2, 4] {
            let result = for_each_shared(
                0..1000,
                threads,
                || (),
                |_, k| if k % 97 == 40 { Err(k) } else { Ok(()) },
            );
            assert_eq!(result, Err(40), "{threads} threads");
        }
    }

    #[test]
    fn each_thread_keeps_its_own_state() {
        let result: Result<(), ()> =
            for_each_shared(0..64, 4, Vec::new, |seen: &mut Vec<usize>, k| {
                // A thread takes items in increasing order.
                assert!(seen.last().is_none_or(|&last| last < k));
                seen.push(k);
                Ok(())
            });
        assert_eq!(result, Ok(()));
    }
}

//! A progress line on stderr for work that takes more than a second: nothing for quick work,
//! nothing when stderr is not a terminal (a pipe, a file, a test), and the elapsed time once a
//! second otherwise, cleared when the work ends.

use std::io::{IsTerminal, Write};
use std::sync::mpsc::{channel, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long work runs before its progress line appears.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// Work in progress; the line goes when this is dropped.
pub(crate) struct Progress {
    stop: Option<Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl Progress {
    /// Starts reporting `what` (e.g. "expanding M of panda") after a second of work.
    pub(crate) fn start(what: &str) -> Progress {
        if !std::io::stderr().is_terminal() {
            return Progress {
                stop: None,
                thread: None,
            };
        }
        let (stop, stopped) = channel::<()>();
        let what = what.to_owned();
        let thread = std::thread::spawn(move || {
            let start = Instant::now();
            let mut shown = false;
            let mut wait = QUIET_FOR;
            while let Err(RecvTimeoutError::Timeout) = stopped.recv_timeout(wait) {
                eprint!("\r{what}… {:.0} s", start.elapsed().as_secs_f64());
                let _ = std::io::stderr().flush();
                shown = true;
                wait = Duration::from_secs(1);
            }
            if shown {
                eprint!("\r\x1b[2K");
            }
        });
        Progress {
            stop: Some(stop),
            thread: Some(thread),
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

//! Two jobs at once, for large inputs only: the caller's thread runs one, a second thread the
//! other. One extra thread per join ([`set_threads`] can forbid it; a join inside the caller's job
//! can start one more for a moment), and it never calls
//! the caller's `interrupt` (in the extension that enters PostgreSQL, which only its own thread
//! may): the second job gets an interrupt of its own that stops it, by unwinding, once the
//! caller's side has unwound (a cancel or an error there). The caller's thread waits for the
//! second job while calling the real interrupt every millisecond, so a cancel is taken as soon as
//! it would be without the thread. The second thread blocks every signal (it inherits the mask
//! set around its creation), so a host's signal handlers (PostgreSQL's) only ever run on the
//! caller's thread.

use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// How many threads one call may use (1 or 2); 2 unless the host says otherwise.
static THREADS: AtomicUsize = AtomicUsize::new(2);

/// Allow one call `n` threads (1: never start a second thread; more than 2 is taken as 2).
pub fn set_threads(n: usize) {
    THREADS.store(n.clamp(1, 2), Ordering::Relaxed);
}

/// Inputs of at least this many vertices are worth a second thread: starting one costs tens of
/// microseconds, and an input this large takes milliseconds per step.
pub const MIN_VERTICES: u64 = 5_000;

/// Threads one call may use now.
pub fn threads() -> usize {
    THREADS.load(Ordering::Relaxed)
}

/// The payload a stopped second job unwinds with (never seen by the caller: it is only thrown
/// while the caller's side is unwinding already).
struct Stopped;

/// Sets the flag when dropped: the caller's side is done or unwinding.
struct StopOnDrop<'a>(&'a AtomicBool);

impl Drop for StopOnDrop<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Run `a` here (with `interrupt`) and `b` beside it when `worth_it` and threads are allowed;
/// else both here, `a` first. Both results are returned as if run one after the other: a panic
/// of `b` is resumed here, after `a` has finished.
pub fn join<RA, RB>(
    worth_it: bool,
    interrupt: &mut dyn FnMut(),
    a: impl FnOnce(&mut dyn FnMut()) -> RA,
    b: impl FnOnce(&mut dyn FnMut()) -> RB + Send,
) -> (RA, RB)
where
    RB: Send,
{
    if !worth_it || threads() < 2 {
        let ra = a(interrupt);
        let rb = b(interrupt);
        return (ra, rb);
    }
    let stop = AtomicBool::new(false);
    // `b` waits here until a thread takes it; if none can be started, this thread does
    let second = std::sync::Mutex::new(Some(b));
    std::thread::scope(|s| {
        // dropped, and so the flag set, before the scope joins the worker, also when `a` or
        // `interrupt` unwinds
        let _stop_on_drop = StopOnDrop(&stop);
        let (tx, rx) = mpsc::channel::<()>();
        let (stop, second) = (&stop, &second);
        let worker = move || {
            let mut stopped = || {
                if stop.load(Ordering::Relaxed) {
                    resume_unwind(Box::new(Stopped));
                }
            };
            let job = second.lock().ok().and_then(|mut b| b.take());
            let r = catch_unwind(AssertUnwindSafe(|| job.map(|b| b(&mut stopped))));
            let _ = tx.send(());
            r
        };
        let handle = {
            let _mask = signals::BlockAll::new();
            std::thread::Builder::new()
                .name("circletree".into())
                .stack_size(16 << 20)
                .spawn_scoped(s, worker)
        };
        let ra = a(interrupt);
        let rb = match handle {
            Ok(handle) => {
                while let Err(mpsc::RecvTimeoutError::Timeout) =
                    rx.recv_timeout(Duration::from_millis(1))
                {
                    interrupt();
                }
                match handle.join() {
                    Ok(Ok(rb)) => rb,
                    Ok(Err(payload)) | Err(payload) => resume_unwind(payload),
                }
            }
            // no thread to be had (a process limit): `b` is still here
            Err(_) => None,
        };
        let rb = match rb {
            Some(rb) => rb,
            None => match second.lock().ok().and_then(|mut b| b.take()) {
                Some(b) => b(interrupt),
                None => resume_unwind(Box::new("circletree: a job was lost between threads")),
            },
        };
        (ra, rb)
    })
}

#[cfg(unix)]
mod signals {
    use nix::sys::signal::{pthread_sigmask, SigSet, SigmaskHow};

    /// Every signal blocked on this thread while it lives (a thread started meanwhile keeps the
    /// mask), the previous mask restored after.
    pub struct BlockAll(Option<SigSet>);

    impl BlockAll {
        pub fn new() -> Self {
            let mut old = SigSet::empty();
            let ok = pthread_sigmask(
                SigmaskHow::SIG_SETMASK,
                Some(&SigSet::all()),
                Some(&mut old),
            );
            BlockAll(ok.ok().map(|()| old))
        }
    }

    impl Drop for BlockAll {
        fn drop(&mut self) {
            if let Some(old) = self.0.take() {
                let _ = pthread_sigmask(SigmaskHow::SIG_SETMASK, Some(&old), None);
            }
        }
    }
}

#[cfg(not(unix))]
mod signals {
    pub struct BlockAll;
    impl BlockAll {
        pub fn new() -> Self {
            BlockAll
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_results_come_back() {
        let mut calls = 0;
        let (a, b) = join(
            true,
            &mut || calls += 1,
            |i| {
                i();
                (0..1000u64).sum::<u64>()
            },
            |i| {
                i();
                (0..10u64).product::<u64>() + 7
            },
        );
        assert_eq!((a, b), (499_500, 7));
        assert!(calls >= 1);
    }

    #[test]
    fn a_panic_of_the_second_job_reaches_the_caller() {
        let r = catch_unwind(|| {
            join(
                true,
                &mut || {},
                |_| 1,
                |_| -> i32 { panic!("second job failed") },
            )
        });
        let msg = r.unwrap_err();
        assert_eq!(msg.downcast_ref::<&str>(), Some(&"second job failed"));
    }

    #[test]
    fn an_unwinding_caller_stops_the_second_job() {
        // the caller's interrupt unwinds (as PostgreSQL's cancel does through pgrx); the second
        // job would otherwise run for ever, and join must not wait for it
        let r = catch_unwind(AssertUnwindSafe(|| {
            join(
                true,
                &mut || resume_unwind(Box::new("cancelled")),
                |i| i(),
                |i| loop {
                    i();
                    std::thread::yield_now();
                },
            )
        }));
        let payload = r.unwrap_err();
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"cancelled"));
    }

    #[test]
    fn one_thread_runs_both_here_in_order() {
        let order = std::sync::Mutex::new(Vec::new());
        let (_, _) = join(
            false,
            &mut || {},
            |_| order.lock().unwrap().push('a'),
            |_| order.lock().unwrap().push('b'),
        );
        assert_eq!(*order.lock().unwrap(), vec!['a', 'b']);
    }
}

//! SIGINT and SIGTERM delete the temporary output folder of a run in progress, then end the
//! process by the same signal (as it would have ended without this).
//!
//! Why a thread and not a handler: deleting a folder tree is not async-signal-safe, and a
//! flag set by a handler would only be seen where the solver looks for it (it does not, in
//! the middle of a factorisation). So both signals are blocked in every thread (set before
//! any thread starts: threads inherit the mask) and one thread waits for them with
//! `sigwait`, where any code may run. Linux (glibc) only; elsewhere the signals keep their
//! default action and a killed run's folder is left to the next run.

/// Blocks SIGINT and SIGTERM and starts the thread that handles them. Call before any
/// other thread starts.
pub fn install() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    linux::install();
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod linux {
    use std::ptr::null_mut;

    pub fn install() {
        // SAFETY: plain libc calls on a local signal set.
        let set = unsafe {
            let mut set: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut set);
            libc::sigaddset(&mut set, libc::SIGINT);
            libc::sigaddset(&mut set, libc::SIGTERM);
            if libc::pthread_sigmask(libc::SIG_BLOCK, &set, null_mut()) != 0 {
                return;
            }
            set
        };
        let spawned = std::thread::Builder::new()
            .name("signals".into())
            .stack_size(64 << 10)
            .spawn(move || wait(set));
        if spawned.is_err() {
            // no thread to handle them: back to the default action
            // SAFETY: as above.
            unsafe { libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, null_mut()) };
        }
    }

    fn wait(set: libc::sigset_t) {
        let mut sig = 0;
        // SAFETY: `set` is initialised; `sig` is a valid out pointer. (sigwait fails only
        // on an invalid set.)
        while unsafe { libc::sigwait(&set, &mut sig) } != 0 {}
        // the lock stays held: no commit starts before the process ends
        let _held = super::super::staging::cancel();
        // SAFETY: default action for `sig`, unblocked in this thread, then raised in it:
        // the process ends by the signal.
        unsafe {
            libc::signal(sig, libc::SIG_DFL);
            let mut one: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut one);
            libc::sigaddset(&mut one, sig);
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &one, null_mut());
            libc::raise(sig);
        }
        std::process::exit(128 + sig);
    }
}

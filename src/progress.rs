//! What long work shows while it runs: one status line on stderr (the stage, e.g. "level 2
//! of 4", then "load step k of N, t, iteration, residual" from Newton), drawn only when
//! both stdout and stderr are terminals and `--quiet` is not given, so that piped or
//! redirected output holds no control characters. `--quiet` also silences what the
//! commands print on stdout (`say!`): only errors remain.
//!
//! The line is drawn by `indicatif` (maintained, rate-limited redraws, clears itself and
//! lets printed lines pass above it) rather than by hand-written escape codes. The state is
//! process-wide because the solver is reached from several commands through the library
//! API, which should not carry a display handle; a library user who never starts a display
//! pays one uncontended lock per Newton iteration.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Duration;

static QUIET: AtomicBool = AtomicBool::new(false);
static BAR: Mutex<Option<ProgressBar>> = Mutex::new(None);

/// `--quiet`: nothing on stdout, no status line.
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Prints a line on stdout unless `--quiet` (above the status line when one is drawn).
#[macro_export]
macro_rules! say {
    () => {
        $crate::progress::print_line("")
    };
    ($($arg:tt)*) => {
        $crate::progress::print_line(&format!($($arg)*))
    };
}

pub fn print_line(line: &str) {
    if quiet() {
        return;
    }
    let bar = BAR.lock().ok().and_then(|b| b.clone());
    match bar {
        Some(b) => b.suspend(|| println!("{line}")),
        None => println!("{line}"),
    }
}

/// The status line of one command, cleared when dropped.
pub struct Display(Option<ProgressBar>);

/// Starts the status line (a no-op unless stdout and stderr are terminals and not quiet).
pub fn start() -> Display {
    if quiet() || !std::io::stdout().is_terminal() || !std::io::stderr().is_terminal() {
        return Display(None);
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed:>4} {prefix}{msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.enable_steady_tick(Duration::from_millis(200));
    if let Ok(mut b) = BAR.lock() {
        *b = Some(bar.clone());
    }
    Display(Some(bar))
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(bar) = self.0.take() {
            bar.finish_and_clear();
            if let Ok(mut b) = BAR.lock() {
                *b = None;
            }
        }
    }
}

fn with_bar(f: impl FnOnce(&ProgressBar)) {
    if let Some(bar) = BAR.lock().ok().and_then(|b| b.clone()) {
        f(&bar);
    }
}

/// The outer stage of the work ("level 2 of 4, h = 0.75"), shown before Newton's part.
pub fn stage(text: &str) {
    with_bar(|b| {
        b.set_prefix(format!("{text}: "));
        b.set_message("");
    });
}

/// A load step starts: `k` of `n` planned steps (1-based), at load time `t`.
pub fn load_step(k: usize, n: usize, t: f64) {
    with_bar(|b| b.set_message(format!("load step {k} of {n}, t = {t:.4}")));
}

/// A Newton iteration of load step `k` of `n` ended with this relative residual.
pub fn iteration(k: usize, n: usize, t: f64, it: usize, residual: f64) {
    with_bar(|b| {
        b.set_message(format!(
            "load step {k} of {n}, t = {t:.4}, iteration {it}, residual {residual:.2e}"
        ))
    });
}

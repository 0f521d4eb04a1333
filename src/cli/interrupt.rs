//! Ctrl-C (SIGINT): "interrupted" on stderr and exit code 130 (128 + SIGINT, what shells report
//! for a process a Ctrl-C ended), never a half-written cache entry or results folder.
//!
//! [`install`] (called once by `main`) receives the signal on a thread of its own (signal-hook's
//! iterator: no code runs in the signal handler, so ours needs no `unsafe`). What a Ctrl-C does
//! depends on what the command is doing:
//!
//! * **Outside a [`Cooperative`] section** (reading, planning, commands that only print, and the
//!   cache commands, whose every change is one rename) the process ends at once.
//! * **Inside one** (a run's execution and the writing of its tables, the report's page) the
//!   first Ctrl-C only raises the flag the engine polls ([`requested`], through
//!   `Progress::cancelled`): no further node starts, the running ones finish and are stored in
//!   the cache, no results folder is written, and the command returns [`Interrupted`]; `main`
//!   says so and exits with 130. A rerun reuses every stored result and gives identical tables.
//! * **A second Ctrl-C** inside a section ends the process as soon as the cache entries being
//!   written are complete: the engine's [`StoreGate`] is closed (no further entry is begun) and
//!   waited for. Nodes still computing are abandoned; a results staging folder being filled is
//!   left to the next run into that folder, which removes it (it names a process that no longer
//!   runs). A third Ctrl-C ends the process without waiting.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{LazyLock, Mutex};

use indicatif::ProgressBar;

use asperity::engine::execute::StoreGate;

/// Exit code of an interrupted command: 128 + SIGINT.
pub const EXIT_CODE: u8 = 130;

/// The error a command returns when a Ctrl-C stopped it before it finished.
#[derive(Debug, thiserror::Error)]
#[error("interrupted")]
pub struct Interrupted;

struct State {
    /// Ctrl-Cs received.
    count: AtomicUsize,
    /// Cooperative sections open.
    sections: AtomicUsize,
    gate: StoreGate,
    /// The progress bar on screen, drawn around messages.
    bar: Mutex<Option<ProgressBar>>,
}

static STATE: LazyLock<State> = LazyLock::new(|| State {
    count: AtomicUsize::new(0),
    sections: AtomicUsize::new(0),
    gate: StoreGate::default(),
    bar: Mutex::new(None),
});

/// Starts receiving Ctrl-C. Without it (where signals cannot be received) Ctrl-C ends the
/// process as the system does.
#[cfg(unix)]
pub fn install() -> std::io::Result<()> {
    use signal_hook::consts::SIGINT;
    let mut signals = signal_hook::iterator::Signals::new([SIGINT])?;
    std::thread::Builder::new()
        .name(String::from("ctrl-c"))
        .spawn(move || {
            for _ in signals.forever() {
                on_ctrl_c();
            }
        })?;
    Ok(())
}

#[cfg(not(unix))]
pub fn install() -> std::io::Result<()> {
    Ok(())
}

fn on_ctrl_c() {
    let state = &*STATE;
    let count = state.count.fetch_add(1, Ordering::SeqCst) + 1;
    if state.sections.load(Ordering::SeqCst) == 0 || count >= 3 {
        stop_now();
    }
    if count == 2 {
        say("interrupted again: stopping once the cache entries being written are complete");
        state.gate.close();
        stop_now();
    }
    say(
        "interrupted: no further node starts; the running ones finish and are cached, no tables \
         are written (Ctrl-C again stops at once)",
    );
}

/// Ends the process: "interrupted", exit code 130.
fn stop_now() -> ! {
    say("interrupted");
    std::process::exit(i32::from(EXIT_CODE))
}

/// A line on stderr, around the progress bar.
fn say(message: &str) {
    let bar = STATE
        .bar
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .clone();
    match bar {
        Some(bar) => bar.suspend(|| eprintln!("{message}")),
        None => eprintln!("{message}"),
    }
}

/// `true` once a Ctrl-C was received.
pub fn requested() -> bool {
    STATE.count.load(Ordering::SeqCst) > 0
}

/// The gate a run's cache writes pass (`Progress::store_gate`).
pub fn store_gate() -> &'static StoreGate {
    &STATE.gate
}

/// Draws messages around `bar` while it is on screen (`None` once it is gone).
pub fn set_bar(bar: Option<ProgressBar>) {
    *STATE
        .bar
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = bar;
}

/// While alive, a first Ctrl-C does not end the process but is left to the command, which polls
/// [`requested`] and stops where it can do so cleanly.
pub struct Cooperative(());

/// Opens a [`Cooperative`] section.
pub fn cooperative() -> Cooperative {
    STATE.sections.fetch_add(1, Ordering::SeqCst);
    Cooperative(())
}

impl Drop for Cooperative {
    fn drop(&mut self) {
        STATE.sections.fetch_sub(1, Ordering::SeqCst);
    }
}

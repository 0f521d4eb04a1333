//! The gate every cache write of a run passes, so a front end can end the process at once
//! without leaving a half-written entry behind (a second Ctrl-C).

use std::sync::{Condvar, Mutex, PoisonError};

/// Counts the cache writes under way (an entry stored, a corrupt one discarded). Once
/// [`StoreGate::close`]d, no further write begins, and `close` returns when the ones under way
/// are complete: the process may then end without leaving anything in the cache's `tmp/`.
/// A front end hands it to a run through [`super::Progress::store_gate`].
#[derive(Debug, Default)]
pub struct StoreGate {
    state: Mutex<GateState>,
    idle: Condvar,
}

#[derive(Debug, Default)]
struct GateState {
    writing: usize,
    closed: bool,
}

/// One write under way; the gate counts it until it is dropped.
pub(super) struct Pass<'a>(&'a StoreGate);

impl StoreGate {
    /// Lets no further write begin and waits until the ones under way are complete.
    pub fn close(&self) {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        state.closed = true;
        while state.writing > 0 {
            state = self
                .idle
                .wait(state)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    /// `true` once closed.
    pub fn is_closed(&self) -> bool {
        self.state
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .closed
    }

    /// A pass for one write, or `None` once the gate is closed (the write must not begin).
    pub(super) fn enter(&self) -> Option<Pass<'_>> {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if state.closed {
            return None;
        }
        state.writing += 1;
        Some(Pass(self))
    }
}

impl Drop for Pass<'_> {
    fn drop(&mut self) {
        let mut state = self.0.state.lock().unwrap_or_else(PoisonError::into_inner);
        state.writing -= 1;
        if state.writing == 0 {
            self.0.idle.notify_all();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::time::Duration;

    #[test]
    fn closing_waits_for_the_writes_under_way_and_admits_no_new_one() {
        let gate = StoreGate::default();
        let finished = AtomicBool::new(false);
        std::thread::scope(|scope| {
            let pass = gate.enter().expect("an open gate admits a write");
            scope.spawn(|| {
                std::thread::sleep(Duration::from_millis(50));
                finished.store(true, Ordering::SeqCst);
                drop(pass);
            });
            gate.close();
            assert!(
                finished.load(Ordering::SeqCst),
                "close returned before the write"
            );
        });
        assert!(gate.is_closed());
        assert!(gate.enter().is_none());
    }
}

//! The progress bar of `asperity run` (indicatif), fed by the engine's progress events.

use std::collections::HashSet;
use std::sync::Mutex;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use asperity::engine::execute::{NodeStatus, Progress, StoreGate};
use asperity::engine::plan::PlannedNode;

/// A progress bar with ETA on stderr (hidden with `--quiet` or when stderr is not a terminal).
/// Each distinct warning is printed once. The run stops starting nodes after a Ctrl-C, and its
/// cache writes pass the gate a second Ctrl-C closes ([`super::interrupt`]).
pub struct BarProgress {
    bar: ProgressBar,
    warned: Mutex<HashSet<String>>,
}

impl BarProgress {
    pub fn new(quiet: bool) -> Self {
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
        if quiet {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} nodes, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        super::interrupt::set_bar(Some(bar.clone()));
        Self {
            bar,
            warned: Mutex::default(),
        }
    }

    pub fn finish(&self) {
        super::interrupt::set_bar(None);
        self.bar.finish_and_clear();
    }
}

impl Progress for BarProgress {
    fn start(&self, total: usize) {
        self.bar.set_length(total as u64);
    }

    fn finished(&self, node: &PlannedNode, status: &NodeStatus) {
        tracing::info!(
            kind = node.task.kind(),
            key = %node.key.short(),
            nodes = %node.names.join(","),
            status = ?status,
            "node finished"
        );
        self.bar
            .set_message(format!("{} {}", node.task.kind(), node.names.join(",")));
        self.bar.inc(1);
    }

    fn warn(&self, message: &str) {
        let mut warned = self
            .warned
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if warned.insert(message.to_string()) {
            self.bar.suspend(|| eprintln!("warning: {message}"));
        }
    }

    fn cancelled(&self) -> bool {
        super::interrupt::requested()
    }

    fn store_gate(&self) -> Option<&StoreGate> {
        Some(super::interrupt::store_gate())
    }
}
